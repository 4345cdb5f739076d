// @ts-check
// A surface given by a formula (surface.kind implicit or graph), as the schema describes it: which
// field holds the formula (the one marked "x-formula" for the kind), and the merge patch that puts one
// of its "x-examples" (engine/formula_examples.h) in force. Pure; the row is formularow.js.

/** @typedef {import("./state.js").AppState} AppState */
/** @typedef {{name: string, title: string, formula: string, parameters: Record<string, number>, X: number[], note: string}} Example */

/**
 * The formula field of the surface in force: its key ("F" or "z") and schema, or null where the
 * surface is not given by a formula.
 * @param {AppState} s
 * @returns {{key: string, spec: any} | null}
 */
export function formulaField(s) {
  const kind = s.surface?.kind;
  const fields = s.schema?.properties?.surface?.properties ?? {};
  for (const [key, spec] of Object.entries(fields))
    if (/** @type {any} */ (spec)["x-formula"] && /** @type {any} */ (spec)["x-surfaces"]?.includes(kind))
      return { key, spec };
  return null;
}

/**
 * The merge patch that puts an example in force: its formula, its parameters (those of the formula
 * before dropped: null), the box chosen anew, and the body at the example's start.
 * @param {string} key "F" or "z"
 * @param {Example} example
 * @param {Record<string, number>} [before] the parameters in force
 */
export function examplePatch(key, example, before = {}) {
  /** @type {Record<string, number | null>} */
  const parameters = {};
  for (const name of Object.keys(before)) parameters[name] = null;
  Object.assign(parameters, example.parameters);
  return { surface: { [key]: example.formula, parameters, bounds: null }, initial: { X: example.X } };
}
