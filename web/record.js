// @ts-check
// Recording from the browser: the view as shown, over a chosen window of the session's time
// (the last N seconds, or from–to), as WebM, MP4, GIF or a zip of PNGs. POST …/recordings starts a
// job on the server (a copy of the timeline: the live view goes on undisturbed), a progress bar
// follows GET /recordings/{id} (jobs.js), and a download link appears when it is done. No physics
// here.
import { api } from "./api.js";
import { el } from "./dom.js";
import { jobs } from "./jobs.js";

// The "GIF for slides" preset: small enough to paste into slides and chat.
const slidesPreset = { format: "gif", width: 640, height: 480, fps: 15 };

/**
 * @param {string} id
 * @param {number} value
 * @param {Record<string, string>} [attributes]
 */
function numberInput(id, value, attributes = {}) {
  return el("input", { id, type: "number", step: "any", value: String(value), size: "5", ...attributes });
}

// Builds the panel in `box`. `app` gives: session() → its id; time() → its current time; view() →
// the view's query parameters (view, layers, scale, yaw, pitch, distance as shown).
/**
 * @param {HTMLElement} box
 * @param {{session: () => string | null, time: () => number,
 *   view: () => Record<string, string | number>}} app
 */
export function setupRecording(box, app) {
  /** @param {string} id @returns {any} */
  const $ = (id) => box.querySelector(`#${id}`);
  box.append(
    el(
      "details",
      { id: "record-details" },
      el("summary", { text: "Record a video or GIF" }),
      el(
        "div",
        { class: "record-row" },
        el(
          "label",
          {},
          el("input", { type: "radio", name: "record-window", id: "record-last", value: "last", checked: "" }),
          " the last ",
          numberInput("record-seconds", 5, { min: "0" }),
          " units of time",
        ),
        el(
          "label",
          {},
          el("input", { type: "radio", name: "record-window", id: "record-range", value: "range" }),
          " from ",
          numberInput("record-from", 0, { min: "0" }),
          " to ",
          numberInput("record-to", 5, { min: "0" }),
        ),
      ),
      el(
        "div",
        { class: "record-row" },
        el(
          "label",
          { text: "Format " },
          el(
            "select",
            { id: "record-format" },
            el("option", { value: "webm", text: "WebM (web)" }),
            el("option", { value: "mp4", text: "MP4 (slides software)" }),
            el("option", { value: "gif", text: "GIF (slides, chat)" }),
            el("option", { value: "png-zip", text: "PNG frames (zip)" }),
          ),
        ),
        el(
          "label",
          { text: "Size " },
          numberInput("record-width", 640, { min: "16", max: "4096", step: "2" }),
          " × ",
          numberInput("record-height", 480, { min: "16", max: "4096", step: "2" }),
          " px",
        ),
        el("label", { text: "Frames/s " }, numberInput("record-fps", 30, { min: "1", max: "120" })),
        el("label", { text: "Speed " }, numberInput("record-speed", 1, { min: "0" }), "×"),
        el("button", {
          id: "record-slides",
          type: "button",
          title: "GIF, 640×480, 15 frames/s",
          text: "GIF for slides",
        }),
      ),
      el(
        "div",
        { class: "record-row" },
        el("button", { id: "record-start", type: "button", text: "● Record" }),
        el("button", { id: "record-cancel", type: "button", text: "Cancel", hidden: "" }),
        el("progress", { id: "record-progress", max: "1", value: "0", hidden: "" }),
        el("span", { id: "record-status", role: "status" }),
        el("a", { id: "record-download", download: "", hidden: "", text: "Download" }),
      ),
    ),
  );

  const say = (/** @type {string} */ text) => ($("record-status").textContent = text);
  const number = (/** @type {string} */ id) => Number($(id).value);
  const recordings = jobs({
    start: $("record-start"),
    cancel: $("record-cancel"),
    progress: $("record-progress"),
    say,
    every: 250,
    queued: "Waiting for another recording to finish…",
    running: (r) => `Recording… ${Math.round(r.progress * 100)}% of ${r.frames} frames`,
    done(r) {
      const link = $("record-download");
      link.href = r.file;
      link.textContent = `Download ${r.format.toUpperCase()} (${(r.bytes / 1e6).toFixed(2)} MB)`;
      link.hidden = false;
      return `Done: ${r.frames} frames.`;
    },
  });

  $("record-slides").onclick = () => {
    $("record-format").value = slidesPreset.format;
    $("record-width").value = slidesPreset.width;
    $("record-height").value = slidesPreset.height;
    $("record-fps").value = slidesPreset.fps;
  };

  function body() {
    let t_start, t_end;
    if ($("record-last").checked) {
      t_end = app.time();
      t_start = Math.max(0, t_end - number("record-seconds"));
    } else {
      t_start = number("record-from");
      t_end = number("record-to");
    }
    const view = app.view();
    /** @type {Record<string, string | number>} */
    const out = {
      t_start,
      t_end,
      fps: number("record-fps"),
      speed: number("record-speed"),
      width: Math.round(number("record-width")),
      height: Math.round(number("record-height")),
      format: $("record-format").value,
      view: view.view,
      layers: view.layers,
      scale: Number(view.scale),
    };
    for (const k of ["yaw", "pitch", "distance"]) if (view[k] !== undefined) out[k] = Number(view[k]);
    return out;
  }

  $("record-start").onclick = async () => {
    if (!app.session()) return;
    $("record-download").hidden = true;
    await recordings.start(`${api}/sessions/${app.session()}/recordings`, body);
  };

  $("record-cancel").onclick = () => recordings.cancel();
}
