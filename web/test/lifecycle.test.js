// The session lifecycle (web/lifecycle.js): the paths a session takes, and the events refused.
import assert from "node:assert/strict";
import { test } from "node:test";
import { can, next, phases, replacing } from "../lifecycle.js";

/** The phase after a run of events from idle. */
const after = (...events) => events.reduce((phase, event) => next(phase, event), "idle");

test("a scene opens: idle → opening → live", () => {
  assert.equal(next("idle", "open"), "opening");
  assert.equal(after("open", "opened"), "live");
});

test("a lost session is rebuilt: live → expired → rebuilding → live", () => {
  assert.equal(after("open", "opened", "lost"), "expired");
  assert.equal(after("open", "opened", "lost", "rebuild"), "rebuilding");
  assert.equal(after("open", "opened", "lost", "rebuild", "rebuilt"), "live");
});

test("a rebuild that fails leaves the session expired (tried again at the next call)", () => {
  assert.equal(after("open", "opened", "lost", "rebuild", "failed"), "expired");
});

test("a scene that fails to open: idle again, or live on the old session when there was one", () => {
  assert.equal(after("open", "failed"), "idle");
  assert.equal(after("open", "opened", "open", "kept"), "live");
});

test("another scene opened over a live or expired session", () => {
  assert.equal(after("open", "opened", "open"), "opening");
  assert.equal(after("open", "opened", "lost", "open", "opened"), "live");
});

test("a page left and shown again from the back/forward cache is rebuilt", () => {
  assert.equal(after("open", "opened", "leave"), "idle");
  assert.equal(after("open", "opened", "leave", "lost", "rebuild", "rebuilt"), "live");
});

test("events that cannot happen are errors naming the event and the phase", () => {
  assert.throws(() => next("idle", "opened"), /"opened" cannot happen while idle/);
  assert.throws(() => next("live", "rebuilt"), /"rebuilt" cannot happen while live/);
  assert.throws(() => next("opening", "open"), /"open" cannot happen while opening/);
  assert.equal(can("rebuilding", "lost"), false); // a second 404 during a rebuild is the same loss
  assert.equal(can("live", "lost"), true);
});

test("calls wait while a session is being made, and only then", () => {
  assert.deepEqual(
    phases.filter((p) => replacing(p)),
    ["opening", "rebuilding"],
  );
});

test("every phase can be reached from idle and can reach live", () => {
  const events = ["open", "opened", "failed", "kept", "lost", "rebuild", "rebuilt", "leave"];
  const reach = (from) => {
    const seen = new Set([from]);
    for (const phase of seen) for (const e of events) if (can(phase, e)) seen.add(next(phase, e));
    return seen;
  };
  assert.deepEqual([...reach("idle")].sort(), [...phases].sort());
  for (const phase of phases) assert.ok(reach(phase).has("live"), phase);
});
