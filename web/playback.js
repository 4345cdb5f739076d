// @ts-check
// The playback bar: play, pause, step, reset and the speed; its state badge and the picture's
// play mark follow the store (the session's "playing" and "rate", and a run that stopped).
import { $ } from "./dom.js";
import { resetView } from "./frame.js";
import { pacedSize } from "./pace.js";
import { say } from "./readout.js";
import { pause, play, reset, step } from "./session.js";
import { mount, store } from "./state.js";

/** @param {import("./state.js").AppState} s @param {import("./state.js").AppState} b */
export function renderPlayback(s, b) {
  const status = s.sample?.status;
  if (
    s.playing === b.playing &&
    s.rate === b.rate &&
    status === b.sample?.status &&
    b.phase === s.phase &&
    s.pace === b.pace &&
    s.size === b.size
  )
    return;
  document.body.dataset.playing = String(s.playing);
  $("play").setAttribute("aria-pressed", String(s.playing));
  $("pause").setAttribute("aria-pressed", String(!s.playing));
  const stopped = Boolean(s.sample) && status !== "ok";
  const state = stopped ? "stopped" : s.playing ? "playing" : "paused";
  // A picture asked smaller for smooth motion (pace.js) says its size, on the picture: in the badge
  // the longer text wrapped the toolbar and changed the picture's size while playing.
  const paced =
    s.playing && s.pace < 1 ? ` picture ${Object.values(pacedSize(s.size, s.pace)).join("×")} for speed` : "";
  $("state-badge").textContent = stopped ? `stopped: ${status}` : s.playing ? `playing at ${s.rate}×` : "paused";
  $("state-badge").title = $("state-badge").textContent ?? "";
  $("state-badge").dataset.pace = String(s.playing ? s.pace : 1);
  $("state-badge").dataset.state = state;
  $("play-state").textContent = stopped ? "■ stopped" : s.playing ? `▶${paced}` : "❚❚ paused";
  $("play-state").dataset.state = state;
  $("frame-play").textContent = s.playing ? "❚❚ Pause" : "▶ Play";
  if (s.rate !== Number($("speed").value) && document.activeElement !== $("speed")) {
    $("speed").value = s.rate;
    $("speed-out").textContent = s.rate;
  }
}

/** @param {() => Promise<unknown>} action */
const reported = (action) => () => action().catch((e) => say(e.message));

export function setupPlayback() {
  mount(renderPlayback);
  $("play").onclick = () => {
    store.update({ rate: Number($("speed").value) });
    play();
  };
  $("pause").onclick = reported(pause);
  $("frame-play").onclick = () => (store.get().playing ? reported(pause)() : $("play").click());
  $("step").onclick = reported(step);
  $("reset").onclick = () => {
    resetView();
    return reported(reset)();
  };
  $("reset-view").onclick = resetView;
  $("speed").oninput = () => ($("speed-out").textContent = $("speed").value);
  // A new speed applies at once while playing; while paused it waits for Play.
  $("speed").onchange = () => {
    store.update({ rate: Number($("speed").value) });
    if (store.get().playing) play();
  };
}
