// The surface's forms (web/surface.js): what the UI reads off a scene's surface and the server's
// resolution of it.
import assert from "node:assert/strict";
import { test } from "node:test";
import { curvatureForm, shownRadius, writtenKind } from "../surface.js";

test("a scene written with kind and radius: its kind", () => {
  assert.equal(writtenKind({ kind: "pseudosphere", radius: 2 }), "pseudosphere");
  assert.equal(curvatureForm({ kind: "sphere" }), false);
});

test("a scene written with K: the kind of its sign, the plane at 0", () => {
  assert.equal(writtenKind({ curvature: -0.5 }), "pseudosphere");
  assert.equal(writtenKind({ curvature: 4 }), "sphere");
  assert.equal(writtenKind({ curvature: 0 }), "plane");
  assert.equal(curvatureForm({ curvature: 0 }), true);
});

test("no surface is the default sphere", () => {
  assert.equal(writtenKind(undefined), "sphere");
  assert.equal(writtenKind({}), "sphere");
});

test("the radius shown is the server's, except on a plane the dial reached", () => {
  assert.equal(shownRadius({ curvature: -0.25 }, { kind: "pseudosphere", radius: 2, curvature: -0.25 }), 2);
  assert.equal(shownRadius({ curvature: 1e-30 }, { kind: "plane", radius: 1, curvature: 0 }), undefined);
  assert.equal(shownRadius({ kind: "plane", radius: 3 }, { kind: "plane", radius: 3, curvature: 0 }), 3);
});
