// What the page's browser tests and benchmarks share: a static server for the built page, headless
// Chromium with WebGPU (puppeteer-core over the DevTools protocol), the page's readiness, canvas
// captures and pixel masks.
import { execFileSync } from "node:child_process";
import { createServer } from "node:http";
import { createRequire } from "node:module";
import { readFileSync, writeFileSync, mkdirSync } from "node:fs";
import { extname, join, resolve } from "node:path";

// node <script> <web dir> <chamfer binary> <out dir> <node_modules dir>
export const [webDir, chamfer, outDir, modules] = process.argv.slice(2, 6).map((p) => resolve(p));
const require = createRequire(join(modules, "x.js"));
const puppeteer = require("puppeteer-core");
export const { PNG } = require("pngjs");
mkdirSync(outDir, { recursive: true });

const TYPES = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".wasm": "application/wasm" };

/// Serves `webDir` on 127.0.0.1 and opens headless Chromium (with WebGPU unless `webgpu` is false);
/// returns {browser, origin, close}.
export async function start({ webgpu = true } = {}) {
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
  // Flags from ../shared/notes/webgpu-in-headless-chromium.md: WebGPU on SwiftShader, canvas composited.
  const browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    args: ["--no-sandbox", ...(webgpu ? ["--enable-unsafe-webgpu"] : []), "--enable-features=Vulkan",
           "--use-vulkan=swiftshader", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
  return {
    browser,
    origin: `http://127.0.0.1:${server.address().port}`,
    close: async () => { await browser.close(); server.close(); },
  };
}

export const SIZE = [480, 360];

/// Opens the page with `query` (after the canvas size) in a new tab.
export async function openPage({ browser, origin }, query = "") {
  const page = await browser.newPage();
  await page.setViewport({ width: 840, height: 720 });
  const messages = [];
  page.on("console", (m) => messages.push(m.text()));
  page.on("pageerror", (e) => messages.push(e.message));
  page.messages = messages;
  await page.goto(`${origin}/?size=${SIZE[0]}x${SIZE[1]}${query}`);
  return page;
}

/// Waits until the page is done (drawn, baked without WebGPU, or showing an error) and checks it is `state`.
export async function settled(page, state = "drawn") {
  await page.waitForFunction(() => ["drawn", "error", "baked"].includes(document.body.dataset.state)
    && (window.chamfer?.framesLeft ?? 0) === 0, { timeout: 180_000 });
  const [now, error] = await page.evaluate(() => [document.body.dataset.state, document.getElementById("error").textContent]);
  expect(now === state, `the page is '${now}', not '${state}': ${error} ${page.messages.join(" | ")}`);
}

/// Gives `file` to the page's file input and waits until it is baked and drawn.
export async function upload(page, file) {
  const name = file.split("/").pop();
  // The same file twice is a change only if the input was emptied in between.
  await page.evaluate(() => { document.getElementById("files").value = ""; });
  await (await page.$("#files")).uploadFile(file);
  await page.waitForFunction((name) => document.getElementById("status").textContent.startsWith(`${name} `)
    || document.body.dataset.state === "error", { timeout: 180_000 }, name);
}

/// The canvas as a PNG, drawn with `view` changes applied.
export async function capture(page, view = {}) {
  const url = await page.evaluate((view) => {
    Object.assign(window.chamfer.view, view);
    return window.chamfer.capture();
  }, view);
  return PNG.sync.read(Buffer.from(url.split(",")[1], "base64"));
}

export function save(png, name) {
  writeFileSync(join(outDir, name), PNG.sync.write(png));
}

/// `chamfer render` of `args` at the page's size, read back.
export function render(args, name) {
  const out = join(outDir, name);
  execFileSync(chamfer, ["render", ...args, "-o", out, "--width", String(SIZE[0]), "--height", String(SIZE[1])]);
  return PNG.sync.read(readFileSync(out));
}

/// Pixels where `a` and `b` differ by more than `threshold` in some channel.
export function differing(a, b, threshold = 40) {
  const mask = new Uint8Array(a.width * a.height);
  for (let i = 0; i < mask.length; i++) {
    for (let c = 0; c < 3; c++) {
      if (Math.abs(a.data[4 * i + c] - b.data[4 * i + c]) > threshold) mask[i] = 1;
    }
  }
  return mask;
}

export const count = (mask) => mask.reduce((n, v) => n + v, 0);

/// Share of `from`'s pixels with a pixel of `to` within one pixel.
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

/// Both ways: the share of `a`'s pixels within 1 px of `b`'s, and of `b`'s within 1 px of `a`'s.
export function overlap(a, b) {
  return [covered(a, b, SIZE[0], SIZE[1]), covered(b, a, SIZE[0], SIZE[1])];
}

export function expect(condition, message) {
  if (!condition) throw new Error(message);
}
