// @ts-check
// The simulation session: one per page, made from a scene (a preset, a share link, this tab's saved copy) and
// deleted when the page goes away; its lifecycle (lifecycle.js) in the store. Every call on it goes
// through call(), which waits for a session being made and rebuilds a lost one from its scene,
// timeline and time. sessionStorage keeps what rebuilds it (scene, timeline, time, view), so a
// reload re-attaches to the session when the server still has it and rebuilds it bit for bit when
// it does not.
import { api, request, sleep, withRetry } from "./api.js";
import { accepted, begin, told } from "./edits.js";
import { can, next, replacing } from "./lifecycle.js";
import { clearHistory } from "./plots.js";
import { num, receive, say } from "./readout.js";
import { fromHash } from "./share.js";
import { store, withView } from "./state.js";
import { writtenKind } from "./surface.js";

/** @typedef {import("./state.js").AppState} AppState */
/** @typedef {import("./lifecycle.js").LifecycleEvent} LifecycleEvent */

/** @param {LifecycleEvent} event */
const go = (event) => store.update((s) => ({ phase: next(s.phase, event) }));

/** The opening or rebuilding under way (calls wait for it). @type {Promise<void> | null} */
let replacement = null;

/** @param {string} name a preset's name, as its card shows it */
export const presetLabel = (name) => name.replaceAll("_", " ");

// The calls on each session not answered yet. A session the page replaces is deleted only once
// they are: a field's change that the blur of a preset's click fires goes to the old session a
// moment before the new one is made, and under load the old one's DELETE overtook it (a 404).
/** @type {Map<string, Set<Promise<unknown>>>} */
const unanswered = new Map();
/**
 * A call on a session that its DELETE waits for (the handles' questions too: asked a moment before
 * a preset's switch, their 404 was a console error under load).
 * @template T @param {string} path @param {Promise<T>} promise @returns {Promise<T>}
 */
export function tracked(path, promise) {
  const id = /^\/sessions\/([^/?]+)/.exec(path)?.[1];
  if (!id) return promise;
  const calls = unanswered.get(id) ?? new Set();
  unanswered.set(id, calls);
  calls.add(promise);
  const done = () => {
    calls.delete(promise);
    if (!calls.size) unanswered.delete(id);
  };
  promise.then(done, done);
  return promise;
}
/** @param {string} id */
const answered = (id) => Promise.allSettled([...(unanswered.get(id) ?? [])]);

/** Whether an answer is the current session's (an answer of the one a preset replaced is not). @param {any} res */
const current = (res) => !res?.id || res.id === store.get().id;

/**
 * A call on the current session. Made while a scene opens (an edit a moment after a preset's
 * click) it goes to the new session, not the old one being deleted (whose 404 would rebuild the old
 * scene over the new); when the server no longer knows the session it is rebuilt and the call made
 * again on the new one.
 * @param {string} method
 * @param {string} path
 * @param {any} [body]
 */
export async function call(method, path, body) {
  if (replacing(store.get().phase) && replacement) {
    const was = store.get().id;
    await replacement.catch(() => {});
    const id = store.get().id;
    if (was && id !== was) path = path.replace(`/sessions/${was}`, `/sessions/${id}`);
  }
  try {
    return await tracked(path, request(method, path, body));
  } catch (e) {
    const { id } = store.get();
    const own = id && path.startsWith(`/sessions/${id}`);
    if (!own || /** @type {any} */ (e).status !== 404) throw e;
    await recover();
    return request(method, path.replace(id, /** @type {string} */ (store.get().id)), body);
  }
}

/**
 * The store's fields from a session answer (create, change, reset): its scene, timeline and
 * parameters in force, and its play state. A preset whose surface the session no longer has stops
 * being its preset (its text would be wrong). `answer`: the answer to a reset or a change, which
 * does not touch the rate: while paused, the speed chosen here and not yet sent (it waits for
 * Play) stays, even when the answer comes after it was chosen.
 * @param {AppState} s
 * @param {any} session
 * @param {{answer?: boolean}} [how]
 * @returns {Partial<AppState>}
 */
function adopted(s, session, { answer = false } = {}) {
  const rate = answer && !session.playing ? s.rate : (session.rate ?? s.rate);
  const preset = s.presets.find((p) => p.name === s.preset);
  const samePreset = preset && writtenKind(preset.scene.surface) === session.surface.kind;
  return {
    scene: session.scene,
    current: session.current,
    surface: session.surface,
    timeline: session.timeline,
    preset: samePreset ? s.preset : null,
    ...(typeof session.playing === "boolean" ? { playing: session.playing, rate } : {}),
  };
}

/**
 * Shows a session (new, re-attached or rebuilt): the frame, event stream and views follow the store.
 * @param {any} session
 * @param {LifecycleEvent} event "opened" or "rebuilt"
 * @param {{keepView?: boolean}} [how] keepView: the camera and history stay (a rebuild)
 */
function attach(session, event, { keepView = false } = {}) {
  if (!keepView) clearHistory();
  store.update((s) => ({
    phase: next(s.phase, event),
    id: session.id,
    ...(keepView ? {} : withView(s, { yaw: null, pitch: null, distance: null })),
    ...adopted(s, session),
    start: session.state.t === 0 ? session.state : s.start,
  }));
  receive(session.state);
  listen();
}

/** Rebuilds a session the server has lost, once however many calls found it gone. */
export function recover() {
  rebuilding ??= rebuild().finally(() => (rebuilding = null));
  return rebuilding;
}
/** @type {Promise<void> | null} */
let rebuilding = null;
async function rebuild() {
  while (store.get().phase === "opening" && replacement) await replacement.catch(() => {});
  const s = store.get();
  if (can(s.phase, "lost")) go("lost");
  go("rebuild");
  const body = s.t > 0 || s.timeline.length ? { scene: s.scene, timeline: s.timeline, until: s.t } : s.scene;
  const made = withRetry("Rebuilding the session", () => request("POST", "/sessions", body));
  replacement = made.then(() => {});
  let created;
  try {
    created = await made;
  } catch (e) {
    go("failed");
    throw e;
  }
  attach(created, "rebuilt", { keepView: true });
  say(`The session had ended on the server; rebuilt at t = ${num(s.t)} from its scene and timeline.`);
  if (s.playing) await play();
}

/**
 * A scene from t = 0, or (a share link, a reload) a scene with its timeline rebuilt up to `until`.
 * One opening at a time: each replaces the session the previous one made (two clicks in quick
 * succession would otherwise both replace the same old session and leave one of theirs behind).
 * @param {any} scene
 * @param {{until?: number, timeline?: any[], preset?: string | null}} [options]
 */
export async function openScene(scene, options = {}) {
  while (replacing(store.get().phase) && replacement) await replacement.catch(() => {});
  const opening = openSceneNow(scene, options);
  replacement = opening;
  try {
    await opening;
  } finally {
    if (replacement === opening) replacement = null;
  }
}
/** @param {any} scene @param {{until?: number, timeline?: any[], preset?: string | null}} options */
async function openSceneNow(scene, { until = 0, timeline = [], preset = null }) {
  const { id: old, borrowed, phase } = store.get();
  go("open");
  const body = until > 0 || timeline.length ? { scene, timeline, until } : scene;
  let created;
  try {
    created = await withRetry("Opening the scene", () => request("POST", "/sessions", body));
  } catch (e) {
    go(phase === "live" ? "kept" : "failed");
    throw e;
  }
  if (old && old !== created.id && old !== borrowed)
    answered(old)
      .then(() => request("DELETE", `/sessions/${old}`))
      .catch(() => {});
  store.update({ preset, modified: timeline.length > 0, playing: false });
  attach(created, "opened");
  say(preset ? `Opened “${presetLabel(preset)}”.` : "Opened the scene.");
}

/**
 * Re-attaches to a session the server has (a borrowed one, or this tab's after a reload).
 * @param {any} session
 */
function reattach(session) {
  go("open");
  attach(session, "opened");
}

// ---- The event stream: one per page. When it ends (the session expired or was deleted, the
// server restarted, a stream limit), the session is checked: rebuilt if gone, listened to again if not.
/** @type {EventSource | null} */
let events = null;
function listen() {
  if (events) events.close();
  const source = (events = new EventSource(`${api}/sessions/${store.get().id}/events?rate=20`));
  source.addEventListener("state", (e) => receive(JSON.parse(e.data)));
  source.onerror = () => {
    if (source.readyState === EventSource.CLOSED && events === source) checkSession();
  };
}

let checking = false;
/** Asks for the session (rebuilt if the server lost it) and listens again. */
export async function checkSession() {
  if (checking) return;
  checking = true;
  try {
    await call("GET", `/sessions/${store.get().id}`);
    await sleep(1000);
    if (!events || events.readyState === EventSource.CLOSED) listen();
  } catch (e) {
    say(`Lost the connection to the server (${/** @type {Error} */ (e).message}); trying again.`);
    await sleep(2000);
    checking = false;
    return checkSession();
  }
  checking = false;
}

// ---- Play, pause, step, reset: the session's "playing" and "rate" come in every session answer.
export async function play() {
  const { id, rate } = store.get();
  try {
    await call("POST", `/sessions/${id}/play`, { rate });
    store.update({ playing: true });
  } catch (e) {
    say(/** @type {Error} */ (e).message);
  }
}

export async function pause() {
  await call("POST", `/sessions/${store.get().id}/pause`, {});
  store.update({ playing: false });
}

export async function step() {
  if (store.get().playing) await pause();
  receive((await call("POST", `/sessions/${store.get().id}/advance`, { steps: 10 })).state, { from: "answer" });
}

export async function reset() {
  const res = await call("POST", `/sessions/${store.get().id}/reset`, {});
  store.update((s) => ({ ...adopted(s, res, { answer: true }), start: res.state }));
  receive(res.state, { restart: true, from: "answer" });
  say("Back to t = 0 with the parameters in force.");
}

/** The changes sent and not answered yet, by their edit's number. @type {Map<number, Promise<any>>} */
const changing = new Map();

/**
 * Settles once every change sent before this edit has been answered and its answer handled. A
 * refused edit shows the value in force at once, and again then: a good answer to an earlier edit
 * that arrives after the refusal (the server applied it first) changed the value in force.
 * @param {import("./edits.js").Edit} edit
 */
export async function earlierAnswered(edit) {
  await Promise.allSettled([...changing].filter(([n]) => n < edit.n).map(([, p]) => p));
  await Promise.resolve(); // each answer's own handler ran on the same settling, before this one
}

/**
 * A change of parameters (a merge patch): continues the run from now (a mark on the plots), or
 * restarts it at t = 0 when the start, the surface or the comparisons changed; the server says
 * which, and so does the status line. `edit` (edits.js) is the control's numbered edit: its answer
 * speaks for it alone, whatever the order the answers come back in. A good answer clears the
 * refusals of the edits made before it, never one made after it; a refusal is thrown, for the
 * caller to show with refused(edit, …).
 * @param {any} patch
 * @param {import("./edits.js").Edit} [edit]
 * @param {{marks?: boolean}} [options] marks: false for a change the page makes itself (simple
 *   mode's geodesic companion), which does not mark the preset "modified"
 */
export async function applyChange(patch, edit = begin(), { marks = true } = {}) {
  const answer = call("PATCH", `/sessions/${store.get().id}`, patch);
  changing.set(edit.n, answer);
  /** @type {any} */
  let res;
  try {
    res = await answer;
  } finally {
    changing.delete(edit.n);
  }
  if (!current(res)) return res; // the scene it changed was replaced meanwhile
  accepted(edit);
  const restarted = res.change.kind === "restarted";
  store.update((s) => ({
    ...adopted(s, res, { answer: true }),
    modified: s.modified || (marks && res.change.kind !== "unchanged"),
    ...(restarted ? { start: res.state } : {}),
  }));
  receive(res.state, { restart: restarted, from: "answer" });
  if (restarted && told(edit)) say(`Restarted at t = 0: ${res.change.reason}`);
  else if (res.change.kind === "continued" && told(edit))
    say(res.change.reason.charAt(0).toUpperCase() + res.change.reason.slice(1)); // the server's words, whole
  return res;
}

// ---- This tab's copy in sessionStorage.
const storeKey = "spinfold.session";
let saved = 0;

/** @param {AppState} s @param {object} [extra] */
function save(s, extra = {}) {
  saved = performance.now();
  try {
    const { id, scene, timeline, t, playing, rate, preset, modified } = s;
    const view = { kind: s.view.kind, layers: s.view.layers };
    sessionStorage.setItem(
      storeKey,
      JSON.stringify({ id, scene, timeline, t, playing, rate, preset, modified, view, ...extra }),
    );
  } catch {
    /* storage full or disabled: a reload starts afresh */
  }
}

/** Keeps the copy current: at once when what rebuilds the session changes, at most once a second for the time. */
export function keepSaved() {
  store.subscribe((s, b) => {
    if (!s.id || s.phase !== "live") return;
    const changed =
      s.id !== b.id ||
      s.scene !== b.scene ||
      s.timeline !== b.timeline ||
      s.playing !== b.playing ||
      s.rate !== b.rate ||
      s.preset !== b.preset ||
      s.modified !== b.modified ||
      s.view.kind !== b.view.kind ||
      s.view.layers !== b.view.layers;
    if (changed || (s.t !== b.t && performance.now() - saved >= 1000)) save(s);
  });
}

function loadSaved() {
  try {
    return JSON.parse(sessionStorage.getItem(storeKey) || "null");
  } catch {
    return null;
  }
}

/**
 * The page goes away: the copy says the session was deleted, and it is (a borrowed one is not).
 * @param {Array<string | null>} others more sessions of this page to delete (a thumbnail's)
 */
export function leave(others) {
  const s = store.get();
  if (s.id) save(s, { deleted: true });
  for (const id of [s.id, ...others])
    if (id && id !== s.borrowed) fetch(`${api}/sessions/${id}`, { method: "DELETE", keepalive: true }).catch(() => {});
  if (events) events.close();
  events = null;
  if (can(s.phase, "leave")) go("leave");
}

/**
 * The session to show on load: a share link's, this tab's (re-attached, or rebuilt when the server
 * no longer has it), or the default preset.
 */
export async function firstSession() {
  // ?session=ID shows a session someone else made (a notebook's Session.show()): it is borrowed,
  // never deleted by this tab.
  const asked = new URLSearchParams(location.search).get("session");
  if (asked) {
    try {
      const session = await request("GET", `/sessions/${encodeURIComponent(asked)}`);
      store.update({ borrowed: session.id });
      reattach(session);
      say("Showing a shared session: changes here change it for everyone who shows it.");
      return;
    } catch (e) {
      if (/** @type {any} */ (e).status !== 404) throw e;
      say("That session is gone; opening the default scene.");
    }
  }
  const shared = fromHash(location.hash);
  if (shared === "damaged") say("The share link is damaged; opening the default scene.");
  else if (shared) {
    store.update((s) => withView(s, shared.view));
    await openScene(shared.scene, {
      until: shared.until,
      timeline: shared.timeline,
      preset: shared.scene.name ?? null,
    });
    if (shared.modified) store.update({ modified: true }); // changed before its run began
    return;
  }
  const mine = loadSaved();
  if (mine?.scene) {
    store.update((s) => ({
      ...withView(s, { kind: mine.view?.kind ?? null, ...(mine.view?.layers ? { layers: mine.view.layers } : {}) }),
      rate: mine.rate ?? 1,
    }));
    // A session this tab deleted as it went away is rebuilt; one it could not delete (a crash, a
    // lost request) is re-attached to when the server still has it.
    if (!mine.deleted) {
      try {
        const session = await request("GET", `/sessions/${mine.id}`);
        store.update({ preset: mine.preset, modified: Boolean(mine.modified) });
        reattach(session);
        store.update({ playing: Boolean(mine.playing) });
        say("Re-attached to this tab's session.");
        return;
      } catch (e) {
        if (/** @type {any} */ (e).status !== 404) throw e;
      }
    }
    await openScene(mine.scene, { until: mine.t, timeline: mine.timeline, preset: mine.preset });
    store.update({ modified: Boolean(mine.modified) });
    if (mine.playing) await play();
    say(`Rebuilt this tab's session at t = ${num(mine.t)}.`);
    return;
  }
  const { presets } = store.get();
  const first = presets.find((p) => p.default) || presets[0]; // the server's default scene
  await openScene(first.scene, { preset: first.name });
}
