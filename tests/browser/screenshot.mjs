// Screenshots of the HMI at the sizes it must fit, for a look by eye:
//
//   NCTWIN_URL=http://127.0.0.1:8080 node screenshot.mjs [out-dir] [page-path]
//
// Writes hmi-1280x800.png and hmi-1920x1080.png (default out-dir: the system temp dir) after
// the page has attached to a session and run its demo program for a few seconds, then
// hmi-<area>-<size>.png of the areas in SHOT_AREAS (default "program,data").

import { mkdtemp, rm } from "node:fs/promises";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { chromium } from "playwright-core";
import { CHROMIUM_ARGS } from "./chromium.mjs";

const BASE = (process.env.NCTWIN_URL || "http://127.0.0.1:8080").replace(/\/+$/, "");
const OUT = process.argv[2] || tmpdir();
const PATH = process.argv[3] || "/?machine=mill-3axis"; // `/` is the start page
const SIZES = [
  { width: 1280, height: 800 },
  { width: 1920, height: 1080 },
];

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
  for (const size of SIZES) {
    await page.setViewportSize(size);
    await page.goto(`${BASE}${PATH}`, { waitUntil: "load" });
    await page.waitForFunction(() => document.getElementById("connection")?.dataset.conn === "online");
    if (process.env.RUN_DEMO !== "0") {
      await page.click("#btn-cycle-start");
      await page.waitForTimeout(4000);
    } else {
      await page.waitForTimeout(1000);
    }
    const file = join(OUT, `hmi-${size.width}x${size.height}.png`);
    await page.screenshot({ path: file });
    console.log(file);
    // The other areas, at the same size (SHOT_AREAS=program,data,... ; empty: none).
    for (const area of (process.env.SHOT_AREAS ?? "program,data").split(",").filter(Boolean)) {
      await page.click(`[data-goto="${area}"]`);
      await page.waitForTimeout(500);
      const shot = join(OUT, `hmi-${area}-${size.width}x${size.height}.png`);
      await page.screenshot({ path: shot });
      console.log(shot);
    }
    await page.click('[data-goto="machine"]');
  }
} finally {
  await context.close();
  await rm(userDataDir, { recursive: true, force: true });
}
