// The numbered edits (web/edits.js): whatever the order their answers come back in, an answer
// speaks for its own edit only.
import assert from "node:assert/strict";
import { test } from "node:test";
import { accepted, begin, latest, refused, told, typedValue } from "../edits.js";

// A control's message line as edits.js uses it.
const line = () => /** @type {HTMLElement} */ (/** @type {unknown} */ ({ textContent: "" }));

test("an earlier edit's late good answer leaves another control's later refusal", () => {
  const r = line(),
    mass = line();
  const first = begin(r),
    second = begin(mass);
  assert.equal(refused(second, "body.mass: must be > 0"), true);
  accepted(first);
  assert.equal(mass.textContent, "body.mass: must be > 0");
});

test("the same control: a late good answer leaves the later refusal, a late refusal is not shown", () => {
  const mass = line();
  const good = begin(mass),
    bad = begin(mass);
  assert.equal(refused(bad, "must be > 0"), true);
  accepted(good);
  assert.equal(mass.textContent, "must be > 0");
  const bad2 = begin(mass),
    good2 = begin(mass);
  accepted(good2);
  assert.equal(mass.textContent, "", "the newer good edit clears the older refusal");
  assert.equal(latest(bad2), false);
  assert.equal(refused(bad2, "must be > 0"), false, "the late refusal is not the control's to show");
  assert.equal(mass.textContent, "");
});

test("a good answer clears the refusals of earlier edits, of any control", () => {
  const mass = line(),
    gamma = line();
  const bad = begin(mass);
  refused(bad, "must be > 0");
  accepted(begin(gamma));
  assert.equal(mass.textContent, "");
});

test("an empty message clears the control's own line only", () => {
  const mass = line(),
    scale = line();
  refused(begin(mass), "must be > 0");
  assert.equal(refused(begin(scale), ""), true);
  assert.equal(mass.textContent, "must be > 0");
});

test("the status line says the newest answered edit, not an older one that comes after it", () => {
  const older = begin(),
    newer = begin();
  assert.equal(told(newer), true);
  assert.equal(told(older), false);
  assert.equal(told(newer), true, "the same edit may say more");
  assert.equal(told(begin()), true);
});

test("a typed field sends a finite number or matrix, and nothing for empty, partial or huge text", () => {
  assert.deepEqual(typedValue("0.25"), { value: 0.25 });
  assert.deepEqual(typedValue(" -3e-2 "), { value: -0.03 });
  assert.deepEqual(typedValue("[[0.6, 0.1], [0.1, 0.3]]", true), {
    value: [
      [0.6, 0.1],
      [0.1, 0.3],
    ],
  });
  assert.deepEqual(typedValue("0.5", true), { value: 0.5 });
  assert.deepEqual(typedValue(""), { error: "enter a number" }, "Number('') is 0: never sent");
  assert.deepEqual(typedValue("   "), { error: "enter a number" });
  assert.deepEqual(typedValue("1e"), { error: "enter a number (got 1e)" });
  assert.deepEqual(typedValue("abc"), { error: "enter a number (got abc)" });
  assert.deepEqual(typedValue("1e400"), { error: "enter a number (got 1e400)" });
  assert.deepEqual(typedValue("1e400", true), {
    error: "enter a number or a matrix such as [[0.6, 0.1], [0.1, 0.3]] (got 1e400)",
  });
  for (const text of ["[]", "[[1, null]]", '"1"', "[[0.6, 0.1], [0.1,", "true"])
    assert.ok("error" in typedValue(text, true), text);
});

test("a decimal comma is the decimal mark; two marks, hexadecimal and words are refused", () => {
  assert.deepEqual(typedValue("0,5"), { value: 0.5 }, "a European 0,5 (a number field read 5)");
  assert.deepEqual(typedValue(",25"), { value: 0.25 });
  assert.deepEqual(typedValue("-1,5e-3"), { value: -0.0015 });
  assert.deepEqual(typedValue("0,5", true), { value: 0.5 }, "a number where a matrix may stand");
  assert.deepEqual(typedValue("1,000.5"), { error: "enter one decimal mark, a point or a comma (got 1,000.5)" });
  assert.deepEqual(typedValue("1.000,5"), { error: "enter one decimal mark, a point or a comma (got 1.000,5)" });
  assert.deepEqual(typedValue("5,"), { value: 5 }, "as Number('5.') is");
  for (const text of ["0x10", "Infinity", "1 000", "1e5.5", "+-1"]) assert.ok("error" in typedValue(text), text);
});

test("a refusal for a rebuilt control goes to the new line of the same id, not the detached one", () => {
  const detached = /** @type {HTMLElement} */ (
    /** @type {unknown} */ ({ textContent: "", id: "phys-spin-error", isConnected: false })
  );
  const rebuilt = { textContent: "", id: "phys-spin-error", isConnected: true };
  const saved = globalThis.document;
  globalThis.document = /** @type {any} */ ({
    getElementById: (/** @type {string} */ id) => (id === rebuilt.id ? rebuilt : null),
  });
  try {
    assert.equal(refused(begin(detached), "initial.spin: too large"), true);
    assert.equal(rebuilt.textContent, "initial.spin: too large");
    assert.equal(detached.textContent, "");
  } finally {
    globalThis.document = saved;
  }
});
