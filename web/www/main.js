// The page: files in (picker, drop, ?url=, or the bundled fandisk), bakes in worker.js, the asset
// drawn by the wasm Viewer on WebGPU, the controls, the downloads. Query parameters: url (a file to
// load), any entry of the view and style schemas (azimuth, elevation, edge_width, ...), size (WxH
// canvas pixels), technique and its parameters (hybrid_step, fin_thickness, ...), section_axis
// (x, y, z, -x, -y, -z) and section_at (0 to 1) for the section slider, any entry of the cut,
// display and animation schemas.
import init, {
  animationSchema, bakeSchema, createViewer, cutSchema, displaySchema, edgeClasses, sectionSchema, styleSchema,
  techniques, viewSchema,
} from "./pkg/chamfer_web.js";

const $ = (id) => document.getElementById(id);
const canvas = $("canvas");
const query = new URLSearchParams(location.search);
const MESH = /\.(obj|gltf|glb|ply|ply\.gz|stl|stl\.gz|3mf)$/i;
let CLASSES = [];  // the runtime's class names (edgeClasses()), set at the start

const state = {
  viewer: null,
  asset: null,         // {name, bytes} on screen
  source: null,        // {name, files} of the last bake, for "bake again"
  // The camera's and the look's keys (the view and style schemas') are added by setUpPanel.
  view: {
    technique: query.get("technique") ?? "joined",
    parameters: {},  // the technique's own (setUpControls)
    classes: [],  // all of CLASSES, set at the start
    highlight: "off",
    edge_color: null,
    background: [1, 1, 1, 1],
    section: null,  // [nx, ny, nz, d] from the section slider (sectionPlane)
  },
  framesLeft: 0,
  framesDrawn: 0,
};
// For the browser tests and the curious: what the page holds.
window.chamfer = state;

function showError(message) {
  const box = $("error");
  box.textContent = message;
  box.hidden = false;
  $("status").textContent = "Error";
  document.body.dataset.state = "error";
}

function clearError() {
  $("error").hidden = true;
}

// --- the worker -------------------------------------------------------------------------------
const worker = new Worker("./worker.js", { type: "module" });
let nextId = 0;
const pending = new Map();
worker.onmessage = ({ data }) => {
  const job = pending.get(data.id);
  if (!job) return;
  if (data.progress) return job.progress?.(data.progress);
  pending.delete(data.id);
  data.error ? job.reject(new Error(data.error)) : job.resolve(data.result);
};
worker.onerror = (e) => showError(`The worker failed: ${e.message}`);
function run(message, progress, transfer = []) {
  const id = nextId++;
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve, reject, progress });
    worker.postMessage({ id, ...message }, transfer);
  });
}

// --- loading ----------------------------------------------------------------------------------
// The bake panel's controls, one per entry of the bake schema (the wasm module's, the same table
// chamfer bake's flags and Python's keywords are made from): a checkbox per flag, a number field per
// number or count, empty for the default. The page bakes compact assets unless told otherwise.
const PAGE_DEFAULTS = { compact: true };
function setUpBakeOptions(schema) {
  state.bakeSchema = schema;
  for (const entry of schema) {
    const { label, input } = control(entry, `bake-${entry.name}`, "none");
    input.dataset.kind = entry.kind;
    if (entry.kind === "flag") input.checked = PAGE_DEFAULTS[entry.name] ?? false;
    $("bake-options").append(label);
  }
}

// One schema entry's control: a checkbox for a flag, a number field (within the entry's range)
// for a number or a count, a text field of comma-separated numbers for a list (a colour), labelled
// with its name and titled with its help.
function control(entry, id, placeholder) {
  const label = document.createElement("label");
  label.title = entry.help;
  const input = document.createElement("input");
  input.id = id;
  if (entry.kind === "flag") {
    input.type = "checkbox";
    label.append(input, ` ${entry.name}`);
  } else if (entry.kind === "numbers") {
    input.type = "text";
    input.size = 12;
    input.placeholder = entry.default?.join(",") ?? placeholder;
    label.append(`${entry.name} `, input);
  } else {
    input.type = "number";
    input.step = entry.kind === "count" ? "1" : "any";
    if (entry.range) [input.min, input.max] = entry.range;
    input.placeholder = entry.default ?? placeholder;
    label.append(`${entry.name} `, input);
  }
  return { label, input };
}

// A panel of controls, one per entry of a schema the wasm module exports (the view's: the camera;
// the style's: edge width, samples, the highlight's numbers; the same tables chamfer render's flags
// are made from), each starting at the entry's default or the query parameter of its name and
// setting the view's key of that name. Dragging and zooming on the canvas move the camera's.
const panels = [];
function setUpPanel(schema, container) {
  const prefix = container.replace("-options", "");
  panels.push({ schema, prefix });
  for (const entry of schema) {
    const given = query.get(entry.name);
    state.view[entry.name] = given === null ? entry.default : parseValue(entry, given);
    const { label, input } = control(entry, `${prefix}-${entry.name}`, "default");
    // Empty is the default (null: the camera's distance that frames the model, say).
    input.addEventListener("change", () => {
      state.view[entry.name] = entry.kind === "flag" ? input.checked
        : input.value === "" ? entry.default : parseValue(entry, input.value);
      redraw();
    });
    $(container).append(label);
  }
  state[`${prefix}Schema`] = schema;
  showPanels();
}

// A control's or a query parameter's text as the entry's value: a flag from "true", a list from
// comma-separated numbers, else a number.
function parseValue(entry, text) {
  if (entry.kind === "flag") return text === "true";
  if (entry.kind === "numbers") return text.split(",").map(Number);
  return Number(text);
}

// The panels show the view the page draws.
function showPanels() {
  for (const { schema, prefix } of panels) {
    for (const entry of schema) {
      const input = $(`${prefix}-${entry.name}`);
      const value = state.view[entry.name];
      if (entry.kind === "flag") input.checked = value;
      else if (entry.kind === "numbers") input.value = value === null ? "" : value.join(",");
      else input.value = value === null ? "" : Number(value.toPrecision(6));
    }
  }
}

// The section slider's plane: across the chosen axis (its sign: which side is cut away), at the
// slider's fraction of the model's bounds; null when off. The section schema's `section` value.
function sectionPlane() {
  const axis = $("section-axis").value;
  const bounds = state.viewer?.bounds() ?? [];
  if (axis === "off" || bounds.length !== 6) return null;
  const k = "xyz".indexOf(axis.slice(-1));
  const sign = axis.startsWith("-") ? -1 : 1;
  const at = Number($("section-at").value);
  const offset = bounds[k] + (bounds[k + 3] - bounds[k]) * (sign > 0 ? at : 1 - at);
  const normal = [0, 0, 0];
  normal[k] = sign;
  return [...normal, sign * offset];
}

// "Play": the chosen animation (the view's `animation`, the first when none is chosen) runs on the
// clock, looping, its `time` set each frame as the time field would set it.
function setUpPlayback() {
  const play = $("play");
  let started = 0;
  const step = (now) => {
    if (!play.checked) return;
    const animations = JSON.parse(state.viewer?.animations() ?? "[]");
    const chosen = animations[state.view.animation ?? 0];
    if (chosen) {
      state.view.animation ??= 0;
      state.view.time = ((now - started) / 1000) % Math.max(chosen.duration, 1e-3);
      $("animation-animation").value = state.view.animation;
      $("animation-time").value = state.view.time.toFixed(3);
      redraw();
    }
    requestAnimationFrame(step);
  };
  play.addEventListener("change", () => {
    if (!play.checked) return;
    started = performance.now();
    requestAnimationFrame(step);
  });
}

function setUpSection() {
  const axis = query.get("section_axis");
  if (axis) $("section-axis").value = axis;
  const at = query.get("section_at");
  if (at) $("section-at").value = at;
  const update = () => { state.view.section = sectionPlane(); redraw(); };
  $("section-axis").addEventListener("change", update);
  $("section-at").addEventListener("input", update);
}

function bakeSettings() {
  const settings = {};
  for (const entry of state.bakeSchema) {
    const input = $(`bake-${entry.name}`);
    if (entry.kind === "flag") {
      if (input.checked) settings[entry.name] = true;
    } else if (input.value !== "") {
      settings[entry.name] = Number(input.value);
    }
  }
  return JSON.stringify(settings);
}

// files: [{name, bytes: Uint8Array}]; the first mesh (or .chamfer) among them is opened.
async function open(files) {
  clearError();
  const main = files.find((f) => /\.chamfer$/i.test(f.name)) ?? files.find((f) => MESH.test(f.name));
  if (!main) {
    return showError(`${files.map((f) => f.name).join(", ")}: no mesh or .chamfer among these ` +
      "(OBJ, glTF, GLB, PLY, .ply.gz, STL, 3MF)");
  }
  document.body.dataset.state = "working";
  try {
    if (/\.chamfer$/i.test(main.name)) {
      $("status").textContent = `Reading ${main.name}…`;
      const { report } = await run({ op: "inspect", name: main.name, bytes: main.bytes });
      return show(main.name, main.bytes, report, null);
    }
    state.source = { name: main.name, files };
    const started = performance.now();
    document.body.dataset.state = "baking";
    const result = await run({ op: "bake", name: main.name, files, settings: bakeSettings() },
      (step) => { $("status").textContent = `${main.name}: ${step}…`; });
    document.body.dataset.state = "working";
    const name = main.name.replace(/(\.gz)?$/i, "").replace(/\.[^.]+$/, "") + ".chamfer";
    result.report.page_ms = performance.now() - started;
    result.report.worker_ms = result.ms;
    show(name, result.asset, result.report, main.name);
  } catch (e) {
    showError(e.message);
  }
}

function show(name, bytes, report, from) {
  state.asset = { name, bytes, report };
  $("stats").textContent = JSON.stringify(report, null, 1);
  $("download-asset").disabled = false;
  $("download-svg").disabled = false;
  if (!state.viewer) {
    $("status").textContent = `${name} baked (no WebGPU to draw it)`;
    document.body.dataset.state = "baked";
    return;
  }
  try {
    state.viewer.show(name, bytes);
    const animations = JSON.parse(state.viewer.animations());
    $("animations").textContent = animations.length
      ? animations.map((a, i) => `${i} "${a.name}" ${a.duration.toFixed(2)} s`).join(", ")
      : "none (a still asset)";
    state.view.distance = null;
    state.view.section = sectionPlane();
    const took = report.worker_ms ? ` in ${report.worker_ms.toFixed(0)} ms` : "";
    $("status").textContent = from ? `${from} baked${took}` : `${name}`;
    redraw();
  } catch (e) {
    showError(e.message);
  }
}

async function fetchFile(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  const name = decodeURIComponent(new URL(url, location.href).pathname.split("/").pop() || "file");
  return { name, bytes: new Uint8Array(await response.arrayBuffer()) };
}

async function openUrl(url) {
  try {
    const main = await fetchFile(url);
    const files = [main];
    // A .gltf's buffers and an OBJ's material libraries sit beside it: fetch them too.
    const text = () => new TextDecoder().decode(main.bytes);
    const references = /\.gltf$/i.test(main.name)
      ? (JSON.parse(text()).buffers ?? []).map((b) => b.uri).filter((uri) => uri && !uri.startsWith("data:"))
      : /\.obj$/i.test(main.name)
        ? [...text().matchAll(/^mtllib\s+(.+?)\s*$/gm)].map((m) => m[1])
        : [];
    for (const reference of references) {
      try {
        const file = await fetchFile(new URL(reference, new URL(url, location.href)).href);
        files.push({ ...file, name: reference });
      } catch {
        // The bake names what is missing (a glTF buffer is an error, an OBJ's materials a warning).
      }
    }
    await open(files);
  } catch (e) {
    showError(e.message);
  }
}

async function readFiles(list) {
  return Promise.all([...list].map(async (file) => ({
    name: file.webkitRelativePath || file.name,
    bytes: new Uint8Array(await file.arrayBuffer()),
  })));
}

$("files").addEventListener("change", async (e) => open(await readFiles(e.target.files)));
addEventListener("dragover", (e) => { e.preventDefault(); document.body.classList.add("dragging"); });
addEventListener("dragleave", () => document.body.classList.remove("dragging"));
addEventListener("drop", async (e) => {
  e.preventDefault();
  document.body.classList.remove("dragging");
  open(await readFiles(e.dataTransfer.files));
});

// --- drawing ----------------------------------------------------------------------------------
// The joined technique sizes its lists from what earlier frames read back: a few more frames after
// each change let it settle.
const SETTLE_FRAMES = 4;

function redraw() {
  if (!state.viewer || !state.asset) return;
  const idle = state.framesLeft === 0;
  state.framesLeft = SETTLE_FRAMES;
  if (idle) requestAnimationFrame(frame);
}

function drawNow() {
  state.viewer.setView(JSON.stringify(state.view));
  state.viewer.draw(canvas.width, canvas.height);
  showPanels();
  state.framesDrawn++;
  // Time from the page's start to its first drawn frame, for the benchmarks.
  state.firstFrameMs ??= performance.now();
}

function frame() {
  try {
    drawNow();
  } catch (e) {
    state.framesLeft = 0;
    return showError(e.message);
  }
  state.framesLeft--;
  if (state.framesLeft > 0) {
    requestAnimationFrame(frame);
  } else {
    document.body.dataset.state = "drawn";
  }
}

// Draws a frame and reads the canvas back in the same task (a WebGPU canvas keeps its picture
// only until the task ends): a PNG data URL. For the browser tests.
state.capture = () => {
  drawNow();
  return canvas.toDataURL("image/png");
};

// --- the orbit camera: drag to turn, wheel or pinch to zoom -----------------------------------
const pointers = new Map();
canvas.addEventListener("pointerdown", (e) => {
  canvas.setPointerCapture(e.pointerId);
  pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
});
canvas.addEventListener("pointerup", (e) => pointers.delete(e.pointerId));
canvas.addEventListener("pointercancel", (e) => pointers.delete(e.pointerId));
canvas.addEventListener("pointermove", (e) => {
  const last = pointers.get(e.pointerId);
  if (!last) return;
  if (pointers.size === 1) {
    state.view.azimuth -= (e.clientX - last.x) * 0.4;
    state.view.elevation = Math.max(-89, Math.min(89, state.view.elevation + (e.clientY - last.y) * 0.4));
  } else if (pointers.size === 2) {
    const other = [...pointers.entries()].find(([id]) => id !== e.pointerId)[1];
    const before = Math.hypot(last.x - other.x, last.y - other.y);
    const after = Math.hypot(e.clientX - other.x, e.clientY - other.y);
    if (before > 0 && after > 0) zoom(before / after);
  }
  pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
  redraw();
});
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  zoom(Math.exp(e.deltaY * 0.001));
  redraw();
}, { passive: false });

function zoom(factor) {
  if (!state.viewer || !state.asset) return;
  const current = state.view.distance ?? state.viewer.distance(canvas.width, canvas.height);
  state.view.distance = Math.max(1e-4, current * factor);
}

// --- controls ---------------------------------------------------------------------------------
function hexToLinear(hex) {
  return [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255).concat(1);
}

function setUpControls(list) {
  state.techniques = list;
  const select = $("technique");
  for (const t of list) {
    select.add(new Option(t.name, t.name, false, t.name === state.view.technique));
  }
  // The technique's own parameters (its module's table, each entry's default the preset's): a
  // control each, setting the view's parameters object by the entry's name; query parameters
  // spell them as chamfer render's flags are spelled, prefix first (hybrid_step=3).
  const describe = (fromQuery) => {
    const t = list.find((t) => t.name === select.value);
    $("technique-summary").textContent = t ? t.summary : "";
    state.view.parameters = {};
    $("technique-options").replaceChildren();
    for (const entry of t?.parameters ?? []) {
      const given = fromQuery ? query.get(`${t.prefix}_${entry.name}`) : null;
      if (given !== null) state.view.parameters[entry.name] = entry.kind === "flag" ? given === "true" : Number(given);
      const { label, input } = control(entry, `technique-${entry.name}`, "preset");
      if (entry.kind === "flag") input.checked = state.view.parameters[entry.name] ?? entry.default;
      else if (given !== null) input.value = given;
      input.addEventListener("change", () => {
        if (entry.kind === "flag") state.view.parameters[entry.name] = input.checked;
        else if (input.value === "") delete state.view.parameters[entry.name];
        else state.view.parameters[entry.name] = Number(input.value);
        redraw();
      });
      $("technique-options").append(label);
    }
  };
  describe(true);
  select.addEventListener("change", () => { state.view.technique = select.value; describe(false); redraw(); });
  for (const name of CLASSES) {
    const label = document.createElement("label");
    const box = Object.assign(document.createElement("input"), { type: "checkbox", checked: true });
    box.addEventListener("change", () => {
      state.view.classes = CLASSES.filter((c, i) => $("classes").querySelectorAll("input")[i].checked);
      redraw();
    });
    label.append(box, ` ${name}`);
    $("classes").append(label);
  }
  const edgeColor = () => {
    state.view.edge_color = $("edge-color-on").checked ? hexToLinear($("edge-color").value) : null;
    redraw();
  };
  $("edge-color").addEventListener("input", edgeColor);
  $("edge-color-on").addEventListener("change", edgeColor);
  $("background").addEventListener("input", (e) => { state.view.background = hexToLinear(e.target.value); redraw(); });
  $("highlight").addEventListener("change", (e) => { state.view.highlight = e.target.value; redraw(); });
  $("rebake").addEventListener("click", () => state.source && open(state.source.files));
  $("download-asset").addEventListener("click", () => {
    download(state.asset.name, new Blob([state.asset.bytes], { type: "application/octet-stream" }));
  });
  $("download-svg").addEventListener("click", async () => {
    try {
      const { svg } = await run({ op: "svg", name: state.asset.name, bytes: state.asset.bytes,
        view: JSON.stringify(state.view), width: canvas.width, height: canvas.height });
      download(state.asset.name.replace(/\.chamfer$/, ".svg"), new Blob([svg], { type: "image/svg+xml" }));
    } catch (e) {
      showError(e.message);
    }
  });
}

function download(name, blob) {
  const link = Object.assign(document.createElement("a"), { href: URL.createObjectURL(blob), download: name });
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
}

// --- start ------------------------------------------------------------------------------------
async function start() {
  await init();
  const size = query.get("size")?.match(/^(\d+)x(\d+)$/);
  if (size) [canvas.width, canvas.height] = [Number(size[1]), Number(size[2])];
  CLASSES = JSON.parse(edgeClasses());
  state.view.classes = [...CLASSES];
  setUpPanel(JSON.parse(viewSchema()), "view-options");
  setUpPanel(JSON.parse(styleSchema()), "style-options");
  // The section's planes are the slider's (sectionSchema's `section` key); the cut look a panel.
  state.sectionSchema = JSON.parse(sectionSchema());
  setUpPanel(JSON.parse(cutSchema()), "cut-options");
  setUpPanel(JSON.parse(displaySchema()), "display-options");
  setUpPanel(JSON.parse(animationSchema()), "animation-options");
  setUpPlayback();
  setUpSection();
  setUpControls(JSON.parse(techniques()));
  setUpBakeOptions(JSON.parse(bakeSchema()));
  try {
    if (!navigator.gpu) throw new Error("this browser has no WebGPU (navigator.gpu is missing)");
    state.viewer = await createViewer(canvas);
    document.body.dataset.adapter = state.viewer.adapter;
  } catch (e) {
    // WebGL2 (OpenGL ES 3.0) has no storage buffers, which every pass of the renderer reads (the
    // mesh pass its environment, each technique its edges), and no compute shaders, which most
    // techniques run: none can draw there.
    const notice = $("notice");
    notice.textContent = `No drawing here: ${e.message}. Chamfer's renderer needs WebGPU: every ` +
      "technique reads storage buffers and most run compute shaders, which WebGL2 lacks. Baking, " +
      "inspecting and the downloads still work.";
    notice.hidden = false;
    canvas.hidden = true;
  }
  await openUrl(query.get("url") ?? "fandisk.obj");
}

start().catch((e) => showError(e.message));
