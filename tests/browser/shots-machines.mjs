// Screenshots of the machine screen for several presets (the 3D view of each structure):
//
//   NCTWIN_URL=http://127.0.0.1:8080 node shots-machines.mjs out-dir [preset ...]
//
// Each preset at 1280x800 (SIZES=1280x800,1920x1080 for more), after the demo program ran a
// few seconds where the machine can run it (RUN_MS, default 3000). Prints the 3D view's
// caption, the tool tip check and the number of programmed points.

import { mkdtemp, rm } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { chromium } from "playwright-core";
import { CHROMIUM_ARGS } from "./chromium.mjs";

const BASE = (process.env.NCTWIN_URL || "http://127.0.0.1:8080").replace(/\/+$/, "");
const OUT = process.argv[2] || tmpdir();
const PRESETS = process.argv.slice(3).length ? process.argv.slice(3) : ["mill-3axis", "mill5-head-ca", "lathe-2axis"];
const SIZES = (process.env.SIZES || "1280x800").split(",").map((s) => {
  const [width, height] = s.split("x").map(Number);
  return { width, height };
});
const RUN_MS = Number(process.env.RUN_MS ?? 3000);

const userDataDir = await mkdtemp(join(tmpdir(), "nctwin-chromium-"));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: process.env.CHROMIUM_PATH || "/usr/bin/chromium",
  headless: true,
  args: CHROMIUM_ARGS,
});
try {
  const page = context.pages()[0] || (await context.newPage());
  page.on("pageerror", (e) => console.error(`pageerror: ${e.message}`));
  page.on("console", (m) => m.type() === "error" && console.error(`console: ${m.text()}`));
  for (const preset of PRESETS) {
    for (const size of SIZES) {
      await page.setViewportSize(size);
      await page.goto(`${BASE}/?machine=${preset}`, { waitUntil: "load" });
      await page.waitForFunction(() => document.getElementById("connection")?.dataset.conn === "online");
      if (process.env.PROGRAM) {
        await page.evaluate(async (text) => {
          const id = new URL(location.href).searchParams.get("session");
          await fetch(`/api/v1/sessions/${id}/run`, { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ program: text, pace: "realtime" }) });
        }, process.env.PROGRAM.replace(/\\n/g, "\n"));
      } else if (RUN_MS > 0) {
        await page.click("#btn-cycle-start");
      }
      await page.waitForTimeout(Math.max(RUN_MS, 1500));
      const info = await page.evaluate(() => ({
        caption: document.getElementById("view3d-caption")?.textContent,
        preview: document.getElementById("view3d-preview")?.textContent,
        tipError: window.__nctwin3d?.tipError(),
        message: document.getElementById("message")?.hidden ? "" : document.getElementById("message-text")?.textContent,
      }));
      const file = join(OUT, `hmi-${preset}-${size.width}x${size.height}.png`);
      await page.screenshot({ path: file });
      console.log(file, JSON.stringify(info));
    }
  }
} finally {
  await context.close();
  await rm(userDataDir, { recursive: true, force: true });
}
