// @ts-check
// Share links: the URL's fragment carries the scene, its timeline, the time, the view and whether a
// preset was changed; opening it rebuilds the same run (the same state and picture, trail
// included) and marks its preset as the sender's was. Pure.

/**
 * The share link of a state, on the page at `base` (origin + path + query).
 * @param {import("./state.js").AppState} state
 * @param {string} base
 */
export function shareUrl(state, base) {
  const params = new URLSearchParams({
    scene: JSON.stringify(state.scene),
    timeline: JSON.stringify(state.timeline),
    t: String(state.t),
    view: state.view.kind ?? "",
    layers: state.view.layers.join(","),
  });
  // A preset changed before its run started has an empty timeline: the mark travels with the link.
  if (state.modified) params.set("modified", "1");
  return `${base}#${params}`;
}

/**
 * What a share link's fragment asks for: null when it has no scene, "damaged" when it cannot be read.
 * @param {string} hash location.hash ("#scene=…")
 * @returns {null | "damaged" | {scene: any, until: number, timeline: any[], modified: boolean,
 *   view: {kind: string | null, layers?: string[]}}}
 */
export function fromHash(hash) {
  if (!hash) return null;
  const params = new URLSearchParams(hash.slice(1));
  if (!params.has("scene")) return null;
  try {
    /** @type {{kind: string | null, layers?: string[]}} */
    const view = { kind: params.get("view") || null };
    const layers = params.get("layers");
    if (layers !== null) view.layers = layers.split(",").filter(Boolean);
    return {
      scene: JSON.parse(/** @type {string} */ (params.get("scene"))),
      until: Number(params.get("t") || 0),
      timeline: JSON.parse(params.get("timeline") || "[]"),
      modified: params.get("modified") === "1",
      view,
    };
  } catch {
    return "damaged";
  }
}
