// @ts-check
// The picture (the live frame stream): one live stream per page (live.js), opened on the session and steered whenever the
// view, camera or size in the store change (one subscriber, not a refresh at every call site); the
// frame's size follows its shown size; the export links follow the same view.
import { api } from "./api.js";
import { $ } from "./dom.js";
import { LiveView } from "./live.js";
import { nextPace, pacedSize } from "./pace.js";
import { initialState, store, withView } from "./state.js";
import { clampTo, toApi } from "./viewparams.js";

/** @typedef {import("./state.js").AppState} AppState */

/**
 * The frame's query parameters for a state: size, view, layers, scale, and the camera when the
 * user moved it (in the route's units).
 * @param {AppState} state
 * @returns {Record<string, string | number>}
 */
export function viewQuery(state) {
  const { view, size, viewParameters: controls } = state;
  /** @type {Record<string, string | number>} */
  const q = {
    width: size.width,
    height: size.height,
    view: view.kind ?? "",
    layers: view.layers.join(","),
    scale: view.scale,
  };
  if (view.yaw !== null && view.pitch !== null)
    Object.assign(q, {
      yaw: toApi(controls, "yaw", view.yaw).toFixed(4),
      pitch: toApi(controls, "pitch", view.pitch).toFixed(4),
    });
  if (view.distance !== null) q.distance = view.distance.toFixed(3);
  if (view.motion !== "steady") q.motion = view.motion; // the server's default otherwise
  return q;
}

/**
 * A frame's PNG address.
 * @param {AppState} state
 * @param {number} width
 * @param {number} height
 */
export function frameUrl(state, width = state.size.width, height = state.size.height) {
  return `${api}/sessions/${state.id}/frame.png?${new URLSearchParams(/** @type {any} */ ({ ...viewQuery(state), width, height }))}`;
}

/**
 * The live stream's query: the frame's, at the paced size while playing (pace.js), saying the width
 * it is shown at in CSS pixels wherever that is not the width drawn (a paced picture, a screen of
 * two device pixels to one), so that the server sizes its text for what the eye sees: the same on
 * the screen as unpaced, and a phone's picture (374 px shown, 748 drawn) the compact overlay
 * instead of a legend 6.5 px high.
 * @param {AppState} state
 */
function liveQuery(state) {
  const pace = state.playing ? state.pace : 1;
  const size = pacedSize(state.size, pace);
  // Always said: a steer merges into the stream's parameters, so one left out would stay as it was.
  return { ...viewQuery(state), ...size, shown: state.size.shown ?? state.size.width };
}

/** @type {LiveView} */
let live;

// Painted frames per second, measured each second while playing, set the pace: two seconds at a
// size decide the next (a change of size starts a new measurement). The address's ?pace=full keeps
// the picture full size (a screen recording, a measurement of the unpaced page).
function watchPace() {
  if (new URLSearchParams(location.search).get("pace") === "full") return;
  /** @type {number[]} */
  let rates = [];
  let painted = live.stats.painted;
  let asked = "";
  setInterval(() => {
    const s = store.get();
    const now = live.stats.painted;
    const key = JSON.stringify(liveQuery(s));
    if (!s.playing || document.hidden || key !== asked) rates = [];
    else rates.push(now - painted);
    painted = now;
    asked = key;
    if (rates.length < 2) return;
    const next = nextPace(s.pace, (rates[0] + rates[1]) / 2);
    rates = [];
    if (next !== s.pace) store.update({ pace: next });
  }, 1000);
}

/**
 * The live view on #frame, following the store; `onGone` when the server no longer knows the session.
 * @param {() => void} onGone
 */
export function setupFrame(onGone) {
  live = new LiveView($("frame"));
  live.onPaint = noteCamera;
  live.onGone = onGone;
  let steered = "";
  store.subscribe((s, b) => {
    if (!s.id || s.phase !== "live") return;
    const params = liveQuery(s);
    const key = JSON.stringify(params);
    if (s.id !== b.id || b.phase !== "live") {
      measureFrame();
      live.open(s.id, liveQuery(store.get()));
      steered = JSON.stringify(liveQuery(store.get()));
    } else if (key !== steered) {
      steered = key;
      live.steer(s.view.yaw === null ? { ...params, aim: "body" } : params);
    }
    renderExports(s);
  });
  fitFrameToWindow();
  measureFrame();
  watchFrameSize();
  watchPace();
}

export const closeFrame = () => live?.close();

/**
 * Shows a picture in place of the live one (the scrubber's), until showLive().
 * @param {ImageBitmap} bitmap
 * @param {Record<string, string>} info the canvas's dataset for it (t, kind, …)
 */
export const showPicture = (bitmap, info) => live?.hold(bitmap, info);
/** The live picture again. */
export const showLive = () => live?.release();

/** The export links: the frame as shown, at the size asked, the state and the trajectory. */
export function renderExports(state = store.get()) {
  if (!state.id) return;
  const pixels = (/** @type {string} */ id, /** @type {number} */ fallback) => {
    const input = $(id);
    // The input's own min and max (the frame route's width and height limits).
    const v = Math.round(Number(input.value) || fallback);
    return Math.max(Number(input.min), Math.min(Number(input.max), v));
  };
  $("export-png").href = frameUrl(state);
  $("export-png-sized").href = frameUrl(state, pixels("png-width", 1920), pixels("png-height", 1080));
  $("export-state").href = `${api}/sessions/${state.id}`;
  $("export-csv").href = `${api}/sessions/${state.id}/trajectory?format=csv`;
}

// The frame is asked at the size it is shown × devicePixelRatio, at most 1920×1080 (the aspect
// kept), and again whenever the shown size changes (window, full screen, phone rotation).
function measureFrame() {
  const box = $("frame").getBoundingClientRect();
  if (box.width < 8 || box.height < 8) return;
  const dpr = window.devicePixelRatio || 1;
  let width = Math.round(box.width * dpr);
  let height = Math.round(box.height * dpr);
  const shrink = Math.min(1, 1920 / width, 1080 / height);
  width = Math.max(16, Math.round(width * shrink));
  height = Math.max(16, Math.round(height * shrink));
  defaultHud(box.width, box.height);
  const shown = Math.round(box.width);
  const { size } = store.get();
  if (width !== size.width || height !== size.height || shown !== size.shown)
    store.update({ size: { width, height, shown } });
}

// A frame shown smaller than this (CSS pixels; a phone, upright or on its side) has no room for
// legible overlay text: it would cover a third of the picture or be a few pixels high, and the
// readout below the frame says the same. Off by default there, on elsewhere; once the teacher
// ticks or unticks "hud", theirs is the choice.
const smallFrame = { width: 520, height: 360 };
/** Whether the frame as shown has room for the overlay's text (not a phone's). */
export function roomForHud() {
  const box = $("frame").getBoundingClientRect();
  return box.width >= smallFrame.width && box.height >= smallFrame.height;
}

/** @param {number} shownWidth @param {number} shownHeight */
function defaultHud(shownWidth, shownHeight) {
  const { view } = store.get();
  if (view.hudChosen) return;
  const want = shownWidth >= smallFrame.width && shownHeight >= smallFrame.height;
  if (want === view.layers.includes("hud")) return;
  const layers = want ? [...view.layers, "hud"] : view.layers.filter((l) => l !== "hud");
  store.update((s) => withView(s, { layers }));
}

// The frame and the bars below it fit the window at load: the frame is never taller than the room
// between its top and the window's bottom less the playback bar and, on a screen at least 700 px
// tall (a laptop, a projector), the View row too (at least 240 px).
// While the run plays the bars are taken as they were when it last was not: a toolbar that wraps
// because its badge says more ("playing at 1×") must not change the picture's size under the
// student (it went from 520 to 485 px high at Play).
/** @type {number | null} */
let barsWhenStill = null;
function fitFrameToWindow() {
  const top = $("frame-box").getBoundingClientRect().top + window.scrollY;
  const measured = $("toolbar").offsetHeight + (window.innerHeight >= 700 ? $("viewbar").offsetHeight : 0);
  if (!store.get().playing || barsWhenStill === null) barsWhenStill = measured;
  const bars = barsWhenStill ?? measured;
  const room = Math.max(240, window.innerHeight - top - bars - 20);
  document.documentElement.style.setProperty("--frame-room", `${Math.round(room)}px`);
}

function watchFrameSize() {
  /** @type {ReturnType<typeof setTimeout> | undefined} */
  let timer;
  new ResizeObserver(() => {
    clearTimeout(timer);
    timer = setTimeout(measureFrame, 120);
  }).observe($("frame"));
  const refit = new ResizeObserver(fitFrameToWindow);
  for (const id of ["gallery", "toolbar", "busy"]) refit.observe($(id));
  refit.observe(/** @type {Element} */ (document.querySelector("header")));
  addEventListener("resize", fitFrameToWindow);
}

// ---- The camera: orbit (keys, drag) and zoom, within the route's ranges.
// Where an orbit starts when the server aimed the camera: the camera of the last 3-D frame painted
// (its X-Spinfold-Frame fields), so that the first turn starts from the picture on the screen.
// Before any, the server's default camera.
const aimed = { yaw: 0.7, pitch: 0.45, distance: 3.4 };

/** @param {import("./live.js").FrameInfo} info */
function noteCamera(info) {
  if (info.yaw === undefined) return;
  Object.assign(aimed, { yaw: Number(info.yaw), pitch: Number(info.pitch), distance: Number(info.distance) });
}

/** @param {AppState} state */
export const is3d = (state) => Boolean(state.views.find((v) => v.name === state.view.kind)?.three_d);

/**
 * The camera turned by (dYaw, dPitch) radians, or set to yaw, pitch (a drag).
 * @param {{dYaw?: number, dPitch?: number, yaw?: number, pitch?: number}} turn
 */
export function orbit({ dYaw = 0, dPitch = 0, yaw, pitch }) {
  store.update((s) => {
    const controls = s.viewParameters;
    return withView(s, {
      yaw: clampTo(controls, "yaw", (yaw ?? s.view.yaw ?? aimed.yaw) + dYaw),
      pitch: clampTo(controls, "pitch", (pitch ?? s.view.pitch ?? aimed.pitch) + dPitch),
    });
  });
}

/** The camera where it is now (or where the server aims it). @param {AppState} state */
export const camera = (state) => ({ yaw: state.view.yaw ?? aimed.yaw, pitch: state.view.pitch ?? aimed.pitch });

/** The camera as the server aims it (at the body, clear of the HUD) and the body at its starting size. */
export const freshCamera = () => ({ yaw: null, pitch: null, distance: null, scale: initialState().view.scale });

/** Undoes orbiting and zooming: Reset view (V), Reset (R) and a preset's opening do it. */
export function resetView() {
  store.update((s) => withView(s, freshCamera()));
}

/** Follow the body (C): the 3-D camera keeps it centred while playing, or stays put (steady). */
export function toggleFollow() {
  store.update((s) => withView(s, { motion: s.view.motion === "follow" ? "steady" : "follow" }));
}

/** Closer by `factor` in the 3-D views; a larger body in the 2-D ones. @param {number} factor */
export function zoom(factor) {
  store.update((s) =>
    is3d(s)
      ? withView(s, { distance: clampTo(s.viewParameters, "distance", (s.view.distance ?? aimed.distance) / factor) })
      : withView(s, { scale: clampTo(s.viewParameters, "scale", s.view.scale * factor) }),
  );
}
