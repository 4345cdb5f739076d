// Browser test of a surface given by a formula in real headless Chromium (playwright-core): a formula
// preset opens in the formula view with its picture painted; the physics panel shows the formula as
// text, its examples and a slider per parameter; a formula the language refuses is refused under the
// field naming its position, the run unchanged; the body is dragged to a new start; an example puts its formula, parameters and start in
// force; a parameter's slider restarts the run on the new surface; the console stays clean.
// Usage: node formula.test.mjs SPINFOLD_BINARY [SCREENSHOT_DIR]
// (with SCREENSHOT_DIR: the page at 1366×900, 1920×1080, 1280×720 and 390×844)
import assert from "node:assert/strict";
import path from "node:path";

import { runSuite, startServer, test } from "./harness.mjs";

const [binary, screenshots] = process.argv.slice(2);
const started = startServer(binary, 21000);
const { base } = started;

const sessionHref = (page) => page.$eval("#export-state", (a) => a.href);
const session = async (page) => (await fetch(await sessionHref(page))).json();
const consoleErrors = [];
function watchConsole(page, name) {
  page.on("console", (m) => {
    // A refused edit's 422 is the browser's own console line for a failed request: expected here.
    if (m.type() === "error" && !/status of 422/.test(m.text())) consoleErrors.push(`${name}: ${m.text()}`);
  });
  page.on("pageerror", (e) => consoleErrors.push(`${name}: ${e.message}`));
}
// What the canvas shows now (web/live.js writes each painted frame's fields on it): a frame has been
// painted since `before` once this differs (its painted count restarts with a new scene's stream, so
// a count alone cannot tell).
const shown = (page) => page.$eval("#frame", (el) => `${el.dataset.seq}/${el.dataset.version}/${el.dataset.painted}`);
async function waitForPaint(page, before) {
  const deadline = Date.now() + 15000;
  while (Date.now() < deadline) {
    if ((await shown(page)) !== before) return;
    await page.waitForTimeout(50);
  }
  throw new Error(`no frame was painted (the canvas still shows ${before})`);
}

async function waitForSession(page, predicate, what) {
  const deadline = Date.now() + 15000;
  while (Date.now() < deadline) {
    const s = await session(page);
    if (predicate(s)) return s;
    await page.waitForTimeout(100);
  }
  throw new Error(`the session never had ${what}`);
}

await runSuite(started, async (browser) => {
  const page = await browser.newPage({ viewport: { width: 1366, height: 900 }, bypassCSP: true });
  watchConsole(page, "formula page");
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
  await page.waitForSelector('.preset[data-name="egg_crate_spin"]', { timeout: 20000 });

  await test("a formula preset opens in the formula view, its picture painted", async () => {
    // The count before the click: the new scene's first frame may be painted before anything here
    // runs again (a paused run paints no other).
    const before = await shown(page);
    await page.click('.preset[data-name="egg_crate_spin"]');
    await waitForSession(page, (x) => x.current?.surface?.kind === "graph", "the egg crate");
    await page.waitForFunction(() => document.querySelector("#view")?.value === "formula", null, { timeout: 10000 });
    await waitForPaint(page, before);
  });

  await test("the body's ring is on the formula surface; a drag starts the run at the point dropped on", async () => {
    await page.waitForSelector("#handle-body:not([hidden])", { timeout: 20000 });
    const title = await page.$eval("#handle-body", (el) => el.title);
    assert.match(title, /now X = \(/, title);
    const before = (await session(page)).current.initial.X;
    const r = await (await page.$("#handle-body")).boundingBox();
    const from = { x: r.x + r.width / 2, y: r.y + r.height / 2 };
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.mouse.move(from.x - 40, from.y + 25, { steps: 6 });
    await page.waitForFunction(() => /X\.0 = /.test(document.querySelector("#handle-tip").textContent), null, { timeout: 10000 });
    await page.mouse.up();
    const after = await waitForSession(page, (x) => JSON.stringify(x.current.initial.X) !== JSON.stringify(before), "a new start");
    assert.equal(after.current.initial.X.length, 3);
    assert.equal(after.current.surface.kind, "graph");
    assert.equal(after.state.t, 0);
  });

  await test("the physics panel shows the formula, its examples and a slider per parameter", async () => {
    await page.waitForSelector("#phys-formula", { timeout: 10000 });
    assert.equal(await page.inputValue("#phys-formula"), "a*sin(x/b)*sin(y/b)");
    assert.match(await page.textContent('label[for="phys-formula"]'), /z = f\(x, y\)/);
    const examples = await page.$$eval("#phys-formula-examples option", (o) => o.map((x) => x.textContent));
    assert.ok(examples.includes("monkey saddle") && examples.includes("two bumps"), examples.join(", "));
    assert.ok(!examples.includes("triaxial ellipsoid"), "an implicit example offered for a graph");
    for (const name of ["a", "b"]) {
      assert.ok(await page.$(`#phys-parameter-${name}-range`), `no slider for ${name}`);
    }
    assert.equal(Number(await page.inputValue("#phys-parameter-a")), 0.4);
    if (screenshots)
      for (const [w, h] of [[1366, 900], [1920, 1080], [1280, 720], [390, 844]]) {
        await page.setViewportSize({ width: w, height: h });
        await page.waitForTimeout(1500);
        await page.screenshot({ path: path.join(screenshots, `formula-${w}x${h}.png`), fullPage: w < 500 });
      }
    await page.setViewportSize({ width: 1366, height: 900 });
  });

  await test("a formula the language refuses is refused under the field at its position; the run is unchanged", async () => {
    const before = await session(page);
    await page.fill("#phys-formula", "a*sin(x) + abs(y)");
    await page.dispatchEvent("#phys-formula", "change");
    await page.waitForFunction(() => document.querySelector("#phys-formula-error").textContent.length > 0, null, {
      timeout: 10000,
    });
    const reason = await page.textContent("#phys-formula-error");
    assert.match(reason, /surface\.z/);
    assert.match(reason, /position 11/);
    assert.match(reason, /abs/);
    const after = await session(page);
    // Nothing changed: the scene in force and its timeline are as they were.
    assert.deepEqual(after.current, before.current);
    assert.equal(after.timeline.length, before.timeline.length);
    // The typed text stays to be corrected.
    assert.equal(await page.inputValue("#phys-formula"), "a*sin(x) + abs(y)");
  });

  await test("an example puts its formula, parameters and start in force, the old parameters gone", async () => {
    await page.selectOption("#phys-formula-examples", "two_bumps");
    const s = await waitForSession(
      page,
      (x) => (x.current?.surface?.z ?? "").includes("exp"),
      "the two bumps",
    );
    assert.deepEqual(Object.keys(s.current.surface.parameters).sort(), ["d", "h", "w"]);
    assert.deepEqual(s.current.initial.X, [-1.9, -1.0, 0.0]);
    await page.waitForSelector("#phys-parameter-d-range", { timeout: 10000 });
    assert.equal(await page.$("#phys-parameter-a"), null, "the egg crate's a is gone");
    assert.equal(await page.textContent("#phys-formula-error"), "");
  });

  await test("a parameter's slider restarts the run on the new surface", async () => {
    const before = await shown(page);
    await page.$eval("#phys-parameter-h-range", (el) => {
      el.value = "1.2";
      el.dispatchEvent(new Event("input", { bubbles: true }));
      el.dispatchEvent(new Event("change", { bubbles: true }));
    });
    const s = await waitForSession(page, (x) => x.current?.surface?.parameters?.h === 1.2, "h = 1.2");
    assert.equal(s.state.status, "ok");
    await waitForPaint(page, before);
  });

  await test("the console stayed clean", async () => {
    assert.deepEqual(consoleErrors, []);
  });
});
