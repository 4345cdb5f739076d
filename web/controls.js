// @ts-check
// The advanced panel of every scene parameter: built from the scene's JSON Schema (GET /api/v1/schema).
// A change is a merge PATCH; a refusal shows the server's message beside the field and the value
// goes back (while it is the field's latest edit: edits.js). Rendered from the store: rebuilt when
// the set of fields changes (another deformation kind, a field given in its other form), otherwise
// its values updated in place.
import { $, el, clear } from "./dom.js";
import { begin, latest, refused, typedValue } from "./edits.js";
import { applyChange, earlierAnswered } from "./session.js";
import { store } from "./state.js";
import { curvatureForm } from "./surface.js";

/** @typedef {import("./state.js").AppState} AppState */
/** @typedef {{path: string[], spec: any, value: any, replaced: boolean}} Field */

// A field the schema marks as belonging to some surface kinds only ("x-surfaces": the torus's
// tube_radius, initial.u where the curvature varies, r where it is constant) shows on those only.
const belongs = (/** @type {any} */ spec, /** @type {string} */ kind) =>
  !spec["x-surfaces"] || spec["x-surfaces"].includes(kind);

/** @param {any} object @param {string[]} path */
const lookup = (object, path) => path.reduce((node, key) => (node ? node[key] : undefined), object);

// A number or a matrix (body.inertia: isotropic J, or [[J11, J12], [J12, J22]]), shown as JSON text.
const matrixOrNumber = (/** @type {any} */ spec) =>
  Boolean(spec.oneOf?.some((/** @type {any} */ b) => b.type === "array"));

/** The value an input shows. @param {Field} f */
function shown(f) {
  if (f.replaced) return "";
  const value = f.value ?? f.spec.default;
  return matrixOrNumber(f.spec) ? JSON.stringify(value) : (value ?? "");
}

/**
 * The fields of the advanced panel, by section, for the parameters in force.
 * @param {AppState} s
 * @returns {Array<{legend: string, fields: Field[], deformationKinds?: string[]}>}
 */
function sections(s) {
  const props = s.schema.properties;
  const current = s.current;
  const kind = /** @type {import("./surface.js").ResolvedSurface} */ (s.surface)?.kind ?? "sphere";
  /** @param {string[]} path @param {any} spec @param {any} [value] */
  const field = (path, spec, value = lookup(current, path)) => ({ path, spec, value, replaced: false });
  const result = [];
  for (const section of ["surface", "body", "initial", "integrator"]) {
    // A field the scene gave in its other form (the schema's dependentSchemas: spin instead of
    // alpha_dot, speed and heading instead of r_dot and phi_dot) shows empty, not its default.
    const replaced = new Set();
    for (const [given, rule] of Object.entries(props[section].dependentSchemas ?? {}))
      if (lookup(current, [section, given]) !== undefined)
        for (const alternative of /** @type {any} */ (rule).not?.anyOf ?? [])
          alternative.required.forEach((/** @type {string} */ k) => replaced.add(k));
    const fields = Object.entries(props[section].properties)
      .filter(([, spec]) => belongs(spec, kind))
      .map(([key, spec]) => ({
        ...field([section, key], spec),
        replaced: replaced.has(key),
      }));
    result.push({ legend: section, fields });
  }
  const deformation = lookup(current, ["potential", "deformation"]);
  const branches = props.potential.properties.deformation.oneOf;
  const radial = props.potential.properties.radial;
  const fields = belongs(radial, kind)
    ? [
        field(
          ["potential", "radial", "gamma"],
          radial.properties.gamma,
          lookup(current, ["potential", "radial", "gamma"]) ?? 0,
        ),
      ]
    : [];
  for (const branch of branches) {
    if (deformation && deformation.kind !== branch.properties.kind.const) continue;
    for (const [key, spec] of Object.entries(branch.properties))
      if (key !== "kind") fields.push(field(["potential", "deformation", key], spec, deformation?.[key]));
    if (!deformation) break; // offer the abc fields when there is no deformation potential yet
  }
  result.push({
    legend: "potential",
    fields,
    deformationKinds: branches.map((/** @type {any} */ b) => b.properties.kind.const),
  });
  result.push({ legend: "run", fields: [field(["on_degenerate"], props.on_degenerate)] });
  return result;
}

/** @param {AppState} s @param {AppState} b */
export function renderControls(s, b) {
  if (!s.current || !s.schema || (s.current === b.current && s.schema === b.schema && $("controls").childElementCount))
    return;
  const form = $("controls");
  const all = sections(s);
  const signature = JSON.stringify(all.map((sec) => sec.fields.map((f) => [f.path, f.replaced])));
  const deformationKind = s.current.potential?.deformation?.kind ?? "none";
  if (form.dataset.signature === signature) {
    for (const f of all.flatMap((sec) => sec.fields)) {
      const input = form.querySelector(`[name="${f.path.join(".")}"]`);
      if (input && document.activeElement !== input) input.value = shown(f);
    }
    const kind = $("field-potential-deformation-kind");
    if (document.activeElement !== kind) kind.value = deformationKind;
    return;
  }
  form.dataset.signature = signature;
  clear(form);
  for (const section of all) {
    const set = el("fieldset", {}, el("legend", { text: section.legend }));
    // The deformation's kind goes before its coefficients (after the radial potential, if any).
    const kindAt = section.fields.findIndex((f) => f.path[1] === "deformation");
    section.fields.forEach((f, i) => {
      if (section.deformationKinds && i === kindAt)
        set.append(deformationKindField(section.deformationKinds, deformationKind));
      set.append(fieldRow(f));
    });
    if (section.deformationKinds && kindAt < 0)
      set.append(deformationKindField(section.deformationKinds, deformationKind));
    form.append(set);
  }
}

/** @param {Field} f */
function fieldRow(f) {
  const { path, spec } = f;
  const name = path.join(".");
  const id = "field-" + path.join("-");
  const unit = spec["x-unit"] && spec["x-unit"] !== "1" ? ` [${spec["x-unit"]}]` : "";
  let input;
  if (spec.enum) {
    input = el("select");
    for (const option of spec.enum) input.add(new Option(option, option));
  } else if (matrixOrNumber(spec)) {
    input = el("input", { type: "text", placeholder: "0.5 or [[0.6, 0.1], [0.1, 0.3]]" });
  } else {
    input = el("input", { type: "text", inputmode: "decimal", autocomplete: "off", class: "number" });
  }
  Object.assign(input, { name, id, title: spec.description || "" });
  input.value = shown(f);
  if (f.replaced) input.placeholder = "from the physical form";
  const error = el("span", { class: "error", id: `${id}-error` });
  input.setAttribute("aria-describedby", error.id);
  input.addEventListener("change", async () => {
    const edit = begin(error);
    const { current, surface } = store.get();
    /** @type {any} */
    const patch = {};
    let node = patch;
    path.slice(0, -1).forEach((key) => (node = node[key] = {}));
    if (spec.enum) node[path[path.length - 1]] = input.value;
    else {
      // A number input whose text is not a number (`1e`, `abc`) has the value "" (badInput).
      const typed = typedValue(input.value, matrixOrNumber(spec));
      if ("error" in typed) {
        // Nothing is sent; the value in force comes back, as after a refusal by the server.
        if (refused(edit, `${name}: ${typed.error}`))
          input.value = shown({ ...f, value: lookup(store.get().current, path), replaced: false });
        return;
      }
      node[path[path.length - 1]] = typed.value;
    }
    // A deformation field needs its kind: the scene's, or abc when there is none yet.
    if (path[1] === "deformation") node.kind = lookup(current, ["potential", "deformation", "kind"]) ?? "abc";
    // The surface is given either by K or by kind and radius: setting one form removes the other.
    if (path[0] === "surface" && path[1] === "curvature") Object.assign(node, { kind: null, radius: null });
    else if (path[0] === "surface" && curvatureForm(current.surface))
      Object.assign(node, {
        kind: node.kind ?? surface?.kind,
        radius: node.radius ?? surface?.radius,
        curvature: null,
      });
    const inForce = () => shown({ ...f, value: lookup(store.get().current, path), replaced: false });
    try {
      await applyChange(patch, edit);
    } catch (e) {
      if (!refused(edit, /** @type {Error} */ (e).message)) return;
      input.value = inForce();
      await earlierAnswered(edit);
      if (latest(edit)) input.value = inForce();
    }
  });
  return el("div", { class: "field" }, el("label", { for: id, text: path[path.length - 1] + unit }), input, error);
}

// The deformation potential's kind: none or one of the schema's. A switch is one merge patch that
// sets the new kind and removes the old kind's fields (null), so the server sees one whole object.
/** @param {string[]} kinds @param {string} value */
function deformationKindField(kinds, value) {
  const input = el("select", { name: "potential.deformation.kind", id: "field-potential-deformation-kind" });
  for (const kind of ["none", ...kinds]) input.add(new Option(kind, kind));
  input.value = value;
  const error = el("span", { class: "error" });
  input.addEventListener("change", async () => {
    const edit = begin(error);
    const deformation = store.get().current.potential?.deformation;
    let replacement = null;
    if (input.value !== "none") {
      /** @type {any} */
      const next = { kind: input.value };
      for (const key of Object.keys(deformation ?? {})) if (key !== "kind") next[key] = null;
      replacement = next;
    }
    try {
      await applyChange({ potential: { deformation: replacement } }, edit);
    } catch (e) {
      if (!refused(edit, /** @type {Error} */ (e).message)) return;
      const inForce = () => store.get().current.potential?.deformation?.kind ?? "none";
      input.value = inForce();
      await earlierAnswered(edit);
      if (latest(edit)) input.value = inForce();
    }
  });
  return el("div", { class: "field" }, el("label", { for: input.id, text: "deformation kind" }), input, error);
}
