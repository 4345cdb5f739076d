// @ts-check
// The samples and their readouts: each sample (the session's state at a time, from the event
// stream or an answer) into the store and the plots, and the views of the latest: the readout line, the screen-reader summary, the
// action variables. No physics: every number is the server's.
import { $, el, clear } from "./dom.js";
import { addSample, lastTime } from "./plots.js";
import { store } from "./state.js";

/** @param {unknown} v */
export const num = (v) => (v === null || v === undefined ? "—" : Number(v).toPrecision(6));

/**
 * A sample from the event stream, or from an answer (from: "answer"). The stream's samples come in
 * order, so one back in time is a restart or reset; an answer can arrive after the stream has
 * already gone past its time (playing), and then it is older news, not a restart.
 * @param {any} sample
 * @param {{restart?: boolean, from?: "stream" | "answer"}} [how]
 */
export function receive(sample, { restart = false, from = "stream" } = {}) {
  if (from === "answer" && !restart && sample.t < lastTime()) return;
  addSample(sample, restart);
  // A run that stops (status not ok) is shown stopped.
  store.update((s) => ({ sample, t: sample.t, playing: sample.status === "ok" && s.playing }));
  if (sample.status !== "ok" && sample.status_detail) say(sample.status_detail);
}

/** @param {string} text the status line */
export function say(text) {
  $("status").textContent = text;
}

// ---- The action variables J = ∮p dq and frequencies ν = ∂E/∂J of separable scenes (a table;
// "—" with the server's reason on hover where one is undefined, one line where there are none).
const actionRows = [
  ["J_r", "J_r", "radial"],
  ["J_phi", "J_φ", "angular (2π p_φ)"],
  ["J_alpha", "J_α", "spin (2π s)"],
  ["J_beta", "J_β", "vorticity (2π p_β)"],
  ["J_x", "J_x", "deformation x"],
  ["J_y", "J_y", "deformation y"],
];
const frequencyRows = [
  ["r", "ν_r", "of r(t)"],
  ["phi", "ν_φ", "precession of the orbit"],
  ["x", "ν_x", "of x²(t)"],
  ["y", "ν_y", "of y²(t)"],
];

/** @param {any} sample */
function renderActions(sample) {
  const box = clear($("actions"));
  const undefinedWhy = sample.undefined ?? {};
  if (!sample.actions) {
    box.append(
      el("p", { class: "note", text: `No action variables: ${undefinedWhy.actions ?? "not a separable scene"}.` }),
    );
    return;
  }
  /** @param {string} group @param {string[]} row @param {string} unit */
  const line = (group, [key, label, what], unit) =>
    el(
      "tr",
      { title: undefinedWhy[`${group}.${key}`] ?? what },
      el("th", { scope: "row", text: label }),
      el("td", { text: num(sample[group]?.[key]) }),
      el("td", { text: unit }),
    );
  box.append(
    el(
      "table",
      {},
      el("caption", { text: "Action variables and frequencies" }),
      el(
        "tbody",
        {},
        ...actionRows.map((r) => line("actions", r, "mass·length²/time")),
        ...frequencyRows.map((r) => line("frequencies", r, "cycles/time")),
      ),
    ),
  );
}

let announced = 0;

/** @param {import("./state.js").AppState} state @param {import("./state.js").AppState} before */
export function renderReadout(state, before) {
  const s = state.sample;
  if (!s || s === before.sample) return;
  const readout = clear($("readout"));
  // Each "name = value" unbroken (a narrow screen wraps between them, never inside a number); the
  // text is the same as one string's.
  // First, and in simple mode too, what a student compares: the circle's radius measured from the
  // path and the one the theory predicts (the server's line; none where the curvature varies).
  const circle = $("circle-line");
  circle.textContent = s.circle?.line ?? "";
  circle.hidden = !circle.textContent;
  // The place in the surface's chart (r or u, and phi), or where it has none (a formula's) in space.
  const place =
    s.r !== undefined
      ? [`r = ${num(s.r)}`, `phi = ${num(s.phi)}`]
      : s.u !== undefined
        ? [`u = ${num(s.u)}`, `phi = ${num(s.phi)}`]
        : Array.isArray(s.X)
          ? [`X = (${s.X.map(num).join(", ")})`, `K = ${num(s.K)}`]
          : [];
  const pairs = [
    [`t = ${num(s.t)}`, ...place, `lambda = ${num(s.lambda)}`, `mu = ${num(s.mu)}`],
    [
      `energy = ${num(s.energy)}`,
      `energy error = ${num(s.energy_error)}`,
      `spin = ${num(s.spin)}`,
      `p_phi = ${num(s.p_phi)}`,
      `det L = ${num(s.det_L)}`,
      `integrator: ${s.integrator}`,
      `status: ${s.status}`,
    ],
  ];
  pairs.forEach((line, i) => {
    if (i > 0) readout.append("\n");
    line.forEach((text, k) => {
      if (k > 0) readout.append("   ");
      readout.append(el("span", { class: "pair", text }));
    });
  });
  readout.dataset.t = s.t;
  if ("actions" in s) renderActions(s);
  // Screen readers hear a short summary, at most once a second.
  const now = performance.now();
  if (now - announced >= 1000) {
    announced = now;
    const announce = $("announce");
    announce.textContent =
      `time ${Number(s.t).toFixed(2)}, spin ${Number(s.spin).toPrecision(3)}, ` +
      `energy error ${Number(s.energy_error ?? 0).toExponential(1)}, ` +
      `${s.status === "ok" ? (state.playing ? "playing" : "paused") : s.status}`;
    announce.dataset.at = String(now); // when it was written [ms, performance.now()]: what the rule spaces
  }
}
