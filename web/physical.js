// @ts-check
// The physical controls, first in the side panel: each a slider and a number, its unit in words, a
// one-line explanation shown on hover and focus. Label, unit and explanation come from the scene's
// JSON Schema (title, x-unit, description: the engine's field table, engine/scene_fields.h), never
// from a table of the UI's own. Rendered from the store: rebuilt when the rows change (another body
// model or potential), otherwise updated in place, so that focus and a dragged slider stay put.
import { sleep } from "./api.js";
import { $, el, clear } from "./dom.js";
import { begin, refused, typedValue } from "./edits.js";
import { formulaField } from "./formula.js";
import { formulaRow, updateFormulaRow } from "./formularow.js";
import { applyChange, earlierAnswered } from "./session.js";
import { store, withView } from "./state.js";
import { curvatureForm, curvatureVaries, shownRadius, surfaceKinds, surfaceSwitch, surfaceTitle } from "./surface.js";
import { showConformal } from "./viewcontrols.js";

/** @typedef {import("./state.js").AppState} AppState */
/**
 * @typedef {{key: string, field?: string, label: string, unit: string, help: string, note?: string,
 *   min: number, max: number, step: number, value: number | undefined, placeholder?: string,
 *   restarts?: boolean, live?: boolean, disabled?: boolean, view?: boolean, before?: () => void,
 *   usual?: [number, number],
 *   patch: ((v: number) => any) | null}} Row
 */

const degree = Math.PI / 180;
const liveInterval = 120; // ms between two changes sent by a dragged live slider

/**
 * A scene field's schema by its path ("potential.deformation.C": the abc branch's).
 * @param {any} schema
 * @param {string} path
 */
function schemaField(schema, path) {
  const [section, ...rest] = path.split(".");
  let spec = schema.properties[section];
  for (const key of rest) {
    if (key !== "deformation" && spec.oneOf)
      spec = spec.oneOf.find((/** @type {any} */ b) => b.properties?.kind?.const === "abc");
    spec = spec.properties[key];
  }
  return spec;
}

// How a schema unit is shown: a pure number ("1") says so; an angle the UI shows in degrees.
const displayUnit = (/** @type {string} */ unit) => ({ 1: "pure number", rad: "degrees" })[unit] ?? unit;

/**
 * A field's words and, where the field table gives one, the span it usually takes (x-usual): the
 * slider's ends, and beyond them a typed value is questioned before it is sent.
 * @param {any} spec
 */
function words(spec) {
  /** @type {[number, number] | undefined} */
  const usual = spec["x-usual"];
  // (A field without one: its allowed range, within ±5.)
  const min = usual?.[0] ?? Math.max(-5, spec.minimum ?? spec.exclusiveMinimum ?? -5);
  const max = usual?.[1] ?? Math.min(5, spec.maximum ?? spec.exclusiveMaximum ?? 5);
  return { label: spec.title, unit: displayUnit(spec["x-unit"]), help: spec.description, min, max, usual };
}

/** @param {AppState} s */
function physicalRows(s) {
  /** @param {string} path */
  const described = (path) => {
    const spec = schemaField(s.schema, path);
    return { field: path, ...words(spec) };
  };
  const current = s.current;
  const initial = current.initial;
  const start = s.start ?? {};
  const rigid = current.body.model === "rigid";
  const deformation = current.potential?.deformation;
  const surface = current.surface;
  const heading = initial.heading ?? start.heading;
  /** @param {number} speed @param {number} heading */
  const speedHeading = (speed, heading) => ({ initial: { speed, heading } });
  /** @type {Row[]} */
  const rows = [
    {
      key: "spin",
      ...described("initial.spin"),
      step: 0.05,
      restarts: true,
      value: initial.spin ?? start.spin,
      patch: (v) => ({ initial: { spin: v } }),
    },
    {
      key: "speed",
      ...described("initial.speed"),
      step: 0.05,
      restarts: true,
      value: initial.speed ?? start.speed,
      patch: (v) => speedHeading(v, heading ?? Math.PI / 2),
    },
    {
      key: "heading",
      ...described("initial.heading"),
      min: -180,
      max: 180,
      step: 1,
      restarts: true,
      value: heading === undefined ? undefined : heading / degree,
      patch: (v) => speedHeading(initial.speed ?? start.speed ?? 0.5, v * degree),
    },
    {
      key: "lambda",
      ...described("initial.lambda"),
      step: 0.05,
      restarts: true,
      value: initial.lambda ?? start.lambda,
      patch: (v) => ({ initial: rigid ? { lambda: v, mu: v } : { lambda: v } }),
    },
  ];
  if (!rigid)
    rows.push({
      key: "mu",
      ...described("initial.mu"),
      step: 0.05,
      restarts: true,
      value: initial.mu ?? start.mu,
      patch: (v) => ({ initial: { mu: v } }),
    });
  // The curvature dial: one slider from the sphere through the plane to the hyperbolic plane. The
  // run continues through K = 0 (the body keeps its place, velocity and frame); the picture
  // switches to the conformal view, the one view that exists on every surface and is continuous in K.
  const byK = curvatureForm(surface);
  const resolved = /** @type {import("./surface.js").ResolvedSurface} */ (s.surface);
  const varies = curvatureVaries(s.schema, resolved.kind);
  if (varies) rows.push(...shapeRows(s));
  else
    rows.push(
      {
        key: "curvature",
        ...described("surface.curvature"),
        step: 0.01,
        live: true,
        // K as given in the K form, else the server's σ/R².
        value: byK ? surface.curvature : resolved.curvature,
        before: showConformal,
        patch: (v) => ({ surface: { curvature: v, kind: null, radius: null } }),
      },
      {
        key: "radius",
        ...described("surface.radius"),
        step: 0.05,
        disabled: byK,
        // Derived from K, the row says so before the field's own description.
        note: byK
          ? resolved.kind === "plane"
            ? "From the curvature: K = 0 is the flat plane, which has no radius."
            : "From the curvature: R = 1/√|K|. To set R, pick the surface above."
          : "",
        value: shownRadius(surface, resolved),
        placeholder: "none",
        patch: (v) => ({ surface: { radius: v } }),
      },
      {
        key: "gamma",
        ...described("potential.radial.gamma"),
        step: 0.01,
        value: current.potential?.radial?.gamma ?? 0,
        patch: (v) => ({ potential: { radial: { gamma: v } } }),
      },
    );
  if (!rigid && (!deformation || deformation.kind === "abc"))
    rows.push({
      key: "C",
      ...described("potential.deformation.C"),
      step: 0.05,
      value: deformation?.C ?? 0,
      patch: (v) => ({ potential: { deformation: { kind: "abc", C: v } } }),
    });
  // (In the conformal view the size is in lengths, so the picture does not change with K.)
  rows.push({
    key: "scale",
    label: "Body size on screen",
    unit:
      s.view.kind === "conformal"
        ? "lengths"
        : formulaField(s)
          ? "× the surface's feature, 1/√max|K|"
          : varies
            ? "× the tube, width or neck"
            : "surface radii",
    min: 0.05,
    max: 1,
    step: 0.01,
    view: true,
    help: "Only the picture: how large the body's ellipse is drawn (+ and − keys in 2-D views).",
    value: s.view.scale,
    patch: null,
  });
  return rows;
}

/**
 * Where the curvature varies: the surface's own parameters (the schema's surface fields that
 * belong to its kind), gravity along −z and translational friction; each restarts the run.
 * @param {AppState} s
 * @returns {Row[]}
 */
function shapeRows(s) {
  const kind = /** @type {import("./surface.js").ResolvedSurface} */ (s.surface).kind;
  const current = s.current;
  const fields = s.schema.properties.surface.properties;
  /** @type {Row[]} */
  const rows = Object.entries(fields)
    .filter(
      ([, spec]) =>
        /** @type {any} */ (spec)["x-surfaces"]?.includes(kind) && /** @type {any} */ (spec).type === "number",
    )
    .map(([key, spec]) => ({
      key,
      field: `surface.${key}`,
      ...words(spec),
      step: 0.05,
      restarts: true,
      value: current.surface?.[key] ?? /** @type {any} */ (spec).default,
      patch: (/** @type {number} */ v) => ({ surface: { [key]: v } }),
    }));
  // A formula's parameters (surface.parameters), each a slider over a range about its value.
  const parameters = /** @type {Record<string, number>} */ (current.surface?.parameters ?? {});
  const parameterSpec = fields.parameters;
  for (const [name, value] of Object.entries(parameters)) {
    const reach = Math.max(5, 2 * Math.abs(value));
    rows.push({
      key: `parameter-${name}`,
      field: `surface.parameters.${name}`,
      label: name,
      unit: "",
      help: `The formula's parameter ${name}. ${parameterSpec?.description ?? ""}`,
      min: value < 0 ? -reach : 0,
      max: reach,
      step: 0.01,
      restarts: true,
      value,
      patch: (/** @type {number} */ v) => ({ surface: { parameters: { [name]: v } } }),
    });
  }
  const height = current.potential?.height;
  if (height?.kind !== "spring") {
    const gravity = s.schema.properties.potential.properties.height.oneOf.find(
      (/** @type {any} */ b) => b.properties?.kind?.const === "gravity",
    ).properties.g;
    rows.push({
      key: "gravity",
      field: "potential.height.g",
      ...words(gravity),
      step: 0.01,
      restarts: true,
      value: height?.g ?? 0,
      patch: (v) => ({ potential: { height: { kind: "gravity", g: v } } }),
    });
  }
  const drag = s.schema.properties.friction.properties.translational;
  rows.push({
    key: "friction",
    field: "friction.translational",
    ...words(drag),
    step: 0.01,
    restarts: true,
    value: current.friction?.translational ?? 0,
    patch: (v) => ({ friction: { translational: v } }),
  });
  return rows;
}

/** @type {Map<string, (row: Row) => void>} each row's update, by key */
const updates = new Map();

/** @param {AppState} s @param {AppState} b */
export function renderPhysical(s, b) {
  if (!s.current || !s.surface || !s.schema) return;
  if (
    s.current === b.current &&
    s.start === b.start &&
    s.view.kind === b.view.kind &&
    s.view.scale === b.view.scale &&
    s.schema === b.schema &&
    $("physical").childElementCount
  )
    return;
  const form = $("physical");
  const rows = physicalRows(s);
  const keys = [formulaField(s)?.key ?? "", ...rows.map((r) => r.key)].join(",");
  if (form.dataset.keys === keys) {
    for (const row of rows) updates.get(row.key)?.(row);
    $("phys-surface").value = s.surface.kind;
    updateFormulaRow(s);
    return;
  }
  form.dataset.keys = keys;
  clear(form);
  updates.clear();
  form.append(
    el("h2", { text: "Physics" }),
    el("p", {
      class: "note",
      text: "↺: changing it restarts the run at t = 0. The others change the run from now on.",
    }),
    surfaceKindRow(s),
  );
  const formula = formulaRow(s);
  if (formula) form.append(formula);
  for (const row of rows) form.append(physicalRow(row));
}

/**
 * A scene field's title from the field table ("Distance r" for initial.r), or the path itself where
 * the schema has none (a companion's field, a path the page does not know).
 * @param {string} path
 */
function titleOf(path) {
  try {
    return schemaField(store.get().schema, path)?.title ?? path;
  } catch {
    return path;
  }
}

/** @param {Row} spec */
function physicalRow(spec) {
  const id = `phys-${spec.key}`;
  const row = el("div", { class: "phys", "data-key": spec.key, "data-field": spec.field });
  const label = el("label", { for: id, text: spec.label + (spec.restarts ? " ↺" : "") });
  const range = el("input", {
    type: "range",
    min: spec.min,
    max: spec.max,
    step: spec.step,
    id: `${id}-range`,
    "aria-label": `${spec.label} slider`,
  });
  // A text field with its own parser (edits.js typedValue): a number field drops a decimal comma.
  const number = el("input", {
    type: "text",
    inputmode: "decimal",
    autocomplete: "off",
    spellcheck: "false",
    class: "number",
    id,
    name: `phys.${spec.key}`,
  });
  const unit = el("span", { class: "unit", text: spec.unit });
  const help = el("small", { class: "help", id: `${id}-help` });
  // Help on demand: shown by its button, not on hover or focus (a row that grows under the pointer
  // moved the field a triple-click aimed at, and the typed digits went nowhere).
  const helpButton = el("button", {
    type: "button",
    class: "help-toggle",
    "aria-expanded": "false",
    "aria-controls": help.id,
    "aria-label": `What ${spec.label} means`,
    text: "?",
  });
  helpButton.addEventListener("click", () => {
    const open = row.classList.toggle("help-open");
    helpButton.setAttribute("aria-expanded", String(open));
  });
  const error = el("span", { class: "error", id: `${id}-error`, role: "alert" });
  // The buttons of a question about a typed value (below): while shown, the field keeps the text.
  const confirm = el("span", { class: "confirm", hidden: true });
  const helpText = () => (spec.note ? `${spec.note} ` : "") + spec.help;
  help.textContent = helpText();
  for (const input of [range, number]) {
    input.setAttribute("aria-describedby", `${help.id} ${error.id}`);
    input.title = helpText();
  }
  // What this code last wrote into the number field: Chrome fires a trusted change when a focused
  // field is left with a value other than the one it had on focus, even one the code wrote (a drag
  // of the slider); that is not the user's edit, and sent later it would undo a newer change.
  let written = "";
  const fill = (/** @type {number | string} */ v) => (written = number.value = String(v));
  const show = (/** @type {number | undefined} */ v) => {
    const known = v !== undefined && v !== null && Number.isFinite(Number(v));
    fill(known ? Number(Number(v).toPrecision(6)) : "");
    number.placeholder = known ? "" : (spec.placeholder ?? "from the rates");
    range.value = known ? v : (spec.min + spec.max) / 2;
  };
  const enable = () => {
    range.disabled = number.disabled = Boolean(spec.disabled);
    row.classList.toggle("derived", Boolean(spec.disabled));
  };
  show(spec.value);
  enable();
  const apply = async (/** @type {number} */ v) => {
    const edit = begin(error);
    if (!Number.isFinite(v)) {
      refused(edit, "a number, please");
      return;
    }
    if (spec.before) spec.before();
    if (spec.view) {
      store.update((s) => withView(s, { scale: v }));
      refused(edit, "");
      return;
    }
    try {
      await applyChange(/** @type {(v: number) => any} */ (spec.patch)(v), edit);
    } catch (e) {
      // The row was rebuilt by nothing (the change was refused): its message stays beside it, and
      // the value in force comes back, unless the row was edited again meanwhile (edits.js).
      // A refusal that names another field (a curvature of 1e9 put the start past the south pole:
      // "initial.r: …") says first which change of this control it refuses.
      // In the field table's words, not its paths: the control's own label, the other field's title.
      const error = /** @type {any} */ (e).problem?.errors?.[0];
      const message = error?.reason ? `${titleOf(error.field)}: ${error.reason}` : /** @type {Error} */ (e).message;
      const own = spec.field && error?.field === spec.field;
      const plain = own ? `${spec.label}: ${error.reason}` : `${spec.label} = ${v} not applied: ${message}`;
      if (refused(edit, plain)) show(spec.value);
    }
  };
  // A live row (the curvature dial) sends while it is dragged, at most one change in flight and
  // one every liveInterval ms, the latest value winning; the slider is not moved under the
  // pointer by the answers meanwhile. A value already sent or in force is not queued: the
  // release's change event repeats the last input's, and queued while the interval runs out it
  // would be sent after whatever changed meanwhile (the surface select's restart) and undo it.
  let sending = false;
  /** @type {number | null} */
  let pending = null;
  /** @type {number | undefined} */
  let sent;
  const live = async (/** @type {number} */ v) => {
    if (sending) {
      pending = v === sent ? null : v;
      return;
    }
    if (v === sent && v === spec.value) return;
    sending = true;
    pending = v;
    while (pending !== null) {
      const nextValue = pending;
      pending = null;
      sent = nextValue;
      const started = performance.now();
      await apply(nextValue);
      await sleep(Math.max(0, liveInterval - (performance.now() - started)));
    }
    sending = false;
    if (document.activeElement !== number) show(spec.value);
  };
  // The same row with the parameters now in force (its closures read spec).
  updates.set(spec.key, (nextSpec) => {
    spec = nextSpec;
    if (document.activeElement !== number && !sending && confirm.hidden) show(spec.value);
    help.textContent = helpText();
    unit.textContent = spec.unit;
    for (const input of [range, number]) input.title = helpText();
    enable();
  });
  // The slider's value on its grid of steps (−2 + 200 × 0.01 is 0, not 1e-16).
  const stepped = () => Number(Number(range.value).toFixed(6));
  const typed = () => typedValue(number.value);
  range.addEventListener("input", () => {
    fill(stepped());
    if (spec.live) live(stepped());
  });
  range.addEventListener("change", () => (spec.live ? live(stepped()) : apply(stepped())));
  number.addEventListener("change", () => {
    if (number.value === written) return;
    const t = typed();
    if ("error" in t) {
      // Nothing is sent: the reason beside the field, the value in force back in it.
      if (refused(begin(error), t.error)) show(spec.value);
      return;
    }
    const v = /** @type {number} */ (t.value);
    const send = () => (spec.live ? live(v) : apply(v));
    if (spec.usual && (v < spec.usual[0] || v > spec.usual[1])) question(v, send);
    else send();
  });
  // A typed value beyond the field's usual span (x-usual) is questioned, not sent: the field keeps
  // what was typed, the line beside it says why, and a button sends it (1e9 was taken without a word).
  const question = (/** @type {number} */ v, /** @type {() => void} */ send) => {
    const edit = begin(error);
    const [lo, hi] = /** @type {[number, number]} */ (spec.usual);
    refused(edit, `${spec.label}: ${v} is far from the usual ${lo} to ${hi}${spec.unit ? ` (${spec.unit})` : ""}.`);
    const use = el("button", { type: "button", class: "confirm-use", text: `Use ${v}` });
    const keep = el("button", { type: "button", class: "confirm-keep", text: "Keep the value in force" });
    const close = () => {
      clear(confirm);
      confirm.hidden = true;
      refused(begin(error), "");
    };
    use.addEventListener("click", () => {
      close();
      send();
    });
    keep.addEventListener("click", () => {
      close();
      show(spec.value);
      number.focus();
    });
    clear(confirm);
    confirm.append(use, keep);
    confirm.hidden = false;
  };
  number.addEventListener("input", () => {
    if (!confirm.hidden) (clear(confirm), (confirm.hidden = true));
  });
  row.append(label, range, number, unit, helpButton, help, error, confirm);
  return row;
}

/** The surface's kind; switching restarts the run. @param {AppState} s */
function surfaceKindRow(s) {
  const select = el("select", { id: "phys-surface", name: "phys.surface", "aria-describedby": "phys-surface-help" });
  // Only the kinds some view draws: the views say what they show.
  const drawn = (/** @type {string} */ kind) => !s.views.length || s.views.some((v) => v.surfaces.includes(kind));
  for (const value of surfaceKinds(s.schema).filter(drawn))
    select.add(new Option(surfaceTitle(s.schema, value), value));
  select.value = /** @type {import("./surface.js").ResolvedSurface} */ (s.surface).kind;
  const help = el("small", {
    class: "help",
    id: "phys-surface-help",
    text: "The curved surface the body lives on; switching restarts the run.",
  });
  select.title = help.textContent;
  const error = el("span", { class: "error", id: "phys-surface-error", role: "alert" });
  select.addEventListener("change", async () => {
    // The pick, read now: the last switch's answer, awaited below, redraws the form and puts its
    // kind back in the select (read after it, the torus's answer turned a pick of the
    // pseudosphere into a second torus: lost without a word, under load in CI).
    const kind = select.value;
    const edit = begin(error);
    // The patch names the fields of the scene it replaces, so it is made from the scene the
    // server has: a switch made while the last one's answer was on its way named the sphere's
    // fields on the torus, and the torus's stayed (refused, the select back, under load in CI).
    await earlierAnswered(edit);
    select.value = kind;
    const { current, surface } = store.get();
    try {
      // Fields of the other kinds go (initial.r on a torus); from the curvature form, that form
      // goes and the radius it implied stays (1 from the plane).
      const start = store.get().start ?? {};
      const physical = {
        spin: current.initial.spin ?? start.spin,
        speed: current.initial.speed ?? start.speed,
        heading: current.initial.heading ?? start.heading,
      };
      const patch = surfaceSwitch(store.get().schema, current, kind, physical);
      if (curvatureForm(current.surface) && !curvatureVaries(store.get().schema, kind))
        patch.surface = { kind, radius: surface?.radius ?? 1, curvature: null };
      await applyChange(patch, edit);
    } catch (e) {
      if (refused(edit, /** @type {Error} */ (e).message)) select.value = store.get().surface?.kind;
    }
  });
  return el("div", { class: "phys" }, el("label", { for: "phys-surface", text: "Surface ↺" }), select, help, error);
}
