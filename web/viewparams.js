// @ts-check
// The view controls' ranges, defaults and layers: from GET /api/v1/view-parameters (the server's
// one table of frame parameters, render/view_parameters.*) instead of clamps copied into the UI.
// Pure: fromContract reads the route's answer.

/**
 * A number parameter in the UI's units (angles in radians): min, max, default (null: none, e.g.
 * the camera aimed at the body), and toApi, the factor from the UI's unit to the route's.
 * @typedef {{min: number, max: number, default: number|null, toApi: number, help: string}} Range
 */
/** @typedef {{name: string, default: boolean, help: string}} Layer */
/**
 * @typedef {{ranges: Record<string, Range>, layers: Layer[], views: string[],
 *   source: "server"}} ViewControls
 */

const degree = Math.PI / 180;
// Units an angle may come in, and the factor from radians to them.
/** @type {Record<string, number>} */
const angleUnits = { rad: 1, radian: 1, degree: 1 / degree, deg: 1 / degree };

/**
 * The view controls from the route's answer: {parameters: [{name, type, unit?, min?, max?,
 * default?, choices?, help}], layers: [{name, default, help}], formats: […]}. An answer without
 * those lists is an Error naming what is missing.
 * @param {any} answer
 * @returns {ViewControls}
 */
export function fromContract(answer) {
  if (!Array.isArray(answer?.parameters)) throw new Error('view-parameters: no "parameters" list');
  if (!Array.isArray(answer?.layers)) throw new Error('view-parameters: no "layers" list');
  /** @type {Record<string, Range>} */
  const ranges = {};
  let views = /** @type {string[]} */ ([]);
  for (const p of answer.parameters) {
    if (p.name === "view" && Array.isArray(p.choices)) views = p.choices.map(String);
    if (p.type !== "number" && p.type !== "integer") continue;
    // An angle is kept in radians here (the camera's drag and keys step in radians) and sent in
    // the route's unit.
    const toApi = (p.unit && angleUnits[p.unit]) || 1;
    const toUi = (/** @type {unknown} */ v) => (typeof v === "number" && Number.isFinite(v) ? v / toApi : null);
    ranges[p.name] = {
      min: toUi(p.min) ?? -Infinity,
      max: toUi(p.max) ?? Infinity,
      default: toUi(p.default),
      toApi,
      help: String(p.help ?? ""),
    };
  }
  const layers = answer.layers.map((/** @type {any} */ l) => ({
    name: String(l.name),
    default: Boolean(l.default),
    help: String(l.help ?? ""),
  }));
  return { ranges, layers, views, source: "server" };
}

/**
 * `value` within the named range (unchanged when the controls do not name it).
 * @param {ViewControls | null} controls
 * @param {string} name
 * @param {number} value
 */
export function clampTo(controls, name, value) {
  const range = controls?.ranges[name];
  return range ? Math.max(range.min, Math.min(range.max, value)) : value;
}

/**
 * A UI value in the route's unit (radians → degrees when the route counts degrees).
 * @param {ViewControls | null} controls
 * @param {string} name
 * @param {number} value
 */
export const toApi = (controls, name, value) => value * (controls?.ranges[name]?.toApi ?? 1);
