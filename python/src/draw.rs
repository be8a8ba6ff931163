//! `chamfer.draw_svg`: hidden-line drawings as `chamfer draw` makes them, from the same camera
//! keywords: `width` and `height`, and the view schema's (`chamfer.VIEW_SCHEMA`, its camera flags).

use std::path::PathBuf;

use chamfer_preprocess::draw::svg::{SvgOptions, write_svg};
use chamfer_preprocess::draw::{Camera, DrawOptions, LineClass, hidden_lines};
use chamfer_preprocess::write::{ensure_not_an_input, write_atomically};
use chamfer_runtime::asset::Asset;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::asset::PyAsset;
use crate::errors::Failure;
use crate::{errors, options};

/// A hidden-line drawing as SVG text, the same as `chamfer draw` writes for the same camera.
///
/// `source` is an Asset, a `.chamfer` file, or a mesh file (baked first, with intersection
/// edges, and the bake options as for bake()). `classes` picks the line classes (contour,
/// boundary, marked, crease, intersection; default all), `hidden` also draws the hidden parts
/// (dashed), `scale` is paper millimetres per model unit (default 96 dpi), `title` defaults to
/// the file's name (or the asset's source). When `output` is given the SVG is also written there
/// atomically. The interpreter is released while drawing.
///
/// The camera orbits the model's bounding box, in a frame of `width` x `height` pixels, where
/// the view keywords put it (chamfer.VIEW_SCHEMA, `chamfer draw`'s camera flags of the same
/// names):
/// {view_keywords}
///
/// The bake options, for a mesh file:
/// {bake_keywords}
#[pyfunction]
#[pyo3(signature = (
    source, output = None, *, width = 1024, height = 768, hidden = false, classes = None,
    scale = None, title = None, **options
))]
#[allow(clippy::too_many_arguments)]
pub fn draw_svg(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    output: Option<PathBuf>,
    width: u32,
    height: u32,
    hidden: bool,
    classes: Option<Vec<String>>,
    scale: Option<f64>,
    title: Option<String>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let frame = 1..=chamfer_runtime::camera::MAX_VIEWPORT;
    if !frame.contains(&width) || !frame.contains(&height) {
        return Err(errors::options(format!(
            "width and height must be 1 to {} pixels, not {width}x{height}",
            frame.end()
        )));
    }
    let (orbit, options) = options::view_from_kwargs(py, options)?;
    // Checked whatever the source: a misspelt keyword is an error even where nothing is baked.
    let bake_options = options::from_kwargs(Some(&options))?.with_intersections(true);
    if scale.is_some_and(|s| !(s.is_finite() && s > 0.0)) {
        return Err(errors::options(
            "scale must be a positive number of millimetres per model unit".into(),
        ));
    }
    let classes = match classes {
        None => LineClass::ALL.to_vec(),
        Some(names) => names
            .iter()
            .map(|name| {
                LineClass::ALL
                    .into_iter()
                    .find(|c| c.name() == name)
                    .ok_or_else(|| {
                        errors::options(format!(
                            "unknown line class {name:?} (contour, boundary, marked, crease, intersection)"
                        ))
                    })
            })
            .collect::<PyResult<_>>()?,
    };
    let draw_options = DrawOptions::DEFAULT
        .with_classes(&classes)
        .with_hidden(hidden);

    let baked;
    let (asset, input): (&Asset, Option<PathBuf>) = match source.cast::<PyAsset>() {
        Ok(held) => (held.get().asset(), None),
        Err(_) => {
            let path: PathBuf = source.extract().map_err(|_| {
                pyo3::exceptions::PyTypeError::new_err(
                    "draw_svg() takes an Asset or the path of an asset or a mesh",
                )
            })?;
            baked = py.detach(|| read_or_bake(&path, &bake_options))?;
            (&baked, Some(path))
        }
    };
    let title = title.unwrap_or_else(|| match &input {
        Some(path) => path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        ),
        None => asset.header.source.clone(),
    });
    let svg_options = SvgOptions::DEFAULT
        .with_mm_per_unit(scale)
        .with_title(title)
        .with_description(format!(
            "Camera: chamfer render {}.",
            orbit.flags([width, height])
        ));
    if let Some(output) = &output {
        let inputs: Vec<&std::path::Path> = input.iter().map(PathBuf::as_path).collect();
        ensure_not_an_input(output, &inputs)
            .map_err(|e| errors::from_library_writing(e, output))?;
    }
    let bounds = [asset.header.bounds_min, asset.header.bounds_max];
    let view = Camera::orbit(bounds, &orbit, [width, height]);
    let svg = py.detach(|| {
        let drawing = hidden_lines(asset, &view, &draw_options);
        let mut svg = Vec::new();
        // Writing into memory cannot fail.
        let _ = write_svg(&drawing, &svg_options, &mut svg);
        svg
    });
    if let Some(output) = &output {
        py.detach(|| write_atomically(output, |out| std::io::Write::write_all(out, &svg)))
            .map_err(|e| errors::from_library_writing(e, output))?;
    }
    // write_svg writes Rust strings: UTF-8.
    Ok(String::from_utf8_lossy(&svg).into_owned())
}

/// A `.chamfer` file decoded, or a mesh file baked.
fn read_or_bake(
    path: &std::path::Path,
    options: &chamfer_preprocess::BakeOptions,
) -> Result<Asset, Failure> {
    let is_asset = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("chamfer"));
    if is_asset {
        let bytes = chamfer_preprocess::load::read(path, &options.limits)?;
        Asset::decode(&bytes).map_err(|e| Failure::Decode(path.to_owned(), e))
    } else {
        Ok(chamfer_preprocess::bake_file(path, options)?.asset)
    }
}
