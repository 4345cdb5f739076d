// The live view as users see it: frames painted per second in a real headless Chromium page (the
// UI's own web/live.js: frames counted when drawn on the canvas, not when served), steer → new
// frame on screen, pause → lossless frame on screen, against the previous design (an event stream
// at 20 Hz and a frame.png fetch per event) measured in the same run; then N viewers of N playing
// sessions (plain streams, frames counted as they arrive). Prints JSON.
// Usage: node bench/live_bench.mjs BASE_URL [SECONDS] [VIEWERS] [PRESET]   (bench/live_bench.sh runs it;
// PRESET: the live view's scene, e.g. spin_vs_geodesic_torus; default the default scene)
import { chromium } from "../web/node_modules/playwright-core/index.mjs";

const base = process.argv[2] || "http://127.0.0.1:8080";
const seconds = Number(process.argv[3] || 5);
const viewers = Number(process.argv[4] || 16);
const sessionBody = process.argv[5] ? JSON.stringify({ preset: process.argv[5] }) : "{}";
const median = (a) => { const s = [...a].sort((x, y) => x - y); return s.length ? s[Math.floor(s.length / 2)] : NaN; };

async function post(path, body = {}) {
  const res = await fetch(base + path, { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
  if (!res.ok) throw new Error(`${path}: ${res.status} ${await res.text()}`);
  return res.json();
}

const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium",
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"],
});
const page = await browser.newPage({ viewport: { width: 1920, height: 1080 }, bypassCSP: true });
await page.goto(`${base}/api/v1/health`);
const result = { seconds };

// Frames painted per second while the session plays, in the live view at this size.
async function livePainted(width, height) {
  return page.evaluate(async ({ width, height, seconds, sessionBody }) => {
    const { LiveView } = await import("/live.js");
    const session = await (await fetch("/api/v1/sessions", { method: "POST", headers: { "Content-Type": "application/json" }, body: sessionBody })).json();
    const canvas = document.body.appendChild(document.createElement("canvas"));
    const live = new LiveView(canvas);
    live.open(session.id, { width, height });
    const post = (path) => fetch(`/api/v1/sessions/${session.id}/${path}`, { method: "POST", headers: { "Content-Type": "application/json" }, body: "{}" });
    await post("play");
    await new Promise((r) => setTimeout(r, 1500));  // warm up
    const start = { ...live.stats }, t0 = performance.now();
    await new Promise((r) => setTimeout(r, seconds * 1000));
    const dt = (performance.now() - t0) / 1000;
    const stats = Object.fromEntries(Object.keys(start).map((k) => [k, (live.stats[k] - start[k]) / dt]));
    await post("pause");
    live.close();
    canvas.remove();
    await fetch(`/api/v1/sessions/${session.id}`, { method: "DELETE" });
    return stats;
  }, { width, height, seconds, sessionBody });
}

// The previous design: an event stream at 20 Hz and a frame.png per state event.
async function previousPainted(width, height) {
  return page.evaluate(async ({ width, height, seconds }) => {
    const session = await (await fetch("/api/v1/sessions", { method: "POST", headers: { "Content-Type": "application/json" }, body: "{}" })).json();
    const canvas = document.body.appendChild(document.createElement("canvas"));
    canvas.width = width; canvas.height = height;
    const context = canvas.getContext("2d");
    let painted = 0, busy = false, pending = false, stop = false;
    const refresh = async () => {
      if (busy) { pending = true; return; }
      busy = true;
      const res = await fetch(`/api/v1/sessions/${session.id}/frame.png?width=${width}&height=${height}`, { cache: "no-cache" });
      const bitmap = await createImageBitmap(await res.blob());
      requestAnimationFrame(() => { context.drawImage(bitmap, 0, 0); bitmap.close(); painted++; });
      busy = false;
      if (pending && !stop) { pending = false; refresh(); }
    };
    const events = new EventSource(`/api/v1/sessions/${session.id}/events?rate=20`);
    events.addEventListener("state", refresh);
    await fetch(`/api/v1/sessions/${session.id}/play`, { method: "POST", headers: { "Content-Type": "application/json" }, body: "{}" });
    await new Promise((r) => setTimeout(r, 1500));
    const p0 = painted, t0 = performance.now();
    await new Promise((r) => setTimeout(r, seconds * 1000));
    const fps = (painted - p0) / ((performance.now() - t0) / 1000);
    stop = true;
    events.close();
    await fetch(`/api/v1/sessions/${session.id}`, { method: "DELETE" });
    canvas.remove();
    return fps;
  }, { width, height, seconds });
}

// Steer (a new camera) → its frame painted; pause → the lossless frame painted [ms].
async function latencies() {
  return page.evaluate(async () => {
    const { LiveView } = await import("/live.js");
    const session = await (await fetch("/api/v1/sessions", { method: "POST", headers: { "Content-Type": "application/json" }, body: "{}" })).json();
    const canvas = document.body.appendChild(document.createElement("canvas"));
    const live = new LiveView(canvas);
    live.open(session.id, { width: 640, height: 480 });
    const painted = (test) => new Promise((resolve) => { live.onPaint = (info) => { if (test(info)) { live.onPaint = null; resolve(performance.now()); } }; });
    await painted((info) => info.kind === "still");
    const steer = [], still = [];
    for (let i = 0; i < 15; i++) {
      const seq = Number(canvas.dataset.seq);
      const done = painted((info) => Number(info.seq) > seq);
      const t0 = performance.now();
      live.steer({ yaw: (0.5 + 0.1 * i).toFixed(4), pitch: "0.3" });
      steer.push((await done) - t0);
      await painted((info) => info.kind === "still");
    }
    const post = (path) => fetch(`/api/v1/sessions/${session.id}/${path}`, { method: "POST", headers: { "Content-Type": "application/json" }, body: "{}" });
    for (let i = 0; i < 7; i++) {
      await post("play");
      await new Promise((r) => setTimeout(r, 500));
      const done = painted((info) => info.kind === "still");
      const t0 = performance.now();
      await post("pause");
      still.push((await done) - t0);
    }
    live.close();
    await fetch(`/api/v1/sessions/${session.id}`, { method: "DELETE" });
    return { steer, still };
  });
}

result.live_640x480 = await livePainted(640, 480);
result.previous_640x480 = await previousPainted(640, 480);
result.live_1280x720 = await livePainted(1280, 720);
result.previous_1280x720 = await previousPainted(1280, 720);
const lat = await latencies();
result.steer_ms = { median: median(lat.steer), all: lat.steer.map((x) => Math.round(x)) };
result.still_ms = { median: median(lat.still), all: lat.still.map((x) => Math.round(x)) };
await browser.close();

// N viewers of N playing sessions: frames that arrive per second on each stream.
async function countFrames(id, until) {
  const controller = new AbortController();
  const res = await fetch(`${base}/api/v1/sessions/${id}/live?viewer=bench`, { signal: controller.signal });
  const reader = res.body.getReader();
  const marker = Buffer.from("X-Spinfold-Frame");
  let frames = 0, tail = Buffer.alloc(0);
  try {
    while (Date.now() < until) {
      const { value, done } = await reader.read();
      if (done) break;
      const chunk = Buffer.concat([tail, Buffer.from(value)]);
      for (let at = chunk.indexOf(marker); at >= 0; at = chunk.indexOf(marker, at + 1)) frames++;
      tail = chunk.subarray(Math.max(0, chunk.length - marker.length + 1));
    }
  } finally {
    controller.abort();
  }
  return frames;
}
const ids = [];
for (let i = 0; i < viewers; i++) ids.push((await post("/api/v1/sessions", {})).id);
for (const id of ids) await post(`/api/v1/sessions/${id}/play`);
await new Promise((r) => setTimeout(r, 1000));
const t0 = Date.now();
const counts = await Promise.all(ids.map((id) => countFrames(id, t0 + seconds * 1000)));
const elapsed = (Date.now() - t0) / 1000;
const each = counts.map((c) => c / elapsed);
result[`viewers_${viewers}`] = { min: Math.min(...each), median: median(each), total: each.reduce((a, b) => a + b, 0) };
for (const id of ids) await fetch(`${base}/api/v1/sessions/${id}`, { method: "DELETE" });
console.log(JSON.stringify(result, null, 1));
