// @ts-check
// For class: the open preset's card, "what to look for" (its claim in plain words: the scenes
// route's look_for, from assets/lessons/), and simple mode — the controls that matter (spin, speed,
// curvature, the geodesic companion, on by default), the rest of the page out of the way. Simple
// mode is kept for the browser (localStorage), like the theme.
import { hasGeodesic, toggleGeodesic } from "./comparisons.js";
import { $ } from "./dom.js";
import { openPreset } from "./gallery.js";
import { presetLabel } from "./session.js";
import { mount, store, withView } from "./state.js";

/** @typedef {import("./state.js").AppState} AppState */

const simpleKey = "spinfold.simple";

/** The preset's card, or "" (your own scene, or a preset without one). @param {AppState} s */
export const lookFor = (s) => s.presets.find((p) => p.name === s.preset)?.look_for ?? "";

/** @param {AppState} s @param {AppState} b */
function renderLesson(s, b) {
  if (s.preset !== b.preset || s.presets !== b.presets) {
    const text = lookFor(s);
    $("look-for").hidden = !text;
    $("look-for-text").textContent = text;
    // The lesson sequence's next preset (the scenes route's `next`), one click on.
    const preset = s.presets.find((p) => p.name === s.preset);
    const next = preset?.next ? s.presets.find((p) => p.name === preset.next) : null;
    const button = $("next-lesson");
    button.hidden = !next;
    if (next) {
      button.textContent = `Next: ${presetLabel(next.name)} ▸`;
      button.dataset.next = next.name;
      button.title = next.chapter === preset.chapter ? next.description : `${next.chapter}: ${next.description}`;
    }
  }
  // A scene opened in simple mode gets the geodesic companion (once: it can be removed again).
  if (document.body.classList.contains("simple") && s.id && s.id !== b.id && s.phase === "live" && !hasGeodesic(s))
    setTimeout(() => {
      if (store.get().id === s.id && !hasGeodesic(store.get())) toggleGeodesic({ bySimpleMode: true });
    }, 0);
}

/** @param {boolean} on */
function setSimple(on) {
  document.body.classList.toggle("simple", on);
  // The overlay in plain words (the server's `plain` layer) while simple mode is on.
  store.update((s) => {
    const has = s.view.layers.includes("plain");
    if (has === on) return {};
    return withView(s, { layers: on ? [...s.view.layers, "plain"] : s.view.layers.filter((l) => l !== "plain") });
  });
  $("simple").setAttribute("aria-pressed", String(on));
  $("simple").textContent = on ? "Full controls" : "Simple mode";
  try {
    localStorage.setItem(simpleKey, on ? "on" : "off");
  } catch {
    /* not kept */
  }
}

export function setupLesson() {
  let on = false;
  try {
    on = localStorage.getItem(simpleKey) === "on";
  } catch {
    /* off */
  }
  setSimple(on);
  $("simple").onclick = () => {
    const next = !document.body.classList.contains("simple");
    setSimple(next);
    const s = store.get();
    if (next && s.id && s.phase === "live" && !hasGeodesic(s)) toggleGeodesic({ bySimpleMode: true });
  };
  $("next-lesson").onclick = () => openPreset($("next-lesson").dataset.next ?? "");
  mount(renderLesson);
}
