// Browser test of the NCTwin HMI: headless Chromium against a server that is already running.
//
//   NCTWIN_URL=http://127.0.0.1:8080 node hmi.test.mjs
//
// Starts nothing itself (scripts/test.sh starts the server). Exits non-zero on failure.

import { mkdtemp, rm } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { chromium } from "playwright-core";

const BASE = (process.env.NCTWIN_URL || "").replace(/\/+$/, "");
const CHROMIUM = process.env.CHROMIUM_PATH || "/usr/bin/chromium";
const TOTAL_TIMEOUT_MS = 120_000;

// A few seconds of real-time motion in X, then program end.
const PROGRAM = ["G0 X0 Y0 Z50", "G1 X100 F3000", "G0 Z100", "M30", ""].join("\n");

const WCS_X = '#positions [data-frame="workpiece"][data-axis="X"]';

const CHROMIUM_ARGS = [
  "--no-sandbox",
  "--disable-gpu",
  "--enable-unsafe-swiftshader",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
  "--no-first-run",
  "--disable-quic",
];

const results = [];
const pageErrors = [];

async function step(name, fn) {
  const t0 = Date.now();
  try {
    await fn();
    results.push({ name, ok: true });
    console.log(`ok   ${name} (${Date.now() - t0} ms)`);
  } catch (e) {
    results.push({ name, ok: false });
    console.log(`FAIL ${name}: ${e.message.split("\n")[0]}`);
    throw e;
  }
}

async function main() {
  if (!BASE) throw new Error("NCTWIN_URL is not set (e.g. NCTWIN_URL=http://127.0.0.1:8080)");
  const userDataDir = await mkdtemp(join(tmpdir(), "nctwin-chromium-"));
  let context;
  let page;
  const watchdog = setTimeout(() => {
    console.error(`hmi test: no result after ${TOTAL_TIMEOUT_MS / 1000} s, giving up`);
    process.exit(2);
  }, TOTAL_TIMEOUT_MS);
  try {
    context = await chromium.launchPersistentContext(userDataDir, {
      executablePath: CHROMIUM,
      headless: true,
      args: CHROMIUM_ARGS,
      viewport: { width: 1440, height: 900 },
    });
    page = context.pages()[0] || (await context.newPage());
    page.setDefaultTimeout(20_000);
    page.on("pageerror", (err) => pageErrors.push(`pageerror: ${err.message}`));
    page.on("console", (msg) => {
      if (msg.type() === "error") pageErrors.push(`console error: ${msg.text()}`);
    });

    await step("page loads", async () => {
      const res = await page.goto(`${BASE}/`, { waitUntil: "load" });
      if (!res || !res.ok()) throw new Error(`GET / answered ${res ? res.status() : "nothing"}`);
    });

    await step("session created and shown", async () => {
      await page.waitForFunction(() => {
        const t = document.getElementById("session-id")?.textContent?.trim();
        return t && t !== "–";
      });
    });

    await step("position table shows WCS X", async () => {
      await page.waitForFunction(
        (sel) => /^-?\d+\.\d+$/.test(document.querySelector(sel)?.textContent?.trim() || ""),
        WCS_X,
      );
    });

    await step("stream connected and status idle", async () => {
      await page.waitForFunction(
        () =>
          document.getElementById("connection")?.dataset.conn === "online" &&
          document.getElementById("status")?.textContent?.trim().toLowerCase() === "idle",
      );
    });

    // Record every status text and WCS X value the page shows from now on.
    await page.evaluate((sel) => {
      const log = { status: [], x: [] };
      window.__hmiLog = log;
      const sample = () => {
        const s = document.getElementById("status")?.textContent?.trim().toLowerCase();
        const x = document.querySelector(sel)?.textContent?.trim();
        if (s && s !== log.status.at(-1)) log.status.push(s);
        if (x && x !== log.x.at(-1)) log.x.push(x);
      };
      sample();
      new MutationObserver(sample).observe(document.body, {
        childList: true,
        characterData: true,
        subtree: true,
      });
    }, WCS_X);

    await step("program entered and started", async () => {
      await page.fill("#program", PROGRAM);
      await page.click("#btn-start");
    });

    await step('status badge shows "running"', async () => {
      await page.waitForFunction(() => window.__hmiLog.status.includes("running"), null, {
        timeout: 15_000,
      });
    });

    await step("WCS X position changes", async () => {
      await page.waitForFunction(() => new Set(window.__hmiLog.x).size >= 3, null, { timeout: 15_000 });
    });

    await step('status badge returns to "idle" at program end', async () => {
      await page.waitForFunction(
        () => {
          const s = window.__hmiLog.status;
          const i = s.indexOf("running");
          return i >= 0 && s.slice(i + 1).includes("idle") && s.at(-1) === "idle";
        },
        null,
        { timeout: 30_000 },
      );
      const x = await page.textContent(WCS_X);
      if (Math.abs(Number(x) - 100) > 1e-3) throw new Error(`WCS X at program end is ${x}, expected 100.000`);
    });

    await step("no error in the message bar", async () => {
      const hidden = await page.locator("#message").isHidden();
      if (!hidden) throw new Error(`message bar shows: ${await page.textContent("#message-text")}`);
    });

    await step("no page or console errors", async () => {
      if (pageErrors.length) throw new Error(pageErrors.join("; "));
    });
  } catch (e) {
    if (page) {
      const log = await page.evaluate(() => window.__hmiLog).catch(() => null);
      if (log) console.error(`seen statuses: ${log.status.join(" → ")}; WCS X values: ${log.x.length}`);
      const msg = await page.textContent("#message-text").catch(() => "");
      if (msg) console.error(`message bar: ${msg}`);
      if (pageErrors.length) console.error(`page errors:\n  ${pageErrors.join("\n  ")}`);
      const shot = join(tmpdir(), `nctwin-hmi-failure-${Date.now()}.png`);
      if (await page.screenshot({ path: shot }).then(() => true, () => false)) {
        console.error(`screenshot: ${shot}`);
      }
    }
    throw e;
  } finally {
    clearTimeout(watchdog);
    if (context) await context.close().catch(() => {});
    await rm(userDataDir, { recursive: true, force: true }).catch(() => {});
  }
}

main().then(
  () => {
    console.log(`hmi: ${results.length} passed, 0 failed`);
    process.exit(0);
  },
  (e) => {
    const passed = results.filter((r) => r.ok).length;
    console.error(`hmi test failed: ${e.message.split("\n")[0]}`);
    console.log(`hmi: ${passed} passed, 1 failed`);
    process.exit(1);
  },
);
