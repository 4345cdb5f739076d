// @ts-check
// The keyboard and the pointer on the picture: Space play/pause, → step, R reset, F full screen,
// G geodesic companion, arrows orbit (on the focused picture; Shift+arrows anywhere), + and − zoom,
// V resets the view (R too), [ and ] change the view, N and P the lesson, comma and period look
// back while paused, ? lists them all, dragging orbits (3-D views). Typing in a field is
// left alone; Space on another button presses it.
import { toggleGeodesic } from "./comparisons.js";
import { $, el } from "./dom.js";
import { openPreset } from "./gallery.js";
import { camera, is3d, orbit, resetView, toggleFollow, zoom } from "./frame.js";
import { toggleFullscreen } from "./presentation.js";
import { say } from "./readout.js";
import { nudgeScrub } from "./scrub.js";
import { pause, play, reset, step } from "./session.js";
import { store } from "./state.js";

/**
 * Every key the page answers to, as the "?" overlay lists them; onKey below acts on the same keys.
 * @type {{keys: string[], does: string}[]}
 */
export const shortcuts = [
  { keys: ["Space"], does: "Play or pause" },
  { keys: ["→"], does: "Step: advance 10 steps (on the focused picture the arrows orbit instead)" },
  { keys: ["R"], does: "Reset: back to t = 0, the view aimed afresh" },
  { keys: ["V"], does: "Reset the view: aim the camera at the bodies again, undo the zoom" },
  { keys: ["C"], does: "Follow the body with the camera, or let it stay put (3-D views)" },
  { keys: ["+", "−"], does: "Zoom in, zoom out" },
  { keys: ["Shift + arrows"], does: "Orbit the camera (3-D views; plain arrows on the focused picture)" },
  { keys: ["G"], does: "Add or remove the geodesic companion" },
  { keys: ["[", "]"], does: "The previous or the next view of this surface" },
  { keys: ["N", "P"], does: "The next or the previous lesson (the gallery's order)" },
  { keys: [",", "."], does: "Look back: an earlier or a later moment of the paused run" },
  {
    keys: ["Tab", "arrows"],
    does: "While paused: to the body's ring or its arrow's tip, then move it (Shift: finer); Enter sends at once, Esc puts it back",
  },
  { keys: ["F"], does: "Full screen" },
  { keys: ["?"], does: "This list; Esc closes it" },
];

const orbitStep = 0.12; // radians per arrow key
const dragRate = 0.01; // radians per CSS pixel dragged

// The keys' actions run one after another: → pressed while R's reset is on its way must not send
// its step before the reset's answer is in (the answers could come back in the other order, and the
// late reset would put t = 0 back over the step's state).
/** @type {Promise<unknown>} */
let queue = Promise.resolve();
/** @param {() => Promise<unknown>} action */
const run = (action) => (queue = queue.then(action).catch((e) => say(e.message)));

/** Orbits, or says where orbiting works. @param {number} dYaw @param {number} dPitch */
function orbitOrSay(dYaw, dPitch) {
  if (is3d(store.get())) orbit({ dYaw, dPitch });
  else say("Orbiting works in the 3-D views; pick one under View.");
}

/** @param {KeyboardEvent} e */
function onKey(e) {
  if (e.ctrlKey || e.metaKey || e.altKey || !store.get().id) return;
  if (/** @type {HTMLDialogElement} */ ($("shortcuts")).open) return; // a modal list: its own keys only
  const target = /** @type {HTMLInputElement} */ (e.target);
  const tag = target.tagName;
  const typing =
    (tag === "INPUT" && target.type !== "range" && target.type !== "checkbox") ||
    tag === "SELECT" ||
    tag === "TEXTAREA";
  if (typing) return;
  const onFrame = target === $("frame");
  const ownButton = target.closest?.("#toolbar") || target === document.body || onFrame || target.type === "range";
  const key = e.key;
  let handled = true;
  if (key === " " && ownButton && target.type !== "range") run(store.get().playing ? pause : play);
  else if (key === " ") handled = false;
  else if ((onFrame || e.shiftKey) && key.startsWith("Arrow")) {
    const d = orbitStep;
    orbitOrSay(
      key === "ArrowLeft" ? d : key === "ArrowRight" ? -d : 0,
      key === "ArrowUp" ? d : key === "ArrowDown" ? -d : 0,
    );
  } else if (key === "ArrowRight" && target.type !== "range") run(step);
  else if (key === "r" || key === "R") {
    resetView();
    run(reset);
  } else if (key === "v" || key === "V") resetView();
  else if (key === "f" || key === "F") toggleFullscreen();
  else if (key === "c" || key === "C") toggleFollow();
  else if (key === "?") showShortcuts();
  else if (key === "g" || key === "G") toggleGeodesic();
  else if (key === "[" || key === "]") cycleView(key === "]" ? 1 : -1);
  else if (key === "n" || key === "N" || key === "p" || key === "P") nextLesson(key === "n" || key === "N" ? 1 : -1);
  else if (key === "," || key === ".") handled = nudgeScrub(key === "," ? -1 : 1);
  else if (key === "+" || key === "=") zoom(1.15);
  else if (key === "-" || key === "_" || key === "−") zoom(1 / 1.15);
  else handled = false;
  if (handled) e.preventDefault();
}

/** The view `d` places on in the View menu's offered views, going round. @param {number} d */
function cycleView(d) {
  const select = /** @type {HTMLSelectElement} */ ($("view"));
  const offered = [...select.options].filter((o) => !o.disabled);
  if (offered.length < 2) return say("This surface has one view.");
  const i = offered.findIndex((o) => o.value === select.value);
  select.value = offered[(i + d + offered.length) % offered.length].value;
  select.dispatchEvent(new Event("change"));
  say(`View: ${select.selectedOptions[0].textContent}.`);
}

/** The preset `d` places on in the lesson sequence (your own scene: the first). @param {number} d */
function nextLesson(d) {
  const { presets, preset } = store.get();
  const i = presets.findIndex((p) => p.name === preset);
  const to = i < 0 ? presets[0] : presets[i + d];
  if (to) openPreset(to.name);
  else say(d > 0 ? "This is the last lesson." : "This is the first lesson.");
}

/** Opens the list of shortcuts (a modal dialog: Esc or its button closes it, focus comes back). */
function showShortcuts() {
  const dialog = /** @type {HTMLDialogElement} */ ($("shortcuts"));
  if (!dialog.open) dialog.showModal();
}

/** Fills the dialog's table from `shortcuts`. */
function buildShortcuts() {
  const rows = $("shortcuts-rows");
  for (const { keys, does } of shortcuts) {
    const th = el("th", { scope: "row" });
    keys.forEach((k, i) => th.append(...(i ? [" ", el("kbd", { text: k })] : [el("kbd", { text: k })])));
    rows.append(el("tr", {}, th, el("td", { text: does })));
  }
  $("shortcuts-open").onclick = showShortcuts;
  $("shortcuts-close").onclick = () => /** @type {HTMLDialogElement} */ ($("shortcuts")).close();
}

export function setupKeys() {
  buildShortcuts();
  document.addEventListener("keydown", onKey);
  const frame = $("frame");
  /** @type {{x: number, y: number, yaw: number, pitch: number} | null} */
  let drag = null;
  frame.addEventListener("pointerdown", (/** @type {PointerEvent} */ e) => {
    frame.focus();
    if (!is3d(store.get())) return;
    drag = { x: e.clientX, y: e.clientY, ...camera(store.get()) };
    frame.setPointerCapture(e.pointerId);
  });
  frame.addEventListener("pointermove", (/** @type {PointerEvent} */ e) => {
    if (!drag) return;
    orbit({ yaw: drag.yaw - (e.clientX - drag.x) * dragRate, pitch: drag.pitch + (e.clientY - drag.y) * dragRate });
  });
  frame.addEventListener("pointerup", () => (drag = null));
}
