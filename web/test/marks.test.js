// The plots' change labels (web/marks.js): never two overlapping.
import assert from "node:assert/strict";
import { test } from "node:test";
import { labelled } from "../marks.js";

test("changes far apart are each labelled", () => {
  assert.deepEqual([...labelled([10, 100, 200], 50)], [0, 1, 2]);
});

test("a burst of changes (a dragged dial) gets one label per label's width", () => {
  const xs = Array.from({ length: 20 }, (_, i) => 100 + 5 * i); // every 5 px
  const kept = [...labelled(xs, 42)].map((i) => xs[i]);
  assert.deepEqual(kept, [100, 145, 190]);
  for (let k = 1; k < kept.length; ++k) assert.ok(kept[k] - kept[k - 1] >= 42);
});

test("no changes, no labels", () => {
  assert.equal(labelled([], 40).size, 0);
});
