// Browser tests of the web UI in real headless Chromium (Debian's, driven by playwright-core):
// load, pick a preset, play and see the frame change, change a field and see the state change,
// an invalid value shows the server's message and changes nothing, the deformation kind switches,
// dragging orbits the camera, a share URL reproduces the
// state, the exports answer. Usage: node ui.test.mjs SPINFOLD_BINARY [SCREENSHOT_DIR]
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import assert from "node:assert/strict";
import path from "node:path";
import { fileURLToPath } from "node:url";

const require = createRequire(path.join(path.dirname(fileURLToPath(import.meta.url)), "../../web/package.json"));
const { chromium } = require("playwright-core");

const [binary, screenshots] = process.argv.slice(2);
const port = 18000 + (process.pid % 1000);
const server = spawn(binary, ["serve", "--port", String(port)], { stdio: ["ignore", "pipe", "inherit"] });
const base = `http://127.0.0.1:${port}/`;
let failed = false;

async function waitForServer() {
  for (let i = 0; i < 100; ++i) {
    try { if ((await fetch(base + "api/v1/health")).ok) return; } catch (e) { /* not yet */ }
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error("server did not start");
}

async function test(name, body) {
  try {
    await body();
    console.log(`ok   ${name}`);
  } catch (e) {
    failed = true;
    console.log(`FAIL ${name}\n${e.stack}`);
  }
}

const readoutT = (page) => page.$eval("#readout", (el) => Number(el.dataset.t));

try {
  await waitForServer();
  const browser = await chromium.launch({
    executablePath: "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
  // The UI under its Content-Security-Policy: it loads, shows its thumbnails and frame (blob: URLs)
  // and plays (EventSource) without a violation. The page driven below bypasses the policy, because
  // playwright-core 1.49's waitForFunction evaluates strings in the page, which the policy forbids
  // (fixed upstream: microsoft/playwright#36986).
  await test("the UI runs under its Content-Security-Policy", async () => {
    const strict = await browser.newPage();
    const violations = [];
    strict.on("console", (m) => { if (/Content.Security.Policy/i.test(m.text())) violations.push(m.text()); });
    strict.on("pageerror", (e) => violations.push(e.message));
    const response = await strict.goto(base);
    assert.match(response.headers()["content-security-policy"], /script-src 'self'/);
    await strict.waitForSelector("body[data-ready=true]", { timeout: 20000 });
    await strict.waitForSelector("#frame[data-painted]", { timeout: 10000 });
    await strict.waitForSelector('.preset img[src^="blob:"]', { timeout: 20000 });
    await strict.click("#play");
    await strict.waitForSelector('#readout:not([data-t="0"])', { timeout: 10000 });
    await strict.click("#pause");
    assert.deepEqual(violations, []);
    await strict.close();
  });

  const page = await browser.newPage({ viewport: { width: 1280, height: 900 }, bypassCSP: true });
  page.on("pageerror", (e) => { failed = true; console.log(`page error: ${e.stack}`); });
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });

  await test("the page loads a session and its frame", async () => {
    await page.waitForFunction(() => Number(document.querySelector("#frame").dataset.painted) >= 1);
    assert.equal(await page.$eval("#frame", (el) => el.width), 640);
    assert.equal(await page.$eval("#frame", (el) => el.dataset.kind), "still");  // paused: the lossless frame
    assert.match(await page.textContent("#readout"), /integrator: exact/);
  });

  await test("picking a preset opens it", async () => {
    await page.click('.preset[data-name="breathing_ellipse_sphere"]');
    await page.waitForFunction(() => document.querySelector("#explanation").textContent.includes("breathes"));
    assert.equal(await readoutT(page), 0);
  });

  await test("play streams motion frames; pause ends with the lossless frame", async () => {
    const before = await page.$eval("#frame", (el) => Number(el.dataset.version));
    await page.click("#play");
    await page.waitForFunction(() => Number(document.querySelector("#readout").dataset.t) > 0.5, null, { timeout: 10000 });
    await page.waitForFunction((v) => Number(document.querySelector("#frame").dataset.version) > v && document.querySelector("#frame").dataset.kind === "motion", before, { timeout: 10000 });
    await page.click("#pause");
    await page.waitForFunction(() => document.querySelector("#frame").dataset.kind === "still", null, { timeout: 10000 });
  });

  await test("moving the speed slider changes how fast the state advances", async () => {
    await page.click("#reset");
    await page.$eval("#speed", (el) => { el.value = "5"; el.dispatchEvent(new Event("input")); el.dispatchEvent(new Event("change")); });
    await page.waitForFunction(() => Number(document.querySelector("#readout").dataset.t) > 2.5, null, { timeout: 10000 });
    await page.click("#pause");
    assert.equal(await page.textContent("#speed-out"), "5");
  });

  await test("changing a field changes the state", async () => {
    await page.fill('[name="initial.r"]', "0.9");
    await page.dispatchEvent('[name="initial.r"]', "change");
    await page.waitForFunction(() => /r = 0\.900000/.test(document.querySelector("#readout").textContent));
  });

  await test("an invalid value shows the server's message and changes nothing", async () => {
    const before = await page.textContent("#readout");
    await page.fill('[name="body.mass"]', "-2");
    await page.dispatchEvent('[name="body.mass"]', "change");
    await page.waitForFunction(() => [...document.querySelectorAll(".error")].some((e) => e.textContent.includes("must be > 0")));
    assert.equal(await page.inputValue('[name="body.mass"]'), "1");
    assert.equal(await page.textContent("#readout"), before);
  });

  await test("switching the deformation kind replaces its fields on the server and in the form", async () => {
    // The parameters in force (a change after t = 0 is a timeline entry; the scene is t = 0's).
    const scene = async () => (await (await fetch(await page.$eval("#export-state", (a) => a.href))).json()).current;
    await page.selectOption('[name="potential.deformation.kind"]', "polar");
    await page.waitForSelector('[name="potential.deformation.ghat"]');
    assert.equal(await page.$('[name="potential.deformation.C"]'), null);
    assert.equal((await scene()).potential.deformation.kind, "polar");
    await page.selectOption('[name="potential.deformation.kind"]', "none");
    await page.waitForFunction(() => !document.querySelector('[name="potential.deformation.ghat"]'));
    assert.equal((await scene()).potential.deformation, undefined);
    await page.selectOption('[name="potential.deformation.kind"]', "abc");
    await page.waitForSelector('[name="potential.deformation.C"]');
    assert.equal((await scene()).potential.deformation.kind, "abc");
  });

  await test("dragging the frame orbits the camera: a new picture", async () => {
    await page.click("#pause");
    await page.waitForFunction(() => document.querySelector("#frame").dataset.kind === "still", null, { timeout: 10000 });
    const before = await page.$eval("#frame", (el) => el.dataset.seq);
    const box = await (await page.$("#frame")).boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 40, { steps: 4 });
    await page.mouse.up();
    await page.waitForFunction((seq) => document.querySelector("#frame").dataset.seq !== seq, before, { timeout: 10000 });
  });

  await test("a parameter change continues the run: no teleport, the initial fields untouched", async () => {
    await page.click("#step");
    await page.waitForTimeout(300);
    const t = await readoutT(page);
    const r = await page.inputValue('[name="initial.r"]');
    await page.fill('[name="body.mass"]', "1.5");
    await page.dispatchEvent('[name="body.mass"]', "change");
    await page.waitForFunction(() => /continuing/.test(document.querySelector("#status").textContent));
    assert.equal(await readoutT(page), t);  // the clock goes on from where it was
    assert.equal(await page.inputValue('[name="initial.r"]'), r);  // no 16-digit refill
    const session = await (await fetch(await page.$eval("#export-state", (a) => a.href))).json();
    assert.equal(session.timeline.at(-1).t, t);
    assert.equal(session.current.body.mass, 1.5);
    // The plots keep their history across the change.
    assert.ok(Number(await page.$eval("#plot-energy", (el) => el.dataset.from)) < t);
  });

  await test("a share URL reproduces the same state", async () => {
    await page.click("#step");
    await page.waitForTimeout(300);
    const t = await readoutT(page);
    const readout = await page.textContent("#readout");
    await page.click("#share");
    const url = page.url();
    assert.match(url, /#scene=/);
    const other = await browser.newPage();
    await other.goto(url);
    await other.waitForSelector("body[data-ready=true]", { timeout: 20000 });
    assert.equal(await readoutT(other), t);
    const strip = (s) => s.replace(/integrator: \w+/, "");
    assert.equal(strip(await other.textContent("#readout")), strip(readout));
    // The same picture, trail included: the frames of both sessions are the same bytes.
    const frameDigest = (p) => p.evaluate(async () => {
      const id = new URL(document.querySelector("#export-state").href).pathname.split("/").pop();
      const res = await fetch(`/api/v1/sessions/${id}/frame.png?width=320&height=240&view=sphere&layers=surface,grid,body,frame,trail,hud`);
      const bytes = new Uint8Array(await crypto.subtle.digest("SHA-256", await res.arrayBuffer()));
      return Array.from(bytes, (b) => b.toString(16).padStart(2, "0")).join("");
    });
    assert.equal(await frameDigest(other), await frameDigest(page));
    await other.close();
  });

  await test("exports answer: PNG, state JSON, trajectory CSV", async () => {
    for (const [id, type] of [["export-png", "image/png"], ["export-state", "application/json"], ["export-csv", "text/csv"]]) {
      const href = await page.$eval(`#${id}`, (a) => a.href);
      const res = await fetch(href);
      assert.equal(res.status, 200, id);
      assert.equal(res.headers.get("content-type"), type);
    }
    const csv = await (await fetch(await page.$eval("#export-csv", (a) => a.href))).text();
    assert.match(csv.split("\n")[0], /^t,r,phi/);
  });

  if (screenshots) {
    await page.screenshot({ path: path.join(screenshots, "desktop.png") });
    await page.setViewportSize({ width: 390, height: 844 });
    await page.waitForTimeout(300);
    await page.screenshot({ path: path.join(screenshots, "phone.png"), fullPage: true });
  }
  await browser.close();
} catch (e) {
  failed = true;
  console.log(e.stack);
} finally {
  server.kill();
}
process.exit(failed ? 1 : 0);
