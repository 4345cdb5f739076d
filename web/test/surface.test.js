// The surface's two forms (web/surface.js): {kind, radius} and {curvature: K} as the server answers them.
import assert from "node:assert/strict";
import { test } from "node:test";
import { curvatureForm, curvatureOf, radiusOf, surfaceKind } from "../surface.js";

test("the kind and radius form: K = ±1/R², 0 on the plane", () => {
  assert.equal(curvatureOf({ kind: "sphere", radius: 2 }), 0.25);
  assert.equal(curvatureOf({ kind: "pseudosphere", radius: 0.5 }), -4);
  assert.equal(curvatureOf({ kind: "plane", radius: 3 }), 0);
  assert.equal(radiusOf({ kind: "sphere", radius: 2 }), 2);
  assert.equal(curvatureForm({ kind: "sphere" }), false);
});

test("the curvature form: K is the server's number; the kind follows its sign", () => {
  assert.equal(curvatureOf({ curvature: -0.5 }), -0.5);
  assert.equal(surfaceKind({ curvature: -0.5 }), "pseudosphere");
  assert.equal(surfaceKind({ curvature: 4 }), "sphere");
  assert.equal(radiusOf({ curvature: 4 }), 0.5);
  assert.equal(surfaceKind({ curvature: 0 }), "plane");
  assert.equal(radiusOf({ curvature: 0 }), undefined); // the plane has no radius in this form
});

test("a curvature below the engine's flat threshold is the plane", () => {
  assert.equal(surfaceKind({ curvature: 1e-25 }), "plane");
  assert.equal(surfaceKind({ curvature: -1e-12 }), "pseudosphere");
});

test("no surface is the default sphere of radius 1", () => {
  assert.equal(surfaceKind(undefined), "sphere");
  assert.equal(curvatureOf({}), 1);
});
