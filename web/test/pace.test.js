import assert from "node:assert/strict";
import { test } from "node:test";
import { nextPace, pacedSize, paceHigh, paceLow, paceScales } from "../pace.js";

test("fewer frames than a lesson needs: one size smaller, down to half the side", () => {
  assert.equal(nextPace(1, 11), 0.8);
  assert.equal(nextPace(0.8, 20), 0.64);
  assert.equal(nextPace(0.5, 5), 0.5);
  assert.equal(nextPace(1, paceLow), 1);
});

test("enough frames that the next size up would still be smooth: one size larger, up to full", () => {
  assert.equal(nextPace(0.5, 60), 0.64);
  assert.equal(nextPace(1, 60), 1);
  // Between the two thresholds nothing changes: no back and forth.
  for (const fps of [paceLow, 40, paceHigh - 1]) assert.equal(nextPace(0.8, fps), 0.8);
  // The step up costs 1/0.64 of the pixels: at paceHigh the larger picture would still paint > paceLow.
  for (let i = 1; i < paceScales.length; i++)
    assert.ok(paceHigh * (paceScales[i] / paceScales[i - 1]) ** 2 > paceLow + 4);
  assert.equal(nextPace(0.7, 60), 1); // not a scale of the table: treated as full size
});

test("the size asked for: the shown size at full scale, at least 16 a side", () => {
  assert.deepEqual(pacedSize({ width: 1280, height: 757 }, 0.5), { width: 640, height: 379 });
  assert.deepEqual(pacedSize({ width: 1280, height: 757 }, 1), { width: 1280, height: 757 });
  assert.deepEqual(pacedSize({ width: 20, height: 20 }, 0.5), { width: 16, height: 16 });
});
