// Spinfold's browser UI: everything comes from the API (presets, schema, state, frames); no
// physics here.
import uPlot from "/vendor/uPlot.esm.js";
import { LiveView } from "/live.js";
import { setupRecording } from "/record.js";
import { setupWorkPrecision } from "/workprecision.js";

const api = "/api/v1";
const embed = new URLSearchParams(location.search).get("embed") === "1";
// scene: the parameters at t = 0; current: those in force now; timeline: the changes since
// ([{t, patch}]); the session is a pure function of scene + timeline + t, and so is a share link
// (and the copy kept in sessionStorage that rebuilds a session after a reload or an expiry).
const ui = {
  id: null, scene: null, current: null, timeline: [], schema: null, presets: [], t: 0, state: null,
  start: null,  // the state at t = 0 (what the physical controls show when the scene gave rates)
  playing: false, rate: 1,
  view: { kind: null, layers: new Set(["surface", "grid", "body", "frame", "trail", "hud"]), yaw: null, pitch: null,
          distance: null, scale: 0.25 },
  size: { width: 640, height: 480 },  // the frame asked of the stream: shown size × devicePixelRatio
  events: null, live: null, plots: null, series: [[], [], [], [], [], []],
  preset: null,  // the preset the session started from (its card is highlighted)
  opening: null,  // the promise of a scene being opened (a new session replacing this one)
  borrowed: null,  // a session shown by ?session=ID (made elsewhere): never deleted here
};
const $ = (id) => document.getElementById(id);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

class ProblemError extends Error {
  constructor(problem, status, retryAfter) {
    super(problem.detail || problem.title || `HTTP ${status}`);
    this.problem = problem;
    this.status = status;
    this.retryAfter = retryAfter;
  }
}

async function request(method, path, body) {
  const options = { method, headers: {} };
  if (body !== undefined) {
    options.headers["Content-Type"] = method === "PATCH" ? "application/merge-patch+json" : "application/json";
    options.body = JSON.stringify(body);
  }
  const res = await fetch(api + path, options);
  if (res.status === 204) return null;
  const data = await res.json().catch(() => ({ title: res.statusText }));
  if (!res.ok) throw new ProblemError(data, res.status, Number(res.headers.get("Retry-After")) || 0);
  return data;
}

// A call on the current session; when the server no longer knows it (expired after 30 minutes
// idle, deleted, or the server restarted without its store) the session is rebuilt from its
// scene, timeline and time, and the call made again on the new one.
async function call(method, path, body) {
  // A scene being opened replaces the session: a call made meanwhile (an edit a moment after a
  // preset's click) goes to the new one, not to the old one being deleted (whose 404 would
  // rebuild the old scene over the new).
  if (ui.opening) {
    const was = ui.id;
    await ui.opening.catch(() => {});
    if (was && ui.id !== was) path = path.replace(`/sessions/${was}`, `/sessions/${ui.id}`);
  }
  try {
    return await request(method, path, body);
  } catch (e) {
    const own = ui.id && path.startsWith(`/sessions/${ui.id}`);
    if (!own || e.status !== 404) throw e;
    const old = ui.id;
    await recover();
    return request(method, path.replace(old, ui.id), body);
  }
}

function status(text) { $("status").textContent = text; }

// ---- A full server (429 or 503 with Retry-After): say so plainly and try again, backing off.
let busyRetry = null;
async function withRetry(what, action) {
  for (let attempt = 0; ; attempt++) {
    try {
      const result = await action();
      $("busy").hidden = true;
      return result;
    } catch (e) {
      if (e.status !== 429 && e.status !== 503) throw e;
      const wait = Math.min(30, Math.max(e.retryAfter || 0, 2 ** Math.min(attempt, 5)));
      $("busy").hidden = false;
      for (let left = wait; left > 0; left--) {
        $("busy-text").textContent = `The server is full (${e.message}). ${what}: trying again in ${left} s.`;
        const skipped = await Promise.race([sleep(1000).then(() => false), new Promise((r) => (busyRetry = () => r(true)))]);
        if (skipped) break;
      }
      $("busy-text").textContent = `${what}: trying again now…`;
    }
  }
}

// ---- Frames: one live stream per page (web/live.js); a change of view, camera or size steers it.
function viewParams() {
  const q = { width: ui.size.width, height: ui.size.height, view: ui.view.kind, layers: [...ui.view.layers].join(","),
              scale: ui.view.scale };
  if (ui.view.yaw !== null) Object.assign(q, { yaw: ui.view.yaw.toFixed(4), pitch: ui.view.pitch.toFixed(4) });
  if (ui.view.distance !== null) q.distance = ui.view.distance.toFixed(3);
  return q;
}

function frameQuery(width = ui.size.width, height = ui.size.height) {
  return `${api}/sessions/${ui.id}/frame.png?${new URLSearchParams({ ...viewParams(), width, height })}`;
}

function updateExports() {
  if (!ui.id) return;
  $("export-png").href = frameQuery();
  const w = Math.max(16, Math.min(4096, Math.round(Number($("png-width").value) || 1920)));
  const h = Math.max(16, Math.min(4096, Math.round(Number($("png-height").value) || 1080)));
  $("export-png-sized").href = frameQuery(w, h);
  $("export-state").href = `${api}/sessions/${ui.id}`;
  $("export-csv").href = `${api}/sessions/${ui.id}/trajectory?format=csv`;
}

function refreshFrame() {
  if (!ui.id) return;
  const params = viewParams();
  if (ui.view.yaw === null) params.aim = "body";
  ui.live.steer(params);
  updateExports();
}

// The frame is asked at the size it is shown × devicePixelRatio, at most 1920×1080 (the aspect
// kept), and again whenever the shown size changes (window, full screen, phone rotation).
function measureFrame() {
  const box = $("frame").getBoundingClientRect();
  if (box.width < 8 || box.height < 8) return false;
  const dpr = window.devicePixelRatio || 1;
  let width = Math.round(box.width * dpr), height = Math.round(box.height * dpr);
  const shrink = Math.min(1, 1920 / width, 1080 / height);
  width = Math.max(16, Math.round(width * shrink));
  height = Math.max(16, Math.round(height * shrink));
  const hudChanged = defaultHud(box.width, box.height);
  if (width === ui.size.width && height === ui.size.height) return hudChanged;
  ui.size = { width, height };
  return true;
}

// A frame shown smaller than kSmallFrame CSS pixels (a phone, upright or on its side) has no room
// for legible overlay text: it would cover a third of the picture or be a few pixels high, and the
// readout below the frame says the same. Off by default there, on elsewhere; once the teacher
// ticks or unticks "hud", theirs is the choice.
const kSmallFrame = { width: 520, height: 360 };
function defaultHud(shownWidth, shownHeight) {
  if (ui.view.hudChosen) return false;
  const want = shownWidth >= kSmallFrame.width && shownHeight >= kSmallFrame.height;
  if (want === ui.view.layers.has("hud")) return false;
  want ? ui.view.layers.add("hud") : ui.view.layers.delete("hud");
  const box = document.querySelector("#layers input[name=layer-hud]");
  if (box) box.checked = want;
  return true;
}

// The frame and the playback bar below it fit the window at load: the frame is never taller than
// the room between its top and the window's bottom less the toolbar (at least 240 px).
function fitFrameToWindow() {
  const top = $("frame-box").getBoundingClientRect().top + window.scrollY;
  const room = Math.max(240, window.innerHeight - top - $("toolbar").offsetHeight - 20);
  document.documentElement.style.setProperty("--frame-room", `${Math.round(room)}px`);
}

let resizeTimer = null;
function watchFrameSize() {
  new ResizeObserver(() => {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(() => { if (measureFrame() && ui.id) refreshFrame(); }, 120);
  }).observe($("frame"));
  const refit = new ResizeObserver(fitFrameToWindow);
  for (const id of ["gallery", "toolbar", "busy"]) refit.observe($(id));
  refit.observe(document.querySelector("header"));
  addEventListener("resize", fitFrameToWindow);
}

// ---- Play state: the session's "playing" and "rate" in every session answer, and what the UI
// asked since; a run that stops (status not ok) is shown stopped.
function setPlaying(playing) {
  ui.playing = playing;
  document.body.dataset.playing = String(playing);
  $("play").setAttribute("aria-pressed", String(playing));
  $("pause").setAttribute("aria-pressed", String(!playing));
  const stopped = ui.state && ui.state.status !== "ok";
  const text = stopped ? `stopped: ${ui.state.status}` : playing ? `playing at ${ui.rate}×` : "paused";
  $("state-badge").textContent = text;
  $("state-badge").dataset.state = stopped ? "stopped" : playing ? "playing" : "paused";
  $("play-state").textContent = stopped ? "■ stopped" : playing ? "▶" : "❚❚ paused";
  $("play-state").dataset.state = $("state-badge").dataset.state;
}

async function play() {
  ui.rate = Number($("speed").value);
  try {
    await call("POST", `/sessions/${ui.id}/play`, { rate: ui.rate });
    setPlaying(true);
  } catch (e) { status(e.message); }
}

async function pause() {
  await call("POST", `/sessions/${ui.id}/pause`, {});
  setPlaying(false);
}

async function step() {
  if (ui.playing) await pause();
  showState((await call("POST", `/sessions/${ui.id}/advance`, { steps: 10 })).state, { from: "answer" });
}

async function reset() {
  const res = await call("POST", `/sessions/${ui.id}/reset`, {});
  adopt(res);
  showState(res.state, { restart: true, from: "answer" });
  ui.start = res.state;
  buildControls();
  status("Back to t = 0 with the parameters in force.");
}

// ---- The action variables J = ∮p dq and frequencies ν = ∂E/∂J of separable scenes (a table;
// "—" with the server's reason on hover where one is undefined, one line where there are none).
const kActions = [["J_r", "J_r", "radial"], ["J_phi", "J_φ", "angular (2π p_φ)"], ["J_alpha", "J_α", "spin (2π s)"],
                  ["J_beta", "J_β", "vorticity (2π p_β)"], ["J_x", "J_x", "deformation x"], ["J_y", "J_y", "deformation y"]];
const kFrequencies = [["r", "ν_r", "of r(t)"], ["phi", "ν_φ", "precession of the orbit"], ["x", "ν_x", "of x²(t)"], ["y", "ν_y", "of y²(t)"]];
function showActions(state) {
  const box = $("actions");
  if (!box || !("actions" in state)) return;
  const undefinedWhy = state.undefined ?? {};
  if (!state.actions) {
    box.innerHTML = "";
    box.append(Object.assign(document.createElement("p"), { className: "note", textContent: `No action variables: ${undefinedWhy.actions ?? "not a separable scene"}.` }));
    return;
  }
  const cell = (group, key, label, what, unit) => {
    const v = state[group]?.[key];
    const why = undefinedWhy[`${group}.${key}`];
    return `<tr title="${why ? why.replace(/"/g, "&quot;") : what}"><th scope="row">${label}</th><td>${v === null || v === undefined ? "—" : Number(v).toPrecision(6)}</td><td>${unit}</td></tr>`;
  };
  box.innerHTML = `<table><caption>Action variables and frequencies</caption><tbody>` +
    kActions.map(([k, l, w]) => cell("actions", k, l, w, "mass·length²/time")).join("") +
    kFrequencies.map(([k, l, w]) => cell("frequencies", k, l, w, "cycles/time")).join("") + `</tbody></table>`;
}

// ---- State, readouts and plots.
const num = (v) => (v === null || v === undefined ? "—" : Number(v).toPrecision(6));
let announced = 0;
// A state from the event stream, or from an answer (from: "answer"). The stream's states come in
// order, so one back in time is a restart or reset; an answer can arrive after the stream has
// already gone past its time (playing), and then it is older news, not a restart.
function showState(state, { restart = false, from = "stream" } = {}) {
  const s = ui.series;
  const last = s[0].length ? s[0][s[0].length - 1] : -Infinity;
  if (from === "answer" && !restart && state.t < last) return;
  ui.state = state;
  ui.t = state.t;
  $("readout").textContent =
    `t = ${num(state.t)}   r = ${num(state.r)}   phi = ${num(state.phi)}   lambda = ${num(state.lambda)}   mu = ${num(state.mu)}\n` +
    `energy = ${num(state.energy)}   energy error = ${num(state.energy_error)}   spin = ${num(state.spin)}   ` +
    `p_phi = ${num(state.p_phi)}   det L = ${num(state.det_L)}   integrator: ${state.integrator}   status: ${state.status}`;
  $("readout").dataset.t = state.t;
  showActions(state);
  // Screen readers hear a short summary, at most once a second.
  const now = performance.now();
  if (now - announced >= 1000) {
    announced = now;
    $("announce").textContent = `time ${Number(state.t).toFixed(2)}, spin ${Number(state.spin).toPrecision(3)}, ` +
      `energy error ${Number(state.energy_error ?? 0).toExponential(1)}, ${state.status === "ok" ? (ui.playing ? "playing" : "paused") : state.status}`;
    $("announce").dataset.at = String(Math.round(now));
  }
  if (state.status !== "ok") {
    if (state.status_detail) status(state.status_detail);
    if (ui.playing) setPlaying(false);
  }
  setPlaying(ui.playing);
  // Back in time: a restart or reset (a change at the current time keeps the history; the plots
  // mark it). The same time again: the sample after a change replaces the one before it.
  if (restart || state.t < last) s.forEach((a) => (a.length = 0));
  else if (state.t === last) s.forEach((a) => a.pop());
  // A long lesson: past 20,000 samples every other one is dropped (the plot keeps its span).
  if (s[0].length >= 20000) s.forEach((a, i) => (s[i] = a.filter((_, k) => k % 2 === 0)));
  s[0].push(state.t);
  s[1].push(energyPoint(state.energy_error));
  const finite = (v) => (Number.isFinite(v) ? v : null);
  s[2].push(finite(state.spin));
  s[3].push(finite(state.p_phi));
  s[4].push(finite(state.C_x));
  s[5].push(finite(state.C_y));
  $("plot-energy").dataset.from = s[0][0];  // the plotted history's start (browser tests read it)
  drawPlots();
  saveSession();
}

// At most one redraw per display refresh however fast states come.
let plotQueued = false;
function drawPlots() {
  if (!ui.plots || plotQueued) return;
  plotQueued = true;
  requestAnimationFrame(() => {
    plotQueued = false;
    const s = ui.series;
    ui.plots.energy.setData([s[0], s[1]]);
    ui.plots.invariants.setData([s[0], s[2], s[3], s[4], s[5]]);
  });
}

// A session's answer to create, change or reset: its scene, timeline and parameters in force.
function adopt(session) {
  ui.scene = session.scene;
  ui.current = session.current;
  ui.timeline = session.timeline;
  if (typeof session.playing === "boolean") {
    ui.rate = session.rate ?? ui.rate;
    setPlaying(session.playing);
  }
  if (ui.plots) { ui.plots.energy.redraw(); ui.plots.invariants.redraw(); }
  showComparisons();
  markGallery();
}

// A dashed line on the plots at every parameter change (the plots keep their history across it).
const changeMarks = {
  hooks: {
    draw: [(u) => {
      const { ctx } = u;
      const { top, height } = u.bbox;
      ctx.save();
      ctx.strokeStyle = "#888";
      ctx.setLineDash([4, 4]);
      ctx.lineWidth = 1;
      for (const change of ui.timeline) {
        const x = Math.round(u.valToPos(change.t, "x", true));
        if (x < u.bbox.left || x > u.bbox.left + u.bbox.width) continue;
        ctx.beginPath();
        ctx.moveTo(x, top);
        ctx.lineTo(x, top + height);
        ctx.stroke();
        ctx.fillStyle = "#888";
        ctx.font = `${Math.round(10 * devicePixelRatio)}px system-ui, sans-serif`;
        ctx.fillText("change", x + 3 * devicePixelRatio, top + 10 * devicePixelRatio);
      }
      ctx.restore();
    }],
  },
};

// ---- The energy-error plot: |ΔH/H| on a log axis over whole decades from 10⁻¹⁶ (round-off) up to
// the decade above the largest value (at least 10⁰ once the error passes 10⁻¹); the ticks and
// their labels are ours (uPlot's log ticks need a non-empty, finite, positive range). A zero or
// round-off error sits on the floor; NaN or infinity is left out (a gap), never plotted.
const energyFloor = 1e-16;
const superscript = (n) => String(n).replace(/[-0-9]/g, (c) => "⁻⁰¹²³⁴⁵⁶⁷⁸⁹"["-0123456789".indexOf(c)]);
const decadeLabel = (v) => (v <= energyFloor ? "≤10⁻¹⁶" : `10${superscript(Math.round(Math.log10(v)))}`);

function energyPoint(error) {
  const e = Math.abs(Number(error));
  if (error === null || error === undefined || !Number.isFinite(e)) return null;
  return Math.min(Math.max(e, energyFloor), 1e300);
}

function energyRange(u, lo, hi) {
  const top = Number.isFinite(hi) && hi > energyFloor ? hi : 1e-15;
  let exponent = Math.ceil(Math.log10(top) - 1e-9);
  if (exponent > -1) exponent = Math.max(exponent, 0);
  return [energyFloor, 10 ** Math.max(-15, Math.min(exponent, 300))];
}

// Decades between the range's ends, every 1, 2, 4 or 8th so that labels do not crowd.
// The labels drawn (the browser tests read them from data-ticks).
// (uPlot's default filter for log axes drops some splits as null; ours keeps every one we made.)
function energyLabels(u, splits) {
  const labels = splits.map((v) => (v === null ? "" : decadeLabel(v)));
  $("plot-energy").dataset.ticks = labels.filter(Boolean).join(" ");
  return labels;
}

function energySplits(u, axis, min, max) {
  const lo = Math.max(-16, Math.round(Math.log10(min))), hi = Math.max(lo + 1, Math.round(Math.log10(max)));
  const room = Math.max(2, Math.floor(u.bbox.height / devicePixelRatio / 18));
  let every = 1;
  while ((hi - lo) / every > room) every *= 2;
  const splits = [];
  for (let e = hi; e >= lo; e -= every) splits.unshift(10 ** e);
  if (splits[0] !== 10 ** lo) splits.unshift(10 ** lo);
  return splits;
}

// Units in the legend: s and p_φ are angular momenta, C_x and C_y energies (own axis, right).
const angularMomentum = "mass·length²/time", energyUnit = "mass·length²/time²";

function makePlots() {
  const width = Math.max(260, Math.min(420, ($("side").clientWidth || 360) - 8));
  const axisStyle = { stroke: "#778", grid: { stroke: "rgba(128,128,128,0.25)" }, ticks: { stroke: "rgba(128,128,128,0.4)" } };
  ui.plots = {
    energy: new uPlot({ width, height: 170, title: "energy error |ΔH/H₀| (from the last change)", plugins: [changeMarks],
                        scales: { x: { time: false }, y: { distr: 3, log: 10, range: energyRange } },
                        axes: [{ ...axisStyle, label: "time" },
                               { ...axisStyle, size: 56, splits: energySplits, filter: (u, splits) => splits, values: energyLabels }],
                        series: [{ label: "t" }, { label: "|ΔH/H₀|", stroke: "#c40", width: 1.5 }] }, [[], []], $("plot-energy")),
    invariants: new uPlot({ width, height: 200, title: "conserved quantities", plugins: [changeMarks],
                            scales: { x: { time: false }, am: {}, en: {} },
                            axes: [{ ...axisStyle, label: "time" },
                                   { ...axisStyle, scale: "am", label: "angular momentum", size: 56 },
                                   { ...axisStyle, scale: "en", side: 1, label: "energy", size: 56, grid: { show: false } }],
                            series: [{ label: "t" },
                                     { label: `spin s (${angularMomentum})`, stroke: "#06c", scale: "am" },
                                     { label: `p_φ (${angularMomentum})`, stroke: "#080", scale: "am", dash: [6, 3] },
                                     { label: `C_x (${energyUnit})`, stroke: "#a0a", scale: "en" },
                                     { label: `C_y (${energyUnit})`, stroke: "#b80", scale: "en", dash: [2, 3] }] },
                          [[], [], [], [], []], $("plot-invariants")),
  };
  new ResizeObserver(() => {
    const w = Math.max(260, Math.min(480, $("side").clientWidth - 8));
    if (Math.abs(w - ui.plots.energy.width) > 4) for (const p of Object.values(ui.plots)) p.setSize({ width: w, height: p.height });
  }).observe($("side"));
}


// ---- One event stream per page. When it ends (the session expired or was deleted, the server
// restarted, a stream limit), the session is checked: rebuilt if gone, listened to again if not.
function listen() {
  if (ui.events) ui.events.close();
  const source = (ui.events = new EventSource(`${api}/sessions/${ui.id}/events?rate=20`));
  source.addEventListener("state", (e) => showState(JSON.parse(e.data)));
  source.onerror = () => { if (source.readyState === EventSource.CLOSED && ui.events === source) checkSession(); };
}

let checking = false;
async function checkSession() {
  if (checking) return;
  checking = true;
  try {
    await call("GET", `/sessions/${ui.id}`);  // rebuilds the session when the server has lost it
    await sleep(1000);
    if (!ui.events || ui.events.readyState === EventSource.CLOSED) listen();
  } catch (e) {
    status(`Lost the connection to the server (${e.message}); trying again.`);
    await sleep(2000);
    checking = false;
    return checkSession();
  }
  checking = false;
}

// ---- Sessions: one per page, deleted when the page goes away; sessionStorage keeps what rebuilds
// it (scene, timeline, time, view), so a reload re-attaches to the session when the server still
// has it and rebuilds it bit for bit when it does not.
const storeKey = "spinfold.session";
let saved = 0;
function saveSession(now = false, extra = {}) {
  if (!ui.id || (!now && performance.now() - saved < 1000)) return;
  saved = performance.now();
  try {
    sessionStorage.setItem(storeKey, JSON.stringify({
      id: ui.id, scene: ui.scene, timeline: ui.timeline, t: ui.t, playing: ui.playing, rate: ui.rate, preset: ui.preset,
      modified: ui.modified, view: { kind: ui.view.kind, layers: [...ui.view.layers] }, ...extra }));
  } catch (e) { /* storage full or disabled: a reload starts afresh */ }
}

function loadSaved() {
  try { return JSON.parse(sessionStorage.getItem(storeKey) || "null"); } catch (e) { return null; }
}

let thumbnailSession = null;  // the gallery's short-lived session, if one is being made
function leave() {
  saveSession(true, { deleted: true });
  for (const id of [ui.id, thumbnailSession])
    if (id && id !== ui.borrowed) fetch(`${api}/sessions/${id}`, { method: "DELETE", keepalive: true }).catch(() => {});
  if (ui.events) ui.events.close();
  ui.events = null;
  ui.live.close();
}

// Shows a session (new, re-attached or rebuilt) and opens its event and live streams.
function attach(session, { keepView = false } = {}) {
  ui.id = session.id;
  if (!keepView) {
    ui.view.yaw = ui.view.pitch = ui.view.distance = null;
    ui.series.forEach((a) => (a.length = 0));
  }
  adopt(session);
  if (session.state.t === 0) ui.start = session.state;
  showState(session.state);
  showExplanation();
  buildControls();
  buildViewControls();
  listen();
  measureFrame();
  ui.live.open(ui.id, viewParams());
  updateExports();
  saveSession(true);
}

let recovering = null;
function recover() {
  recovering ??= (async () => {
    const wasPlaying = ui.playing;
    const body = ui.t > 0 || ui.timeline.length ? { scene: ui.scene, timeline: ui.timeline, until: ui.t } : ui.scene;
    const created = await withRetry("Rebuilding the session", () => request("POST", "/sessions", body));
    attach(created, { keepView: true });
    status(`The session had ended on the server; rebuilt at t = ${num(ui.t)} from its scene and timeline.`);
    if (wasPlaying) await play();
  })().finally(() => (recovering = null));
  return recovering;
}

// A scene from t = 0, or (a share link, a reload) a scene with its timeline rebuilt up to `until`.
async function openScene(scene, options = {}) {
  // One opening at a time: each replaces the session the previous one made (two clicks in quick
  // succession would otherwise both replace the same old session and leave one of theirs behind).
  while (ui.opening) await ui.opening.catch(() => {});
  const opening = openSceneNow(scene, options);
  ui.opening = opening;
  try {
    await opening;
  } finally {
    if (ui.opening === opening) ui.opening = null;
  }
}
async function openSceneNow(scene, { until = 0, timeline = [], preset = null } = {}) {
  const old = ui.id;
  const body = until > 0 || timeline.length ? { scene, timeline, until } : scene;
  const created = await withRetry("Opening the scene", () => request("POST", "/sessions", body));
  if (old && old !== created.id && old !== ui.borrowed) request("DELETE", `/sessions/${old}`).catch(() => {});
  ui.preset = preset;
  ui.modified = timeline.length > 0;
  setPlaying(false);
  attach(created);
  status(preset ? `Opened “${label(preset)}”.` : "Opened the scene.");
}

// The session to show on load: a share link's, this tab's (re-attached, or rebuilt when the
// server no longer has it), or the default preset.
async function firstSession() {
  // ?session=ID shows a session someone else made (a notebook's Session.show()): it is borrowed,
  // never deleted by this tab.
  const asked = new URLSearchParams(location.search).get("session");
  if (asked) {
    try {
      const session = await request("GET", `/sessions/${encodeURIComponent(asked)}`);
      ui.borrowed = session.id;
      attach(session);
      status("Showing a shared session: changes here change it for everyone who shows it.");
      return;
    } catch (e) {
      if (e.status !== 404) throw e;
      status("That session is gone; opening the default scene.");
    }
  }
  const shared = fromHash();
  if (shared) return openScene(shared.scene, { until: shared.until, timeline: shared.timeline, preset: shared.scene.name ?? null });
  const mine = loadSaved();
  if (mine?.scene) {
    ui.view.kind = mine.view?.kind ?? null;
    if (mine.view?.layers) ui.view.layers = new Set(mine.view.layers);
    ui.rate = mine.rate ?? 1;
    $("speed").value = ui.rate;
    $("speed-out").textContent = ui.rate;
    // A session this tab deleted as it went away is rebuilt; one it could not delete (a crash, a
    // lost request) is re-attached to when the server still has it.
    try {
      if (mine.deleted) throw Object.assign(new Error("deleted"), { status: 404 });
      const session = await request("GET", `/sessions/${mine.id}`);
      ui.preset = mine.preset;
      ui.modified = mine.modified;
      attach(session);
      setPlaying(Boolean(mine.playing));
      status("Re-attached to this tab's session.");
      return;
    } catch (e) {
      if (e.status !== 404) throw e;
    }
    ui.preset = mine.preset;
    await openScene(mine.scene, { until: mine.t, timeline: mine.timeline, preset: mine.preset });
    ui.modified = mine.modified;
    markGallery();
    if (mine.playing) await play();
    status(`Rebuilt this tab's session at t = ${num(mine.t)}.`);
    return;
  }
  const first = ui.presets.find((p) => p.name === "spinning_rigid_sphere") || ui.presets[0];
  await openScene(first.scene, { preset: first.name });
}

// ---- Controls built from the scene's JSON Schema. A change is a PATCH; a refusal shows the
// server's message beside the field and the value goes back.
function fieldFor(path, spec, value) {
  const row = document.createElement("div");
  row.className = "field";
  const label = document.createElement("label");
  label.textContent = path[path.length - 1] + (spec["x-unit"] && spec["x-unit"] !== "1" ? ` [${spec["x-unit"]}]` : "");
  let input;
  if (spec.enum) {
    input = document.createElement("select");
    for (const option of spec.enum) input.add(new Option(option, option));
    input.value = value ?? spec.default;
  } else if (matrixOrNumber(spec)) {
    // A number or a matrix (body.inertia: isotropic J, or [[J11, J12], [J12, J22]]), as text.
    input = document.createElement("input");
    input.type = "text";
    input.value = JSON.stringify(value ?? spec.default);
    input.placeholder = "0.5 or [[0.6, 0.1], [0.1, 0.3]]";
  } else {
    input = document.createElement("input");
    input.type = "number";
    input.step = "any";
    input.value = value ?? spec.default;
  }
  input.name = path.join(".");
  input.title = spec.description || "";
  label.htmlFor = input.id = "field-" + path.join("-");
  const error = document.createElement("span");
  error.className = "error";
  error.id = input.id + "-error";
  input.setAttribute("aria-describedby", error.id);
  input.addEventListener("change", async () => {
    const patch = {};
    let node = patch;
    path.slice(0, -1).forEach((key) => (node = node[key] = {}));
    try {
      node[path[path.length - 1]] = spec.enum ? input.value : matrixOrNumber(spec) ? JSON.parse(input.value) : Number(input.value);
    } catch (e) {
      error.textContent = `${path.join(".")}: write a number or a matrix such as [[0.6, 0.1], [0.1, 0.3]] (got ${input.value})`;
      return;
    }
    // A deformation field needs its kind: the scene's, or abc when there is none yet.
    if (path[1] === "deformation") node.kind = lookup(ui.current, ["potential", "deformation", "kind"]) ?? "abc";
    // The surface is given either by K or by kind and radius: setting one form removes the other.
    if (path[0] === "surface" && path[1] === "curvature") Object.assign(node, { kind: null, radius: null });
    else if (path[0] === "surface" && curvatureForm())
      Object.assign(node, { kind: node.kind ?? surfaceKind(), radius: node.radius ?? radiusOf() ?? 1, curvature: null });
    try {
      await applyChange(patch, path[0] === "surface" || path[1] === "deformation");
    } catch (e) {
      error.textContent = e.message;
      const kept = lookup(ui.current, path) ?? spec.default;
      input.value = matrixOrNumber(spec) ? JSON.stringify(kept) : kept;
    }
  });
  row.append(label, input, error);
  return row;
}

const matrixOrNumber = (spec) => Boolean(spec.oneOf?.some((branch) => branch.type === "array"));

// The deformation potential's kind: none or one of the schema's. A switch is one merge patch that
// sets the new kind and removes the old kind's fields (null), so the server sees one whole object.
function deformationKindField(branches, deformation) {
  const row = document.createElement("div");
  row.className = "field";
  const label = document.createElement("label");
  label.textContent = "deformation kind";
  const input = document.createElement("select");
  input.add(new Option("none", "none"));
  for (const branch of branches) input.add(new Option(branch.properties.kind.const, branch.properties.kind.const));
  input.value = deformation?.kind ?? "none";
  input.name = "potential.deformation.kind";
  label.htmlFor = input.id = "field-potential-deformation-kind";
  const error = document.createElement("span");
  error.className = "error";
  input.addEventListener("change", async () => {
    let replacement = null;
    if (input.value !== "none") {
      replacement = { kind: input.value };
      for (const key of Object.keys(deformation ?? {})) if (key !== "kind") replacement[key] = null;
    }
    try {
      await applyChange({ potential: { deformation: replacement } }, true);
    } catch (e) {
      error.textContent = e.message;
      input.value = deformation?.kind ?? "none";
    }
  });
  row.append(label, input, error);
  return row;
}

function lookup(object, path) { return path.reduce((node, key) => (node ? node[key] : undefined), object); }

// ---- The surface in either of its forms: {kind, radius} or {curvature: K} (K > 0 the sphere of
// radius 1/√K, 0 the plane, K < 0 the hyperbolic plane of radius 1/√−K; |K| below the server's
// 1e-24 is the plane).
const kFlatCurvature = 1e-24;
const kindOfCurvature = (K) => (Math.abs(K) < kFlatCurvature ? "plane" : K > 0 ? "sphere" : "pseudosphere");
const curvatureForm = (surface = ui.current.surface) => typeof surface?.curvature === "number";
function surfaceKind(surface = ui.current.surface) {
  if (curvatureForm(surface)) return kindOfCurvature(surface.curvature);
  return surface?.kind ?? "sphere";
}
function curvatureOf(surface = ui.current.surface) {
  if (curvatureForm(surface)) return surface.curvature;
  const R = surface.radius ?? 1;
  return { sphere: 1, plane: 0, pseudosphere: -1 }[surfaceKind(surface)] / (R * R);
}
// The radius the surface has now (derived from K in the curvature form; none on the plane there).
function radiusOf(surface = ui.current.surface) {
  if (!curvatureForm(surface)) return surface.radius ?? 1;
  return surfaceKind(surface) === "plane" ? undefined : 1 / Math.sqrt(Math.abs(surface.curvature));
}

function buildControls() {
  buildPhysical();
  const form = $("controls");
  form.textContent = "";
  const props = ui.schema.properties;
  for (const section of ["surface", "body", "initial", "integrator"]) {
    const set = document.createElement("fieldset");
    set.innerHTML = `<legend>${section}</legend>`;
    // A field the scene gave in its other form (the schema's dependentSchemas: spin instead of
    // alpha_dot, speed and heading instead of r_dot and phi_dot) shows empty, not its default.
    const replaced = new Set();
    for (const [given, rule] of Object.entries(props[section].dependentSchemas ?? {}))
      if (lookup(ui.current, [section, given]) !== undefined)
        for (const alternative of rule.not?.anyOf ?? []) alternative.required.forEach((k) => replaced.add(k));
    for (const [key, spec] of Object.entries(props[section].properties)) {
      const field = fieldFor([section, key], spec, lookup(ui.current, [section, key]));
      if (replaced.has(key)) {
        const input = field.querySelector("input, select");
        input.value = "";
        input.placeholder = "from the physical form";
      }
      set.append(field);
    }
    form.append(set);
  }
  const potential = document.createElement("fieldset");
  potential.innerHTML = "<legend>potential</legend>";
  const gamma = props.potential.properties.radial.properties.gamma;
  potential.append(fieldFor(["potential", "radial", "gamma"], gamma, lookup(ui.current, ["potential", "radial", "gamma"]) ?? 0));
  const deformation = lookup(ui.current, ["potential", "deformation"]);
  potential.append(deformationKindField(props.potential.properties.deformation.oneOf, deformation));
  for (const branch of props.potential.properties.deformation.oneOf) {
    const kind = branch.properties.kind.const;
    if (deformation && deformation.kind !== kind) continue;
    for (const [key, spec] of Object.entries(branch.properties))
      if (key !== "kind") potential.append(fieldFor(["potential", "deformation", key], spec, deformation?.[key]));
    if (!deformation) break;  // offer the abc fields when there is no deformation potential yet
  }
  form.append(potential);
  const degenerate = document.createElement("fieldset");
  degenerate.innerHTML = "<legend>run</legend>";
  degenerate.append(fieldFor(["on_degenerate"], props.on_degenerate, ui.current.on_degenerate));
  form.append(degenerate);
}

// A change of parameters: continues the run from now (a mark on the plots), or restarts it at
// t = 0 when the start, the surface or the comparisons changed; the server says which, and so
// does the status line. A good edit clears every refusal still shown.
async function applyChange(patch, rebuild = false) {
  const before = surfaceKind();
  const res = await call("PATCH", `/sessions/${ui.id}`, patch);
  document.querySelectorAll(".error").forEach((e) => (e.textContent = ""));
  if (res.change.kind !== "unchanged") ui.modified = true;
  adopt(res);
  showState(res.state, { restart: res.change.kind === "restarted", from: "answer" });
  if (res.change.kind === "restarted") {
    ui.start = res.state;
    status(`Restarted at t = 0: ${res.change.reason}`);
  } else if (res.change.kind === "continued") {
    status(`Changed at t = ${num(res.change.t)}, continuing: ${res.change.reason}`);
  }
  const kindChanged = surfaceKind(res.current.surface) !== before;
  if (kindChanged) showExplanation();
  if (rebuild || res.change.kind === "restarted") { buildControls(); buildViewControls(); refreshFrame(); }
  else {
    buildPhysical();
    // The curvature dial crossed K = 0 (the run continues): the views offered follow the surface.
    if (kindChanged) {
      const was = ui.view.kind;
      buildViewControls();
      if (ui.view.kind !== was) refreshFrame();
    }
  }
  return res;
}

// ---- Physical controls first: each a slider and a number, its unit in words, a one-line
// explanation shown on hover and focus. The paper's coordinates are in the advanced panel.
// Label, unit and explanation come from the scene's JSON Schema (title, x-unit, description: the
// engine's field table, engine/scene_fields.h), never from a table of the UI's own.
const degree = Math.PI / 180;

// A scene field's schema by its path ("potential.deformation.C": the abc branch's).
function schemaField(path) {
  const [section, ...rest] = path.split(".");
  let spec = ui.schema.properties[section];
  for (const key of rest) {
    if (key !== "deformation" && spec.oneOf) spec = spec.oneOf.find((b) => b.properties?.kind?.const === "abc");
    spec = spec.properties[key];
  }
  return spec;
}

// How a schema unit is shown: a pure number ("1") says so; an angle the UI shows in degrees.
const displayUnit = (unit) => ({ "1": "pure number", rad: "degrees" })[unit] ?? unit;

// The label, unit and help of a physical row from the schema.
function described(path) {
  const spec = schemaField(path);
  return { field: path, label: spec.title, unit: displayUnit(spec["x-unit"]), help: spec.description };
}

function physicalRows() {
  const initial = ui.current.initial, start = ui.start ?? {};
  const rigid = ui.current.body.model === "rigid";
  const deformation = ui.current.potential?.deformation;
  const kind = surfaceKind();
  const speedHeading = (speed, heading) => ({ initial: { speed, heading } });
  const rows = [
    { key: "spin", ...described("initial.spin"), min: -3, max: 3, step: 0.05, restarts: true,
      value: initial.spin ?? start.spin, patch: (v) => ({ initial: { spin: v } }) },
    { key: "speed", ...described("initial.speed"), min: 0, max: 3, step: 0.05, restarts: true,
      value: initial.speed ?? start.speed, patch: (v) => speedHeading(v, initial.heading ?? start.heading ?? Math.PI / 2) },
    { key: "heading", ...described("initial.heading"), min: -180, max: 180, step: 1, restarts: true,
      value: (initial.heading ?? start.heading ?? undefined) === undefined ? undefined : (initial.heading ?? start.heading) / degree,
      patch: (v) => speedHeading(initial.speed ?? start.speed ?? 0.5, v * degree) },
    { key: "lambda", ...described("initial.lambda"), min: 0.2, max: 3, step: 0.05, restarts: true,
      value: initial.lambda ?? start.lambda, patch: (v) => ({ initial: rigid ? { lambda: v, mu: v } : { lambda: v } }) },
  ];
  if (!rigid)
    rows.push({ key: "mu", ...described("initial.mu"), min: 0.2, max: 3, step: 0.05, restarts: true,
                value: initial.mu ?? start.mu, patch: (v) => ({ initial: { mu: v } }) });
  // The curvature dial: one slider from the sphere through the plane to the hyperbolic plane. The
  // run continues through K = 0 (the body keeps its place, velocity and frame); the picture
  // switches to the conformal view, the one view that exists on every surface and is continuous in K.
  const byK = curvatureForm();
  rows.push(
    { key: "curvature", ...described("surface.curvature"), min: -2, max: 2, step: 0.01, live: true,
      value: curvatureOf(), before: showConformal,
      patch: (v) => ({ surface: { curvature: v, kind: null, radius: null } }) },
    { key: "radius", ...described("surface.radius"), min: 0.25, max: 5, step: 0.05, disabled: byK,
      // Derived from K, the row says so before the field's own description.
      note: byK ? (kind === "plane" ? "From the curvature: K = 0 is the flat plane, which has no radius."
                                    : "From the curvature: R = 1/√|K|. To set R, pick the surface above.") : "",
      value: radiusOf(), placeholder: "none", patch: (v) => ({ surface: { radius: v } }) },
    { key: "gamma", ...described("potential.radial.gamma"), min: 0, max: 1, step: 0.01,
      value: ui.current.potential?.radial?.gamma ?? 0, patch: (v) => ({ potential: { radial: { gamma: v } } }) });
  if (!rigid && (!deformation || deformation.kind === "abc"))
    rows.push({ key: "C", ...described("potential.deformation.C"), min: 0, max: 5, step: 0.05,
                value: deformation?.C ?? 0, patch: (v) => ({ potential: { deformation: { kind: "abc", C: v } } }) });
  // (In the conformal view the size is in lengths, so the picture does not change with K.)
  rows.push({ key: "scale", label: "Body size on screen", unit: ui.view.kind === "conformal" ? "lengths" : "surface radii", min: 0.05, max: 1, step: 0.01, view: true,
              help: "Only the picture: how large the body's ellipse is drawn (+ and − keys in 2-D views).",
              value: ui.view.scale, patch: null });
  return rows;
}

// Rebuilt when the rows change (another body model or potential); otherwise the values are
// updated in place, so that focus and a slider being dragged stay where they are.
function buildPhysical() {
  const form = $("physical");
  const rows = physicalRows();
  const keys = rows.map((r) => r.key).join(",");
  if (form.dataset.keys === keys) {
    for (const row of rows) form.querySelector(`[data-key="${row.key}"]`).update(row);
    form.querySelector("#phys-surface").value = surfaceKind();
    return;
  }
  form.dataset.keys = keys;
  form.textContent = "";
  const legend = document.createElement("h2");
  legend.textContent = "Physics";
  const note = document.createElement("p");
  note.className = "note";
  note.textContent = "↺: changing it restarts the run at t = 0. The others change the run from now on.";
  form.append(legend, note, surfaceKindRow());
  for (const row of rows) form.append(physicalRow(row));
}

function physicalRow(spec) {
  const row = document.createElement("div");
  row.className = "phys";
  row.dataset.key = spec.key;
  if (spec.field) row.dataset.field = spec.field;  // the scene field it sets (its schema describes it)
  const id = `phys-${spec.key}`;
  const label = document.createElement("label");
  label.htmlFor = id;
  label.textContent = spec.label + (spec.restarts ? " ↺" : "");
  const range = document.createElement("input");
  Object.assign(range, { type: "range", min: spec.min, max: spec.max, step: spec.step, id: `${id}-range` });
  range.setAttribute("aria-label", `${spec.label} slider`);
  const number = document.createElement("input");
  Object.assign(number, { type: "number", step: "any", id, name: `phys.${spec.key}` });
  const unit = document.createElement("span");
  unit.className = "unit";
  unit.textContent = spec.unit;
  const help = document.createElement("small");
  help.className = "help";
  help.id = `${id}-help`;
  const helpText = () => (spec.note ? `${spec.note} ` : "") + spec.help;
  help.textContent = helpText();
  const error = document.createElement("span");
  error.className = "error";
  error.id = `${id}-error`;
  error.setAttribute("role", "alert");
  for (const input of [range, number]) {
    input.setAttribute("aria-describedby", `${help.id} ${error.id}`);
    input.title = helpText();
  }
  const show = (v) => {
    const known = v !== undefined && v !== null && Number.isFinite(Number(v));
    number.value = known ? Number(Number(v).toPrecision(6)) : "";
    number.placeholder = known ? "" : spec.placeholder ?? "from the rates";
    range.value = known ? v : (spec.min + spec.max) / 2;
  };
  const enable = () => {
    range.disabled = number.disabled = Boolean(spec.disabled);
    row.classList.toggle("derived", Boolean(spec.disabled));
  };
  show(spec.value);
  enable();
  // A live row (the curvature dial) sends while it is dragged, at most one change in flight and
  // one every kLiveInterval ms, the latest value winning; the slider is not moved under the
  // pointer by the answers meanwhile.
  // (The release's change event repeats the last input's value: not sent again while in force.)
  let sending = false, pending = null, sent;
  const live = async (v) => {
    pending = v;
    if (sending) return;
    sending = true;
    while (pending !== null) {
      const next = pending;
      pending = null;
      if (next === sent && next === spec.value) continue;
      sent = next;
      const started = performance.now();
      await apply(next);
      await sleep(Math.max(0, kLiveInterval - (performance.now() - started)));
    }
    sending = false;
    if (document.activeElement !== number) show(spec.value);
  };
  // The same row with the parameters now in force (its closures read spec).
  row.update = (next) => {
    spec = next;
    if (document.activeElement !== number && !sending) show(spec.value);
    help.textContent = helpText();
    unit.textContent = spec.unit;
    for (const input of [range, number]) input.title = helpText();
    enable();
  };
  const apply = async (v) => {
    if (!Number.isFinite(v)) { error.textContent = "a number, please"; return; }
    if (spec.before) spec.before();
    if (spec.view) {
      ui.view.scale = v;
      show(v);
      error.textContent = "";
      refreshFrame();
      return;
    }
    try {
      await applyChange(spec.patch(v));
    } catch (e) {
      show(spec.value);
      // The row was rebuilt by nothing (the change was refused): its message stays beside it.
      error.textContent = e.message;
    }
  };
  // The slider's value on its grid of steps (−2 + 200 × 0.01 is 0, not 1e-16).
  const stepped = () => Number(Number(range.value).toFixed(6));
  const typed = () => (number.value === "" ? NaN : Number(number.value));
  range.addEventListener("input", () => {
    number.value = stepped();
    if (spec.live) live(stepped());
  });
  range.addEventListener("change", () => (spec.live ? live(stepped()) : apply(stepped())));
  number.addEventListener("change", () => (spec.live && Number.isFinite(typed()) ? live(typed()) : apply(typed())));
  row.append(label, range, number, unit, help, error);
  return row;
}

const kLiveInterval = 120;  // ms between two changes sent by a dragged live slider

// The curvature dial shows the conformal view (the sphere's 3-D view and the Poincaré disk do not
// exist on every side of K = 0); the view menu says so.
function showConformal() {
  if (ui.view.kind === "conformal" || !ui.views.some((v) => v.name === "conformal")) return;
  ui.view.kind = "conformal";
  ui.view.yaw = ui.view.pitch = ui.view.distance = null;
  $("view").value = "conformal";
  refreshFrame();
  buildPhysical();  // the body size's unit: lengths in this view
  saveSession(true);
}

function surfaceKindRow() {
  const row = document.createElement("div");
  row.className = "phys";
  const label = document.createElement("label");
  label.htmlFor = "phys-surface";
  label.textContent = "Surface ↺";
  const select = document.createElement("select");
  select.id = "phys-surface";
  select.name = "phys.surface";
  for (const [value, text] of [["sphere", "sphere (positive curvature)"], ["pseudosphere", "hyperbolic plane (negative curvature)"], ["plane", "flat plane (no curvature)"]])
    select.add(new Option(text, value));
  select.value = surfaceKind();
  const help = document.createElement("small");
  help.className = "help";
  help.id = "phys-surface-help";
  help.textContent = "The curved surface the body lives on; switching restarts the run.";
  select.setAttribute("aria-describedby", help.id);
  select.title = help.textContent;
  const error = document.createElement("span");
  error.className = "error";
  select.addEventListener("change", async () => {
    try {
      // From the curvature form: that form goes, the radius it implied stays (1 from the plane).
      const surface = curvatureForm() ? { kind: select.value, radius: radiusOf() ?? 1, curvature: null } : { kind: select.value };
      await applyChange({ surface }, true);
    } catch (e) {
      error.textContent = e.message;
      select.value = surfaceKind();
    }
  });
  row.append(label, select, help, error);
  return row;
}

// ---- Comparisons: the geodesic companion (one click or G) and a fan of spins (vary). The
// legend is drawn in the picture by the server (the hud layer).
function hasGeodesic() { return (ui.current?.companions ?? []).some((c) => c.geodesic); }

function showComparisons() {
  if (!ui.current) return;
  const on = hasGeodesic();
  $("geodesic").setAttribute("aria-pressed", String(on));
  $("geodesic").textContent = on ? "− Geodesic companion" : "+ Geodesic companion";
}

async function toggleGeodesic() {
  const companions = ui.current.companions ?? [];
  const next = hasGeodesic() ? companions.filter((c) => !c.geodesic)
                             : [...companions, { geodesic: true, label: "geodesic (s = 0)" }];
  try {
    await applyChange({ companions: next.length ? next : null }, true);
    if (!ui.view.layers.has("hud")) { ui.view.layers.add("hud"); ui.view.hudChosen = true; buildViewControls(true); refreshFrame(); }
  } catch (e) { status(e.message); }
}

async function addFan() {
  const from = Number($("fan-from").value), to = Number($("fan-to").value);
  const count = Math.max(2, Math.min(8, Math.round(Number($("fan-count").value) || 4)));
  const values = Array.from({ length: count }, (_, i) => Number((from + ((to - from) * i) / (count - 1)).toPrecision(6)));
  try {
    await applyChange({ vary: { field: "initial.spin", values } }, true);
  } catch (e) { status(`The fan was refused: ${e.message}`); }
}

async function clearComparisons() {
  try { await applyChange({ companions: null, vary: null }, true); } catch (e) { status(e.message); }
}

// ---- Views and layers.
function buildViewControls(force = false) {
  const shown = ui.views.filter((v) => v.surfaces.includes(surfaceKind()));  // the server's table, in its order
  const kinds = shown.map((v) => v.name);
  const select = $("view");
  select.textContent = "";
  for (const v of shown) {
    const option = new Option(v.title, v.name);
    option.title = v.description;
    select.add(option);
  }
  if (!kinds.includes(ui.view.kind)) ui.view.kind = kinds[0];
  select.value = ui.view.kind;
  const layers = $("layers");
  if (force) layers.textContent = "";
  if (!layers.childElementCount)
    for (const layer of ["surface", "grid", "body", "frame", "trail", "hud", "actions"]) {
      const label = document.createElement("label");
      label.title = { surface: "the shaded surface", grid: "its geodesic grid", body: "the body's ellipse", frame: "the frame arrows",
                      trail: "the path so far", hud: "the text overlay and the legend of the bodies",
                      actions: "the action variables and their frequencies, in the text overlay" }[layer];
      label.innerHTML = `<input type="checkbox" name="layer-${layer}" ${ui.view.layers.has(layer) ? "checked" : ""}> ${layer}`;
      label.firstChild.addEventListener("change", (e) => {
        e.target.checked ? ui.view.layers.add(layer) : ui.view.layers.delete(layer);
        if (layer === "hud") ui.view.hudChosen = true;
        refreshFrame();
      });
      layers.append(label);
    }
}

const is3d = () => Boolean(ui.views.find((v) => v.name === ui.view.kind)?.three_d);
function orbit(dYaw, dPitch) {
  if (!is3d()) { status("Orbiting works in the 3-D views; pick one under View."); return; }
  ui.view.yaw = (ui.view.yaw ?? 0.7) + dYaw;
  ui.view.pitch = Math.max(-1.5, Math.min(1.5, (ui.view.pitch ?? 0.45) + dPitch));
  refreshFrame();
}

function zoom(factor) {
  if (is3d()) ui.view.distance = Math.max(1.2, Math.min(100, (ui.view.distance ?? 3.4) / factor));
  else ui.view.scale = Math.max(0.02, Math.min(10, ui.view.scale * factor));
  refreshFrame();
  const scale = document.getElementById("phys-scale");
  if (scale) scale.value = Number(ui.view.scale.toPrecision(6));
}

// ---- Gallery in teaching order: the default first, then spin against geodesic, then
// deformation, then the rest (in the server's order).
const teachingOrder = ["spinning_rigid_sphere", "geodesic_rigid_sphere", "spin_vs_geodesic_sphere", "spin_vs_geodesic_pseudosphere",
                       "spin_fan_sphere", "opposite_spins_sphere", "spinning_rigid_pseudosphere", "geodesic_rigid_pseudosphere",
                       "spinning_rigid_plane", "breathing_ellipse_sphere", "deforming_spin_pseudosphere",
                       "deforming_spin_vs_geodesic_pseudosphere"];
const rank = (name) => { const i = teachingOrder.indexOf(name); return i < 0 ? teachingOrder.length : i; };
const label = (name) => name.replaceAll("_", " ");

function markGallery() {
  document.querySelectorAll(".preset").forEach((b) => {
    const active = b.dataset.name === ui.preset;
    b.classList.toggle("active", active);
    b.setAttribute("aria-pressed", String(active));
    b.classList.toggle("modified", active && Boolean(ui.modified));
    b.querySelector(".mark").textContent = active ? (ui.modified ? "modified" : "selected") : "";
  });
}

function showExplanation() {
  const preset = ui.presets.find((p) => p.name === ui.preset);
  const sameSurface = preset && surfaceKind(preset.scene.surface ?? {}) === surfaceKind();
  // A switch of surface makes the preset's text wrong: say what is shown instead.
  if (preset && !sameSurface) { ui.preset = null; markGallery(); }
  $("explanation").textContent = preset && sameSurface ? preset.description
    : `Your own scene on the ${{ sphere: "sphere", pseudosphere: "hyperbolic plane", plane: "flat plane" }[surfaceKind()]}.`;
}

async function buildGallery() {
  const gallery = $("gallery");
  const presets = [...ui.presets].sort((a, b) => rank(a.name) - rank(b.name));
  for (const preset of presets) {
    const button = document.createElement("button");
    button.type = "button";
    button.className = "preset";
    button.dataset.name = preset.name;
    button.title = preset.description;
    button.innerHTML = `<img alt=""><b></b><span class="mark"></span><small></small>`;
    button.querySelector("b").textContent = label(preset.name);
    button.querySelector("small").textContent = preset.description;
    button.addEventListener("click", () => openScene(preset.scene, { preset: preset.name }).catch((e) => status(e.message)));
    gallery.append(button);
  }
  markGallery();
  // Thumbnails rendered by the server, one short-lived session at a time, kept for the tab.
  for (const preset of presets) {
    const img = gallery.querySelector(`[data-name="${preset.name}"] img`);
    const key = `spinfold.thumb.${preset.name}`;
    try {
      let blob;
      const cached = sessionStorage.getItem(key);
      if (cached) {
        blob = new Blob([Uint8Array.from(atob(cached), (c) => c.charCodeAt(0))], { type: "image/png" });
      } else {
        const s = await request("POST", "/sessions", preset.scene);
        thumbnailSession = s.id;
        await request("POST", `/sessions/${s.id}/advance`, { until: 2 });
        const res = await fetch(`${api}/sessions/${s.id}/frame.png?width=160&height=120&layers=surface,grid,body,trail`);
        blob = await res.blob();
        await request("DELETE", `/sessions/${s.id}`);
        thumbnailSession = null;
        const bytes = new Uint8Array(await blob.arrayBuffer());
        try { sessionStorage.setItem(key, btoa(String.fromCharCode(...bytes))); } catch (e) { /* full: fetch again next time */ }
      }
      img.src = URL.createObjectURL(blob);
    } catch (e) { /* a missing thumbnail is not worth an error */ }
  }
}

// ---- Share: the URL carries the scene, its timeline, the time and the view; opening it rebuilds
// the same run (the same state and picture, trail included).
function shareUrl() {
  const params = new URLSearchParams({ scene: JSON.stringify(ui.scene), timeline: JSON.stringify(ui.timeline),
                                       t: String(ui.t), view: ui.view.kind,
                                       layers: [...ui.view.layers].join(",") });
  return `${location.origin}${location.pathname}${location.search}#${params}`;
}

function fromHash() {
  if (!location.hash) return null;
  const params = new URLSearchParams(location.hash.slice(1));
  if (!params.has("scene")) return null;
  try {
    const shared = { scene: JSON.parse(params.get("scene")), until: Number(params.get("t") || 0),
                     timeline: JSON.parse(params.get("timeline") || "[]") };
    ui.view.kind = params.get("view");
    if (params.has("layers")) ui.view.layers = new Set(params.get("layers").split(",").filter(Boolean));
    return shared;
  } catch (e) {
    status("The share link is damaged; opening the default scene.");
    return null;
  }
}

// ---- Presentation: full screen, themes.
function toggleFullscreen() {
  if (document.fullscreenElement) document.exitFullscreen().catch(() => {});
  else $("frame-box").requestFullscreen().then(() => $("frame").focus()).catch((e) => status(`Full screen refused: ${e.message}`));
}

function setTheme(dark) {
  document.documentElement.dataset.theme = dark ? "dark" : "light";
  $("theme").setAttribute("aria-pressed", String(dark));
  $("theme").textContent = dark ? "Light theme" : "Dark theme";
  try { localStorage.setItem("spinfold.theme", dark ? "dark" : "light"); } catch (e) { /* not kept */ }
}

// ---- Keyboard: Space play/pause, → step, R reset, F full screen, G geodesic companion, arrows
// orbit (on the focused picture; Shift+arrows anywhere), + and − zoom. Typing in a field is left
// alone; Space on another button presses that button.
function onKey(e) {
  if (e.ctrlKey || e.metaKey || e.altKey || !ui.id) return;
  const target = e.target;
  const tag = target.tagName;
  const typing = (tag === "INPUT" && target.type !== "range" && target.type !== "checkbox") || tag === "SELECT" || tag === "TEXTAREA";
  if (typing) return;
  const onFrame = target === $("frame");
  const ownButton = target.closest?.("#toolbar") || target === document.body || onFrame || target.type === "range";
  const key = e.key;
  let handled = true;
  if (key === " " && ownButton && target.type !== "range") (ui.playing ? pause() : play()).catch((err) => status(err.message));
  else if (key === " ") handled = false;
  else if ((onFrame || e.shiftKey) && key.startsWith("Arrow")) {
    const d = 0.12;
    orbit(key === "ArrowLeft" ? d : key === "ArrowRight" ? -d : 0, key === "ArrowUp" ? d : key === "ArrowDown" ? -d : 0);
  } else if (key === "ArrowRight" && target.type !== "range") step().catch((err) => status(err.message));
  else if (key === "r" || key === "R") reset().catch((err) => status(err.message));
  else if (key === "f" || key === "F") toggleFullscreen();
  else if (key === "g" || key === "G") toggleGeodesic();
  else if (key === "+" || key === "=") zoom(1.15);
  else if (key === "-" || key === "_" || key === "−") zoom(1 / 1.15);
  else handled = false;
  if (handled) e.preventDefault();
}

// ---- Wiring.
function wire() {
  $("play").onclick = () => play();
  $("pause").onclick = () => pause().catch((e) => status(e.message));
  $("step").onclick = () => step().catch((e) => status(e.message));
  $("reset").onclick = () => reset().catch((e) => status(e.message));
  $("speed").oninput = () => ($("speed-out").textContent = $("speed").value);
  // A new speed applies at once while playing; while paused it waits for Play.
  $("speed").onchange = () => {
    ui.rate = Number($("speed").value);
    if (ui.playing) play();
    else setPlaying(false);
    saveSession(true);
  };
  $("view").onchange = () => {
    ui.view.kind = $("view").value;
    ui.view.yaw = ui.view.pitch = ui.view.distance = null;
    refreshFrame();
    buildPhysical();  // the body size's unit follows the view
  };
  $("geodesic").onclick = () => toggleGeodesic();
  $("fan").onclick = () => addFan();
  $("fan-clear").onclick = () => clearComparisons();
  $("fullscreen").onclick = () => toggleFullscreen();
  $("theme").onclick = () => setTheme(document.documentElement.dataset.theme !== "dark");
  $("busy-retry").onclick = () => busyRetry && busyRetry();
  for (const id of ["png-width", "png-height"]) $(id).onchange = updateExports;
  $("share").onclick = async () => {
    const url = shareUrl();
    history.replaceState(null, "", url);
    try { await navigator.clipboard.writeText(url); } catch (e) { /* the address bar has it */ }
    status("Share link copied (and in the address bar).");
  };
  document.addEventListener("keydown", onKey);
  document.addEventListener("fullscreenchange", () => document.body.classList.toggle("fullscreen", Boolean(document.fullscreenElement)));
  addEventListener("pagehide", leave);
  addEventListener("pageshow", (e) => { if (e.persisted && ui.id) recover().catch((err) => status(err.message)); });
  // Orbit the camera by dragging (3-D views).
  let drag = null;
  $("frame").addEventListener("pointerdown", (e) => {
    $("frame").focus();
    if (!is3d()) return;
    drag = { x: e.clientX, y: e.clientY, yaw: ui.view.yaw ?? 0.7, pitch: ui.view.pitch ?? 0.45 };
    $("frame").setPointerCapture(e.pointerId);
  });
  $("frame").addEventListener("pointermove", (e) => {
    if (!drag) return;
    ui.view.yaw = drag.yaw - (e.clientX - drag.x) * 0.01;
    ui.view.pitch = Math.max(-1.5, Math.min(1.5, drag.pitch + (e.clientY - drag.y) * 0.01));
    refreshFrame();
  });
  $("frame").addEventListener("pointerup", () => (drag = null));
}

// The tab's icon, made here as a blob: URL: the page's Content-Security-Policy allows images from
// 'self' and blob: only (a data: icon is refused), and without an icon the browser would ask
// for /favicon.ico, which the server does not have.
function setIcon() {
  const svg = `<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 32 32"><circle cx="16" cy="16" r="14" fill="#233"/>` +
              `<ellipse cx="16" cy="16" rx="9" ry="5" fill="#f90" transform="rotate(-30 16 16)"/></svg>`;
  const link = document.createElement("link");
  link.rel = "icon";
  link.href = URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" }));
  document.head.append(link);
}

async function main() {
  setIcon();
  if (embed) document.body.classList.add("embed");
  let dark = matchMedia("(prefers-color-scheme: dark)").matches;
  try { dark = (localStorage.getItem("spinfold.theme") ?? (dark ? "dark" : "light")) === "dark"; } catch (e) { /* default */ }
  setTheme(dark);
  ui.live = new LiveView($("frame"));
  ui.live.onGone = () => checkSession();
  [ui.schema, ui.presets, ui.views] = await withRetry("Loading", () =>
    Promise.all([request("GET", "/schema"), request("GET", "/scenes"), request("GET", "/views")]));
  wire();
  // Recording (web/record.js): the Record panel, given the session, its time and the view.
  setupRecording($("record-panel"), { session: () => ui.id, time: () => ui.t, view: viewParams });
  // "Which integrator for this scene?" (web/workprecision.js): its "Use …" is a change like any other.
  setupWorkPrecision($("wp-panel"), { session: () => ui.id, apply: (patch) => applyChange(patch, true) });
  makePlots();
  fitFrameToWindow();
  measureFrame();
  watchFrameSize();
  await firstSession();
  document.body.dataset.ready = "true";
  if (!embed) buildGallery();
}

main().catch((e) => status(`error: ${e.message}`));
