// @ts-check
// The surface as the server resolved it: each session answer names it ({"surface": {kind, radius,
// curvature}}, server/context.cpp) in either of the scene's forms, {kind, radius} or {curvature: K},
// so the UI never re-derives the kind from K (the engine's flat threshold stays in the engine). Pure.

/** A name in the schema's surface.kind enum ("sphere", "torus", …). @typedef {string} SurfaceKind */
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

// The kinds, their menu words and which of them have a K that varies come from the scene's schema
// (surface.kind's "enum", "x-titles", "x-curvature-varies": engine/scene_fields.h's one table).
/** @param {any} schema */
const kindSpec = (schema) => schema?.properties?.surface?.properties?.kind ?? {};

/** Every surface kind, in the table's order. @param {any} schema @returns {SurfaceKind[]} */
export const surfaceKinds = (schema) => kindSpec(schema).enum ?? [];

/** A menu's words for a kind ("hyperbolic plane (negative curvature)"); its name before the schema is in. @param {any} schema @param {string} kind */
export const surfaceTitle = (schema, kind) => kindSpec(schema)["x-titles"]?.[kind] ?? kind;

/** Whether the curvature varies from place to place on a kind (the engine's chart_free: no polar chart). @param {any} schema @param {string} kind */
export const curvatureVaries = (schema, kind) => (kindSpec(schema)["x-curvature-varies"] ?? []).includes(kind);

/**
 * The merge patch that switches a scene to another surface kind: the kind, and null for every
 * field the scene gives that the schema marks as belonging to other kinds only ("x-surfaces":
 * initial.r on a torus, the torus's radii or friction on a sphere), so the server refuses nothing.
 * The physical values the teacher sees (spin, speed, heading) go with it: the coordinate rates
 * alone mean another spin and speed on another surface (a torus made spin 1 into 0.679 and speed
 * 0.5 into 2.08 without a word).
 * @param {any} schema the scene's JSON Schema
 * @param {any} scene the scene in force
 * @param {string} kind
 * @param {{spin?: number, speed?: number, heading?: number}} [physical] the values shown
 */
export function surfaceSwitch(schema, scene, kind, physical = {}) {
  /** @type {any} */
  const patch = { surface: { kind } };
  for (const [key, value] of Object.entries(physical))
    if (typeof value === "number" && Number.isFinite(value)) (patch.initial ??= {})[key] = value;
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
