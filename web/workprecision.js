// @ts-check
// "Which integrator for this scene?": POST /api/v1/work-precision with the session's id starts a job
// on the server that runs each integrator on the scene as it is now (from its start) at tightening
// tolerances or steps, measures its error at T against an independent reference and times it. A
// progress bar follows GET …/{id} (jobs.js); then the plot (the job's SVG), the recommendation,
// and a button that sets the recommended integrator on the session through the app's own PATCH.
// No physics here.
import { api } from "./api.js";
import { el } from "./dom.js";
import { begin, latest, refused } from "./edits.js";
import { jobs } from "./jobs.js";

// 3 significant digits, small ones as 1e-5 (not 0.00001), as the recommendation writes them.
/** @param {number} x */
function short(x) {
  const rounded = Number(x.toPrecision(3));
  return rounded !== 0 && Math.abs(rounded) < 1e-3 ? rounded.toExponential() : String(rounded);
}
// "tol 1e-6", "dt 0.0123": a setting.
const setting = (/** @type {{parameter: string, value: number}} */ p) => `${p.parameter} ${short(p.value)}`;

// Whether the recommended integrator (the object PATCH takes) is what the session runs already:
// each of its fields has the value in force. Then the panel says so instead of offering it.
/** @param {Record<string, unknown>} recommended @param {Record<string, unknown> | undefined} inForce */
export function alreadyInForce(recommended, inForce) {
  return !!inForce && Object.entries(recommended).every(([key, value]) => inForce[key] === value);
}

// Builds the panel in `box`. `app` gives: session() → its id; inForce() → the integrator in force
// now (the session's current scene's); apply(patch, edit) → the app's PATCH of the session (its
// controls and status line follow), a promise.
/**
 * @param {HTMLElement} box
 * @param {{session: () => string | null, inForce: () => Record<string, unknown> | undefined,
 *   apply: (patch: any, edit: import("./edits.js").Edit) => Promise<unknown>}} app
 */
export function setupWorkPrecision(box, app) {
  /** @param {string} id @returns {any} */
  const $ = (id) => box.querySelector(`#${id}`);
  box.append(
    el(
      "details",
      { id: "wp-details" },
      el("summary", { text: "Which integrator for this scene?" }),
      el("p", {
        class: "note",
        id: "wp-about",
        text:
          "Runs each integrator on this scene as it is now, from its start, at tightening tolerances " +
          "or steps; measures its error at time T against an independent reference and times it. " +
          "Seconds to a minute, on the server.",
      }),
      el(
        "div",
        { class: "wp-row" },
        // Each label holds its input, so that a narrow screen wraps them as pairs.
        el(
          "label",
          { text: "Horizon T [time] " },
          el("input", {
            id: "wp-t-end",
            type: "number",
            step: "any",
            min: "0",
            placeholder: "20 periods",
            "aria-describedby": "wp-about",
          }),
        ),
        el(
          "label",
          { text: "Target error " },
          el("input", { id: "wp-target", type: "number", step: "any", min: "1e-15", max: "1", value: "1e-10" }),
        ),
      ),
      el(
        "div",
        { class: "wp-row" },
        el("button", { id: "wp-start", type: "button", text: "Measure the integrators" }),
        el("button", { id: "wp-cancel", type: "button", text: "Cancel", hidden: "" }),
        el("progress", { id: "wp-progress", max: "1", value: "0", hidden: "", "aria-label": "Measuring" }),
        el("span", { id: "wp-status", role: "status" }),
      ),
      el(
        "div",
        { id: "wp-result", hidden: "" },
        el("p", { id: "wp-recommendation" }),
        el(
          "div",
          { class: "wp-row" },
          el("button", { id: "wp-use", type: "button", hidden: "" }),
          el("span", { id: "wp-use-status", role: "status" }),
        ),
        el("img", { id: "wp-plot", alt: "" }),
        el(
          "p",
          { class: "wp-links" },
          el("a", { id: "wp-svg", target: "_blank", text: "Plot (SVG)" }),
          " ",
          el("a", { id: "wp-png", target: "_blank", text: "Plot (PNG)" }),
          " ",
          el("a", { id: "wp-csv", download: "work_precision.csv", text: "Data (CSV)" }),
        ),
      ),
    ),
  );

  /** @type {any} */
  let recommended = null; // the result's recommended setting, with the integrator PATCH takes
  const say = (/** @type {string} */ text) => ($("wp-status").textContent = text);
  const measurements = jobs({
    start: $("wp-start"),
    cancel: $("wp-cancel"),
    progress: $("wp-progress"),
    say,
    every: 300,
    queued: "Waiting for another measurement to finish…",
    running: (job) =>
      job.stage === "reference"
        ? `Computing the reference at T = ${short(job.t_end)}…`
        : `Measuring… ${job.methods_done} of ${job.methods} integrators done`,
    done(job) {
      show(job);
      return `Done: ${job.result.points.length} runs of ${job.methods} integrators over T = ${short(job.t_end)}.`;
    },
    hideProgress: true,
  });

  function body() {
    /** @type {{session: string | null, t_end?: number, target_error?: number}} */
    const out = { session: app.session() };
    const tEnd = $("wp-t-end").value.trim();
    if (tEnd !== "") out.t_end = Number(tEnd);
    const target = $("wp-target").value.trim();
    if (target !== "") out.target_error = Number(target);
    return out;
  }

  /** @param {any} job */
  function show(job) {
    const r = job.result;
    $("wp-recommendation").textContent = r.recommendation;
    recommended = r.recommended;
    const kept = !!recommended && alreadyInForce(recommended.integrator, app.inForce());
    $("wp-use").hidden = !recommended || kept;
    if (recommended) $("wp-use").textContent = `Use ${recommended.method} at ${setting(recommended)}`;
    $("wp-use-status").textContent = kept
      ? `The session runs ${recommended.method} at ${setting(recommended)} already.`
      : "";
    const plot = $("wp-plot");
    plot.hidden = !r.plot_svg;
    if (r.plot_svg) {
      plot.src = r.plot_svg;
      plot.alt =
        `Work-precision plot over T = ${job.t_end}: wall time per unit simulated time against the state ` +
        `error at T, one curve per integrator (the data: ${r.points.length} runs in the CSV)`;
    }
    for (const [id, href] of [
      ["wp-svg", r.plot_svg],
      ["wp-png", r.plot_png],
      ["wp-csv", r.data_csv],
    ]) {
      $(id).hidden = !href;
      if (href) $(id).href = href;
    }
    $("wp-result").hidden = false;
  }

  $("wp-start").onclick = async () => {
    if (!app.session()) return;
    $("wp-result").hidden = true;
    await measurements.start(`${api}/work-precision`, body);
  };

  $("wp-cancel").onclick = () => measurements.cancel();

  // Its answer is shown beside the button like a control's (edits.js: only the latest click's).
  $("wp-use").onclick = async () => {
    if (!recommended) return;
    const chosen = recommended;
    const line = $("wp-use-status");
    const edit = begin(line);
    try {
      await app.apply({ integrator: chosen.integrator }, edit);
      if (latest(edit)) line.textContent = `The session now runs ${chosen.method} at ${setting(chosen)}.`;
    } catch (e) {
      refused(edit, /** @type {Error} */ (e).message);
    }
  };
}
