// Spinfold's browser UI: everything comes from the API (presets, schema, state, frames); no
// physics here.
import uPlot from "/vendor/uPlot.esm.js";
import { LiveView } from "/live.js";

const api = "/api/v1";
// scene: the parameters at t = 0; current: those in force now; timeline: the changes since
// ([{t, patch}]); the session is a pure function of scene + timeline, and so is a share link.
const ui = {
  id: null, scene: null, current: null, timeline: [], schema: null, presets: [], version: -1, t: 0,
  view: { kind: null, layers: new Set(["surface", "grid", "body", "frame", "trail", "hud"]), yaw: null, pitch: null },
  events: null, live: null, plots: null, series: [[], [], [], [], [], []],
};
const $ = (id) => document.getElementById(id);

class ProblemError extends Error {
  constructor(problem) { super(problem.detail || problem.title); this.problem = problem; }
}

async function call(method, path, body) {
  const options = { method, headers: {} };
  if (body !== undefined) {
    options.headers["Content-Type"] = method === "PATCH" ? "application/merge-patch+json" : "application/json";
    options.body = JSON.stringify(body);
  }
  const res = await fetch(api + path, options);
  if (res.status === 204) return null;
  const data = await res.json();
  if (!res.ok) throw new ProblemError(data);
  return data;
}

function status(text) { $("status").textContent = text; }

// ---- Frames: one live stream per page (web/live.js); a change of view or camera steers it.
function viewParams(width = 640, height = 480) {
  const q = { width, height, view: ui.view.kind, layers: [...ui.view.layers].join(",") };
  if (ui.view.yaw !== null) Object.assign(q, { yaw: ui.view.yaw.toFixed(4), pitch: ui.view.pitch.toFixed(4) });
  return q;
}

function frameQuery(width = 640, height = 480) {
  return `${api}/sessions/${ui.id}/frame.png?${new URLSearchParams(viewParams(width, height))}`;
}

function refreshFrame() {
  if (!ui.id) return;
  const params = viewParams();
  if (ui.view.yaw === null) params.aim = "body";
  ui.live.steer(params);
  $("export-png").href = frameQuery();
}

// ---- State, readouts and plots.
function showState(state) {
  ui.t = state.t;
  const num = (v) => (v === null || v === undefined ? "—" : Number(v).toPrecision(6));
  $("readout").textContent =
    `t = ${num(state.t)}   r = ${num(state.r)}   phi = ${num(state.phi)}   lambda = ${num(state.lambda)}   mu = ${num(state.mu)}\n` +
    `energy = ${num(state.energy)}   energy error = ${num(state.energy_error)}   spin = ${num(state.spin)}   ` +
    `p_phi = ${num(state.p_phi)}   det L = ${num(state.det_L)}   integrator: ${state.integrator}   status: ${state.status}`;
  $("readout").dataset.t = state.t;
  if (state.status !== "ok" && state.status_detail) status(state.status_detail);
  const s = ui.series;
  // Back in time: a restart or reset (a change at the current time keeps the history; the plots
  // mark it). The same time again: the sample after a change replaces the one before it.
  const last = s[0].length ? s[0][s[0].length - 1] : -Infinity;
  if (state.t < last) s.forEach((a) => (a.length = 0));
  else if (state.t === last) s.forEach((a) => a.pop());
  s[0].push(state.t);
  s[1].push(Math.max(Math.abs(state.energy_error ?? 0), 1e-16));
  s[2].push(state.spin);
  s[3].push(state.p_phi);
  s[4].push(state.C_x ?? null);
  s[5].push(state.C_y ?? null);
  $("plot-energy").dataset.from = s[0][0];  // the plotted history's start (browser tests read it)
  if (ui.plots) {
    ui.plots.energy.setData([s[0], s[1]]);
    ui.plots.invariants.setData([s[0], s[2], s[3], s[4], s[5]]);
  }
}

// A session's answer to create, change or reset: its scene, timeline and parameters in force.
function adopt(session) {
  ui.scene = session.scene;
  ui.current = session.current;
  ui.timeline = session.timeline;
  if (ui.plots) { ui.plots.energy.redraw(); ui.plots.invariants.redraw(); }
}

// A dashed line on the plots at every parameter change (the plots keep their history across it).
const changeMarks = {
  hooks: {
    draw: [(u) => {
      const { ctx } = u;
      const { top, height } = u.bbox;
      ctx.save();
      ctx.strokeStyle = "#888";
      ctx.setLineDash([4, 4]);
      ctx.lineWidth = 1;
      for (const change of ui.timeline) {
        const x = Math.round(u.valToPos(change.t, "x", true));
        if (x < u.bbox.left || x > u.bbox.left + u.bbox.width) continue;
        ctx.beginPath();
        ctx.moveTo(x, top);
        ctx.lineTo(x, top + height);
        ctx.stroke();
      }
      ctx.restore();
    }],
  },
};

// Whole decades from 1e-16 (uPlot tick formatting stops there) up to above the largest value: finite, positive, never empty.
function logRange(u, lo, hi) {
  const top = Number.isFinite(hi) && hi > 0 ? hi : 1e-15;
  return [1e-16, Math.max(1e-15, 10 ** Math.ceil(Math.log10(top) + 0.01))];
}

function makePlots() {
  const width = Math.max(260, Math.min(420, ($("side").clientWidth || 360) - 8));
  ui.plots = {
    // Log scale with a range that never collapses (uPlot cannot tick an empty log range).
    energy: new uPlot({ width, height: 160, title: "relative energy error", plugins: [changeMarks],
                        scales: { x: { time: false }, y: { distr: 3, log: 10, range: logRange } },
                        series: [{}, { label: "|ΔH/H|", stroke: "#c40" }] }, [[], []], $("plot-energy")),
    invariants: new uPlot({ width, height: 180, title: "spin, p_φ, C_x, C_y", plugins: [changeMarks], scales: { x: { time: false } },
                            series: [{}, { label: "spin", stroke: "#06c" }, { label: "p_φ", stroke: "#080" },
                                     { label: "C_x", stroke: "#a0a" }, { label: "C_y", stroke: "#aa0" }] },
                          [[], [], [], [], []], $("plot-invariants")),
  };
}

function listen() {
  if (ui.events) ui.events.close();
  ui.events = new EventSource(`${api}/sessions/${ui.id}/events?rate=20`);
  ui.events.addEventListener("state", (e) => showState(JSON.parse(e.data)));
}

// ---- Controls built from the scene's JSON Schema. A change is a PATCH; a refusal shows the
// server's message beside the field and the value goes back.
function fieldFor(path, spec, value) {
  const row = document.createElement("div");
  row.className = "field";
  const label = document.createElement("label");
  label.textContent = path[path.length - 1] + (spec["x-unit"] && spec["x-unit"] !== "1" ? ` [${spec["x-unit"]}]` : "");
  let input;
  if (spec.enum) {
    input = document.createElement("select");
    for (const option of spec.enum) input.add(new Option(option, option));
    input.value = value ?? spec.default;
  } else {
    input = document.createElement("input");
    input.type = "number";
    input.step = "any";
    input.value = value ?? spec.default;
  }
  input.name = path.join(".");
  input.title = spec.description || "";
  label.htmlFor = input.id = "field-" + path.join("-");
  const error = document.createElement("span");
  error.className = "error";
  input.addEventListener("change", async () => {
    const patch = {};
    let node = patch;
    path.slice(0, -1).forEach((key) => (node = node[key] = {}));
    node[path[path.length - 1]] = spec.enum ? input.value : Number(input.value);
    // A deformation field needs its kind: the scene's, or abc when there is none yet.
    if (path[1] === "deformation") node.kind = lookup(ui.current, ["potential", "deformation", "kind"]) ?? "abc";
    try {
      await applyChange(patch, path[0] === "surface" || path[1] === "deformation");
      error.textContent = "";
    } catch (e) {
      error.textContent = e.message;
      input.value = lookup(ui.current, path) ?? spec.default;
    }
  });
  row.append(label, input, error);
  return row;
}

// The deformation potential's kind: none or one of the schema's. A switch is one merge patch that
// sets the new kind and removes the old kind's fields (null), so the server sees one whole object.
function deformationKindField(branches, deformation) {
  const row = document.createElement("div");
  row.className = "field";
  const label = document.createElement("label");
  label.textContent = "deformation kind";
  const input = document.createElement("select");
  input.add(new Option("none", "none"));
  for (const branch of branches) input.add(new Option(branch.properties.kind.const, branch.properties.kind.const));
  input.value = deformation?.kind ?? "none";
  input.name = "potential.deformation.kind";
  label.htmlFor = input.id = "field-potential-deformation-kind";
  const error = document.createElement("span");
  error.className = "error";
  input.addEventListener("change", async () => {
    let replacement = null;
    if (input.value !== "none") {
      replacement = { kind: input.value };
      for (const key of Object.keys(deformation ?? {})) if (key !== "kind") replacement[key] = null;
    }
    try {
      await applyChange({ potential: { deformation: replacement } }, true);
    } catch (e) {
      error.textContent = e.message;
      input.value = deformation?.kind ?? "none";
    }
  });
  row.append(label, input, error);
  return row;
}

// A change of parameters: continues the run from now (a mark on the plots), or restarts it at
// t = 0 when the start or the surface changed; the server says which.
async function applyChange(patch, rebuild) {
  const res = await call("PATCH", `/sessions/${ui.id}`, patch);
  adopt(res);
  showState(res.state);
  if (res.change.kind !== "unchanged") status(res.change.reason);
  if (rebuild || res.change.kind === "restarted") { buildControls(); buildViewControls(); refreshFrame(); }
  return res;
}

function lookup(object, path) { return path.reduce((node, key) => (node ? node[key] : undefined), object); }

function buildControls() {
  const form = $("controls");
  form.textContent = "";
  const props = ui.schema.properties;
  for (const section of ["surface", "body", "initial", "integrator"]) {
    const set = document.createElement("fieldset");
    set.innerHTML = `<legend>${section}</legend>`;
    // A field the scene gave in its other form (the schema's dependentSchemas: spin instead of
    // alpha_dot, speed and heading instead of r_dot and phi_dot) shows empty, not its default.
    const replaced = new Set();
    for (const [given, rule] of Object.entries(props[section].dependentSchemas ?? {}))
      if (lookup(ui.current, [section, given]) !== undefined)
        for (const alternative of rule.not?.anyOf ?? []) alternative.required.forEach((k) => replaced.add(k));
    for (const [key, spec] of Object.entries(props[section].properties)) {
      const field = fieldFor([section, key], spec, lookup(ui.current, [section, key]));
      if (replaced.has(key)) {
        const input = field.querySelector("input");
        input.value = "";
        input.placeholder = "from the physical form";
      }
      set.append(field);
    }
    form.append(set);
  }
  const potential = document.createElement("fieldset");
  potential.innerHTML = "<legend>potential</legend>";
  const gamma = props.potential.properties.radial.properties.gamma;
  potential.append(fieldFor(["potential", "radial", "gamma"], gamma, lookup(ui.current, ["potential", "radial", "gamma"]) ?? 0));
  const deformation = lookup(ui.current, ["potential", "deformation"]);
  potential.append(deformationKindField(props.potential.properties.deformation.oneOf, deformation));
  for (const branch of props.potential.properties.deformation.oneOf) {
    const kind = branch.properties.kind.const;
    if (deformation && deformation.kind !== kind) continue;
    for (const [key, spec] of Object.entries(branch.properties))
      if (key !== "kind") potential.append(fieldFor(["potential", "deformation", key], spec, deformation?.[key]));
    if (!deformation) break;  // offer the abc fields when there is no deformation potential yet
  }
  form.append(potential);
  const degenerate = document.createElement("fieldset");
  degenerate.innerHTML = "<legend>run</legend>";
  degenerate.append(fieldFor(["on_degenerate"], props.on_degenerate, ui.current.on_degenerate));
  form.append(degenerate);
}

// ---- Views and layers.
function buildViewControls() {
  const kinds = { sphere: ["sphere", "disk"], pseudosphere: ["disk", "hyperboloid"], plane: ["plane"] }[ui.current.surface.kind];
  const select = $("view");
  select.textContent = "";
  kinds.forEach((k) => select.add(new Option(k, k)));
  if (!kinds.includes(ui.view.kind)) ui.view.kind = kinds[0];
  select.value = ui.view.kind;
  const layers = $("layers");
  if (!layers.childElementCount)
    for (const layer of ["surface", "grid", "body", "frame", "trail", "hud"]) {
      const label = document.createElement("label");
      label.innerHTML = `<input type="checkbox" name="layer-${layer}" ${ui.view.layers.has(layer) ? "checked" : ""}> ${layer}`;
      label.firstChild.addEventListener("change", (e) => {
        e.target.checked ? ui.view.layers.add(layer) : ui.view.layers.delete(layer);
        refreshFrame();
      });
      layers.append(label);
    }
}

// ---- Sessions.
// A scene from t = 0, or (a share link) a scene with its timeline rebuilt up to `until`.
async function openScene(scene, { until = 0, timeline = [] } = {}) {
  if (ui.id) call("DELETE", `/sessions/${ui.id}`).catch(() => {});
  const created = await call("POST", "/sessions", until > 0 || timeline.length ? { scene, timeline, until } : scene);
  ui.id = created.id;
  ui.view.yaw = ui.view.pitch = null;
  ui.series.forEach((a) => (a.length = 0));
  adopt(created);
  showState(created.state);
  $("explanation").textContent = created.scene.description || "";
  buildControls();
  buildViewControls();
  $("export-state").href = `${api}/sessions/${ui.id}`;
  $("export-csv").href = `${api}/sessions/${ui.id}/trajectory?format=csv`;
  document.querySelectorAll(".preset").forEach((b) => b.classList.toggle("active", b.dataset.name === created.scene.name));
  listen();
  ui.live.open(ui.id, viewParams());
  $("export-png").href = frameQuery();
  status(`session ${ui.id}`);
}

async function buildGallery() {
  const gallery = $("gallery");
  for (const preset of ui.presets) {
    const button = document.createElement("button");
    button.className = "preset";
    button.dataset.name = preset.name;
    button.title = preset.description;
    button.innerHTML = `<img alt=""><b>${preset.name.replaceAll("_", " ")}</b><small></small>`;
    button.querySelector("small").textContent = preset.description;
    button.addEventListener("click", () => openScene(preset.scene));
    gallery.append(button);
  }
  // Thumbnails rendered by the server, one short-lived session at a time.
  for (const preset of ui.presets) {
    try {
      const s = await call("POST", "/sessions", preset.scene);
      await call("POST", `/sessions/${s.id}/advance`, { until: 2 });
      const res = await fetch(`${api}/sessions/${s.id}/frame.png?width=160&height=120&layers=surface,grid,body,trail`);
      const img = gallery.querySelector(`[data-name="${preset.name}"] img`);
      img.src = URL.createObjectURL(await res.blob());
      await call("DELETE", `/sessions/${s.id}`);
    } catch (e) { /* a missing thumbnail is not worth an error */ }
  }
}

// ---- Share: the URL carries the scene, its timeline, the time and the view; opening it rebuilds
// the same run (the same state and picture, trail included).
function shareUrl() {
  const params = new URLSearchParams({ scene: JSON.stringify(ui.scene), timeline: JSON.stringify(ui.timeline),
                                       t: String(ui.t), view: ui.view.kind,
                                       layers: [...ui.view.layers].join(",") });
  return `${location.origin}${location.pathname}#${params}`;
}

function fromHash() {
  if (!location.hash) return null;
  const params = new URLSearchParams(location.hash.slice(1));
  if (!params.has("scene")) return null;
  ui.view.kind = params.get("view");
  if (params.has("layers")) ui.view.layers = new Set(params.get("layers").split(",").filter(Boolean));
  return { scene: JSON.parse(params.get("scene")), until: Number(params.get("t") || 0),
           timeline: JSON.parse(params.get("timeline") || "[]") };
}

// ---- Wiring.
function wire() {
  $("play").onclick = () => call("POST", `/sessions/${ui.id}/play`, { rate: Number($("speed").value) }).catch((e) => status(e.message));
  $("pause").onclick = () => call("POST", `/sessions/${ui.id}/pause`, {});
  $("step").onclick = async () => showState((await call("POST", `/sessions/${ui.id}/advance`, { steps: 10 })).state);
  $("reset").onclick = async () => {
    const res = await call("POST", `/sessions/${ui.id}/reset`, {});
    adopt(res);
    showState(res.state);
    buildControls();
  };
  $("speed").oninput = () => ($("speed-out").textContent = $("speed").value);
  $("speed").onchange = () => call("POST", `/sessions/${ui.id}/pause`, {}).then(() => $("play").onclick());
  $("view").onchange = () => { ui.view.kind = $("view").value; ui.view.yaw = ui.view.pitch = null; refreshFrame(); };
  $("share").onclick = async () => {
    const url = shareUrl();
    history.replaceState(null, "", url);
    try { await navigator.clipboard.writeText(url); } catch (e) { /* the address bar has it */ }
    status("share link in the address bar");
  };
  // Orbit the camera by dragging (3-D views).
  let drag = null;
  $("frame").addEventListener("pointerdown", (e) => {
    if (ui.view.kind !== "sphere" && ui.view.kind !== "hyperboloid") return;
    drag = { x: e.clientX, y: e.clientY, yaw: ui.view.yaw ?? 0.7, pitch: ui.view.pitch ?? 0.45 };
    $("frame").setPointerCapture(e.pointerId);
  });
  $("frame").addEventListener("pointermove", (e) => {
    if (!drag) return;
    ui.view.yaw = drag.yaw - (e.clientX - drag.x) * 0.01;
    ui.view.pitch = Math.max(-1.5, Math.min(1.5, drag.pitch + (e.clientY - drag.y) * 0.01));
    refreshFrame();
  });
  $("frame").addEventListener("pointerup", () => (drag = null));
}

async function main() {
  ui.live = new LiveView($("frame"));
  [ui.schema, ui.presets] = await Promise.all([call("GET", "/schema"), call("GET", "/scenes")]);
  wire();
  makePlots();
  const shared = fromHash();
  const first = shared ? shared.scene : (ui.presets.find((p) => p.name === "spinning_rigid_sphere") || ui.presets[0]).scene;
  await openScene(first, shared ? { until: shared.until, timeline: shared.timeline } : {});
  document.body.dataset.ready = "true";
  buildGallery();
}

main().catch((e) => status(`error: ${e.message}`));
