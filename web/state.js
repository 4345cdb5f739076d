// @ts-check
// The UI's state in one store: every view is a render(state) subscribed here, so a change is made
// in one place (update) and each view redraws what it shows from the state, instead of a dozen
// call sites remembering which views to refresh. No framework: get/update/subscribe is all the
// views need, and a framework would add a build step the embedded, CSP-locked page does not have.

/** @typedef {import("./lifecycle.js").Phase} Phase */

/**
 * What the picture shows: the view, its layers and the camera (null: aimed at the body by the
 * server). yaw and pitch in radians, distance in surface radii, scale in surface radii (lengths in
 * the conformal view).
 * @typedef {{kind: string|null, layers: string[], yaw: number|null, pitch: number|null,
 *   distance: number|null, scale: number, motion: string, hudChosen: boolean}} ViewState
 */

/**
 * The scene holds the parameters at t = 0, current those in force now, timeline the changes since
 * ([{t, patch}]); the session is a pure function of scene + timeline + t, and so is a share link
 * (and the copy kept in sessionStorage that rebuilds a session after a reload or an expiry).
 * @typedef {{
 *   phase: Phase,
 *   id: string|null,
 *   borrowed: string|null,
 *   scene: any, current: any, timeline: Array<{t: number, patch: any}>,
 *   surface: import("./surface.js").ResolvedSurface | null,
 *   t: number, sample: any, start: any,
 *   playing: boolean, rate: number,
 *   preset: string|null, modified: boolean,
 *   view: ViewState,
 *   size: {width: number, height: number, shown?: number}, pace: number,
 *   schema: any, presets: any[], views: any[],
 *   viewParameters: import("./viewparams.js").ViewControls|null,
 * }} AppState
 */

/** @template S @typedef {(state: S, previous: S) => void} Listener */

/**
 * A store of one immutable state: update replaces it by a shallow merge and calls every listener
 * with the new and the previous state (synchronously, in subscription order).
 * @template {object} S
 * @param {S} initial
 */
export function createStore(initial) {
  let state = initial;
  /** @type {Set<Listener<S>>} */
  const listeners = new Set();
  // Changes not yet delivered, [previous, next]: an update made by a listener is delivered after
  // the current round, so every listener sees every change, in order.
  /** @type {Array<[S, S]>} */
  const pending = [];
  let delivering = false;
  return {
    /** @returns {S} */
    get: () => state,
    /**
     * A patch, or a function of the state that returns one.
     * @param {Partial<S> | ((state: S) => Partial<S>)} change
     */
    update(change) {
      const patch = typeof change === "function" ? change(state) : change;
      const previous = state;
      state = { ...state, ...patch };
      pending.push([previous, state]);
      if (delivering) return;
      delivering = true;
      try {
        for (let change = pending.shift(); change; change = pending.shift())
          for (const listener of [...listeners]) listener(change[1], change[0]);
      } finally {
        delivering = false;
        pending.length = 0;
      }
    },
    /**
     * @param {Listener<S>} listener
     * @returns {() => void} unsubscribes
     */
    subscribe(listener) {
      listeners.add(listener);
      return () => {
        listeners.delete(listener);
      };
    },
  };
}

/** @returns {AppState} */
export function initialState() {
  return {
    phase: "idle",
    id: null,
    borrowed: null,
    scene: null,
    current: null,
    surface: null,
    timeline: [],
    t: 0,
    sample: null,
    start: null,
    playing: false,
    rate: 1,
    preset: null,
    modified: false,
    view: {
      kind: null,
      layers: ["surface", "grid", "body", "frame", "trail", "hud", "bending", "drift"],
      yaw: null,
      pitch: null,
      distance: null,
      scale: 0.25,
      motion: "steady", // the 3-D camera while playing: "steady" (stays put) or "follow" (keeps the body centred)
      hudChosen: false,
    },
    size: { width: 640, height: 480 },
    pace: 1, // the fraction of `size` the live picture is asked at while playing (pace.js)
    schema: null,
    presets: [],
    views: [],
    viewParameters: null,
  };
}

/**
 * The view with some of its fields changed.
 * @param {AppState} state
 * @param {Partial<ViewState>} change
 * @returns {Partial<AppState>}
 */
export const withView = (state, change) => ({ view: { ...state.view, ...change } });

/** The app's one store. */
export const store = createStore(initialState());

/**
 * Shows a view: renders it now from the state as it is (against the initial state, so that it
 * draws whatever is already set), then at every change.
 * @param {(state: AppState, previous: AppState) => void} render
 * @returns {() => void} unsubscribes
 */
export function mount(render) {
  render(store.get(), initialState());
  return store.subscribe(render);
}
