// The view-parameter consumer (web/viewparams.js): the contract of GET /api/v1/view-parameters
// (fixture below), the page's fallback, and the clamps and units the camera uses.
import assert from "node:assert/strict";
import { test } from "node:test";
import { clampTo, fromContract, toApi } from "../viewparams.js";

// An answer of the route as the contract gives it (angles in degrees here, to check the units).
const answer = {
  parameters: [
    { name: "view", type: "enum", choices: ["sphere", "poincare", "conformal"], default: null, help: "the picture" },
    { name: "yaw", type: "number", unit: "degree", min: -180, max: 180, help: "camera azimuth" },
    { name: "pitch", type: "number", unit: "degree", min: -88.8, max: 88.8, help: "camera elevation" },
    { name: "distance", type: "number", unit: "radii", min: 1.2, max: 100, help: "camera distance" },
    { name: "scale", type: "number", min: 0, max: 10, default: 0.25, help: "body size" },
    { name: "width", type: "integer", unit: "pixel", min: 16, max: 4096, default: 640, help: "frame width" },
  ],
  layers: [
    { name: "surface", default: true, help: "the shaded surface" },
    { name: "actions", default: false, help: "the action variables" },
  ],
  formats: [{ name: "png" }],
};

test("numbers become ranges; angles in degrees are kept in radians and sent in degrees", () => {
  const controls = fromContract(answer);
  assert.equal(controls.source, "server");
  assert.ok(Math.abs(controls.ranges.yaw.max - Math.PI) < 1e-12);
  assert.ok(Math.abs(controls.ranges.pitch.min + (88.8 * Math.PI) / 180) < 1e-12);
  assert.ok(Math.abs(toApi(controls, "yaw", Math.PI / 2) - 90) < 1e-9);
  assert.deepEqual(
    { min: controls.ranges.distance.min, max: controls.ranges.distance.max, toApi: controls.ranges.distance.toApi },
    { min: 1.2, max: 100, toApi: 1 },
  );
  assert.equal(controls.ranges.scale.default, 0.25);
  assert.equal(controls.ranges.yaw.default, null); // none given: the camera is aimed at the body
  assert.equal(controls.ranges.width.max, 4096); // integers are ranges too
  assert.ok(!("view" in controls.ranges)); // an enum is not a range
});

test("the view's choices and the layers with their defaults and help", () => {
  const controls = fromContract(answer);
  assert.deepEqual(controls.views, ["sphere", "poincare", "conformal"]);
  assert.deepEqual(controls.layers, [
    { name: "surface", default: true, help: "the shaded surface" },
    { name: "actions", default: false, help: "the action variables" },
  ]);
});

test("radians stay radians", () => {
  const controls = fromContract({
    parameters: [{ name: "pitch", type: "number", unit: "rad", min: -1.55, max: 1.55 }],
    layers: [],
  });
  assert.equal(controls.ranges.pitch.max, 1.55);
  assert.equal(toApi(controls, "pitch", 0.5), 0.5);
});

test("a parameter without min or max is unbounded on that side", () => {
  const controls = fromContract({ parameters: [{ name: "trail", type: "number", unit: "time", min: 0 }], layers: [] });
  assert.equal(controls.ranges.trail.min, 0);
  assert.equal(controls.ranges.trail.max, Infinity);
  assert.equal(clampTo(controls, "trail", 1e9), 1e9);
});

test("an answer without its lists is an error naming the list", () => {
  assert.throws(() => fromContract({ layers: [] }), /no "parameters" list/);
  assert.throws(() => fromContract({ parameters: [] }), /no "layers" list/);
  assert.throws(() => fromContract(null), /no "parameters" list/);
});

test("clampTo keeps a value within its range, and leaves unnamed ones alone", () => {
  const controls = fromContract(answer);
  assert.equal(clampTo(controls, "distance", 0.5), 1.2);
  assert.equal(clampTo(controls, "distance", 500), 100);
  assert.equal(clampTo(controls, "distance", 3), 3);
  assert.equal(clampTo(controls, "zoom", 1e6), 1e6);
  assert.equal(clampTo(null, "distance", 0.5), 0.5);
});
