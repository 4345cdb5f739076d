// @ts-check
// The view menu and the layer toggles: the server's views that exist on the surface shown (in its
// order), the layers of GET /api/v1/view-parameters, rendered from the store.
import { request } from "./api.js";
import { $, el, clear } from "./dom.js";
import { is3d, toggleFollow } from "./frame.js";
import { mount, store, withView } from "./state.js";
import { fromContract } from "./viewparams.js";

/** @typedef {import("./state.js").AppState} AppState */

/**
 * The view controls from the server (GET /api/v1/view-parameters: the one table of view parameters
 * and layers, render/view_parameters.h).
 * @returns {Promise<import("./viewparams.js").ViewControls>}
 */
export async function loadViewParameters() {
  return fromContract(await request("GET", "/view-parameters"));
}

/** The views offered on the surface shown. @param {AppState} s */
const offered = (s) => s.views.filter((v) => v.surfaces.includes(s.surface?.kind));

/**
 * Keeps the view one the surface has: the first offered when the surface changed under it (the
 * curvature dial across K = 0, a new scene).
 * @param {AppState} s
 */
function keepViewOffered(s) {
  if (!s.surface || !s.views.length) return;
  const kinds = offered(s).map((v) => v.name);
  if (kinds.length && !kinds.includes(/** @type {string} */ (s.view.kind)))
    store.update((now) => withView(now, { kind: kinds[0], yaw: null, pitch: null, distance: null }));
}

/** @param {AppState} s @param {AppState} b */
function renderViewMenu(s, b) {
  if (s.views === b.views && s.view.kind === b.view.kind && s.surface?.kind === b.surface?.kind) return;
  const select = clear($("view"));
  for (const v of offered(s)) select.add(Object.assign(new Option(v.title, v.name), { title: v.description }));
  if (s.view.kind) select.value = s.view.kind;
}

/** @param {AppState} s @param {AppState} b */
function renderLayers(s, b) {
  const box = $("layers");
  if (s.viewParameters !== b.viewParameters && s.viewParameters) {
    clear(box);
    for (const layer of s.viewParameters.layers)
      box.append(
        el(
          "label",
          { title: layer.help },
          el("input", { type: "checkbox", name: `layer-${layer.name}` }),
          ` ${layer.name}`,
        ),
      );
  }
  for (const input of box.querySelectorAll("input"))
    input.checked = s.view.layers.includes(input.name.replace(/^layer-/, ""));
}

export function setupViewControls() {
  mount((s, b) => {
    keepViewOffered(s);
    renderViewMenu(s, b);
    renderLayers(s, b);
    // Follow body: a 3-D camera's choice (a 2-D view is framed afresh with every picture).
    $("follow").setAttribute("aria-pressed", String(s.view.motion === "follow"));
    /** @type {HTMLButtonElement} */ ($("follow")).disabled = !is3d(s);
  });
  $("follow").addEventListener("click", toggleFollow);
  $("view").addEventListener("change", () =>
    store.update((s) => withView(s, { kind: $("view").value, yaw: null, pitch: null, distance: null })),
  );
  $("layers").addEventListener("change", (/** @type {Event} */ e) => {
    const input = /** @type {HTMLInputElement} */ (e.target);
    const layer = input.name.replace(/^layer-/, "");
    store.update((s) => {
      const layers = input.checked ? [...s.view.layers, layer] : s.view.layers.filter((l) => l !== layer);
      return withView(s, { layers, hudChosen: s.view.hudChosen || layer === "hud" });
    });
  });
}

/** The curvature dial shows the conformal view (the one view on every side of K = 0). */
export function showConformal() {
  const s = store.get();
  if (s.view.kind === "conformal" || !s.views.some((v) => v.name === "conformal")) return;
  store.update((now) => withView(now, { kind: "conformal", yaw: null, pitch: null, distance: null }));
}
