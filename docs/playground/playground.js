// The playground (docs/playground/index.md): woodpile's library compiled to WebAssembly
// (crates/woodpile-wasm) runs a scenario in the page. The module takes the scenario's TOML and
// answers JSON: the run's summary.json object, its contact forces, and its warnings; or the
// message `woodpile simulate` prints for a scenario it refuses.

const TABLE1_MM = [20, 30, 40, 50, 60, 70, 80];
const $ = (id) => document.getElementById(id);

let module = null;

async function loadModule() {
  const response = await fetch("woodpile.wasm");
  if (!response.ok) throw new Error(`woodpile.wasm: HTTP ${response.status}`);
  const bytes = await response.arrayBuffer();
  const imports = { page: { now_ms: () => performance.now() } };
  const { instance } = await WebAssembly.instantiate(bytes, imports);
  return instance.exports;
}

// One run: the TOML's bytes into the module's buffer, the run, the JSON answer back.
function runToml(toml) {
  const input = new TextEncoder().encode(toml);
  const at = module.woodpile_input(input.length);
  new Uint8Array(module.memory.buffer, at, input.length).set(input);
  const started = performance.now();
  const length = module.woodpile_run();
  const computeMs = performance.now() - started;
  const bytes = new Uint8Array(module.memory.buffer, module.woodpile_output(), length);
  const answer = JSON.parse(new TextDecoder().decode(bytes));
  answer.compute_ms = computeMs;
  if (answer.ok) {
    // The samples: times, then every sample's contact forces (copied out of the module).
    const all = new Float64Array(module.memory.buffer, module.woodpile_samples(), module.woodpile_samples_len()).slice();
    const n = answer.series.n_samples;
    answer.series.times_s = all.subarray(0, n);
    answer.series.contact_forces_n = all.subarray(n);
  }
  return answer;
}

// The scenario the controls describe, as TOML (the same keys a scenario file takes).
function tomlFromControls() {
  const lengths = $("rods").value.trim().split(/[\s,]+/).filter((s) => s.length > 0);
  const lines = ["[chain]"];
  if ($("cells").value === "table1") {
    lines.push(`rods_mm = [${lengths.join(", ")}]`);
  } else {
    const diameter = $("diameter").value.trim();
    const entries = lengths.map(
      (l) => `  { kind = "rod", length_mm = ${l}, diameter_mm = ${diameter}, material = "fused-quartz" },`,
    );
    lines.push("elements = [", ...entries, "]");
  }
  lines.push("", "[excitation]", 'kind = "impact"', `velocity_m_s = ${$("speed").value.trim()}`);
  const restitution = $("restitution").value.trim();
  if (restitution !== "" && restitution !== "1") {
    lines.push("", "[damping]", 'contact = "restitution"', `restitution = ${restitution}`);
  }
  lines.push(
    "",
    "[run]",
    `duration_s = ${$("duration").value.trim()}e-3`,
    `peak_tolerance = ${$("tolerance").value.trim()}`,
  );
  return lines.join("\n") + "\n";
}

function formatNumber(value, unit) {
  if (unit === "ms") return `${value.toFixed(1)} ms`;
  if (unit === "s") return `${(value * 1e3).toFixed(1)} ms`;
  return `${Number(value).toPrecision(6)} ${unit}`.trim();
}

// A figure: its full-precision number in data-value, a readable one in the text; a figure that
// means nothing (a ratio when no wave arrived) shows why, with no number.
function showFigure(id, value, unit, why) {
  const element = $(id);
  if (value === null || value === undefined || !Number.isFinite(value)) {
    element.removeAttribute("data-value");
    element.textContent = why;
    return;
  }
  element.setAttribute("data-value", String(value));
  element.textContent = formatNumber(value, unit);
}

// A refusal: the message, and no figure or curve of an earlier run left beside it.
function showError(message) {
  const box = $("error");
  box.textContent = message;
  box.hidden = false;
  for (const id of ["incident_peak_force_n", "transmitted_peak_force_n", "transmission_ratio", "compute_ms", "wall_time_s", "integrator"]) {
    $(id).removeAttribute("data-value");
    $(id).textContent = "—";
  }
  lastSeries = null;
  $("contacts").replaceChildren();
  for (const id of ["curves", "map"]) $(id).getContext("2d").clearRect(0, 0, $(id).width, $(id).height);
  $("results").setAttribute("data-state", "error");
}

function run() {
  const toml = $("toml").value;
  $("error").hidden = true;
  $("warnings").replaceChildren();
  let answer;
  try {
    answer = runToml(toml);
  } catch (e) {
    showError(`the page could not run the module: ${e}`);
    return;
  }
  history.replaceState(null, "", `#scenario=${encodeURIComponent(toml)}`);
  if (!answer.ok) {
    showError(`error: ${answer.error}`);
    return;
  }
  const s = answer.summary;
  showFigure("incident_peak_force_n", s.incident_peak_force_n, "N", "—");
  showFigure("transmitted_peak_force_n", s.transmitted_peak_force_n, "N", "—");
  showFigure(
    "transmission_ratio",
    s.transmission_ratio,
    "",
    "no ratio: the wave never reached the sensor (run longer)",
  );
  showFigure("compute_ms", answer.compute_ms, "ms", "—");
  showFigure("wall_time_s", s.wall_time_s, "s", "not measured");
  $("integrator").textContent =
    `${s.integrator.method}, ${s.integrator.steps} steps, energy balance ${s.energy.max_relative_error.toExponential(1)}`;
  for (const warning of answer.warnings) {
    const item = document.createElement("li");
    item.textContent = `warning: ${warning}`;
    $("warnings").append(item);
  }
  lastSeries = answer.series;
  chooseContacts(answer.series);
  drawCurves();
  drawMap(answer.series);
  $("results").setAttribute("data-state", "done");
}

let lastSeries = null;

function chooseContacts(series) {
  const select = $("contacts");
  select.replaceChildren();
  series.contact_names.forEach((name, c) => {
    const option = document.createElement("option");
    option.value = String(c);
    option.textContent = `contact ${c} (${name})`;
    option.selected = c === 0 || c === series.n_contacts - 1;
    select.append(option);
  });
}

const PALETTE = ["#8c510a", "#01665e", "#c51b7d", "#4d9221", "#2166ac", "#b2182b", "#542788"];

// Axes in a canvas: the plot's rectangle and the maps from data to pixels.
function axes(ctx, width, height, [t0, t1], [f0, f1], labels) {
  const box = { left: 72, right: width - 12, top: 12, bottom: height - 40 };
  const x = (t) => box.left + ((t - t0) / (t1 - t0)) * (box.right - box.left);
  const y = (f) => box.bottom - ((f - f0) / (f1 - f0 || 1)) * (box.bottom - box.top);
  ctx.strokeStyle = "#444";
  ctx.fillStyle = "#222";
  ctx.font = "12px sans-serif";
  ctx.strokeRect(box.left, box.top, box.right - box.left, box.bottom - box.top);
  for (let k = 0; k <= 5; k++) {
    const t = t0 + ((t1 - t0) * k) / 5;
    ctx.fillText((t * 1e3).toFixed(2), x(t) - 12, box.bottom + 16);
    const f = f0 + ((f1 - f0) * k) / 5;
    if (labels.forces) ctx.fillText(f.toPrecision(3), 24, y(f) + 4);
  }
  ctx.fillText(labels.x, (box.left + box.right) / 2 - 30, height - 6);
  ctx.save();
  ctx.translate(14, (box.top + box.bottom) / 2 + 30);
  ctx.rotate(-Math.PI / 2);
  ctx.fillText(labels.y, 0, 0);
  ctx.restore();
  return { box, x, y };
}

function drawCurves() {
  const canvas = $("curves");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const series = lastSeries;
  if (!series || series.times_s.length < 2) return;
  const chosen = Array.from($("contacts").selectedOptions).map((o) => Number(o.value));
  const n = series.n_contacts;
  const times = series.times_s;
  let fmax = 0;
  for (const c of chosen) {
    for (let k = 0; k < times.length; k++) fmax = Math.max(fmax, series.contact_forces_n[k * n + c]);
  }
  const span = [times[0], times[times.length - 1]];
  const { x, y } = axes(ctx, canvas.width, canvas.height, span, [0, fmax || 1], {
    x: "time (ms)",
    y: "force (N)",
    forces: true,
  });
  chosen.forEach((c, i) => {
    ctx.strokeStyle = PALETTE[i % PALETTE.length];
    ctx.beginPath();
    for (let k = 0; k < times.length; k++) {
      const px = x(times[k]);
      const py = y(series.contact_forces_n[k * n + c]);
      if (k === 0) ctx.moveTo(px, py);
      else ctx.lineTo(px, py);
    }
    ctx.stroke();
    ctx.fillStyle = ctx.strokeStyle;
    ctx.fillText(`contact ${c}`, canvas.width - 90, 28 + 14 * i);
  });
}

// A dark-to-bright ramp (brown to yellow) for the force map.
function colour(u) {
  const v = Math.max(0, Math.min(1, u));
  const r = Math.round(30 + 225 * Math.min(1, 1.6 * v));
  const g = Math.round(20 + 215 * v * v);
  const b = Math.round(40 + 60 * (1 - v));
  return `rgb(${r},${g},${b})`;
}

function drawMap(series) {
  const canvas = $("map");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const n = series.n_contacts;
  const times = series.times_s;
  if (times.length < 2) return;
  const fmax = series.contact_forces_n.reduce((m, f) => Math.max(m, f), 0) || 1;
  const span = [times[0], times[times.length - 1]];
  const { box, x } = axes(ctx, canvas.width, canvas.height, span, [0, n], {
    x: "time (ms)",
    y: "contact",
  });
  const rowHeight = (box.bottom - box.top) / n;
  const columns = Math.min(times.length, Math.floor(box.right - box.left));
  for (let j = 0; j < columns; j++) {
    const k = Math.floor((j * (times.length - 1)) / Math.max(1, columns - 1));
    const left = x(times[k]);
    const width = Math.ceil((box.right - box.left) / columns) + 1;
    for (let c = 0; c < n; c++) {
      ctx.fillStyle = colour(series.contact_forces_n[k * n + c] / fmax);
      ctx.fillRect(left, box.top + c * rowHeight, width, Math.ceil(rowHeight));
    }
  }
  ctx.fillStyle = "#222";
  const every = Math.max(1, Math.ceil(n / 8));
  for (let c = 0; c < n; c += every) {
    ctx.fillText(String(c), 40, box.top + (c + 0.5) * rowHeight + 4);
  }
  ctx.fillText(`max ${fmax.toPrecision(4)} N`, box.right - 100, canvas.height - 6);
}

function copyLink() {
  const link = `${location.origin}${location.pathname}#scenario=${encodeURIComponent($("toml").value)}`;
  $("link").value = link;
  $("link").hidden = false;
  $("link").select();
  if (navigator.clipboard) navigator.clipboard.writeText(link).catch(() => {});
}

function downloadScenario() {
  const blob = new Blob([$("toml").value], { type: "application/toml" });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = "scenario.toml";
  a.click();
  URL.revokeObjectURL(a.href);
}

async function main() {
  $("rods-help").textContent = `Table 1 lengths: ${TABLE1_MM.join(", ")} mm`;
  $("from-controls").addEventListener("click", () => {
    $("toml").value = tomlFromControls();
    run();
  });
  $("run").addEventListener("click", run);
  $("contacts").addEventListener("change", drawCurves);
  $("copy-link").addEventListener("click", copyLink);
  $("download").addEventListener("click", downloadScenario);
  try {
    module = await loadModule();
  } catch (e) {
    showError(`the WebAssembly module did not load: ${e}`);
    return;
  }
  $("results").setAttribute("data-state", "ready");
  const hash = location.hash;
  if (hash.startsWith("#scenario=")) {
    $("toml").value = decodeURIComponent(hash.slice("#scenario=".length));
  } else {
    $("toml").value = tomlFromControls();
  }
  run();
}

await main();
