//! [`Technique::Fins`](crate::render::Technique::Fins): seed 003's geometry-shader inking, in the
//! vertex shader (`shaders/fins.wgsl`): per edge instance, twelve vertices, a fin per front-facing
//! face whose edge is a silhouette or a crease, extruded along that face's corner normals, crease
//! fins biased towards the camera (Listing 3).

use super::pulled::{Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, PARAMS, asset};
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::{GpuAsset, Pipelines, RenderError, Target, Technique};

pub(crate) static MODULE: PullModule<Fins> = PullModule::new();

const BINDINGS: Bindings = Bindings::draw(
    "fins",
    &[
        FRAME,
        PARAMS,
        asset::TOPOLOGY,
        asset::EDGE_VERTICES,
        asset::ATTRIBUTES,
        asset::RENDER_NORMALS,
        asset::FIN_CORNERS,
    ],
);

/// `FinParams` in `shaders/fins.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct FinParams {
    thickness: f32,
    in_pixels: u32,
    z_bias: f32,
    _pad: u32,
}

pub(crate) struct Fins;

fn shader() -> Shader {
    use chamfer_shaders as wgsl;
    Shader::new(
        "fins.wgsl",
        &[wgsl::COMMON, wgsl::FLAT, wgsl::FINS],
        vec![Program::draw("fin_vertex", "flat_fragment", &BINDINGS)],
    )
}

/// The fin pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct FinPipelines {
    fins: wgpu::RenderPipeline,
}

impl PipelineSet for FinPipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            fins: compiled.render(
                "fin_vertex",
                Some("flat_fragment"),
                Raster::over_mesh(cache.target()),
            )?,
        })
    }
}

impl Pull for Fins {
    type Params = FinParams;
    type Pipelines = FinPipelines;
    type Draw = ();
    const BINDINGS: &'static Bindings = &BINDINGS;

    fn shaders(_target: &Target) -> Vec<Shader> {
        vec![shader()]
    }

    fn structs() -> Vec<Layout> {
        vec![layout!(
            "FinParams",
            FinParams,
            [thickness, in_pixels, z_bias, _pad]
        )]
    }

    fn params(cx: &FrameContext<'_>, drawn: &Drawn<'_>) -> Option<FinParams> {
        let Technique::Fins {
            world_thickness,
            z_bias,
        } = cx.style.technique
        else {
            return None;
        };
        let finite = |v: f32| if v.is_finite() { v } else { 0.0 };
        let [lo, hi] = drawn.asset.bounds().map(glam::Vec3::from);
        Some(FinParams {
            thickness: finite(world_thickness.unwrap_or(cx.style.width())),
            in_pixels: u32::from(world_thickness.is_none()),
            z_bias: finite(z_bias.unwrap_or(2e-3 * (hi - lo).length())),
            _pad: 0,
        })
    }

    fn draw(set: &FinPipelines, _: (), pass: &mut wgpu::RenderPass<'_>, asset: &GpuAsset) {
        pass.set_pipeline(&set.fins);
        pass.draw(0..12, 0..asset.edge_count);
    }
}
