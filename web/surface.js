// @ts-check
// The surface's kind, curvature and radius: in either of the scene's forms, {kind, radius} or {curvature: K}, as the server
// answered it (the session's `current.surface`): K > 0 the sphere of radius 1/√K, 0 the plane,
// K < 0 the hyperbolic plane of radius 1/√−K. Pure. K itself is the server's number where the scene
// gives it; only the kind of a K-form surface is read off K here (the session answer does not name it).

/** @typedef {"sphere" | "pseudosphere" | "plane"} SurfaceKind */
/** @typedef {{kind?: SurfaceKind, radius?: number, curvature?: number | null}} Surface */

// |K| below the engine's kFlatCurvature (engine/surface.h) is the plane. The server does not say
// which kind a K-form surface resolved to; the views it offers for it follow from this.
const flatBelow = 1e-24;

/** @param {Surface | undefined | null} surface */
export const curvatureForm = (surface) => typeof surface?.curvature === "number";

/**
 * @param {Surface | undefined | null} surface
 * @returns {SurfaceKind}
 */
export function surfaceKind(surface) {
  if (curvatureForm(surface)) {
    const K = /** @type {number} */ (surface?.curvature);
    return Math.abs(K) < flatBelow ? "plane" : K > 0 ? "sphere" : "pseudosphere";
  }
  return surface?.kind ?? "sphere";
}

/**
 * K [1/length²]: the server's number in the K form; ±1/R² (0 on the plane) in the other.
 * @param {Surface} surface
 */
export function curvatureOf(surface) {
  if (curvatureForm(surface)) return /** @type {number} */ (surface.curvature);
  const R = surface.radius ?? 1;
  return { sphere: 1, plane: 0, pseudosphere: -1 }[surfaceKind(surface)] / (R * R);
}

/**
 * The radius the surface has now [length] (1/√|K| in the K form; none on the plane there).
 * @param {Surface} surface
 * @returns {number | undefined}
 */
export function radiusOf(surface) {
  if (!curvatureForm(surface)) return surface.radius ?? 1;
  return surfaceKind(surface) === "plane"
    ? undefined
    : 1 / Math.sqrt(Math.abs(/** @type {number} */ (surface.curvature)));
}

/** @type {Record<SurfaceKind, string>} */
export const surfaceName = { sphere: "sphere", pseudosphere: "hyperbolic plane", plane: "flat plane" };
