import assert from "node:assert/strict";
import { test } from "node:test";
import { LiveView } from "../live.js";

// The browser's pieces LiveView touches, as stubs: a canvas, the frame clock, fetch.
globalThis.requestAnimationFrame = () => 0;
const canvas = /** @type {any} */ ({ dataset: {}, width: 0, height: 0, getContext: () => ({ drawImage() {} }) });

// A fetch that answers the stream at once (a body that never ends until aborted) and holds every
// PATCH until released, recording each request with its signal.
function stubFetch() {
  const patches = [];
  globalThis.fetch = (url, init = {}) => {
    if (init.method !== "PATCH") {
      const body = new ReadableStream({
        start(controller) {
          init.signal?.addEventListener("abort", () => controller.error(new DOMException("aborted", "AbortError")));
        },
      });
      return Promise.resolve(new Response(body, { status: 200 }));
    }
    return new Promise((resolve, reject) => {
      const entry = { url, signal: init.signal, answer: (status) => resolve(new Response(null, { status })) };
      init.signal?.addEventListener("abort", () => reject(new DOMException("aborted", "AbortError")));
      patches.push(entry);
    });
  };
  return patches;
}

const tick = () => new Promise((r) => setTimeout(r, 10));

test("a steer on its way when the page closes the stream is cancelled with it, and nothing more is sent", async () => {
  const patches = stubFetch();
  const live = new LiveView(canvas);
  live.open("s1", { width: 400, height: 300 });
  await tick();
  assert.equal(live.connected, true);
  const steering = live.steer({ yaw: 1 });
  await tick();
  assert.equal(patches.length, 1);
  live.steer({ yaw: 2 }); // waits behind the first
  // The page leaves this stream (a restart, a new session): the server forgets its viewer, so the
  // steer on its way would be answered 404, a console error. It is aborted instead.
  live.close();
  assert.equal(patches[0].signal?.aborted, true, "the steer in flight is cancelled with its stream");
  await steering; // ends quietly
  await tick();
  assert.equal(patches.length, 1, "the waiting steer is not sent to the closed stream");
  assert.equal(live.steering, false);
});

test("a steer answered 404 while its stream reconnects is sent again, not dropped", async () => {
  const patches = stubFetch();
  const live = new LiveView(canvas);
  live.open("s2", { width: 400, height: 300 });
  await tick();
  const steering = live.steer({ yaw: 1 });
  await tick();
  patches[0].answer(404);
  await new Promise((r) => setTimeout(r, 150)); // the first back-off is 100 ms
  assert.equal(patches.length, 2);
  assert.match(patches[1].url, /yaw=1/);
  patches[1].answer(204);
  await steering;
  assert.equal(patches.length, 2);
  live.close();
});
