// Browser test of the curvature dial in real headless Chromium (playwright-core): while the default
// scene plays, the "Curvature K" control is set to 1, 0.5, 0, −0.5 and −1 (the slider, then the
// number field); every change continues the run (no restart, the clock goes on), the session ends
// on surface {curvature: -1}, the view switched to conformal, the live frame keeps coming and the
// console stays clean. A drag of the slider through many values sends few changes.
// Usage: node curvature_dial.test.mjs SPINFOLD_BINARY [SCREENSHOT_DIR]
// (with SCREENSHOT_DIR: pictures at K = 1, 0 and −1 at 1366×900 and the row on a 390×844 phone)
import assert from "node:assert/strict";
import path from "node:path";

import { runSuite, startServer, test } from "./harness.mjs";

const [binary, screenshots] = process.argv.slice(2);
const started = startServer(binary, 20000);
const { base } = started;

const readoutT = (page) => page.$eval("#readout", (el) => Number(el.dataset.t));
const sessionHref = (page) => page.$eval("#export-state", (a) => a.href);
const session = async (page) => (await fetch(await sessionHref(page))).json();
const consoleErrors = [];
function watchConsole(page, name) {
  page.on("console", (m) => { if (m.type() === "error") consoleErrors.push(`${name}: ${m.text()}`); });
  page.on("pageerror", (e) => consoleErrors.push(`${name}: ${e.message}`));
}

// The changes the page sent (PATCH of its session; not the live stream's PATCH …/live) and the
// server's answers.
const isChange = (r) => r.method() === "PATCH" && /\/api\/v1\/sessions\/[^/?]+$/.test(new URL(r.url()).pathname);
function watchPatches(page) {
  const patches = { sent: 0, answers: [] };
  page.on("request", (r) => { if (isChange(r)) patches.sent++; });
  page.on("response", async (r) => {
    if (!isChange(r.request())) return;
    try { patches.answers.push({ status: r.status(), ...(await r.json()) }); } catch (e) { patches.answers.push({ status: r.status() }); }
  });
  return patches;
}

// Sets the dial the way a pointer does (input events, then change on release) or by typing.
const slide = (page, K) => page.$eval("#phys-curvature-range", (el, v) => {
  el.value = String(v);
  el.dispatchEvent(new Event("input", { bubbles: true }));
  el.dispatchEvent(new Event("change", { bubbles: true }));
}, K);
async function type(page, K) {
  await page.fill("#phys-curvature", String(K));
  await page.dispatchEvent("#phys-curvature", "change");
}
// Waits until the server's parameters in force have K and the page has shown the answer.
async function settled(page, patches, K) {
  const deadline = Date.now() + 10000;
  while (Date.now() < deadline) {
    const last = patches.answers.at(-1);
    if (last?.current?.surface?.curvature === K && patches.answers.length === patches.sent) return last;
    await page.waitForTimeout(50);
  }
  throw new Error(`the server never answered with curvature ${K} (${patches.answers.length} answers)`);
}

await runSuite(started, async (browser) => {
  // bypassCSP: playwright-core 1.49's waitForFunction evaluates strings in the page (see ui.test.mjs).
  const page = await browser.newPage({ viewport: { width: 1366, height: 900 }, bypassCSP: true });
  watchConsole(page, "dial page");
  const patches = watchPatches(page);
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
  await page.waitForFunction(() => Number(document.querySelector("#frame").dataset.painted) >= 1);

  await test("the dial shows the default scene's curvature, +1/R², and no restart mark", async () => {
    assert.equal(Number(await page.inputValue("#phys-curvature")), 1);
    assert.equal(await page.textContent('label[for="phys-curvature"]'), "Curvature K");
    assert.equal(await page.textContent('[data-key="curvature"] .unit'), "1/length²");
    assert.match(await page.textContent("#phys-curvature-help"), /continues through 0/);
    assert.deepEqual(await page.$eval("#phys-curvature-range", (el) => [el.min, el.max, el.step]), ["-2", "2", "0.01"]);
    assert.equal(await page.$eval("#phys-radius", (el) => el.disabled), false);
  });

  await test("K = 1, 0.5, 0, −0.5, −1 while playing: the run continues, the view is conformal, the frame lives", async () => {
    const id = (await session(page)).id;
    await page.click("#play");
    await page.waitForFunction(() => Number(document.querySelector("#readout").dataset.t) > 0.5, null, { timeout: 10000 });
    // The clock as the page shows it, sampled throughout.
    await page.evaluate(() => {
      window.__times = [];
      window.__clock = setInterval(() => window.__times.push(Number(document.querySelector("#readout").dataset.t)), 50);
    });
    const shots = { 1: "k-plus1", 0: "k-0", [-1]: "k-minus1" };
    let firstChange = null;
    for (const [i, K] of [1, 0.5, 0, -0.5, -1].entries()) {
      if (i < 4) await slide(page, K); else await type(page, K);
      const answer = await settled(page, patches, K);
      firstChange ??= answer.change.t;
      assert.equal(await page.$eval("#view", (el) => el.value), "conformal");
      const kind = K > 0 ? "sphere" : K === 0 ? "plane" : "pseudosphere";
      assert.equal(await page.$eval("#phys-surface", (el) => el.value), kind, `K = ${K}`);
      if (screenshots && K in shots) {
        await page.waitForTimeout(3000);
        await page.screenshot({ path: path.join(screenshots, `${shots[K]}.png`) });
      } else await page.waitForTimeout(400);
    }
    const times = await page.evaluate(() => { clearInterval(window.__clock); return window.__times; });
    for (let i = 1; i < times.length; i++) assert.ok(times[i] >= times[i - 1], `the clock went back: ${times[i - 1]} → ${times[i]}`);
    assert.ok(times.every((t) => t > 0), "the clock was reset to 0");
    assert.ok(patches.answers.length >= 5);
    // K = 1 on the default sphere of radius 1 is the same surface in the other form: unchanged;
    // every other value continues the run (never a restart, even as K changes sign).
    const [first, ...rest] = patches.answers;
    assert.ok(["unchanged", "continued"].includes(first.change?.kind), JSON.stringify(first.change ?? first));
    for (const a of rest) assert.equal(a.change?.kind, "continued", JSON.stringify(a.change ?? a));
    // The scene on the server: the same session, later, on K = −1, and no restart in its timeline.
    const s = await session(page);
    assert.equal(s.id, id);
    assert.deepEqual(s.current.surface, { curvature: -1 });
    assert.ok(s.state.t > firstChange, `${s.state.t} after the first change at ${firstChange}`);
    assert.ok(s.timeline.length >= 4, `${s.timeline.length} changes in the timeline`);
    assert.ok(s.timeline.every((c) => c.t > 0));
    // The live frame keeps coming after the last change, in the conformal view, and the run plays.
    const version = await page.$eval("#frame", (el) => Number(el.dataset.version));
    await page.waitForFunction((v) => Number(document.querySelector("#frame").dataset.version) > v + 2, version, { timeout: 10000 });
    assert.equal(await page.$eval("body", (b) => b.dataset.playing), "true");
    assert.equal(await page.$eval("#frame", (el) => el.dataset.kind), "motion");
    // The radius is derived from K: 1/√|K| = 1, shown and not editable.
    assert.equal(Number(await page.inputValue("#phys-radius")), 1);
    assert.equal(await page.$eval("#phys-radius", (el) => el.disabled), true);
    assert.match(await page.textContent("#explanation"), /hyperbolic plane/);
    // In the conformal view the body's drawn size is in lengths.
    assert.equal(await page.textContent('[data-key="scale"] .unit'), "lengths");
  });

  await test("a drag from +1 through 0 to −1 sends a few changes, not one per step, and ends on −1", async () => {
    await slide(page, 1);
    await settled(page, patches, 1);
    const before = patches.sent;
    // 201 input events a few ms apart (a pointer drag), then the release.
    const started = Date.now();
    await page.$eval("#phys-curvature-range", async (el) => {
      for (let k = 100; k >= -100; k--) {
        el.value = String(k / 100);
        el.dispatchEvent(new Event("input", { bubbles: true }));
        await new Promise((r) => setTimeout(r, 5));
      }
      el.dispatchEvent(new Event("change", { bubbles: true }));
    });
    const last = await settled(page, patches, -1);
    const took = Date.now() - started, sent = patches.sent - before;
    // At most one change per 120 ms (and the last value), far fewer than the 201 steps.
    assert.ok(sent >= 2 && sent <= took / 120 + 2 && sent < 50, `${sent} changes for one drag of ${took} ms`);
    assert.equal(last.change.kind, "continued");
    assert.equal(Number(await page.inputValue("#phys-curvature")), -1);
    assert.equal(Number(await page.inputValue("#phys-curvature-range")), -1);
    assert.deepEqual((await session(page)).current.surface, { curvature: -1 });
  });

  await test("the surface select still restarts, on the kind K implied, with its radius", async () => {
    await page.focus("#phys-surface");  // (a focused number field is not refilled under the typing)
    await page.selectOption("#phys-surface", "sphere");
    await page.waitForFunction(() => /Restarted at t = 0/.test(document.querySelector("#status").textContent));
    const s = await session(page);
    assert.deepEqual(s.current.surface, { kind: "sphere", radius: 1 });
    // The number field is refilled once the drag's last send has waited out its interval (up to
    // 120 ms after the restart's answer under load: CI read −1 once).
    await page.waitForFunction(() => Number(document.querySelector("#phys-curvature").value) === 1, null, { timeout: 5000 });
    assert.equal(Number(await page.inputValue("#phys-curvature")), 1);
    assert.equal(await page.$eval("#phys-radius", (el) => el.disabled), false);
    await page.click("#pause");
  });

  // The race CI met once: the number field, focused since it was typed in, is refilled by the drag;
  // leaving it for the surface select fires a (trusted) change with the value in force while the
  // dial still waits out its interval; once the select's restart was answered, that stale K was
  // sent after it and undid the user's choice. Here all within the interval, in the page.
  await test("leaving the dial's number field for the surface select sends no stale K after the restart", async () => {
    await page.focus("#phys-curvature");
    const before = patches.sent;
    const status = await page.$eval("#phys-curvature-range", async (range) => {
      const shown = () => document.querySelector("#status").textContent;
      const was = shown();
      range.value = "-0.9";
      range.dispatchEvent(new Event("input", { bubbles: true }));
      range.dispatchEvent(new Event("change", { bubbles: true }));
      const until = async (ok, what) => {
        const deadline = Date.now() + 5000;
        while (!ok()) {
          if (Date.now() > deadline) throw new Error(`${what}: the status says "${shown()}"`);
          await new Promise((r) => setTimeout(r, 2));
        }
      };
      await until(() => shown() !== was, "the drag's answer");
      const select = document.querySelector("#phys-surface");
      select.focus();  // the number field's change fires here, with −0.9
      select.value = "sphere";
      select.dispatchEvent(new Event("change", { bubbles: true }));
      await until(() => /Restarted at t = 0/.test(shown()), "the restart's answer");
      await new Promise((r) => setTimeout(r, 600));  // past the dial's interval
      return shown();
    });
    assert.match(status, /Restarted at t = 0/);
    assert.equal(patches.sent - before, 2, "the drag's −0.9 and the restart, nothing after");
    assert.deepEqual((await session(page)).current.surface, { kind: "sphere", radius: 1 / Math.sqrt(0.9) });
    assert.equal(await page.$eval("#phys-surface", (el) => el.value), "sphere");
  });

  if (screenshots) {
    const phone = await browser.newPage({ bypassCSP: true, viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true, deviceScaleFactor: 2 });
    watchConsole(phone, "phone");
    await phone.goto(base);
    await phone.waitForSelector("body[data-ready=true]", { timeout: 20000 });
    await slide(phone, -0.5);
    await phone.waitForTimeout(1500);
    await phone.$eval('[data-key="curvature"]', (el) => el.scrollIntoView({ block: "center" }));
    await phone.focus("#phys-curvature");  // its help shows on focus
    await phone.waitForTimeout(300);
    await phone.screenshot({ path: path.join(screenshots, "phone-390x844.png") });
    await phone.close();
  }

  await test("the console has no errors", async () => {
    assert.deepEqual(consoleErrors, []);
  });
});
