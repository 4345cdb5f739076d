// @ts-check
// The surface as the server resolved it: each session answer names it ({"surface": {kind, radius,
// curvature}}, server/context.cpp) in either of the scene's forms, {kind, radius} or {curvature: K},
// so the UI never re-derives the kind from K (the engine's flat threshold stays in the engine). Pure.

/** @typedef {"sphere" | "pseudosphere" | "plane" | "torus" | "spheroid" | "bump" | "catenoid"} SurfaceKind */
/** A scene's surface as written. @typedef {{kind?: SurfaceKind, radius?: number, curvature?: number | null}} Surface */
/** The server's resolution of it. @typedef {{kind: SurfaceKind, radius: number, curvature: number}} ResolvedSurface */

/** Whether a scene gives its surface by K (the curvature dial) rather than kind and radius. @param {Surface | undefined | null} surface */
export const curvatureForm = (surface) => typeof surface?.curvature === "number";

/**
 * The kind of a surface as written in a scene the server has not resolved (a preset's): its kind,
 * or the sign of its K.
 * @param {Surface | undefined | null} surface
 * @returns {SurfaceKind}
 */
export function writtenKind(surface) {
  if (curvatureForm(surface)) {
    const K = /** @type {number} */ (surface?.curvature);
    return K > 0 ? "sphere" : K < 0 ? "pseudosphere" : "plane";
  }
  return surface?.kind ?? "sphere";
}

/**
 * The radius a control shows [length]: the server's, none on the plane of a K-form scene (there
 * R is only the length scale, not something the dial set).
 * @param {Surface} given the scene's surface in force
 * @param {ResolvedSurface} resolved
 * @returns {number | undefined}
 */
export const shownRadius = (given, resolved) =>
  curvatureForm(given) && resolved.kind === "plane" ? undefined : resolved.radius;

/** @type {Record<SurfaceKind, string>} */
export const surfaceName = {
  sphere: "sphere",
  pseudosphere: "hyperbolic plane",
  plane: "flat plane",
  torus: "torus",
  spheroid: "spheroid",
  bump: "bump on the plane",
  catenoid: "catenoid",
};

/** Whether the curvature varies from place to place on a kind (the engine's curvature_varies). */
export const curvatureVaries = (/** @type {string} */ kind) => ["torus", "spheroid", "bump", "catenoid"].includes(kind);

/**
 * The merge patch that switches a scene to another surface kind: the kind, and null for every
 * field the scene gives that the schema marks as belonging to other kinds only ("x-surfaces":
 * initial.r on a torus, the torus's radii or friction on a sphere), so the server refuses nothing.
 * @param {any} schema the scene's JSON Schema
 * @param {any} scene the scene in force
 * @param {string} kind
 */
export function surfaceSwitch(schema, scene, kind) {
  /** @type {any} */
  const patch = { surface: { kind } };
  const foreign = (/** @type {any} */ spec) => spec?.["x-surfaces"] && !spec["x-surfaces"].includes(kind);
  for (const [section, spec] of Object.entries(schema.properties ?? {})) {
    const given = scene[section];
    if (given === undefined || given === null) continue;
    if (foreign(spec)) {
      patch[section] = null;
      continue;
    }
    if (typeof given !== "object") continue;
    for (const key of Object.keys(given))
      if (foreign(/** @type {any} */ (spec).properties?.[key])) (patch[section] ??= {})[key] = null;
  }
  return patch;
}
