// The web page in headless Chromium (issue 26), driven over the DevTools protocol by puppeteer-core:
// run by scripts/test-web.sh after scripts/web.sh has built target/web. Every check reads pixels or
// bytes back; a failed check ends the run with a non-zero status.
//
//   node web/tests/browser.mjs <web dir> <chamfer binary> <out dir> <node_modules dir>
import { execFileSync } from "node:child_process";
import { createServer } from "node:http";
import { createRequire } from "node:module";
import { readFileSync, writeFileSync, mkdirSync } from "node:fs";
import { extname, join, resolve } from "node:path";

const [webDir, chamfer, outDir, modules] = process.argv.slice(2).map((p) => resolve(p));
const require = createRequire(join(modules, "x.js"));
const puppeteer = require("puppeteer-core");
const { PNG } = require("pngjs");
mkdirSync(outDir, { recursive: true });

// --- a static server for the page ------------------------------------------------------------
const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".wasm": "application/wasm" };
const server = createServer((request, response) => {
  const path = decodeURIComponent(new URL(request.url, "http://x").pathname);
  const file = join(webDir, path === "/" ? "index.html" : path);
  try {
    if (!file.startsWith(webDir)) throw new Error("outside");
    const body = readFileSync(file);
    response.writeHead(200, { "content-type": TYPES[extname(file)] ?? "application/octet-stream" });
    response.end(body);
  } catch {
    response.writeHead(404).end();
  }
});
await new Promise((done) => server.listen(0, "127.0.0.1", done));
const origin = `http://127.0.0.1:${server.address().port}`;

// Flags from ../shared/notes/webgpu-in-headless-chromium.md: WebGPU on SwiftShader, canvas composited.
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  args: ["--no-sandbox", "--enable-unsafe-webgpu", "--enable-features=Vulkan", "--use-vulkan=swiftshader",
         "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
});

let failures = 0;
async function check(name, body) {
  const started = Date.now();
  try {
    await body();
    console.log(`ok   ${name} (${Date.now() - started} ms)`);
  } catch (e) {
    failures++;
    console.log(`FAIL ${name}: ${e.message}`);
  }
}
function expect(condition, message) {
  if (!condition) throw new Error(message);
}

// --- the page ---------------------------------------------------------------------------------
const SIZE = [480, 360];
async function openPage(query = "") {
  const page = await browser.newPage();
  await page.setViewport({ width: 840, height: 720 });
  const messages = [];
  page.on("console", (m) => messages.push(m.text()));
  page.on("pageerror", (e) => messages.push(e.message));
  page.messages = messages;
  await page.goto(`${origin}/?size=${SIZE[0]}x${SIZE[1]}${query}`);
  return page;
}
// Waits until the page has drawn (or shown an error) since `since` frames.
async function settled(page, state = "drawn") {
  await page.waitForFunction(() => ["drawn", "error", "baked"].includes(document.body.dataset.state)
    && (window.chamfer?.framesLeft ?? 0) === 0, { timeout: 180_000 });
  const [now, error] = await page.evaluate(() => [document.body.dataset.state, document.getElementById("error").textContent]);
  expect(now === state, `the page is '${now}', not '${state}': ${error} ${page.messages.join(" | ")}`);
}
// The canvas as RGBA, drawn with `view` changes applied.
async function capture(page, view = {}) {
  const url = await page.evaluate((view) => {
    Object.assign(window.chamfer.view, view);
    return window.chamfer.capture();
  }, view);
  return PNG.sync.read(Buffer.from(url.split(",")[1], "base64"));
}
function save(png, name) {
  writeFileSync(join(outDir, name), PNG.sync.write(png));
}
function readPng(path) {
  return PNG.sync.read(readFileSync(path));
}
function render(args, name) {
  const out = join(outDir, name);
  execFileSync(chamfer, ["render", ...args, "-o", out, "--width", String(SIZE[0]), "--height", String(SIZE[1])]);
  return readPng(out);
}

// Pixels where `a` and `b` differ by more than `threshold` in some channel.
function differing(a, b, threshold = 40) {
  const mask = new Uint8Array(a.width * a.height);
  for (let i = 0; i < mask.length; i++) {
    for (let c = 0; c < 3; c++) {
      if (Math.abs(a.data[4 * i + c] - b.data[4 * i + c]) > threshold) mask[i] = 1;
    }
  }
  return mask;
}
const count = (mask) => mask.reduce((n, v) => n + v, 0);
// Share of `from`'s pixels with a pixel of `to` within one pixel.
function covered(from, to, width, height) {
  let hits = 0, total = 0;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      if (!from[y * width + x]) continue;
      total++;
      search: for (let dy = -1; dy <= 1; dy++) {
        for (let dx = -1; dx <= 1; dx++) {
          const [u, v] = [x + dx, y + dy];
          if (u >= 0 && v >= 0 && u < width && v < height && to[v * width + u]) { hits++; break search; }
        }
      }
    }
  }
  return total ? hits / total : 0;
}
function overlap(a, b) {
  return [covered(a, b, SIZE[0], SIZE[1]), covered(b, a, SIZE[0], SIZE[1])];
}

const CAMERA = ["--azimuth", "-50", "--elevation", "30"];
const fandisk = "fixtures/meshes/fandisk.obj";

await check("the page loads the bundled fandisk and draws the edges chamfer render draws", async () => {
  const page = await openPage("&azimuth=-50&elevation=30");
  const loaded = Date.now();
  await settled(page);
  console.log(`     page load to drawn: ${Date.now() - loaded} ms; ${await page.evaluate(() => document.body.dataset.adapter)}`);
  const edges = await capture(page);
  const mesh = await capture(page, { classes: [] });
  save(edges, "fandisk-page.png");
  // The README's picture of the page: edges back on, its settings shown.
  await capture(page, { classes: ["contour", "boundary", "marked", "ridge", "valley", "intersection"] });
  await page.screenshot({ path: join(outDir, "page.png"), fullPage: true });
  const pageEdges = differing(edges, mesh);
  const cliEdges = differing(render([fandisk, ...CAMERA], "fandisk-cli.png"),
                             render([fandisk, ...CAMERA, "--style", "mesh"], "fandisk-cli-mesh.png"));
  const control = differing(render([fandisk, "--azimuth", "-35", "--elevation", "30"], "fandisk-control.png"),
                            render([fandisk, "--azimuth", "-35", "--elevation", "30", "--style", "mesh"], "fandisk-control-mesh.png"));
  expect(count(pageEdges) > 2000, `only ${count(pageEdges)} edge pixels in the page`);
  const [pageInCli, cliInPage] = overlap(pageEdges, cliEdges);
  const [pageInControl, controlInPage] = overlap(pageEdges, control);
  console.log(`     edge pixels ${count(pageEdges)} page / ${count(cliEdges)} cli; overlap ${pageInCli.toFixed(4)} / ${cliInPage.toFixed(4)}; control ${pageInControl.toFixed(4)} / ${controlInPage.toFixed(4)}`);
  expect(pageInCli >= 0.95 && cliInPage >= 0.95, "the page's edges and chamfer render's differ");
  expect(Math.min(pageInControl, controlInPage) < 0.95, "the control camera passes: the comparison cannot fail");
  await page.close();
});

await check("switching the technique changes the picture", async () => {
  const page = await openPage();
  await settled(page);
  const joined = await capture(page);
  await page.select("#technique", "fins");
  await settled(page);
  const fins = await capture(page);
  const changed = count(differing(joined, fins));
  expect(changed > 500, `only ${changed} pixels changed`);
  await page.close();
});

await check("a PLY given through the file input bakes in the worker and draws", async () => {
  const page = await openPage();
  await settled(page);
  const before = await capture(page);
  const input = await page.$("#files");
  await input.uploadFile("fixtures/shapes/cube-marked-le.ply");
  await page.waitForFunction(() => document.getElementById("status").textContent.includes("cube-marked-le.ply"), { timeout: 60_000 });
  await settled(page);
  const cube = await capture(page);
  const mesh = await capture(page, { classes: [] });
  expect(count(differing(before, cube)) > 1000, "the picture did not change");
  expect(count(differing(cube, mesh)) > 300, "the cube has no edges drawn");
  const name = await page.evaluate(() => window.chamfer.asset.name);
  expect(name === "cube-marked-le.chamfer", `asset named ${name}`);
  await page.close();
});

await check("a truncated file shows the error in the page, naming the file", async () => {
  const page = await openPage();
  await settled(page);
  const input = await page.$("#files");
  await input.uploadFile("fixtures/broken/truncated.ply");
  await settled(page, "error");
  const text = await page.evaluate(() => document.getElementById("error").textContent);
  expect(text.includes("truncated.ply"), `the error does not name the file: ${text}`);
  console.log(`     ${text.split("\n")[0]}`);
  await page.close();
});

await check("the asset baked in the page is byte-identical to chamfer bake's", async () => {
  for (const [file, compact] of [[fandisk, true], ["fixtures/shapes/cube-marked-le.ply", false]]) {
    const name = file.split("/").pop();
    const page = await openPage();
    await settled(page);
    await page.evaluate((compact) => { document.getElementById("compact").checked = compact; }, compact);
    const input = await page.$("#files");
    await input.uploadFile(file);
    await page.waitForFunction((name) => document.getElementById("status").textContent.startsWith(`${name} baked`),
      { timeout: 120_000 }, name);
    await settled(page);
    const bytes = Buffer.from(await page.evaluate(() => [...window.chamfer.asset.bytes]));
    const out = join(outDir, `cli-${compact ? "compact" : "plain"}.chamfer`);
    execFileSync(chamfer, ["bake", file, "-o", out, ...(compact ? ["--compact"] : [])], { stdio: "ignore" });
    const cli = readFileSync(out);
    expect(bytes.length > 0 && bytes.equals(cli), `${file}${compact ? " --compact" : ""}: ${bytes.length} bytes in the page, ${cli.length} from the CLI, not the same`);
    console.log(`     ${file}${compact ? " --compact" : ""}: ${cli.length} bytes, identical`);
    await page.close();
  }
});

await browser.close();
server.close();
if (failures) {
  console.log(`${failures} browser check(s) failed`);
  process.exit(1);
}
