// The store (web/state.js): get, update (a patch or a function of the state), subscribe, and the
// order in which listeners see changes made by listeners.
import assert from "node:assert/strict";
import { test } from "node:test";
import { createStore, initialState, withView } from "../state.js";

test("update merges a patch and keeps the other fields", () => {
  const store = createStore({ a: 1, b: { c: 2 } });
  store.update({ a: 3 });
  assert.deepEqual(store.get(), { a: 3, b: { c: 2 } });
});

test("update takes a function of the state", () => {
  const store = createStore({ n: 1 });
  store.update((s) => ({ n: s.n + 1 }));
  store.update((s) => ({ n: s.n * 10 }));
  assert.equal(store.get().n, 20);
});

test("the state is replaced, never changed in place (views compare by identity)", () => {
  const store = createStore({ n: 1 });
  const before = store.get();
  store.update({ n: 2 });
  assert.notEqual(store.get(), before);
  assert.equal(before.n, 1);
});

test("listeners get the new and the previous state; unsubscribing stops them", () => {
  const store = createStore({ n: 0 });
  const seen = [];
  const stop = store.subscribe((s, b) => seen.push([b.n, s.n]));
  store.update({ n: 1 });
  stop();
  store.update({ n: 2 });
  assert.deepEqual(seen, [[0, 1]]);
});

test("an update made by a listener reaches every listener after the current round, in order", () => {
  const store = createStore({ n: 0 });
  const first = [];
  const second = [];
  store.subscribe((s) => {
    first.push(s.n);
    if (s.n === 1) store.update({ n: 2 });
  });
  store.subscribe((s, b) => second.push([b.n, s.n]));
  store.update({ n: 1 });
  assert.deepEqual(first, [1, 2]);
  // The second listener sees 0→1 before 1→2, although the change to 2 was made during the first round.
  assert.deepEqual(second, [
    [0, 1],
    [1, 2],
  ]);
  assert.equal(store.get().n, 2);
});

test("a listener that throws does not leave the store stuck", () => {
  const store = createStore({ n: 0 });
  let calls = 0;
  const stop = store.subscribe(() => {
    calls++;
    throw new Error("view failed");
  });
  assert.throws(() => store.update({ n: 1 }), /view failed/);
  stop();
  const seen = [];
  store.subscribe((s) => seen.push(s.n));
  store.update({ n: 2 });
  assert.deepEqual(seen, [2]);
  assert.equal(calls, 1);
});

test("withView changes the view and leaves the rest of it", () => {
  const state = initialState();
  const patch = withView(state, { kind: "conformal" });
  assert.equal(patch.view?.kind, "conformal");
  assert.deepEqual(patch.view?.layers, state.view.layers);
  assert.equal(state.view.kind, null); // the state it came from is unchanged
});

test("the initial state: no session, idle, the default layers", () => {
  const state = initialState();
  assert.equal(state.phase, "idle");
  assert.equal(state.id, null);
  assert.ok(state.view.layers.includes("trail"));
  assert.ok(!state.view.layers.includes("actions"));
});

test("mount renders a view at once from the state as it is, then at every change", async () => {
  const { mount, store } = await import("../state.js");
  store.update({ rate: 2 });
  const seen = [];
  const stop = mount((s, b) => seen.push([b.rate, s.rate]));
  store.update({ rate: 3 });
  stop();
  store.update({ rate: 4 });
  assert.deepEqual(seen, [
    [1, 2], // against the initial state: what is already set is drawn
    [2, 3],
  ]);
});
