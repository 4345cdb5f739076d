// @ts-check
// The edits of the session's parameters and what the page says about them, one rule in one place.
// Answers come back in any order (a slow good answer after a quick refusal), so every edit is
// numbered as it is made, and an answer speaks only for its own edit:
// - a refusal is shown in the message line of the control that made the edit, and the value goes
//   back, only while that edit is the control's latest (a later edit of the control decides);
// - a good answer clears the refusals of the edits made before it (their values went back; the
//   newer good edit supersedes them), never the refusal of an edit made after it;
// - the status line says the answer to the newest edit that says one, never an older edit's answer
//   that arrives after a newer one's.
// No physics, requests or imports here (a pure module, unit-tested in test/edits.test.js):
// session.js's applyChange sends the edits.

/**
 * One edit: its number in the page's order of edits, and the message line (a `.error` element) of
 * the control that made it; null for one whose refusal goes to the status line (a comparison).
 * @typedef {{n: number, line: HTMLElement | null}} Edit
 */

/** The number of the last edit made. */
let made = 0;
/** Each control's latest edit, by its message line. @type {WeakMap<HTMLElement, number>} */
const latestOf = new WeakMap();
/** The lines that show a refusal, with the edit it was for. @type {Map<HTMLElement, number>} */
const shown = new Map();
/** The newest edit whose answer the status line said (0: none yet). */
let said = 0;

/**
 * A new edit by the control with this message line: from now on the control's older edits no
 * longer write into the line.
 * @param {HTMLElement | null} [line]
 * @returns {Edit}
 */
export function begin(line = null) {
  const edit = { n: ++made, line };
  if (line) latestOf.set(line, edit.n);
  return edit;
}

/**
 * Whether this edit is still its control's latest (an edit without a line is always its own latest).
 * @param {Edit} edit
 */
export const latest = (edit) => !edit.line || latestOf.get(edit.line) === edit.n;

/**
 * The edit was refused (by the server, or by the page before sending it: not a number): its
 * message in the control's line (`""` clears it), when the edit is still the control's latest.
 * Returns whether it was shown, that is whether the control should show its value in force again.
 * (An edit without a line says its refusal in the status line: see told.)
 * @param {Edit} edit
 * @param {string} message
 */
export function refused(edit, message) {
  if (!edit.line || !latest(edit)) return false;
  const line = shownLine(edit.line);
  line.textContent = message;
  if (message) shown.set(line, edit.n);
  else shown.delete(line);
  return true;
}

/**
 * The line a message for this control goes to: itself, or, where the form was rebuilt while the
 * edit was answered (a surface switch rebuilds the physics rows), the new line of the same id, so
 * that a refusal is not written into a line no longer on the page.
 * @param {HTMLElement} line
 */
function shownLine(line) {
  if (line.isConnected !== false || !line.id) return line;
  return globalThis.document?.getElementById(line.id) ?? line;
}

/**
 * The edit was accepted: the refusals of the edits made before it go, those of later edits stay.
 * @param {Edit} edit
 */
export function accepted(edit) {
  for (const [line, n] of shown)
    if (n < edit.n) {
      line.textContent = "";
      shown.delete(line);
    }
}

/**
 * Whether the status line may say the answer to this edit: not when it already says the answer to
 * a newer edit. A yes counts as said.
 * @param {Edit} edit
 */
export function told(edit) {
  if (edit.n < said) return false;
  said = edit.n;
  return true;
}

// A decimal number as a person writes it: digits with one decimal mark, a point or a comma ("0.5",
// "0,5", ",5"), an optional sign and exponent. Not hexadecimal, "Infinity" or thousands separators.
const decimal = /^[+-]?(\d+([.,]\d*)?|[.,]\d+)(e[+-]?\d+)?$/i;

/**
 * What a typed field would send: a finite number, or, where a matrix may stand instead (`matrix`),
 * a JSON number or a non-empty array of them, nested. A decimal comma is the decimal mark ("0,5" is
 * 0.5: a European teacher's value, which a number field on an English page read as 5); a text with
 * two marks ("1,000.5", "1.000,5") is refused, not guessed. An empty, partial or non-numeric text,
 * or one past a double's range (`1e400`), sends nothing: `error` says what to enter instead, and the
 * session keeps its value (`Number("")` is 0, and JSON turns Infinity into null).
 * @param {string} text
 * @param {boolean} [matrix]
 * @returns {{value: number | any[]} | {error: string}}
 */
export function typedValue(text, matrix = false) {
  const trimmed = text.trim();
  /** @type {(v: unknown) => boolean} */
  const finite = (v) =>
    typeof v === "number" ? Number.isFinite(v) : Array.isArray(v) && v.length > 0 && v.every(finite);
  if (!matrix || !trimmed.startsWith("[")) {
    if ((trimmed.match(/[.,]/g) ?? []).length > 1)
      return { error: `enter one decimal mark, a point or a comma (got ${trimmed})` };
    const value = decimal.test(trimmed) ? Number(trimmed.replace(",", ".")) : NaN;
    if (Number.isFinite(value)) return { value };
  } else {
    try {
      const value = JSON.parse(trimmed);
      if (finite(value)) return { value };
    } catch {
      // not JSON: said below
    }
  }
  const what = matrix ? "enter a number or a matrix such as [[0.6, 0.1], [0.1, 0.3]]" : "enter a number";
  return { error: trimmed === "" ? what : `${what} (got ${trimmed})` };
}
