// @ts-check
// The comparisons: the geodesic companion (one click or G) and a fan of spins (vary). The legend is
// drawn in the picture by the server (the hud layer). A refusal is said in the status line, unless
// a newer edit's answer is there already (edits.js).
import { $ } from "./dom.js";
import { begin, told, typedValue } from "./edits.js";
import { roomForHud } from "./frame.js";
import { say } from "./readout.js";
import { applyChange } from "./session.js";
import { mount, store, withView } from "./state.js";

/** @param {import("./state.js").AppState} s */
export const hasGeodesic = (s) => (s.current?.companions ?? []).some((/** @type {any} */ c) => c.geodesic);

/** @param {import("./state.js").AppState} s @param {import("./state.js").AppState} b */
export function renderComparisons(s, b) {
  if (!s.current || s.current === b.current) return;
  const on = hasGeodesic(s);
  $("geodesic").setAttribute("aria-pressed", String(on));
  $("geodesic").textContent = on ? "− Geodesic companion" : "+ Geodesic companion";
}

/**
 * Adds or removes the geodesic companion; its legend needs the hud, which is switched on where the
 * frame has room for it (on a phone the overlay would cover much of the picture: the dashed trail
 * tells the companion apart there). `bySimpleMode`: simple mode adds it itself, which leaves the
 * preset unmarked (the teacher changed nothing).
 * @param {{bySimpleMode?: boolean}} [options]
 */
export async function toggleGeodesic({ bySimpleMode = false } = {}) {
  const s = store.get();
  const companions = s.current.companions ?? [];
  const next = hasGeodesic(s)
    ? companions.filter((/** @type {any} */ c) => !c.geodesic)
    : [...companions, { geodesic: true, label: "geodesic (s = 0)" }];
  const edit = begin();
  try {
    await applyChange({ companions: next.length ? next : null }, edit, { marks: !bySimpleMode });
    store.update((now) =>
      now.view.layers.includes("hud") || !roomForHud()
        ? {}
        : withView(now, { layers: [...now.view.layers, "hud"], hudChosen: true }),
    );
  } catch (e) {
    if (told(edit)) say(/** @type {Error} */ (e).message);
  }
}

/** Companions from the same start with spins spread over the range asked. */
async function addFan() {
  const typedFrom = typedValue(/** @type {HTMLInputElement} */ ($("fan-from")).value);
  const typedTo = typedValue(/** @type {HTMLInputElement} */ ($("fan-to")).value);
  if ("error" in typedFrom || "error" in typedTo) {
    say(`The fan's spins: ${"error" in typedFrom ? typedFrom.error : /** @type {{error: string}} */ (typedTo).error}`);
    return;
  }
  const from = /** @type {number} */ (typedFrom.value);
  const to = /** @type {number} */ (typedTo.value);
  const count = Math.max(2, Math.min(8, Math.round(Number($("fan-count").value) || 4)));
  const values = Array.from({ length: count }, (_, i) =>
    Number((from + ((to - from) * i) / (count - 1)).toPrecision(6)),
  );
  const edit = begin();
  try {
    await applyChange({ vary: { field: "initial.spin", values } }, edit);
  } catch (e) {
    if (told(edit)) say(`The fan was refused: ${/** @type {Error} */ (e).message}`);
  }
}

async function clearComparisons() {
  const edit = begin();
  try {
    await applyChange({ companions: null, vary: null }, edit);
  } catch (e) {
    if (told(edit)) say(/** @type {Error} */ (e).message);
  }
}

export function setupComparisons() {
  mount(renderComparisons);
  $("geodesic").onclick = () => toggleGeodesic();
  $("fan").onclick = () => addFan();
  $("fan-clear").onclick = () => clearComparisons();
}
