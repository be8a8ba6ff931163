//! `chamfer.draw_svg`: hidden-line drawings as `chamfer draw` makes them, from the same camera
//! keywords (its `--width --height --azimuth --elevation --distance --ortho` flags).

use std::path::PathBuf;

use chamfer_preprocess::draw::svg::{SvgOptions, write_svg};
use chamfer_preprocess::draw::{DrawOptions, LineClass, View, hidden_lines};
use chamfer_preprocess::write::{ensure_not_an_input, write_atomically};
use chamfer_runtime::asset::Asset;
use glam::Vec3;
use glam::camera::rh::{proj::directx, view::look_at_mat4};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::asset::PyAsset;
use crate::errors::Failure;
use crate::{errors, options};

/// Where the orbit camera sits: `chamfer draw`'s camera flags.
struct Orbit {
    width: u32,
    height: u32,
    azimuth: f32,
    elevation: f32,
    distance: Option<f32>,
    ortho: bool,
}

/// The vertical field of view of the perspective camera, degrees (the runtime's `Orbit` default).
const FOV_Y_DEG: f32 = 35.0;

impl Orbit {
    /// The checks of `chamfer draw`'s camera flags, as OptionsError.
    fn check(&self) -> PyResult<()> {
        if !(1..=16_384).contains(&self.width) || !(1..=16_384).contains(&self.height) {
            return Err(errors::options(format!(
                "width and height must be 1 to 16384 pixels, not {}x{}",
                self.width, self.height
            )));
        }
        if !self.azimuth.is_finite() || !self.elevation.is_finite() {
            return Err(errors::options(
                "azimuth and elevation must be finite".into(),
            ));
        }
        if self.distance.is_some_and(|d| !(d.is_finite() && d > 0.0)) {
            return Err(errors::options("distance must be a positive number".into()));
        }
        Ok(())
    }

    /// The camera flags as `chamfer render` takes them: the drawing's description names them.
    fn describe(&self) -> String {
        let mut flags = format!(
            "--width {} --height {} --azimuth {} --elevation {}",
            self.width, self.height, self.azimuth, self.elevation
        );
        if let Some(d) = self.distance {
            flags += &format!(" --distance {d}");
        }
        if self.ortho {
            flags += " --ortho";
        }
        flags
    }

    /// The view framing `bounds` from this orbit.
    ///
    /// The same arithmetic as `chamfer_runtime::render::Camera::orbit`, which lives behind the
    /// runtime's wgpu feature that this package does not build; tests/test_draw.py checks that the
    /// drawings equal `chamfer draw`'s byte for byte, so the two cannot drift apart unseen.
    fn view(&self, bounds: [[f32; 3]; 2]) -> View {
        let viewport = [self.width, self.height];
        let [lo, hi] = bounds.map(Vec3::from);
        let center = (lo + hi) * 0.5;
        let radius = ((hi - lo).length() * 0.5).max(1e-6);
        let aspect = viewport[0].max(1) as f32 / viewport[1].max(1) as f32;
        let (azimuth, elevation) = (self.azimuth.to_radians(), self.elevation.to_radians());
        let towards_eye = Vec3::new(
            elevation.cos() * azimuth.sin(),
            elevation.sin(),
            elevation.cos() * azimuth.cos(),
        );
        let fov_y = FOV_Y_DEG.to_radians().clamp(1e-3, 3.0);
        let fov_x = 2.0 * ((fov_y * 0.5).tan() * aspect).atan();
        let fit = radius / (fov_y.min(fov_x) * 0.5).sin();
        let distance = self.distance.unwrap_or(fit * 1.02).max(1e-6);
        let eye = center + towards_eye * distance;
        let up = if towards_eye.y.abs() > 0.999 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let model_view = look_at_mat4(eye, center, up);
        let (near, far) = (
            (distance - radius * 1.5).max(distance * 1e-3),
            distance + radius * 1.5,
        );
        let projection = if self.ortho {
            let half_height = radius * 1.02 * aspect.recip().max(1.0);
            directx::orthographic(
                -half_height * aspect,
                half_height * aspect,
                -half_height,
                half_height,
                distance - radius * 1.5,
                far,
            )
        } else {
            directx::perspective(fov_y, aspect, near, far)
        };
        View {
            model_view,
            projection,
            viewport,
        }
    }
}

/// A hidden-line drawing as SVG text, the same as `chamfer draw` writes for the same camera.
///
/// `source` is an Asset, a `.chamfer` file, or a mesh file (baked first, with intersection
/// edges, and the bake options as for bake()). The camera orbits the model's bounding box:
/// `azimuth` turns around +Y (0 looks from +Z), `elevation` rises above the horizon (degrees),
/// `distance` from the centre (default: frame the model), `ortho` for an orthographic view, in a
/// frame of `width` x `height` pixels. `classes` picks the line classes (contour, boundary,
/// marked, crease, intersection; default all), `hidden` also draws the hidden parts (dashed),
/// `scale` is paper millimetres per model unit (default 96 dpi), `title` defaults to the file's
/// name (or the asset's source). When `output` is given the SVG is also written there
/// atomically. The interpreter is released while drawing.
#[pyfunction]
#[pyo3(signature = (
    source, output = None, *, width = 1024, height = 768, azimuth = 35.0, elevation = 25.0,
    distance = None, ortho = false, hidden = false, classes = None, scale = None, title = None,
    **options
))]
#[allow(clippy::too_many_arguments)]
pub fn draw_svg(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    output: Option<PathBuf>,
    width: u32,
    height: u32,
    azimuth: f32,
    elevation: f32,
    distance: Option<f32>,
    ortho: bool,
    hidden: bool,
    classes: Option<Vec<String>>,
    scale: Option<f64>,
    title: Option<String>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let orbit = Orbit {
        width,
        height,
        azimuth,
        elevation,
        distance,
        ortho,
    };
    orbit.check()?;
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
            let bake_options = options::from_kwargs(options)?.with_intersections(true);
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
        .with_description(format!("Camera: chamfer render {}.", orbit.describe()));
    if let Some(output) = &output {
        let inputs: Vec<&std::path::Path> = input.iter().map(PathBuf::as_path).collect();
        ensure_not_an_input(output, &inputs)
            .map_err(|e| errors::from_library_writing(e, output))?;
    }
    let view = orbit.view([asset.header.bounds_min, asset.header.bounds_max]);
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
