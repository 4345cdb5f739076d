// @ts-check
// The preset gallery and the scene's explanation: the presets in the server's lesson sequence
// (assets/lessons/sequence.txt), a label at each chapter, with thumbnails the server renders.
import { api, request } from "./api.js";
import { $, el } from "./dom.js";
import { freshCamera } from "./frame.js";
import { say } from "./readout.js";
import { openScene, presetLabel } from "./session.js";
import { store, withView } from "./state.js";
import { surfaceTitle } from "./surface.js";

/** @typedef {import("./state.js").AppState} AppState */

/** The gallery's short-lived session, while a thumbnail is being made. @type {string | null} */
let thumbnailSession = null;
export const thumbnailInProgress = () => thumbnailSession;

/** The preset shown is highlighted, marked "modified" once changed. @param {AppState} s @param {AppState} b */
export function renderGalleryMarks(s, b) {
  if (s.preset === b.preset && s.modified === b.modified && s.presets === b.presets) return;
  document.querySelectorAll(".preset").forEach((card) => {
    const button = /** @type {HTMLElement} */ (card);
    const active = button.dataset.name === s.preset;
    button.classList.toggle("active", active);
    button.setAttribute("aria-pressed", String(active));
    button.classList.toggle("modified", active && s.modified);
    /** @type {HTMLElement} */ (button.querySelector(".mark")).textContent = active
      ? s.modified
        ? "modified"
        : "selected"
      : "";
  });
}

/** The preset's description, or what is shown instead. @param {AppState} s @param {AppState} b */
export function renderExplanation(s, b) {
  if (!s.surface || (s.preset === b.preset && s.surface === b.surface)) return;
  const preset = s.presets.find((p) => p.name === s.preset);
  $("explanation").textContent = preset
    ? preset.description
    : `Your own scene on the ${surfaceTitle(s.schema, s.surface.kind)}.`;
}

/**
 * Opens a preset by name (a card, the lesson card's "Next"). It opens in its surface's own view,
 * aimed afresh: nothing of the last scene's view stays (the disk view of an H² preset carried over
 * to a sphere, a zoom put the body under the HUD).
 * @param {string} name
 */
export function openPreset(name) {
  const preset = store.get().presets.find((p) => p.name === name);
  if (!preset) return;
  openScene(preset.scene, { preset: preset.name })
    .then(() => store.update((s) => withView(s, { ...freshCamera(), kind: null })))
    .catch((e) => say(e.message));
}

/** The cards, then their thumbnails, one short-lived session at a time, kept for the tab. */
export async function buildGallery() {
  const gallery = $("gallery");
  const presets = store.get().presets;
  presets.forEach((preset, i) => {
    if (i === 0 || preset.chapter !== presets[i - 1].chapter)
      gallery.append(el("h2", { class: "chapter", text: preset.chapter ?? "" }));
    const button = el(
      "button",
      { type: "button", class: "preset", "data-name": preset.name, title: preset.description },
      el("img", { alt: "" }),
      el("b", { text: presetLabel(preset.name) }),
      el("span", { class: "mark" }),
      el("small", { text: preset.description }),
    );
    button.addEventListener("click", () => openPreset(preset.name));
    gallery.append(button);
  });
  const s = store.get();
  renderGalleryMarks(s, { ...s, presets: [] });
  for (const preset of presets) {
    const img = gallery.querySelector(`[data-name="${preset.name}"] img`);
    const key = `spinfold.thumb.${preset.name}`;
    try {
      let blob;
      const cached = sessionStorage.getItem(key);
      if (cached) {
        blob = new Blob([Uint8Array.from(atob(cached), (c) => c.charCodeAt(0))], { type: "image/png" });
      } else {
        const made = await request("POST", "/sessions", preset.scene);
        thumbnailSession = made.id;
        await request("POST", `/sessions/${made.id}/advance`, { until: 2 });
        const res = await fetch(
          `${api}/sessions/${made.id}/frame.png?width=160&height=120&layers=surface,grid,body,trail`,
        );
        blob = await res.blob();
        await request("DELETE", `/sessions/${made.id}`);
        thumbnailSession = null;
        const bytes = new Uint8Array(await blob.arrayBuffer());
        try {
          sessionStorage.setItem(key, btoa(String.fromCharCode(...bytes)));
        } catch {
          /* full: fetch again next time */
        }
      }
      img.src = URL.createObjectURL(blob);
    } catch {
      /* a missing thumbnail is not worth an error */
    }
  }
}
