// @ts-check
// The plots (uPlot): the energy error |ΔH/H₀| on a log axis, and the conserved quantities, over
// the history of the samples shown; a dashed line at every parameter change in the timeline.
import uPlot from "/vendor/uPlot.esm.js";
import { $ } from "./dom.js";
import { labelled } from "./marks.js";
import { store } from "./state.js";

/** The plotted history: t, |ΔH/H₀|, spin, p_φ, C_x, C_y. @type {Array<Array<number|null>>} */
const series = [[], [], [], [], [], []];
/** @type {{energy: any, invariants: any} | null} */
let plots = null;

/** The last plotted time (−∞ when none). */
export const lastTime = () => {
  const t = series[0];
  return t.length ? /** @type {number} */ (t[t.length - 1]) : -Infinity;
};

/** Forgets the history (a new session). */
export function clearHistory() {
  series.forEach((a) => (a.length = 0));
  draw();
}

/**
 * A sample onto the history. Back in time is a restart or reset (a change at the current time keeps
 * the history; the plots mark it); the same time again replaces the sample before the change.
 * @param {any} sample
 * @param {boolean} restart
 */
export function addSample(sample, restart) {
  const last = lastTime();
  if (restart || sample.t < last) series.forEach((a) => (a.length = 0));
  else if (sample.t === last) series.forEach((a) => a.pop());
  // A long lesson: past 20,000 samples every other one is dropped (the plot keeps its span).
  if (series[0].length >= 20000) series.forEach((a, i) => (series[i] = a.filter((_, k) => k % 2 === 0)));
  const finite = (/** @type {any} */ v) => (Number.isFinite(v) ? v : null);
  series[0].push(sample.t);
  series[1].push(energyPoint(sample.energy_error));
  series[2].push(finite(sample.spin));
  series[3].push(finite(sample.p_phi));
  series[4].push(finite(sample.C_x));
  series[5].push(finite(sample.C_y));
  $("plot-energy").dataset.from = series[0][0]; // the plotted history's start (browser tests read it)
  draw();
}

// At most one redraw per display refresh however fast samples come.
let queued = false;
function draw() {
  if (!plots || queued) return;
  queued = true;
  requestAnimationFrame(() => {
    queued = false;
    if (!plots) return;
    plots.energy.setData([series[0], series[1]]);
    plots.invariants.setData([series[0], series[2], series[3], series[4], series[5]]);
  });
}

// A dashed line on the plots at every parameter change (the plots keep their history across it),
// labelled where the label has room (marks.js).
const changeMarks = {
  hooks: {
    draw: [
      (/** @type {any} */ u) => {
        const { ctx } = u;
        const { top, height } = u.bbox;
        ctx.save();
        ctx.strokeStyle = "#888";
        ctx.setLineDash([4, 4]);
        ctx.lineWidth = 1;
        ctx.fillStyle = "#888";
        ctx.font = `${Math.round(10 * devicePixelRatio)}px system-ui, sans-serif`;
        const xs = store
          .get()
          .timeline.map((/** @type {{t: number}} */ change) => Math.round(u.valToPos(change.t, "x", true)))
          .filter((/** @type {number} */ x) => x >= u.bbox.left && x <= u.bbox.left + u.bbox.width);
        const gap = 3 * devicePixelRatio;
        const named = labelled(xs, ctx.measureText("change").width + 2 * gap);
        xs.forEach((/** @type {number} */ x, /** @type {number} */ i) => {
          ctx.beginPath();
          ctx.moveTo(x, top);
          ctx.lineTo(x, top + height);
          ctx.stroke();
          if (named.has(i)) ctx.fillText("change", x + gap, top + 10 * devicePixelRatio);
        });
        ctx.restore();
      },
    ],
  },
};

// ---- The energy-error axis: |ΔH/H| over whole decades from 10⁻¹⁶ (round-off) up to the decade
// above the largest value (at least 10⁰ once the error passes 10⁻¹); the ticks and their labels are
// ours (uPlot's log ticks need a non-empty, finite, positive range). A zero or round-off error sits
// on the floor; NaN or infinity is left out (a gap), never plotted.
export const energyFloor = 1e-16;
const superscript = (/** @type {number} */ n) =>
  String(n).replace(/[-0-9]/g, (c) => "⁻⁰¹²³⁴⁵⁶⁷⁸⁹"["-0123456789".indexOf(c)]);
/** @param {number} v */
export const decadeLabel = (v) => (v <= energyFloor ? "≤10⁻¹⁶" : `10${superscript(Math.round(Math.log10(v)))}`);

/**
 * The plotted point of an energy error: |e| within [10⁻¹⁶, 10³⁰⁰], null (a gap) when not finite.
 * @param {unknown} error
 * @returns {number | null}
 */
export function energyPoint(error) {
  const e = Math.abs(Number(error));
  if (error === null || error === undefined || !Number.isFinite(e)) return null;
  return Math.min(Math.max(e, energyFloor), 1e300);
}

/**
 * The y range: the floor up to the decade above hi.
 * @param {unknown} _u
 * @param {number} _lo
 * @param {number} hi
 * @returns {[number, number]}
 */
export function energyRange(_u, _lo, hi) {
  const top = Number.isFinite(hi) && hi > energyFloor ? hi : 1e-15;
  let exponent = Math.ceil(Math.log10(top) - 1e-9);
  if (exponent > -1) exponent = Math.max(exponent, 0);
  return [energyFloor, 10 ** Math.max(-15, Math.min(exponent, 300))];
}

// The labels drawn (the browser tests read them from data-ticks).
/** @param {unknown} _u @param {Array<number|null>} splits */
function energyLabels(_u, splits) {
  const labels = splits.map((v) => (v === null ? "" : decadeLabel(v)));
  $("plot-energy").dataset.ticks = labels.filter(Boolean).join(" ");
  return labels;
}

// Decades between the range's ends, every 1, 2, 4 or 8th so that labels do not crowd.
// (uPlot's default filter for log axes drops some splits as null; ours keeps every one we made.)
/** @param {any} u @param {unknown} _axis @param {number} min @param {number} max */
function energySplits(u, _axis, min, max) {
  const lo = Math.max(-16, Math.round(Math.log10(min)));
  const hi = Math.max(lo + 1, Math.round(Math.log10(max)));
  const room = Math.max(2, Math.floor(u.bbox.height / devicePixelRatio / 18));
  let every = 1;
  while ((hi - lo) / every > room) every *= 2;
  const splits = [];
  for (let e = hi; e >= lo; e -= every) splits.unshift(10 ** e);
  if (splits[0] !== 10 ** lo) splits.unshift(10 ** lo);
  return splits;
}

// Units in the legend: s and p_φ are angular momenta, C_x and C_y energies (own axis, right).
const angularMomentum = "mass·length²/time";
const energyUnit = "mass·length²/time²";

/** Makes both plots in the side panel; they follow its width and redraw at every change of the timeline. */
export function setupPlots() {
  const width = Math.max(260, Math.min(420, ($("side").clientWidth || 360) - 8));
  const axisStyle = {
    stroke: "#778",
    grid: { stroke: "rgba(128,128,128,0.25)" },
    ticks: { stroke: "rgba(128,128,128,0.4)" },
  };
  plots = {
    energy: new uPlot(
      {
        width,
        height: 170,
        title: "energy error |ΔH/H₀| (from the last change)",
        plugins: [changeMarks],
        scales: { x: { time: false }, y: { distr: 3, log: 10, range: energyRange } },
        axes: [
          { ...axisStyle, label: "time" },
          {
            ...axisStyle,
            size: 56,
            splits: energySplits,
            filter: (/** @type {unknown} */ _u, /** @type {number[]} */ splits) => splits,
            values: energyLabels,
          },
        ],
        series: [{ label: "t" }, { label: "|ΔH/H₀|", stroke: "#c40", width: 1.5 }],
      },
      [[], []],
      $("plot-energy"),
    ),
    invariants: new uPlot(
      {
        width,
        height: 200,
        title: "conserved quantities",
        plugins: [changeMarks],
        scales: { x: { time: false }, am: {}, en: {} },
        axes: [
          { ...axisStyle, label: "time" },
          { ...axisStyle, scale: "am", label: "angular momentum", size: 56 },
          { ...axisStyle, scale: "en", side: 1, label: "energy", size: 56, grid: { show: false } },
        ],
        series: [
          { label: "t" },
          { label: `spin s (${angularMomentum})`, stroke: "#06c", scale: "am" },
          { label: `p_φ (${angularMomentum})`, stroke: "#080", scale: "am", dash: [6, 3] },
          { label: `C_x (${energyUnit})`, stroke: "#a0a", scale: "en" },
          { label: `C_y (${energyUnit})`, stroke: "#b80", scale: "en", dash: [2, 3] },
        ],
      },
      [[], [], [], [], []],
      $("plot-invariants"),
    ),
  };
  new ResizeObserver(() => {
    if (!plots) return;
    const w = Math.max(260, Math.min(480, $("side").clientWidth - 8));
    if (Math.abs(w - plots.energy.width) > 4)
      for (const p of Object.values(plots)) p.setSize({ width: w, height: p.height });
  }).observe($("side"));
  store.subscribe((state, before) => {
    if (plots && state.timeline !== before.timeline) for (const p of Object.values(plots)) p.redraw();
  });
}
