// @ts-check
// The formula row of the physical controls (physical.js) on a surface given by a formula: its formula
// as text, a menu of the schema's examples, and the refusal shown under the field with the position
// the server names. The parameters are sliders among the physical rows. The rule, the wording and the
// examples are the engine's; this module sends the text and shows the answer.
import { $, el } from "./dom.js";
import { begin, refused } from "./edits.js";
import { examplePatch, formulaField } from "./formula.js";
import { applyChange } from "./session.js";
import { store } from "./state.js";

/** @typedef {import("./state.js").AppState} AppState */
/** @typedef {import("./formula.js").Example} Example */

/** @type {((s: AppState) => void) | null} */
let update = null;

/** The formula row, or null on a surface that has none. @param {AppState} s */
export function formulaRow(s) {
  const field = formulaField(s);
  update = null;
  if (!field) return null;
  const { key, spec } = field;
  const id = "phys-formula";
  const label = el("label", { for: id, text: `${spec.title ?? key} ↺` });
  const input = el("input", {
    type: "text",
    id,
    name: `phys.formula`,
    class: "formula",
    autocomplete: "off",
    spellcheck: "false",
    maxlength: String(spec.maxLength ?? 4096),
    "aria-describedby": `${id}-help ${id}-error`,
  });
  const examples = el("select", { id: `${id}-examples`, name: "phys.formula-examples", "aria-label": "Examples" });
  examples.add(new Option("Examples…", ""));
  /** @type {Example[]} */
  const list = spec["x-examples"] ?? [];
  for (const e of list) examples.add(new Option(e.title, e.name));
  const help = el("small", { class: "help", id: `${id}-help`, text: spec.description ?? "" });
  const error = el("span", { class: "error", id: `${id}-error`, role: "alert" });
  let written = "";
  const show = (/** @type {AppState} */ now) => {
    const text = now.current?.surface?.[key] ?? spec.default ?? "";
    if (document.activeElement !== input) written = input.value = text;
  };
  show(s);
  update = show;
  const send = async (/** @type {any} */ patch, /** @type {() => void} */ undo) => {
    const edit = begin(error);
    try {
      await applyChange(patch, edit);
      refused(edit, "");
    } catch (e) {
      if (refused(edit, /** @type {Error} */ (e).message)) undo();
    }
  };
  input.addEventListener("change", () => {
    if (input.value === written) return;
    const text = input.value;
    // A refused formula stays in the field to be corrected; the reason, with its position, below it.
    send({ surface: { [key]: text } }, () => {});
  });
  examples.addEventListener("change", () => {
    const example = list.find((e) => e.name === examples.value);
    examples.value = "";
    if (!example) return;
    input.value = example.formula;
    help.textContent = `${example.note}. ${spec.description ?? ""}`;
    send(examplePatch(key, example, store.get().current?.surface?.parameters ?? {}), () => show(store.get()));
  });
  return el(
    "div",
    { class: "phys formula-row", "data-key": "formula", "data-field": `surface.${key}` },
    label,
    input,
    examples,
    help,
    error,
  );
}

/** Refreshes the formula row's text from the scene in force (unless it is being edited). @param {AppState} s */
export function updateFormulaRow(s) {
  if (update && $("phys-formula")) update(s);
}
