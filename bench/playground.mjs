// The playground's speed in headless Chromium, and its screenshot for the docs.
//
// Serves a built site (`mkdocs build`) on 127.0.0.1, opens the playground on the paper's
// optimised 20-rod chain (1 ms, peak_tolerance 1e-5) in Debian's headless Chromium driven over
// the DevTools protocol (real time: the numbers' check, scripts/playground_check.py, runs on
// virtual time, where the page's clock stands still), and prints the page's compute_ms of the
// first run (the module just compiled) and the median of RUNS more, clicked one after another;
// with `--woodpile BIN`, the native `BIN simulate` of the same TOML run between the page's runs
// (its summary's wall_time_s, the library's own time, beside the page's), and their ratio.
// `--screenshot PNG` saves the page after the first run, and beside it PNG with `-refused`
// before its extension: the page's answer to a scenario the library refuses.
//
// Usage: node --experimental-websocket bench/playground.mjs SITE_DIR [RUNS] [--screenshot PNG]
//        [--woodpile target/release/woodpile]

import { spawn, execFileSync } from "node:child_process";
import { createServer } from "node:http";
import { mkdtempSync, readFileSync, writeFileSync, existsSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, extname, resolve } from "node:path";

const args = process.argv.slice(2);
const shotAt = args.indexOf("--screenshot");
const screenshot = shotAt >= 0 ? args.splice(shotAt, 2)[1] : null;
const binAt = args.indexOf("--woodpile");
const woodpile = binAt >= 0 ? args.splice(binAt, 2)[1] : null;
const [site, runsArg] = args;
const runs = Number(runsArg ?? 9);
const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".wasm": "application/wasm", ".png": "image/png" };
const PAPER_CHAIN = `[chain]
rods_mm = [50, 80, 80, 80, 60, 70, 80, 80, 40, 30, 40, 40, 40, 30, 50, 40, 20, 20, 30, 50]
[excitation]
kind = "impact"
velocity_m_s = 1.98
[run]
duration_s = 1e-3
peak_tolerance = 1e-5
`;

const server = createServer((request, response) => {
  let path = join(resolve(site), decodeURIComponent(new URL(request.url, "http://x").pathname));
  if (path.endsWith("/")) path = join(path, "index.html");
  if (!existsSync(path)) {
    response.writeHead(404).end();
    return;
  }
  response.writeHead(200, { "content-type": TYPES[extname(path)] ?? "application/octet-stream" });
  response.end(readFileSync(path));
});
await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
const url = `http://127.0.0.1:${server.address().port}/playground/#scenario=${encodeURIComponent(PAPER_CHAIN)}`;

const profile = mkdtempSync(join(tmpdir(), "woodpile-chromium-"));
const chromium = spawn("chromium", [
  "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
  "--disable-background-networking", "--disable-component-update", "--disable-sync",
  "--remote-debugging-port=0", `--user-data-dir=${profile}`, "--window-size=1100,2300", "about:blank",
], { stdio: "ignore" });
const sleep = (ms) => new Promise((ok) => setTimeout(ok, ms));
let port = null;
for (let i = 0; i < 200 && port === null; i++) {
  await sleep(50);
  const file = join(profile, "DevToolsActivePort");
  if (existsSync(file)) port = readFileSync(file, "utf8").split("\n")[0];
}
const targets = await (await fetch(`http://127.0.0.1:${port}/json/list`)).json();
const socket = new WebSocket(targets.find((t) => t.type === "page").webSocketDebuggerUrl);
await new Promise((ok) => socket.addEventListener("open", ok));
let nextId = 1;
const pending = new Map();
socket.addEventListener("message", (event) => {
  const message = JSON.parse(event.data);
  if (pending.has(message.id)) pending.get(message.id)(message.result);
});
const send = (method, params = {}) =>
  new Promise((ok) => {
    const id = nextId++;
    pending.set(id, ok);
    socket.send(JSON.stringify({ id, method, params }));
  });
const evaluate = async (expression) =>
  (await send("Runtime.evaluate", { expression, returnByValue: true })).result.value;
const computeMs = () => evaluate(`document.getElementById("compute_ms").dataset.value ?? null`);
const waitFor = async (predicate) => {
  for (let i = 0; i < 600; i++) {
    if (await evaluate(predicate)) return;
    await sleep(50);
  }
  throw new Error(`timed out waiting for ${predicate}`);
};

await send("Page.navigate", { url });
await waitFor(`document.getElementById("results")?.dataset.state === "done"`);
const first = Number(await computeMs());
if (screenshot) {
  // The page down to the force map (not the text below it, which shows the last screenshot).
  const bottom = await evaluate(`document.getElementById("map").getBoundingClientRect().bottom + scrollY + 12`);
  const { data } = await send("Page.captureScreenshot", {
    format: "png",
    captureBeyondViewport: true,
    clip: { x: 0, y: 0, width: 1100, height: bottom, scale: 1 },
  });
  writeFileSync(screenshot, Buffer.from(data, "base64"));
}
const scratch = mkdtempSync(join(tmpdir(), "woodpile-native-"));
writeFileSync(join(scratch, "paper.toml"), PAPER_CHAIN);
const nativeMs = () => {
  execFileSync(woodpile, ["simulate", join(scratch, "paper.toml"), "--out", join(scratch, "run"), "--quiet", "--overwrite"]);
  return 1e3 * JSON.parse(readFileSync(join(scratch, "run", "summary.json"), "utf8")).wall_time_s;
};
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const warm = [];
const library = [];
const native = [];
for (let i = 0; i < runs; i++) {
  await evaluate(`document.getElementById("results").dataset.state = "running"; document.getElementById("run").click()`);
  await waitFor(`document.getElementById("results").dataset.state === "done"`);
  warm.push(Number(await computeMs()));
  library.push(1e3 * Number(await evaluate(`document.getElementById("wall_time_s").dataset.value`)));
  if (woodpile) native.push(nativeMs());
}
const transmitted = await evaluate(`document.getElementById("transmitted_peak_force_n").dataset.value ?? null`);
if (screenshot) {
  const bad = JSON.stringify("[chain]\nrods_mm = [80, 45]\n");
  await evaluate(`document.getElementById("toml").value = ${bad}; document.getElementById("run").click()`);
  await waitFor(`document.getElementById("results").dataset.state === "error"`);
  const box = await evaluate(
    `(() => { const r = document.getElementById("toml").getBoundingClientRect();
      const e = document.getElementById("error").getBoundingClientRect();
      return { x: r.left - 8, y: r.top + scrollY - 8, width: r.width + 16, height: e.bottom - r.top + 16 }; })()`,
  );
  const { data } = await send("Page.captureScreenshot", {
    format: "png",
    captureBeyondViewport: true,
    clip: { ...box, scale: 1 },
  });
  writeFileSync(screenshot.replace(/\.png$/, "-refused.png"), Buffer.from(data, "base64"));
}
console.log(`paper chain, 1 ms at peak_tolerance 1e-5, in headless Chromium: first run ${first.toFixed(1)} ms, ` +
  `median of ${runs} more ${median(warm).toFixed(1)} ms, the library's own time in them ${median(library).toFixed(1)} ms ` +
  `(transmitted peak ${transmitted} N)`);
if (woodpile) {
  console.log(`native (${woodpile}), the same TOML between the page's runs: ${median(native).toFixed(2)} ms; ` +
    `page / native: first run ${(first / median(native)).toFixed(1)}, later runs ${(median(warm) / median(native)).toFixed(1)} ` +
    `(library time ${(median(library) / median(native)).toFixed(1)})`);
}
if (screenshot) console.log(`screenshot: ${screenshot}`);
socket.close();
chromium.kill();
server.close();
