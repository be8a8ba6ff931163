//! `chamfer.draw_svg`, `draw_pdf` and `draw_dxf`: hidden-line and section drawings as `chamfer
//! draw` makes them, from the same keywords: `width` and `height`, the view schema's
//! (`chamfer.VIEW_SCHEMA`, its camera flags), the section's (`chamfer.SECTION_SCHEMA`) and the line
//! roles' styles (`chamfer.DRAWING_STYLE_SCHEMA`).

use std::path::PathBuf;

use chamfer_preprocess::draw::dxf::write_dxf;
use chamfer_preprocess::draw::paper::{ModelUnit, PaperOptions, parse_scale, section_note};
use chamfer_preprocess::draw::pdf::write_pdf;
use chamfer_preprocess::draw::section::drawing_plane;
use chamfer_preprocess::draw::style::DrawingStyle;
use chamfer_preprocess::draw::svg::write_svg;
use chamfer_preprocess::draw::{Camera, DrawOptions, LineClass, hidden_lines, units_per_px};
use chamfer_preprocess::write::{ensure_not_an_input, write_atomically};
use chamfer_runtime::asset::Asset;
use chamfer_runtime::section::Section;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::asset::PyAsset;
use crate::errors::Failure;
use crate::{errors, options};

/// A hidden-line drawing as SVG text, the same as `chamfer draw` writes for the same camera.
///
/// `source` is an Asset, a `.chamfer` file, or a mesh file (baked first, with intersection
/// edges, and the bake options as for bake()). `classes` picks the line classes (contour,
/// boundary, marked, crease, intersection, cut, hatch; default all), `hidden` also draws the
/// hidden parts (dashed), `scale` is paper millimetres per model unit (a number, default 96 dpi)
/// or a ratio paper:real (`"1:50"`) of model lengths in `units` (mm, cm, m, in, ft), `title`
/// defaults to the file's name (or the asset's source). When `output` is given the drawing is
/// also written there atomically. The interpreter is released while drawing.
///
/// The camera orbits the model's bounding box, in a frame of `width` x `height` pixels, where
/// the view keywords put it (chamfer.VIEW_SCHEMA, `chamfer draw`'s camera flags of the same
/// names):
/// {view_keywords}
///
/// A section drawing (chamfer.SECTION_SCHEMA, `chamfer draw --section`) keeps the half the plane
/// keeps and draws the cut outline and the hatched cut faces:
/// {section_keywords}
///
/// Each line role is a layer with its own style (chamfer.DRAWING_STYLE_SCHEMA, the style flags of
/// `chamfer draw`):
/// {style_keywords}
///
/// The bake options, for a mesh file:
/// {bake_keywords}
#[pyfunction]
#[pyo3(signature = (
    source, output = None, *, width = 1024, height = 768, hidden = false, classes = None,
    scale = None, units = "mm", title = None, **options
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
    scale: Option<&Bound<'_, PyAny>>,
    units: &str,
    title: Option<String>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let scale = read_scale(scale, units)?;
    let request = Request::new(py, [width, height], hidden, classes, scale, title, options)?;
    let svg = request.draw(py, source, output, Format::Svg)?;
    // write_svg writes Rust strings: UTF-8.
    Ok(String::from_utf8_lossy(&svg).into_owned())
}

/// A hidden-line drawing as PDF bytes, the same as `chamfer draw -o FILE.pdf` writes: one page at
/// the scale asked for, each line role an optional content group (a layer). The arguments are
/// draw_svg's.
#[pyfunction]
#[pyo3(signature = (
    source, output = None, *, width = 1024, height = 768, hidden = false, classes = None,
    scale = None, units = "mm", title = None, **options
))]
#[allow(clippy::too_many_arguments)]
pub fn draw_pdf<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    output: Option<PathBuf>,
    width: u32,
    height: u32,
    hidden: bool,
    classes: Option<Vec<String>>,
    scale: Option<&Bound<'_, PyAny>>,
    units: &str,
    title: Option<String>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyBytes>> {
    let scale = read_scale(scale, units)?;
    let request = Request::new(py, [width, height], hidden, classes, scale, title, options)?;
    let pdf = request.draw(py, source, output, Format::Pdf)?;
    Ok(PyBytes::new(py, &pdf))
}

/// A hidden-line drawing as DXF text, the same as `chamfer draw -o FILE.dxf` writes: a layer per
/// line role, LWPOLYLINE entities, millimetres. The arguments are draw_svg's.
#[pyfunction]
#[pyo3(signature = (
    source, output = None, *, width = 1024, height = 768, hidden = false, classes = None,
    scale = None, units = "mm", title = None, **options
))]
#[allow(clippy::too_many_arguments)]
pub fn draw_dxf(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    output: Option<PathBuf>,
    width: u32,
    height: u32,
    hidden: bool,
    classes: Option<Vec<String>>,
    scale: Option<&Bound<'_, PyAny>>,
    units: &str,
    title: Option<String>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let scale = read_scale(scale, units)?;
    let request = Request::new(py, [width, height], hidden, classes, scale, title, options)?;
    let dxf = request.draw(py, source, output, Format::Dxf)?;
    Ok(String::from_utf8_lossy(&dxf).into_owned())
}

/// `scale` (a number or a ratio text) as paper millimetres per model unit.
fn read_scale(scale: Option<&Bound<'_, PyAny>>, units: &str) -> PyResult<Option<f64>> {
    let unit = ModelUnit::named(units).map_err(|e| errors::options(format!("units: {e}")))?;
    let ratio = scale.is_some_and(|s| s.extract::<String>().is_ok_and(|t| t.contains(':')));
    if unit != ModelUnit::Millimetre && !ratio {
        return Err(errors::options(format!(
            "units applies to a scale ratio (scale=\"1:50\", units={units:?})"
        )));
    }
    let Some(scale) = scale else {
        return Ok(None);
    };
    let text = if let Ok(text) = scale.extract::<String>() {
        text
    } else if scale.is_instance_of::<pyo3::types::PyBool>() {
        return Err(errors::options(
            "scale must be a number or a ratio like \"1:50\"".into(),
        ));
    } else {
        let number: f64 = scale.extract().map_err(|_| {
            errors::options("scale must be a number or a ratio like \"1:50\"".into())
        })?;
        number.to_string()
    };
    parse_scale(&text, unit)
        .map(Some)
        .map_err(|e| errors::options(format!("scale: {e}")))
}

#[derive(Clone, Copy)]
enum Format {
    Svg,
    Pdf,
    Dxf,
}

/// A drawing's arguments, checked before anything is read.
struct Request {
    viewport: [u32; 2],
    orbit: chamfer_runtime::camera::Orbit,
    bake_options: chamfer_preprocess::BakeOptions,
    draw_options: DrawOptions,
    section: Option<chamfer_runtime::section::Plane>,
    style: DrawingStyle,
    scale: Option<f64>,
    title: Option<String>,
}

impl Request {
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        viewport: [u32; 2],
        hidden: bool,
        classes: Option<Vec<String>>,
        scale: Option<f64>,
        title: Option<String>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let [width, height] = viewport;
        let frame = 1..=chamfer_runtime::camera::MAX_VIEWPORT;
        if !frame.contains(&width) || !frame.contains(&height) {
            return Err(errors::options(format!(
                "width and height must be 1 to {} pixels, not {width}x{height}",
                frame.end()
            )));
        }
        let (orbit, options) = options::view_from_kwargs(py, options)?;
        let (section, options) =
            options::group_from_kwargs::<Section>(py, "section", Some(&options))?;
        let (style, options) =
            options::group_from_kwargs::<DrawingStyle>(py, "drawing_style", Some(&options))?;
        style.check().map_err(|e| errors::options(e.to_string()))?;
        let plane = drawing_plane(&section).map_err(|e| errors::options(e.to_string()))?;
        // Checked whatever the source: a misspelt keyword is an error even where nothing is baked.
        let bake_options = options::from_kwargs(Some(&options))?.with_intersections(true);
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
                                "unknown line class {name:?} (contour, boundary, marked, crease, intersection, cut, hatch)"
                            ))
                        })
                })
                .collect::<PyResult<_>>()?,
        };
        Ok(Self {
            viewport,
            orbit,
            bake_options,
            draw_options: DrawOptions::DEFAULT
                .with_classes(&classes)
                .with_hidden(hidden)
                .with_section(plane),
            section: plane,
            style,
            scale,
            title,
        })
    }

    /// Reads or bakes `source`, draws it, writes it to `output` if given, and returns the bytes.
    fn draw(
        self,
        py: Python<'_>,
        source: &Bound<'_, PyAny>,
        output: Option<PathBuf>,
        format: Format,
    ) -> PyResult<Vec<u8>> {
        let baked;
        let (asset, input): (&Asset, Option<PathBuf>) = match source.cast::<PyAsset>() {
            Ok(held) => (held.get().asset(), None),
            Err(_) => {
                let path: PathBuf = source.extract().map_err(|_| {
                    pyo3::exceptions::PyTypeError::new_err(
                        "a drawing takes an Asset or the path of an asset or a mesh",
                    )
                })?;
                let options = &self.bake_options;
                baked = py.detach(|| read_or_bake(&path, options))?;
                (&baked, Some(path))
            }
        };
        let title = self.title.clone().unwrap_or_else(|| match &input {
            Some(path) => path.file_name().map_or_else(
                || path.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            ),
            None => asset.header.source.clone(),
        });
        let mut description = format!(
            "Camera: chamfer render {}.",
            self.orbit.flags(self.viewport)
        );
        if let Some(plane) = &self.section {
            description += &section_note(plane);
        }
        let paper = PaperOptions::DEFAULT
            .with_mm_per_unit(self.scale)
            .with_title(title)
            .with_description(description);
        if let Some(output) = &output {
            let extension = output
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            let (wanted, function) = match format {
                Format::Svg => ("svg", "draw_svg"),
                Format::Pdf => ("pdf", "draw_pdf"),
                Format::Dxf => ("dxf", "draw_dxf"),
            };
            if extension
                .as_deref()
                .is_some_and(|e| ["svg", "pdf", "dxf"].contains(&e) && e != wanted)
            {
                return Err(errors::options(format!(
                    "{}: {function}() writes .{wanted}, not .{}",
                    output.display(),
                    extension.unwrap_or_default()
                )));
            }
            let inputs: Vec<&std::path::Path> = input.iter().map(PathBuf::as_path).collect();
            ensure_not_an_input(output, &inputs)
                .map_err(|e| errors::from_library_writing(e, output))?;
        }
        let bounds = [asset.header.bounds_min, asset.header.bounds_max];
        let view = Camera::orbit(bounds, &self.orbit, self.viewport);
        let mm_per_px = paper.mm_per_px_at(units_per_px(asset, &view));
        let options = self.draw_options.with_hatch(self.style.hatch(mm_per_px));
        let style = self.style;
        let bytes = py.detach(|| {
            let drawing = hidden_lines(asset, &view, &options);
            let mut bytes = Vec::new();
            // Writing into memory cannot fail.
            let _ = match format {
                Format::Svg => write_svg(&drawing, &style, &paper, &mut bytes),
                Format::Pdf => write_pdf(&drawing, &style, &paper, &mut bytes),
                Format::Dxf => write_dxf(&drawing, &style, &paper, &mut bytes),
            };
            bytes
        });
        if let Some(output) = &output {
            py.detach(|| write_atomically(output, |out| std::io::Write::write_all(out, &bytes)))
                .map_err(|e| errors::from_library_writing(e, output))?;
        }
        Ok(bytes)
    }
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
