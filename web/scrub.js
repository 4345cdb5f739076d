// @ts-check
// The scrubber: while the run is paused, a slider along its time from 0 to now shows the picture of
// any earlier moment (frame.jpg?at=T: the server replays the run to T). One picture is asked for at
// a time and the newest position wins; at the slider's end, or once the run moves, the live picture
// is back.
import { api } from "./api.js";
import { $ } from "./dom.js";
import { showLive, showPicture, viewQuery } from "./frame.js";
import { mount, store } from "./state.js";

/** @typedef {import("./state.js").AppState} AppState */

let asking = false;
/** @type {number | null} the position not yet shown */
let wanted = null;

/** "t = 1.25 of 4.5": the time shown, to the slider's resolution. @param {number} at @param {number} now */
export const scrubLabel = (at, now) => `t = ${Number(at.toPrecision(4))} of ${Number(now.toPrecision(4))}`;

/** Shows the newest wanted position, one request at a time. */
async function showWanted() {
  if (asking || wanted === null) return;
  const s = store.get();
  const at = wanted;
  wanted = null;
  if (!s.id || s.playing) return;
  if (at >= s.t) {
    delete $("frame").dataset.scrub;
    showLive();
    return;
  }
  asking = true;
  try {
    const q = new URLSearchParams(/** @type {any} */ ({ ...viewQuery(s), at: String(at), quality: "85" }));
    const res = await fetch(`${api}/sessions/${s.id}/frame.jpg?${q}`);
    if (res.ok && store.get().id === s.id && !store.get().playing && store.get().t === s.t) {
      const bitmap = await createImageBitmap(await res.blob());
      showPicture(bitmap, { t: String(at), kind: "scrub" });
      $("frame").dataset.scrub = String(at);
    }
  } finally {
    asking = false;
    showWanted();
  }
}

/** @param {AppState} s @param {AppState} b */
function renderScrub(s, b) {
  const shown = Boolean(s.id) && s.phase === "live" && !s.playing && s.t > 0;
  const box = $("scrub-box");
  const slider = /** @type {HTMLInputElement} */ ($("scrub"));
  if (shown !== !box.hidden) box.hidden = !shown;
  if (!shown || s.t !== b.t || s.id !== b.id) {
    // The run moved (or the slider went away): its end is now, and the live picture is shown.
    slider.max = String(s.t);
    slider.value = String(s.t);
    $("scrub-out").textContent = scrubLabel(s.t, s.t);
    if ($("frame").dataset.scrub !== undefined) {
      delete $("frame").dataset.scrub;
      wanted = null;
      showLive();
    }
  }
}

/** Shows the slider's position. */
function scrubbed() {
  const slider = /** @type {HTMLInputElement} */ ($("scrub"));
  const now = store.get().t;
  const at = Math.min(Number(slider.value), now);
  $("scrub-out").textContent = scrubLabel(at, now);
  wanted = at;
  showWanted();
}

/**
 * The keys' look back: the slider moved by a fiftieth of the run, back (−1) or on (+1); false when
 * there is no slider (the run plays, or has not begun).
 * @param {number} direction
 */
export function nudgeScrub(direction) {
  if ($("scrub-box").hidden) return false;
  const slider = /** @type {HTMLInputElement} */ ($("scrub"));
  const now = store.get().t;
  slider.value = String(Math.max(0, Math.min(now, Number(slider.value) + (direction * now) / 50)));
  scrubbed();
  return true;
}

export function setupScrub() {
  $("scrub").oninput = scrubbed;
  mount(renderScrub);
}
