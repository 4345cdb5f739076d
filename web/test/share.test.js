// Share links (web/share.js): a state's link read back gives the same scene, timeline, time and view.
import assert from "node:assert/strict";
import { test } from "node:test";
import { fromHash, shareUrl } from "../share.js";
import { initialState } from "../state.js";

test("a share link round-trips the scene, timeline, time and view", () => {
  const state = {
    ...initialState(),
    scene: { surface: { curvature: -0.5 }, body: { model: "rigid" } },
    timeline: [{ t: 1.5, patch: { initial: { spin: 2 } } }],
    t: 3.25,
    view: { ...initialState().view, kind: "conformal", layers: ["surface", "trail"] },
  };
  const url = shareUrl(state, "http://host/?embed=1");
  assert.ok(url.startsWith("http://host/?embed=1#"));
  const shared = fromHash(new URL(url).hash);
  assert.ok(shared && shared !== "damaged");
  assert.deepEqual(shared.scene, state.scene);
  assert.deepEqual(shared.timeline, state.timeline);
  assert.equal(shared.until, 3.25);
  assert.deepEqual(shared.view, { kind: "conformal", layers: ["surface", "trail"] });
  assert.equal(shared.modified, false);
});

// A preset changed at t = 0 (its timeline empty) opened "selected", not "modified" (issue 34).
test("a share link says whether its preset was changed", () => {
  const changed = { ...initialState(), scene: { name: "spinning_rigid_sphere" }, timeline: [], modified: true };
  const shared = fromHash(new URL(shareUrl(changed, "http://host/")).hash);
  assert.ok(shared && shared !== "damaged");
  assert.equal(shared.modified, true);
  assert.equal(new URL(shareUrl({ ...changed, modified: false }, "http://host/")).hash.includes("modified"), false);
});

test("no fragment, or one without a scene, is no share link", () => {
  assert.equal(fromHash(""), null);
  assert.equal(fromHash("#frame"), null);
});

test("a damaged link says so", () => {
  assert.equal(fromHash("#scene=%7Bnot-json"), "damaged");
});
