// The Record panel in real headless Chromium (Debian's, driven by playwright-core): under the
// page's Content-Security-Policy, "GIF for slides" sets its preset, a from–to window is recorded
// with a progress bar, and the download link gives the GIF; a bad window shows the server's reason.
// Usage: node record.test.mjs SPINFOLD_BINARY [SCREENSHOT_DIR]
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";

import { runSuite, startServer, test } from "./harness.mjs";

const [binary, screenshots] = process.argv.slice(2);
const started = startServer(binary, 19000);
const { base } = started;

await runSuite(started, async (browser) => {
  // Under the page's own policy (no bypassCSP): waits use selectors, not evaluated strings.
  const context = await browser.newContext({ acceptDownloads: true, viewport: { width: 1280, height: 1000 } });
  const page = await context.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  page.on("console", (m) => { if (m.type() === "error" && !/status of 422/.test(m.text())) errors.push(m.text()); });
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });

  await test("GIF for slides sets 640×480 at 15 frames/s", async () => {
    await page.click("#record-details summary");
    await page.click("#record-slides");
    assert.equal(await page.inputValue("#record-format"), "gif");
    assert.equal(await page.inputValue("#record-width"), "640");
    assert.equal(await page.inputValue("#record-height"), "480");
    assert.equal(await page.inputValue("#record-fps"), "15");
  });

  await test("a window that ends before it starts shows the server's reason", async () => {
    await page.check("#record-range");
    await page.fill("#record-from", "2");
    await page.fill("#record-to", "1");
    await page.click("#record-start");
    await page.waitForSelector("#record-status:has-text('t_end')", { timeout: 10000 });
    assert.match(await page.textContent("#record-status"), /must be a finite number > t_start/);
    assert.equal(await page.isHidden("#record-download"), true);
  });

  await test("Record: progress, then a download link to the GIF", async () => {
    await page.fill("#record-width", "160");
    await page.fill("#record-height", "120");
    await page.fill("#record-from", "0");
    await page.fill("#record-to", "1");
    await page.click("#record-start");
    await page.waitForSelector("#record-progress:visible", { timeout: 5000 });
    await page.waitForSelector("#record-download:visible", { timeout: 60000 });
    assert.equal(await page.$eval("#record-progress", (p) => p.value), 1);
    assert.match(await page.textContent("#record-status"), /Done: 15 frames/);
    assert.match(await page.textContent("#record-download"), /Download GIF/);
    const [download] = await Promise.all([page.waitForEvent("download"), page.click("#record-download")]);
    assert.match(download.suggestedFilename(), /^spinfold-.*-t0-1\.gif$/);
    const bytes = fs.readFileSync(await download.path());
    assert.equal(bytes.subarray(0, 6).toString("latin1"), "GIF89a");
    assert.equal(bytes.readUInt16LE(6), 160);  // the logical screen: the size asked for
    assert.equal(bytes.readUInt16LE(8), 120);
  });

  if (screenshots) {
    await page.$eval("#record-panel", (el) => el.scrollIntoView());
    await page.screenshot({ path: path.join(screenshots, "record-panel.png") });
  }
  await test("no page or console errors", async () => assert.deepEqual(errors, []));
});
