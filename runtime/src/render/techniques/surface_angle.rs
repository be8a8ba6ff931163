//! [`Technique::SurfaceAngle`](crate::render::Technique::SurfaceAngle): surface-angle contours
//! (thesis §7.1, `shaders/surface_angle.wgsl`): the mesh drawn once more over itself, inked where its
//! normal is nearly perpendicular to the view.

use chamfer_shaders as wgsl;

use super::pulled::{Draws, Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, PARAMS};
use crate::render::gpu_asset::VERTEX_LAYOUTS;
use crate::render::layout::{Layout, layout};
use crate::render::modules::Program;
use crate::render::pipelines::Raster;
use crate::render::{Target, Technique};

pub(crate) static MODULE: PullModule<SurfaceAngle> = PullModule::new();

crate::schema! {
    /// Parameters of the surface-angle contours (§7.1): `chamfer render
    /// --surface-angle-threshold`, the page's technique panel.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct SurfaceAngleSettings {
        /// |N·V| below which a pixel is inked: wider contours where the surface curves slowly.
        threshold: f32 = 0.2, { group: "surface_angle", value: "DOT", range: Some((0.0, 1.0)),
            example: 0.45, conflicts: [], requires: [] },
    }
}

#[derive(Debug)]
pub(crate) struct SurfaceAngle;

/// `AngleParams` in `shaders/surface_angle.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct AngleParams {
    threshold: f32,
}

impl Pull for SurfaceAngle {
    const PRESETS: &'static [crate::render::Preset] = &[crate::render::Preset {
        name: "surface-angle",
        summary: "pixels whose normal is nearly perpendicular to the view (thesis §7.1)",
        technique: crate::render::Technique::SurfaceAngle(SurfaceAngleSettings { threshold: 0.2 }),
    }];

    type Params = AngleParams;
    type Draw = ();
    const BINDINGS: &'static Bindings = &Bindings::draw("surface angle", &[FRAME, PARAMS]);
    const SHADER: (&'static str, &'static [&'static str]) = (
        "surface_angle.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::SURFACE_ANGLE,
        ],
    );
    const DRAWS: Draws = Draws::Mesh;
    const PROGRAMS: &'static [Program] = &[Program::draw(
        "angle_vertex",
        "angle_fragment",
        Self::BINDINGS,
    )];
    const STRUCTS: &'static [Layout] = &[layout!("AngleParams", AngleParams, [threshold])];

    fn raster(target: &Target) -> Raster<'static> {
        Raster {
            buffers: &VERTEX_LAYOUTS,
            ..Raster::over_mesh(target)
        }
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<AngleParams> {
        let Technique::SurfaceAngle(SurfaceAngleSettings { threshold }) = cx.style.technique else {
            return None;
        };
        let threshold = if threshold.is_finite() {
            threshold.clamp(0.0, 1.0)
        } else {
            0.0
        };
        Some(AngleParams { threshold })
    }
}
