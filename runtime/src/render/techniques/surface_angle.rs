//! [`Technique::SurfaceAngle`](crate::render::Technique::SurfaceAngle): surface-angle contours
//! (thesis §7.1, `shaders/surface_angle.wgsl`): the mesh drawn once more over itself, inked where its
//! normal is nearly perpendicular to the view.

use super::pulled::{Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, PARAMS};
use crate::render::gpu_asset::vertex_layouts;
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::{GpuAsset, Pipelines, RenderError, Target, Technique};

pub(crate) static MODULE: PullModule<SurfaceAngle> = PullModule::new();

const BINDINGS: Bindings = Bindings::draw("surface angle", &[FRAME, PARAMS]);

/// `AngleParams` in `shaders/surface_angle.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct AngleParams {
    threshold: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

pub(crate) struct SurfaceAngle;

fn shader() -> Shader {
    use chamfer_shaders as wgsl;
    Shader::new(
        "surface_angle.wgsl",
        &[wgsl::COMMON, wgsl::SURFACE_ANGLE],
        vec![Program::draw("angle_vertex", "angle_fragment", &BINDINGS)],
    )
}

/// The pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct AnglePipelines {
    angle: wgpu::RenderPipeline,
}

impl PipelineSet for AnglePipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            angle: compiled.render(
                "angle_vertex",
                Some("angle_fragment"),
                Raster {
                    buffers: &vertex_layouts(),
                    ..Raster::over_mesh(cache.target())
                },
            )?,
        })
    }
}

impl Pull for SurfaceAngle {
    type Params = AngleParams;
    type Pipelines = AnglePipelines;
    type Draw = ();
    const BINDINGS: &'static Bindings = &BINDINGS;

    fn shaders(_target: &Target) -> Vec<Shader> {
        vec![shader()]
    }

    fn structs() -> Vec<Layout> {
        vec![layout!(
            "AngleParams",
            AngleParams,
            [threshold, _pad0, _pad1, _pad2]
        )]
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<AngleParams> {
        let Technique::SurfaceAngle { threshold } = cx.style.technique else {
            return None;
        };
        Some(AngleParams {
            threshold: if threshold.is_finite() {
                threshold.clamp(0.0, 1.0)
            } else {
                0.0
            },
            _pad0: 0,
            _pad1: 0,
            _pad2: 0,
        })
    }

    fn draw(set: &AnglePipelines, _: (), pass: &mut wgpu::RenderPass<'_>, asset: &GpuAsset) {
        pass.set_pipeline(&set.angle);
        super::draw_mesh(pass, asset);
    }
}
