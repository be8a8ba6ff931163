//! [`Technique::Fins`](crate::render::Technique::Fins): seed 003's geometry-shader inking, in the
//! vertex shader (`shaders/fins.wgsl`): per edge instance, twelve vertices, a fin per front-facing
//! face whose edge is a silhouette or a crease, extruded along that face's corner normals, crease
//! fins biased towards the camera (Listing 3). Every instance of an asset is drawn by one draw (a
//! batch, issue 28): its parameters depend on the asset, not the instance.

use chamfer_shaders as wgsl;

use super::pulled::{Draws, Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::Technique;
use crate::render::bindings::{Bindings, FRAME, INSTANCE_FRAMES, PARAMS, asset};
use crate::render::layout::{Layout, layout};
use crate::render::modules::Program;

pub(crate) static MODULE: PullModule<Fins> = PullModule::new();

crate::schema! {
    /// Parameters of the fins (seed 003): `chamfer render --fin-thickness`, `--fin-z-bias`, the
    /// page's technique panel.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct FinSettings {
        /// The fin's length in model units; unset: the edge width in pixels at each vertex's depth.
        thickness: Option<f32> = None, { group: "fin", value: "LENGTH",
            range: Some((0.0, crate::schema::FINITE)), example: Some(0.05), conflicts: [],
            requires: [] },
        /// How far crease fins move towards the camera, model units; unset: 0.2 % of the model's
        /// bounding-box diagonal; 0: no bias (the article's z-fighting).
        z_bias: Option<f32> = None, { group: "fin", value: "LENGTH",
            range: Some((0.0, crate::schema::FINITE)), example: Some(0.0), conflicts: [],
            requires: [] },
    }
}

#[derive(Debug)]
pub(crate) struct Fins;

/// `FinParams` in `shaders/fins.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct FinParams {
    thickness: f32,
    in_pixels: u32,
    z_bias: f32,
}

impl Pull for Fins {
    const PRESETS: &'static [crate::render::Preset] = &[crate::render::Preset {
        name: "fins",
        summary: "fins extruded along the normals, with a z-bias (seed 003)",
        technique: crate::render::Technique::Fins(FinSettings {
            thickness: None,
            z_bias: None,
        }),
    }];

    type Params = FinParams;
    type Draw = ();
    const BINDINGS: &'static Bindings = &Bindings::draw(
        "fins",
        &[
            FRAME,
            PARAMS,
            asset::TOPOLOGY,
            asset::EDGE_VERTICES,
            asset::ATTRIBUTES,
            asset::RENDER_NORMALS,
            asset::FIN_CORNERS,
            INSTANCE_FRAMES,
        ],
    );
    const SHADER: (&'static str, &'static [&'static str]) = (
        "fins.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::BATCH,
            wgsl::FLAT,
            wgsl::FINS,
        ],
    );
    const BATCHED: bool = true;
    const DRAWS: Draws = Draws::PerEdge(12);
    const PROGRAMS: &'static [Program] =
        &[Program::draw("fin_vertex", "flat_fragment", Self::BINDINGS)];
    const STRUCTS: &'static [Layout] = &[layout!(
        "FinParams",
        FinParams,
        [thickness, in_pixels, z_bias]
    )];

    fn params(cx: &FrameContext<'_>, drawn: &Drawn<'_>) -> Option<FinParams> {
        let Technique::Fins(FinSettings {
            thickness: world_thickness,
            z_bias,
        }) = cx.style.technique
        else {
            return None;
        };
        let finite = |v: f32| if v.is_finite() { v } else { 0.0 };
        let [lo, hi] = drawn.asset.bounds().map(glam::Vec3::from);
        Some(FinParams {
            thickness: finite(world_thickness.unwrap_or(cx.style.width())),
            in_pixels: u32::from(world_thickness.is_none()),
            z_bias: finite(z_bias.unwrap_or(2e-3 * (hi - lo).length())),
        })
    }
}
