// @ts-check
// Where the plots' "change" labels go: beside each change's dashed line, left out where the label
// would overlap the one before it (a dragged dial makes a change every 120 ms, and their labels
// ran into one grey smear). A pure module (unit-tested in test/marks.test.js); plots.js draws.

/**
 * The positions, among the dashed lines' `xs` (ascending, in pixels), whose label is written: the
 * first, then each one at least `width` pixels (the label's width and a gap) right of the last
 * labelled one.
 * @param {number[]} xs
 * @param {number} width
 * @returns {Set<number>} indexes into xs
 */
export function labelled(xs, width) {
  const out = new Set();
  let free = -Infinity;
  xs.forEach((x, i) => {
    if (x < free) return;
    out.add(i);
    free = x + width;
  });
  return out;
}
