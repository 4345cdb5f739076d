// @ts-check
// Direct manipulation: while the run is paused, the main body and the tip of its velocity arrow are
// handles on the picture. Dragging the body starts the run again from where it is dropped; dragging
// the arrow's tip starts it again from where the body is, with the velocity drawn. The server says
// where the handles are (GET handles) and what a drop sets (GET drop: render/drag.h inverts the
// view's own projection); the answer goes back in the session's PATCH, as the form's edits do, and
// is refused alike. Keys: Tab to a handle, the arrow keys move it (Shift: finer), and the change is
// sent once they stop (Enter: at once; Esc: put back).
import { request } from "./api.js";
import { $ } from "./dom.js";
import { viewQuery } from "./frame.js";
import { say } from "./readout.js";
import { applyChange, tracked } from "./session.js";
import { mount, store } from "./state.js";

/** @typedef {import("./state.js").AppState} AppState */
/** @typedef {{x: number, y: number}} Point frame pixels, from the top left */
/** @typedef {"body" | "arrow"} Handle */

/** @type {{body: Point | null, arrow: Point | null, text: string} | null} the server's, for `asked` */
let placed = null;
let asked = ""; // the query the handles were asked for
let version = 0; // bumped by every change that can move the handles
/** @type {Point | null} where a dragged or keyed handle is now, before the server has it */
let moving = null;
/** @type {Handle} */
let which = "body";
/** @type {number | undefined} */
let keyTimer;
let previewing = false;
let dragged = false; // the pointer moved since it took hold of a ring
/** @type {Point | null} */
let previewWanted = null;

const keyStep = 8; // CSS pixels per arrow key (Shift: 2)
const keyPause = 500; // ms after the last key before the change is sent

/** Whether the handles belong on the picture: a live, paused run whose picture is now's. @param {AppState} s */
const wanted = (s) =>
  Boolean(s.id && s.views.find((v) => v.name === s.view.kind)?.surfaces.includes(s.surface?.kind)) &&
  s.phase === "live" &&
  !s.playing &&
  $("frame").dataset.scrub === undefined;

/** The query of the picture shown (a paused picture is full size). @param {AppState} s */
const pictureQuery = (s) => new URLSearchParams(/** @type {any} */ (viewQuery(s)));

/**
 * Where the frame's pixels are on the page, within #frame-box: the canvas letterboxes the picture
 * (object-fit: contain) in its box.
 */
function pictureBox() {
  const canvas = /** @type {HTMLCanvasElement} */ ($("frame"));
  const { width, height } = store.get().size;
  const cw = canvas.clientWidth,
    ch = canvas.clientHeight;
  const scale = Math.min(cw / width, ch / height);
  return {
    scale,
    left: canvas.offsetLeft + canvas.clientLeft + (cw - width * scale) / 2,
    top: canvas.offsetTop + canvas.clientTop + (ch - height * scale) / 2,
    width,
    height,
  };
}

/** @param {Point} p frame pixels → CSS pixels in #frame-box */
function toPage(p) {
  const b = pictureBox();
  return { x: b.left + p.x * b.scale, y: b.top + p.y * b.scale };
}

/** @param {number} x @param {number} y CSS pixels in #frame-box → frame pixels, kept in the frame */
function toFrame(x, y) {
  const b = pictureBox();
  return {
    x: Math.min(b.width, Math.max(0, (x - b.left) / b.scale)),
    y: Math.min(b.height, Math.max(0, (y - b.top) / b.scale)),
  };
}

/**
 * The arrow's tip on the page, drawn back along the arrow to within the picture (18 px in) when a
 * long arrow ends outside it: its ring stays on the picture to take hold of.
 * @param {Point} from @param {Point} to CSS pixels in #frame-box
 */
function withinPicture(from, to) {
  const box = pictureBox();
  const lo = { x: box.left + 18, y: box.top + 18 },
    hi = { x: box.left + box.width * box.scale - 18, y: box.top + box.height * box.scale - 18 };
  let f = 1;
  for (const k of /** @type {("x" | "y")[]} */ (["x", "y"])) {
    const d = to[k] - from[k];
    if (to[k] > hi[k] && d > 0) f = Math.min(f, (hi[k] - from[k]) / d);
    if (to[k] < lo[k] && d < 0) f = Math.min(f, (lo[k] - from[k]) / d);
  }
  f = Math.max(0, f);
  return { x: from.x + f * (to.x - from.x), y: from.y + f * (to.y - from.y) };
}

/** The arrow's tip as drawn (withinPicture), in frame pixels; null without an arrow. */
function shownArrow() {
  if (!placed?.body || !placed.arrow) return null;
  const at = withinPicture(toPage(placed.body), toPage(placed.arrow));
  return toFrame(at.x, at.y);
}

/** Draws the handles and the arrow where they are (or hides them). */
function draw() {
  const bodyButton = $("handle-body"),
    arrowButton = $("handle-arrow"),
    svg = $("handles-arrow"),
    tip = $("handle-tip");
  const shown = wanted(store.get()) && placed?.body;
  if (!shown || !placed?.body) {
    bodyButton.hidden = arrowButton.hidden = tip.hidden = true;
    svg.setAttribute("visibility", "hidden");
    return;
  }
  let body = placed.body,
    arrow = placed.arrow;
  if (moving && which === "body" && arrow) arrow = { x: arrow.x + moving.x - body.x, y: arrow.y + moving.y - body.y };
  if (moving && which === "body") body = moving;
  if (moving && which === "arrow") arrow = moving;
  const b = toPage(body);
  Object.assign(bodyButton.style, { left: `${b.x}px`, top: `${b.y}px` });
  bodyButton.hidden = false;
  if (arrow) {
    const a = withinPicture(b, toPage(arrow));
    Object.assign(arrowButton.style, { left: `${a.x}px`, top: `${a.y}px` });
    arrowButton.hidden = false;
    const line = $("arrow-line");
    line.setAttribute("x1", String(b.x));
    line.setAttribute("y1", String(b.y));
    line.setAttribute("x2", String(a.x));
    line.setAttribute("y2", String(a.y));
    svg.setAttribute("visibility", "visible");
  } else {
    arrowButton.hidden = true;
    svg.setAttribute("visibility", "hidden");
  }
  tip.hidden = !moving || !tip.textContent;
  if (!tip.hidden) {
    // Beside the pointer, kept inside the picture's box (a phone's narrow frame).
    const at = toPage(moving ?? body);
    const room = $("frame-box").clientWidth - tip.offsetWidth - 4;
    const left = at.x + 18 <= room ? at.x + 18 : Math.max(4, at.x - 18 - tip.offsetWidth);
    Object.assign(tip.style, { left: `${left}px`, top: `${Math.max(4, at.y - 34)}px` });
  }
}

/** Asks the server where the handles are for the picture shown, newest wins. */
async function ask() {
  const s = store.get();
  if (!wanted(s)) {
    draw();
    return;
  }
  const query = `${s.id}?${pictureQuery(s)}#${version}`;
  if (query === asked) {
    draw();
    return;
  }
  asked = query;
  try {
    const path = `/sessions/${s.id}/handles?${pictureQuery(s)}`;
    const answer = await tracked(path, request("GET", path));
    if (asked !== query) return; // a newer question was asked meanwhile
    placed = { body: answer.body, arrow: answer.arrow, text: "" };
    // For tests and tools: the picture the rings were placed on (its query).
    $("handle-body").dataset.picture = String(pictureQuery(s));
    $("handle-body").title = describe(answer.place, "body");
    $("handle-arrow").title = describe(answer.place, "arrow");
  } catch {
    placed = null; // the session went, or the view cannot say: no handles
  }
  draw();
}

/** The handles' hover text: what they set and what it is now. @param {any} place @param {Handle} handle */
function describe(place, handle) {
  const n = (/** @type {number} */ v) => Number(v.toPrecision(4));
  // The place as the scene gives it: a chart's (r or u, phi), or a point X on a surface with none.
  const where = Array.isArray(place.X)
    ? `X = (${place.X.map(n).join(", ")})`
    : `${"r" in place ? `r = ${n(place.r)}` : `u = ${n(place.u)}`}, phi = ${n(place.phi)}`;
  return handle === "body"
    ? `Drag to start the run here instead (now ${where})`
    : `Drag the tip to change the velocity it starts with (now speed = ${n(place.speed)})`;
}

/** The drop route's address for a drop of the handle taken at `p`. @param {AppState} s @param {Point} p */
function dropPath(s, p) {
  const q = pictureQuery(s);
  q.set("x", p.x.toFixed(2));
  q.set("y", p.y.toFixed(2));
  q.set("handle", which);
  return `/sessions/${s.id}/drop?${q}`;
}

/** What a drop at `p` would set, shown beside the pointer while dragging (one question at a time). */
async function preview() {
  if (previewing || !previewWanted) return;
  const p = previewWanted;
  previewWanted = null;
  previewing = true;
  try {
    const path = dropPath(store.get(), p);
    const answer = await tracked(path, request("GET", path));
    // Simple mode's words (the plain layer): no coordinate names for a class.
    $("handle-tip").textContent = store.get().view.layers.includes("plain") ? answer.plain : answer.text;
  } catch {
    $("handle-tip").textContent = which === "body" ? "off the surface" : "turn the view first";
  } finally {
    previewing = false;
    if (moving) draw();
    preview();
  }
}

/** Sends the drop at `p`: the server's fields in the session's PATCH. @param {Point} p */
async function drop(p) {
  const s = store.get();
  try {
    const path = dropPath(s, p);
    const answer = await tracked(path, request("GET", path));
    if (store.get().id !== s.id || store.get().playing) return;
    await applyChange({ initial: answer.initial });
  } catch (e) {
    // The server's reason alone ("shows no part of the surface …"), without the problem's field
    // and value, which name the frame's pixel.
    const reason = /** @type {any} */ (e).problem?.errors?.[0]?.reason ?? /** @type {Error} */ (e).message;
    say(`Not moved: the drop ${reason}.`);
  } finally {
    moving = null;
    $("handle-tip").textContent = "";
    version++;
    ask();
  }
}

/** @param {Handle} handle */
function setupHandle(handle) {
  const button = $(`handle-${handle}`);
  button.addEventListener("pointerdown", (/** @type {PointerEvent} */ e) => {
    if (!placed) return;
    e.preventDefault();
    e.stopPropagation();
    which = handle;
    button.focus();
    button.setPointerCapture(e.pointerId);
    moving = handle === "body" ? placed.body : placed.arrow;
    dragged = false;
  });
  button.addEventListener("pointermove", (/** @type {PointerEvent} */ e) => {
    if (!moving || which !== handle || !button.hasPointerCapture(e.pointerId)) return;
    const box = $("frame-box").getBoundingClientRect();
    moving = toFrame(e.clientX - box.left, e.clientY - box.top);
    dragged = true;
    previewWanted = moving;
    preview();
    draw();
  });
  // The browser took the pointer (a scroll, another touch): the handle goes back, nothing is sent.
  button.addEventListener("pointercancel", () => {
    if (which !== handle) return;
    moving = null;
    draw();
  });
  button.addEventListener("pointerup", (/** @type {PointerEvent} */ e) => {
    if (!moving || which !== handle) return;
    button.releasePointerCapture(e.pointerId);
    if (dragged) drop(moving);
    else {
      moving = null; // a click (or a tap that focuses the ring) sends nothing
      draw();
    }
  });
  button.addEventListener("keydown", (/** @type {KeyboardEvent} */ e) => {
    const d = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] }[e.key];
    if (!d && e.key !== "Enter" && e.key !== "Escape") return;
    e.preventDefault();
    e.stopPropagation(); // the page's own arrow keys orbit and step
    clearTimeout(keyTimer);
    if (e.key === "Escape") {
      moving = null;
      draw();
      return;
    }
    if (!placed) return;
    if (which !== handle) moving = null;
    which = handle;
    const from = moving ?? (handle === "body" ? placed.body : shownArrow());
    if (!from) return;
    if (!d) {
      if (moving) drop(moving); // Enter
      return;
    }
    const step = (e.shiftKey ? 2 : keyStep) / pictureBox().scale;
    moving = { x: from.x + d[0] * step, y: from.y + d[1] * step };
    const b = pictureBox();
    moving = { x: Math.min(b.width, Math.max(0, moving.x)), y: Math.min(b.height, Math.max(0, moving.y)) };
    previewWanted = moving;
    preview();
    draw();
    const at = moving;
    keyTimer = window.setTimeout(() => drop(at), keyPause);
  });
}

/** @param {AppState} s @param {AppState} b */
function renderHandles(s, b) {
  if (
    s.id !== b.id ||
    s.t !== b.t ||
    s.playing !== b.playing ||
    s.phase !== b.phase ||
    s.scene !== b.scene ||
    s.current !== b.current ||
    s.view !== b.view ||
    s.size !== b.size ||
    s.surface !== b.surface ||
    s.views !== b.views
  ) {
    version++;
    if (!moving) ask();
  }
}

export function setupHandles() {
  setupHandle("body");
  setupHandle("arrow");
  mount(renderHandles);
  new ResizeObserver(draw).observe($("frame"));
  // The scrubber's picture is an earlier one: no handles on it.
  new MutationObserver(() => (wanted(store.get()) ? ask() : draw())).observe($("frame"), {
    attributes: true,
    attributeFilter: ["data-scrub"],
  });
}
