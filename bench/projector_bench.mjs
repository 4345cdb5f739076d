// Smooth playback on a projector: painted frames per second of the real page (web/, its live view
// and its pacing, pace.js) at 1920×1080 in headless Chromium, a preset playing, against the same page
// with ?pace=full (the picture always full size) in the same run. Counted from the canvas's
// data-painted after a warm-up that lets the pace settle. Prints JSON lines.
// Usage: node bench/projector_bench.mjs BASE_URL [SECONDS] [PRESET]   (bench/projector_bench.sh
// starts the server; run it with `stress-ng --cpu 1` beside it for "the other core busy")
import { chromium } from "../web/node_modules/playwright-core/index.mjs";

const base = process.argv[2] || "http://127.0.0.1:8080/";
const seconds = Number(process.argv[3] || 10);
const preset = process.argv[4] || "spin_vs_geodesic_torus";

const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium",
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"],
});
for (const mode of ["full", "paced"]) {
  const page = await browser.newPage({ viewport: { width: 1920, height: 1080 }, bypassCSP: true });
  await page.goto(base + (mode === "full" ? "?pace=full" : ""));
  await page.waitForSelector("body[data-ready=true]");
  await page.click(`.preset[data-name="${preset}"]`);
  await page.waitForFunction((p) => document.querySelector(".preset.active")?.dataset.name === p, preset);
  await page.click("#play");
  await page.waitForTimeout(8000); // the pace settles: a step each 2 s
  const painted = async () => Number(await page.$eval("#frame", (el) => el.dataset.painted));
  const before = await painted();
  const started = Date.now();
  await page.waitForTimeout(seconds * 1000);
  const rate = ((await painted()) - before) / ((Date.now() - started) / 1000);
  const shown = await page.evaluate(async () => {
    const { store } = await import("/state.js");
    const f = document.querySelector("#frame");
    return { pace: store.get().pace, size: store.get().size, frame: [f.width, f.height] };
  });
  console.log(JSON.stringify({ mode, preset, seconds, painted_per_second: Number(rate.toFixed(1)), ...shown }));
  await page.close();
}
await browser.close();
