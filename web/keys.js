// @ts-check
// The keyboard and the pointer on the picture: Space play/pause, → step, R reset, F full screen,
// G geodesic companion, arrows orbit (on the focused picture; Shift+arrows anywhere), + and − zoom,
// V resets the view (R too), dragging orbits (3-D views). Typing in a field is left alone; Space on another button presses it.
import { toggleGeodesic } from "./comparisons.js";
import { $ } from "./dom.js";
import { camera, is3d, orbit, resetView, zoom } from "./frame.js";
import { toggleFullscreen } from "./presentation.js";
import { say } from "./readout.js";
import { pause, play, reset, step } from "./session.js";
import { store } from "./state.js";

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
  else if (key === "g" || key === "G") toggleGeodesic();
  else if (key === "+" || key === "=") zoom(1.15);
  else if (key === "-" || key === "_" || key === "−") zoom(1 / 1.15);
  else handled = false;
  if (handled) e.preventDefault();
}

export function setupKeys() {
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
