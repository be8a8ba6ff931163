//! The page's Web Worker calls these: bake dropped files, inspect an asset, draw its SVG. Each is a
//! plain Rust function (tested natively) under a thin wasm-bindgen wrapper.

use std::path::Path;

use chamfer_preprocess::draw::paper::PaperOptions;
use chamfer_preprocess::draw::style::DrawingStyle;
use chamfer_preprocess::draw::svg::write_svg;
use chamfer_preprocess::draw::{DrawOptions, LineClass, hidden_lines};
use chamfer_preprocess::inspect::summary;
use chamfer_preprocess::{Companions, bake_with_companions, compact};
use chamfer_runtime::asset::Asset;
use chamfer_runtime::schema::Schema;
use wasm_bindgen::prelude::*;

use crate::settings::{BakeSettings, ViewSettings, bake_settings};

/// A baked asset: the `.chamfer` file's bytes and its `chamfer inspect --json` report (with the
/// bake's warnings and step times).
#[wasm_bindgen]
#[derive(Debug)]
pub struct Baked {
    asset: Vec<u8>,
    report: String,
}

#[wasm_bindgen]
impl Baked {
    /// The `.chamfer` file's bytes.
    #[wasm_bindgen(getter)]
    pub fn asset(&self) -> Vec<u8> {
        self.asset.clone()
    }

    /// The report, JSON.
    #[wasm_bindgen(getter)]
    pub fn report(&self) -> String {
        self.report.clone()
    }
}

/// Bakes the file `name` among `files` (name, bytes: the dropped file and its companions) as
/// `chamfer bake` would bake it from a folder holding them, with `settings` (JSON,
/// [`BakeSettings`]). `progress` hears each step's name before it starts. Errors name the file.
pub fn bake_files(
    name: &str,
    files: &[(String, Vec<u8>)],
    settings: &BakeSettings,
    progress: &mut dyn FnMut(&str),
) -> Result<Baked, String> {
    let (options, compact) = settings.options().map_err(|e| e.to_string())?;
    let (_, bytes) = files
        .iter()
        .find(|(file, _)| file == name)
        .ok_or_else(|| format!("{name}: not among the given files"))?;
    progress("baking");
    let path = Path::new(name);
    let baked = bake_with_companions(path, bytes, Companions::Memory(files), &options)
        .map_err(|e| e.to_string())?;
    progress("encoding");
    let mut asset = Vec::new();
    compact::encode(&baked.asset, compact.as_ref(), &mut asset)
        .map_err(|e| format!("{name}: cannot encode the asset: {e}"))?;
    let mut report = summary(&baked.asset, asset.len() as u64, None);
    report["warnings"] = baked.warnings.clone().into();
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    report["bake_ms"] = serde_json::json!({
        "parse": ms(baked.timings.parse),
        "processing": ms(baked.timings.processing()),
    });
    Ok(Baked {
        asset,
        report: report.to_string(),
    })
}

/// `chamfer inspect --json` of a `.chamfer` file's bytes; errors name the file.
pub fn inspect_asset(name: &str, bytes: &[u8]) -> Result<String, String> {
    let invalid = |e: &dyn std::fmt::Display| format!("{name}: not a valid .chamfer asset: {e}");
    let asset = Asset::decode(bytes).map_err(|e| invalid(&e))?;
    let precision = Asset::precision(bytes).map_err(|e| invalid(&e))?;
    Ok(summary(&asset, bytes.len() as u64, Some(precision)).to_string())
}

/// `chamfer draw`'s hidden-line SVG of an asset, from the camera `view` places in a `width` ×
/// `height` frame; only the classes `view` draws.
pub fn svg_of(
    name: &str,
    bytes: &[u8],
    view: &ViewSettings,
    size: [u32; 2],
) -> Result<String, String> {
    let asset =
        Asset::decode(bytes).map_err(|e| format!("{name}: not a valid .chamfer asset: {e}"))?;
    let camera = view.camera([asset.header.bounds_min, asset.header.bounds_max], size);
    // The section on screen, when it is one plane (a drawing takes no box): a section drawing.
    let plane = chamfer_preprocess::draw::section::drawing_plane(&view.section)
        .map_err(|e| format!("{name}: {e}"))?;
    let mut classes = view.line_classes()?;
    if plane.is_some() {
        classes.extend([LineClass::Cut, LineClass::Hatch]);
    }
    let drawing = hidden_lines(
        &asset,
        &camera,
        &DrawOptions::DEFAULT
            .with_classes(&classes)
            .with_section(plane),
    );
    let mut svg = Vec::new();
    write_svg(
        &drawing,
        &DrawingStyle::default(),
        &PaperOptions::default().with_title(name),
        &mut svg,
    )
    .map_err(|e| format!("{name}: cannot write the drawing: {e}"))?;
    String::from_utf8(svg).map_err(|e| format!("{name}: the drawing is not text: {e}"))
}

fn js_error(message: String) -> JsError {
    JsError::new(&message)
}

/// [`bake_files`] for the page: `names[i]` is the name of `contents[i]`; `settings` is JSON;
/// `progress` is called with each step's name.
#[wasm_bindgen]
pub fn bake(
    name: &str,
    names: Vec<String>,
    contents: Vec<js_sys::Uint8Array>,
    settings: &str,
    progress: &js_sys::Function,
) -> Result<Baked, JsError> {
    if names.len() != contents.len() {
        return Err(js_error(format!(
            "{} names for {} files",
            names.len(),
            contents.len()
        )));
    }
    let files: Vec<(String, Vec<u8>)> = names
        .into_iter()
        .zip(contents.iter().map(js_sys::Uint8Array::to_vec))
        .collect();
    let settings = bake_settings(settings).map_err(js_error)?;
    let mut report = |step: &str| {
        // A progress listener that throws must not stop the bake.
        let _ = progress.call1(&JsValue::NULL, &JsValue::from_str(step));
    };
    bake_files(name, &files, &settings, &mut report).map_err(js_error)
}

/// [`inspect_asset`] for the page.
#[wasm_bindgen]
pub fn inspect(name: &str, bytes: &[u8]) -> Result<String, JsError> {
    inspect_asset(name, bytes).map_err(js_error)
}

/// [`svg_of`] for the page: `view` is JSON.
#[wasm_bindgen]
pub fn draw_svg(
    name: &str,
    bytes: &[u8],
    view: &str,
    width: u32,
    height: u32,
) -> Result<String, JsError> {
    let view = ViewSettings::from_json(view).map_err(js_error)?;
    svg_of(name, bytes, &view, [width, height]).map_err(js_error)
}

/// The bake's schema, as JSON: every option `chamfer bake` has (`BakeSettings`' table: name, kind,
/// group, default, example, range, help, conflicts, requires), from which the page builds its
/// bake panel.
#[wasm_bindgen(js_name = bakeSchema)]
pub fn bake_schema() -> String {
    BakeSettings::schema_json().to_string()
}

/// The view schema, as JSON: the orbit camera's entries (`chamfer render`'s camera flags), from
/// which the page builds its view panel; the view settings take the same keys.
#[wasm_bindgen(js_name = viewSchema)]
pub fn view_schema() -> String {
    chamfer_runtime::camera::Orbit::schema_json().to_string()
}

/// The style schema, as JSON: the look's numbers (`chamfer render`'s `--edge-width`, `--samples`,
/// the highlight's material and light), from which the page builds its style panel; the view
/// settings take the same keys.
#[wasm_bindgen(js_name = styleSchema)]
pub fn style_schema() -> String {
    chamfer_runtime::render::StyleSettings::schema_json().to_string()
}

/// The section schema, as JSON: the section planes and box (`chamfer render --section`,
/// `--section-box`); the view settings take the same keys (the page's slider sets `section`).
#[wasm_bindgen(js_name = sectionSchema)]
pub fn section_schema() -> String {
    chamfer_runtime::section::Section::schema_json().to_string()
}

/// The cut schema, as JSON: how the cut faces and the cut outline look (`chamfer render`'s
/// `--no-caps`, `--cap-*`, `--cut-outline-*`), from which the page builds its section panel.
#[wasm_bindgen(js_name = cutSchema)]
pub fn cut_schema() -> String {
    chamfer_runtime::section::CutSettings::schema_json().to_string()
}

/// The display schema, as JSON: face modes, hidden edges' style, distance fade (`chamfer render`'s
/// `--hidden-line`, `--xray`, `--wireframe`, `--hidden-*`, `--fade-*`), from which the page builds
/// its display panel; the view settings take the same keys.
#[wasm_bindgen(js_name = displaySchema)]
pub fn display_schema() -> String {
    chamfer_runtime::render::DisplaySettings::schema_json().to_string()
}

/// The animation schema, as JSON: the pose of an animated asset (`chamfer render`'s
/// `--animation`, `--time`, `--pose`), from which the page builds its animation panel; the view
/// settings take the same keys.
#[wasm_bindgen(js_name = animationSchema)]
pub fn animation_schema() -> String {
    chamfer_runtime::rig::AnimationSettings::schema_json().to_string()
}

/// The edge classes' names, as JSON (`chamfer render --classes` takes the same).
#[wasm_bindgen(js_name = edgeClasses)]
pub fn edge_classes() -> String {
    serde_json::Value::from(chamfer_runtime::render::EdgeClasses::names().collect::<Vec<_>>())
        .to_string()
}

/// The techniques the runtime has, as JSON: `[{name, summary, post_process, prefix, parameters}]`,
/// `parameters` the technique's own table (its module's schema, each entry's `default` the
/// preset's value; empty for a technique without any), from which the page builds its technique
/// panel; the view settings' `parameters` object takes the same names.
#[wasm_bindgen]
pub fn techniques() -> String {
    let all: Vec<serde_json::Value> = chamfer_runtime::render::Technique::all()
        .iter()
        .map(|t| {
            let parameters = t.parameters();
            serde_json::json!({
                "name": t.name(),
                "summary": t.summary(),
                "post_process": t.is_post_process(),
                "prefix": parameters.map(|p| p.prefix()),
                "parameters": parameters.map_or(serde_json::json!([]), |p| p.schema_json()),
            })
        })
        .collect();
    serde_json::Value::from(all).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use chamfer_tests::fixture;

    /// Issue 40: every entry of the bake schema the page builds its panel from, given as JSON
    /// (the page's settings) with its example value, bakes what the same settings bake through
    /// the library (chamfer bake's flags are checked against those too, preprocess/tests/cli.rs).
    #[test]
    fn every_schema_option_set_in_the_page_settings_bakes_what_the_settings_bake() {
        let schema: serde_json::Value = serde_json::from_str(&bake_schema()).expect("json");
        let entries = schema.as_array().expect("an array");
        assert_eq!(entries.len(), BakeSettings::ENTRIES.len());
        let mesh = fixture("meshes/fandisk.obj");
        let files = vec![(
            "fandisk.obj".to_owned(),
            std::fs::read(&mesh).expect("mesh"),
        )];
        for entry in entries {
            let name = entry["name"].as_str().expect("a name");
            let mut json = serde_json::Map::new();
            let requires = entry["requires"].as_array().expect("requires");
            for needed in requires.iter().filter_map(|n| n.as_str()).chain([name]) {
                let example = schema
                    .as_array()
                    .and_then(|all| all.iter().find(|e| e["name"] == needed))
                    .map(|e| e["example"].clone())
                    .expect("an example");
                json.insert(needed.to_owned(), example);
            }
            let json = serde_json::Value::Object(json).to_string();
            let settings = bake_settings(&json).expect("settings");
            let baked = bake_files("fandisk.obj", &files, &settings, &mut |_| {}).expect(name);
            let mut direct = BakeSettings::default();
            for needed in requires.iter().filter_map(|n| n.as_str()).chain([name]) {
                BakeSettings::entry(needed)
                    .expect("known")
                    .set_example(&mut direct);
            }
            assert_eq!(settings, direct, "{json}");
            let (options, compact) = direct.options().expect("options");
            let on_disk = chamfer_preprocess::bake_file(&mesh, &options).expect("on disk");
            let mut expected = Vec::new();
            compact::encode(&on_disk.asset, compact.as_ref(), &mut expected).expect("encode");
            assert!(baked.asset == expected, "{json}: other bytes");
        }
    }

    #[test]
    fn a_dropped_gltf_and_its_buffer_bake_to_chamfer_bakes_bytes() {
        let gltf = fixture("shapes/two-materials-external.gltf");
        let files = vec![
            (
                "two-materials-external.gltf".to_owned(),
                std::fs::read(&gltf).expect("gltf"),
            ),
            (
                "two-materials.bin".to_owned(),
                std::fs::read(fixture("shapes/two-materials.bin")).expect("bin"),
            ),
        ];
        let settings = crate::settings::bake_settings(r#"{"compact": true}"#).expect("settings");
        let mut steps = Vec::new();
        let baked = bake_files(
            "two-materials-external.gltf",
            &files,
            &settings,
            &mut |step| steps.push(step.to_owned()),
        )
        .expect("baked");
        let (options, compact) = settings.options().expect("options");
        let on_disk = chamfer_preprocess::bake_file(&gltf, &options).expect("on disk");
        let mut expected = Vec::new();
        compact::encode(&on_disk.asset, compact.as_ref(), &mut expected).expect("encode");
        assert_eq!(baked.asset, expected);
        assert_eq!(steps, ["baking", "encoding"]);
        let report: serde_json::Value = serde_json::from_str(&baked.report).expect("json");
        assert_eq!(report["bytes"]["total"], expected.len());
        let inspected: serde_json::Value =
            serde_json::from_str(&inspect_asset("x.chamfer", &baked.asset).expect("inspect"))
                .expect("json");
        assert_eq!(inspected["triangles"], report["triangles"]);
    }

    #[test]
    fn refusals_name_the_file() {
        let files = vec![("part.obj".to_owned(), b"v 0 0 0\nf 1 2 3\n".to_vec())];
        let settings = BakeSettings::default();
        let error = bake_files("part.obj", &files, &settings, &mut |_| {}).expect_err("bad");
        assert!(error.contains("part.obj"), "{error}");
        let error = bake_files("other.obj", &files, &settings, &mut |_| {}).expect_err("absent");
        assert!(
            error.contains("other.obj: not among the given files"),
            "{error}"
        );
        let error = inspect_asset("broken.chamfer", b"CHAMFER?").expect_err("not an asset");
        assert!(
            error.starts_with("broken.chamfer: not a valid .chamfer asset"),
            "{error}"
        );
        let error = svg_of("broken.chamfer", b"", &ViewSettings::default(), [64, 64])
            .expect_err("not an asset");
        assert!(error.starts_with("broken.chamfer"), "{error}");
    }

    #[test]
    fn the_drawing_is_chamfer_draws_svg() {
        let files = vec![(
            "cube.obj".to_owned(),
            std::fs::read(fixture("shapes/cube.obj")).expect("cube"),
        )];
        let baked =
            bake_files("cube.obj", &files, &BakeSettings::default(), &mut |_| {}).expect("baked");
        let svg = svg_of(
            "cube.chamfer",
            &baked.asset,
            &ViewSettings::default(),
            [320, 240],
        )
        .expect("svg");
        assert!(svg.starts_with("<?xml") || svg.starts_with("<svg"), "{svg}");
        assert!(svg.contains("<title>cube.chamfer</title>"), "{svg}");
        assert!(svg.matches("<polyline").count() + svg.matches("<path").count() > 0);
    }
}
