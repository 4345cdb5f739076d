// @ts-check
// Smooth playback on a slow machine: while the run plays, the live picture is asked at a fraction
// of its shown size (the canvas scales it up) when fewer frames are painted than a lesson needs.
// On a 2-core machine decoding a 1280×757 JPEG takes Chromium ~30 ms, a quarter of that at half the
// side, and the browser, renderer and encoder share the cores: a smaller picture keeps the motion
// smooth where the full one would be a slide show. Paused, the picture is full size (the lossless
// still frame). Pure: the rule alone; frame.js measures and steers.

/** The fractions of the shown size tried, largest first (each ~0.64 of the pixels before). */
export const paceScales = [1, 0.8, 0.64, 0.5];
/** Painted frames/s below which the picture gets smaller. */
export const paceLow = 24;
/**
 * Painted frames/s from which it gets larger again: the next size up costs 1/0.64 as many pixels,
 * so it is tried only where it would still paint ~30 (no back and forth at the edge).
 */
export const paceHigh = 47;

/**
 * The fraction of the shown size to ask for next, from the painted frames/s measured at `scale`.
 * @param {number} scale the fraction in use (one of paceScales)
 * @param {number} painted frames painted per second over the last measurement, while playing
 * @returns {number}
 */
export function nextPace(scale, painted) {
  const i = Math.max(0, paceScales.indexOf(scale));
  if (painted < paceLow && i + 1 < paceScales.length) return paceScales[i + 1];
  if (painted >= paceHigh && i > 0) return paceScales[i - 1];
  return paceScales[i];
}

/**
 * The size asked for at a fraction of the shown one (at least 16 a side; the shown size at 1).
 * @param {{width: number, height: number}} size
 * @param {number} scale
 */
export const pacedSize = (size, scale) =>
  scale === 1
    ? size
    : { width: Math.max(16, Math.round(size.width * scale)), height: Math.max(16, Math.round(size.height * scale)) };
