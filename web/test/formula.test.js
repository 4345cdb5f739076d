// The formula row's pure parts (web/formula.js): which field a surface's formula is, and the patch an
// example sends.
import assert from "node:assert/strict";
import { test } from "node:test";
import { examplePatch, formulaField } from "../formula.js";

const schema = {
  properties: {
    surface: {
      properties: {
        kind: { enum: ["sphere", "kindF", "kindZ"] },
        F: { type: "string", "x-formula": true, "x-surfaces": ["kindF"] },
        z: { type: "string", "x-formula": true, "x-surfaces": ["kindZ"] },
        radius: { type: "number" },
      },
    },
  },
};

test("the formula field is the one of the surface's kind, none on a surface without a formula", () => {
  assert.equal(formulaField(/** @type {any} */ ({ schema, surface: { kind: "kindF" } }))?.key, "F");
  assert.equal(formulaField(/** @type {any} */ ({ schema, surface: { kind: "kindZ" } }))?.key, "z");
  assert.equal(formulaField(/** @type {any} */ ({ schema, surface: { kind: "sphere" } })), null);
});

test("an example replaces the formula and its parameters, drops the old ones and the box, moves the start", () => {
  const example = {
    name: "egg_crate",
    title: "egg crate",
    formula: "a*sin(x/b)*sin(y/b)",
    parameters: { a: 0.4, b: 1 },
    X: [-2.5, 0.3, 0],
    note: "",
  };
  assert.deepEqual(examplePatch("z", example, { a: 2, h: 0.8 }), {
    surface: { z: "a*sin(x/b)*sin(y/b)", parameters: { a: 0.4, h: null, b: 1 }, bounds: null },
    initial: { X: [-2.5, 0.3, 0] },
  });
});
