// @ts-check
// The browser UI's entry point: everything comes from the API (presets, schema, views, view parameters,
// state, frames); no physics here. This file only wires the modules: the store (state.js) holds the
// state, each view renders from it, and the session (session.js) is the one thing that talks to the
// simulation.
import { reportBusyTo, request, retryNow, withRetry } from "./api.js";
import { setupComparisons } from "./comparisons.js";
import { renderControls } from "./controls.js";
import { $ } from "./dom.js";
import { closeFrame, renderExports, setupFrame, viewQuery } from "./frame.js";
import { buildGallery, renderExplanation, renderGalleryMarks, thumbnailInProgress } from "./gallery.js";
import { setupHandles } from "./handles.js";
import { setupKeys } from "./keys.js";
import { setupLesson } from "./lesson.js";
import { renderPhysical } from "./physical.js";
import { setupPlayback } from "./playback.js";
import { setupPlots } from "./plots.js";
import { setupPresentation } from "./presentation.js";
import { renderReadout, say } from "./readout.js";
import { setupRecording } from "./record.js";
import { setupScrub } from "./scrub.js";
import { applyChange, checkSession, firstSession, keepSaved, leave, recover } from "./session.js";
import { shareUrl } from "./share.js";
import { mount, store, withView } from "./state.js";
import { loadViewParameters, setupViewControls } from "./viewcontrols.js";
import { setupWorkPrecision } from "./workprecision.js";

async function main() {
  const embed = setupPresentation();
  reportBusyTo({
    show(text) {
      $("busy").hidden = false;
      $("busy-text").textContent = text;
    },
    hide: () => ($("busy").hidden = true),
  });
  $("busy-retry").onclick = retryNow;
  const [schema, presets, views, viewParameters] = await withRetry("Loading", () =>
    Promise.all([request("GET", "/schema"), request("GET", "/scenes"), request("GET", "/views"), loadViewParameters()]),
  );
  // The layers a session starts with: the server's defaults (a share link or this tab's copy may
  // replace them below).
  const layers = viewParameters.layers.filter((l) => l.default).map((l) => l.name);
  store.update((s) => ({ schema, presets, views, viewParameters, ...withView(s, { layers }) }));

  // The views, each a render(state, previous) of the store.
  for (const render of [renderReadout, renderPhysical, renderControls, renderExplanation, renderGalleryMarks])
    mount(render);
  // The session's lifecycle phase on the page (idle, opening, live, expired, rebuilding), for
  // tests and for looking at a page that misbehaves.
  mount((s, b) => {
    if (s.phase !== b.phase || !document.body.dataset.phase) document.body.dataset.phase = s.phase;
  });
  setupPlayback();
  setupScrub();
  setupHandles();
  setupLesson();
  setupViewControls();
  setupComparisons();
  setupKeys();
  keepSaved();
  // Recording (record.js): the Record panel, given the session, its time and the view.
  setupRecording($("record-panel"), {
    session: () => store.get().id,
    time: () => store.get().t,
    view: () => viewQuery(store.get()),
  });
  // "Which integrator for this scene?" (workprecision.js): its "Use …" is a change like any other.
  setupWorkPrecision($("wp-panel"), {
    session: () => store.get().id,
    inForce: () => store.get().current?.integrator,
    apply: applyChange,
  });
  setupPlots();
  setupFrame(() => checkSession());

  for (const id of ["png-width", "png-height"]) $(id).onchange = () => renderExports();
  $("share").onclick = async () => {
    const url = shareUrl(store.get(), `${location.origin}${location.pathname}${location.search}`);
    history.replaceState(null, "", url);
    try {
      await navigator.clipboard.writeText(url);
    } catch {
      /* the address bar has it */
    }
    say("Share link copied (and in the address bar).");
  };
  addEventListener("pagehide", () => {
    leave([thumbnailInProgress()]);
    closeFrame();
  });
  addEventListener("pageshow", (e) => {
    if (e.persisted && store.get().id) recover().catch((err) => say(err.message));
  });

  await firstSession();
  document.body.dataset.ready = "true";
  if (!embed) buildGallery();
}

main().catch((e) => say(`error: ${e.message}`));
