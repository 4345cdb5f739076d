// Accessibility of the page by axe-core (@axe-core/playwright) in real headless Chromium: no
// violation of the WCAG 2.x A/AA rules axe checks, on a laptop (1366×900) and a phone (390×844),
// with the opening scene selected in the gallery (its "selected" mark shown) and after a change
// (the "modified" mark); and in the dark colour scheme.
// Usage: node axe.test.mjs SPINFOLD_BINARY [SCREENSHOT_DIR]
// (with SCREENSHOT_DIR: the page at 1366×900, 1920×1080 and 390×844)
import assert from "node:assert/strict";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

import { runSuite, startServer, test } from "./harness.mjs";

const require = createRequire(path.join(path.dirname(fileURLToPath(import.meta.url)), "../../web/package.json"));
const { default: AxeBuilder } = await import(require.resolve("@axe-core/playwright"));

const [binary, screenshots] = process.argv.slice(2);
const started = startServer(binary, 25000);
const { base } = started;

const describe = (violations) =>
  violations.map((v) => `${v.id} (${v.impact}): ${v.help}\n` +
    v.nodes.map((n) => `    ${n.target.join(" ")}: ${n.failureSummary.replace(/\n/g, " ")}`).join("\n")).join("\n");

async function opened(browser, width, height, colorScheme = "light") {
  // bypassCSP: playwright-core 1.49's waitForFunction evaluates strings in the page (see ui.test.mjs).
  // (A context of its own: axe-core/playwright opens pages in it.)
  const context = await browser.newContext({ viewport: { width, height }, bypassCSP: true, colorScheme });
  const page = await context.newPage();
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
  await page.waitForFunction(() => Number(document.querySelector("#frame").dataset.painted) >= 1);
  await page.waitForSelector('.preset img[src^="blob:"]', { timeout: 20000 });
  return page;
}

await runSuite(started, async (browser) => {
  for (const [width, height, scheme] of [[1366, 900, "light"], [390, 844, "light"], [1366, 900, "dark"]]) {
    await test(`axe-core: no violations at ${width}×${height} (${scheme}), a preset selected, then modified, then stepped (the scrubber, the drag rings, the circle's line), then in simple mode`, async () => {
      const page = await opened(browser, width, height, scheme);
      assert.equal(await page.textContent(".preset.active .mark"), "selected");
      const first = await new AxeBuilder({ page }).analyze();
      assert.equal(first.violations.length, 0, describe(first.violations));
      assert.ok(first.passes.some((rule) => rule.id === "color-contrast"), "the contrast rule ran");
      await page.fill("#phys-spin", "0.5");
      await page.dispatchEvent("#phys-spin", "change");
      await page.waitForFunction(() => document.querySelector(".preset.active .mark")?.textContent === "modified");
      const second = await new AxeBuilder({ page }).analyze();
      assert.equal(second.violations.length, 0, describe(second.violations));
      // Stepped and paused: the scrubber over the picture (its contrast and its label).
      await page.click("#step");
      await page.waitForSelector("#scrub-box:not([hidden])");
      // And the drag rings on the body and its arrow, and the circle's line under the card.
      await page.waitForSelector("#handle-body:not([hidden])", { timeout: 20000 });
      await page.waitForSelector("#circle-line:not([hidden])", { timeout: 20000 });
      const third = await new AxeBuilder({ page }).analyze();
      assert.equal(third.violations.length, 0, describe(third.violations));
      // Simple mode: the header's pressed button, the card.
      await page.click("#simple");
      await page.waitForSelector("#look-for:not([hidden])");
      const fourth = await new AxeBuilder({ page }).analyze();
      assert.equal(fourth.violations.length, 0, describe(fourth.violations));
      await page.click("#simple");
      await page.context().close();
    });
  }
  if (screenshots)
    for (const [width, height] of [[1366, 900], [1920, 1080], [390, 844]]) {
      const page = await opened(browser, width, height);
      await page.screenshot({ path: path.join(screenshots, `page-${width}x${height}.png`), fullPage: width === 390 });
      await page.context().close();
    }
});
