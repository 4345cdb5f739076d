// @ts-check
// The session's lifecycle: one state machine instead of flags scattered over the code,
//   idle ──open──▶ opening ──opened──▶ live ──lost──▶ expired ──rebuild──▶ rebuilding ──rebuilt──▶ live
// A call made while a session is opening or rebuilding waits for it (it belongs to the new one); a
// 404 on the session (expired after 30 minutes idle, deleted, a server restarted without its store)
// is "lost", and the session is rebuilt from its scene, timeline and time. Pure: no DOM, no fetch.

/** @typedef {"idle" | "opening" | "live" | "expired" | "rebuilding"} Phase */
/** @typedef {"open" | "opened" | "failed" | "kept" | "lost" | "rebuild" | "rebuilt" | "leave"} LifecycleEvent */

/** @type {Record<Phase, Partial<Record<LifecycleEvent, Phase>>>} */
const transitions = {
  idle: { open: "opening", lost: "expired" }, // lost: a page shown again from the back/forward cache
  opening: { opened: "live", failed: "idle", kept: "live" }, // kept: the open failed, the old session stays
  live: { open: "opening", lost: "expired", leave: "idle" },
  expired: { rebuild: "rebuilding", open: "opening", leave: "idle" },
  rebuilding: { rebuilt: "live", failed: "expired", leave: "idle" },
};

/** @type {readonly Phase[]} */
export const phases = /** @type {Phase[]} */ (Object.keys(transitions));

/**
 * The phase after `event`, or an Error naming both when the event cannot happen in that phase.
 * @param {Phase} phase
 * @param {LifecycleEvent} event
 * @returns {Phase}
 */
export function next(phase, event) {
  const to = transitions[phase]?.[event];
  if (!to) throw new Error(`session lifecycle: "${event}" cannot happen while ${phase}`);
  return to;
}

/**
 * Whether `event` can happen in `phase`.
 * @param {Phase} phase
 * @param {LifecycleEvent} event
 */
export const can = (phase, event) => Boolean(transitions[phase]?.[event]);

/**
 * A session is being made: calls wait for it, their session id is the new one.
 * @param {Phase} phase
 */
export const replacing = (phase) => phase === "opening" || phase === "rebuilding";
