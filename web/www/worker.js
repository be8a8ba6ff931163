// The page's bakes, inspections and drawings, off the main thread so the page never freezes.
// Messages in: {id, op: "bake" | "inspect" | "svg", ...}; out: {id, progress} while it works, then
// {id, result} or {id, error}.
import init, { bake, draw_svg, inspect } from "./pkg/chamfer_web.js";

const ready = init();

self.onmessage = async ({ data }) => {
  const { id, op } = data;
  const progress = (step) => self.postMessage({ id, progress: step });
  try {
    await ready;
    const started = performance.now();
    let result;
    if (op === "bake") {
      const baked = bake(data.name, data.files.map((f) => f.name), data.files.map((f) => f.bytes),
                         data.settings, progress);
      result = { asset: baked.asset, report: JSON.parse(baked.report) };
    } else if (op === "inspect") {
      result = { report: JSON.parse(inspect(data.name, data.bytes)) };
    } else if (op === "svg") {
      result = { svg: draw_svg(data.name, data.bytes, data.view, data.width, data.height) };
    } else {
      throw new Error(`unknown operation ${op}`);
    }
    result.ms = performance.now() - started;
    self.postMessage({ id, result }, result.asset ? [result.asset.buffer] : []);
  } catch (e) {
    self.postMessage({ id, error: e instanceof Error ? e.message : String(e) });
  }
};
