// The web page's figures for BENCHMARKS.md (issue 26): the .wasm's size (raw and gzip), the time from
// page load to the first drawn frame, and bake times in the page's worker against the native
// `chamfer bake` (two threads and one) in the same run. Run by scripts/bench-web.sh.
//
//   node web/tests/bench.mjs <web dir> <chamfer binary> <out dir> <node_modules dir>
import { execFileSync } from "node:child_process";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { gzipSync } from "node:zlib";

import { chamfer, openPage, outDir, settled, start, upload, webDir } from "./harness.mjs";

const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const RUNS = Number(process.env.RUNS ?? 5);

const wasm = readFileSync(join(webDir, "pkg/chamfer_web_bg.wasm"));
const glue = readFileSync(join(webDir, "pkg/chamfer_web.js"));
console.log(`wasm: ${(wasm.length / 1024).toFixed(0)} KiB raw, ${(gzipSync(wasm, { level: 9 }).length / 1024).toFixed(0)} KiB gzip; ` +
  `JS glue ${(glue.length / 1024).toFixed(0)} KiB raw, ${(gzipSync(glue, { level: 9 }).length / 1024).toFixed(0)} KiB gzip`);

const session = await start();
const loads = [];
for (let i = 0; i < RUNS; i++) {
  const page = await openPage(session);
  await settled(page);
  loads.push(await page.evaluate(() => window.chamfer.firstFrameMs));
  await page.close();
}
console.log(`page load to first drawn frame (fetch + bake of fandisk.obj in the worker + upload + frame): ` +
  `median ${median(loads).toFixed(0)} ms of ${RUNS} (${loads.map((t) => t.toFixed(0)).join(", ")})`);

function native(file, threads) {
  const times = [];
  for (let i = 0; i < RUNS; i++) {
    const started = process.hrtime.bigint();
    execFileSync(chamfer, ["bake", file, "-o", join(outDir, "bench.chamfer"), "--compact"],
      { stdio: "ignore", env: { ...process.env, ...(threads ? { RAYON_NUM_THREADS: String(threads) } : {}) } });
    times.push(Number(process.hrtime.bigint() - started) / 1e6);
  }
  return median(times);
}

for (const file of ["fixtures/meshes/fandisk.obj", "fixtures/meshes/stanford-bunny.obj"]) {
  const page = await openPage(session);
  await settled(page);
  const times = [];
  for (let i = 0; i < RUNS; i++) {
    await page.evaluate(() => { window.chamfer.asset = null; document.getElementById("status").textContent = ""; });
    await upload(page, file);
    await settled(page);
    times.push(await page.evaluate(() => window.chamfer.asset.report.worker_ms));
  }
  await page.close();
  const inPage = median(times);
  const [two, one] = [native(file, 0), native(file, 1)];
  console.log(`${file}: bake + compact encode, median of ${RUNS}: page worker ${inPage.toFixed(0)} ms; ` +
    `native chamfer bake (whole process) ${two.toFixed(0)} ms on all cores = ${(inPage / two).toFixed(2)}x, ` +
    `${one.toFixed(0)} ms on one thread = ${(inPage / one).toFixed(2)}x`);
}
await session.close();
