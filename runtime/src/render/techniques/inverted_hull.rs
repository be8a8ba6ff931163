//! [`Technique::InvertedHull`](crate::render::Technique::InvertedHull): the expanded inverted hull
//! (thesis §7.2, `shaders/inverted_hull.wgsl`): the mesh pushed out along its normals, front faces
//! culled, in the contour colour.

use super::pulled::{Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, PARAMS, asset};
use crate::render::gpu_asset::vertex_layouts;
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::{GpuAsset, Pipelines, RenderError, Target, Technique};

pub(crate) static MODULE: PullModule<InvertedHull> = PullModule::new();

const BINDINGS: Bindings = Bindings::draw(
    "inverted hull",
    &[
        FRAME,
        PARAMS,
        asset::VERTEX_NORMALS,
        asset::RENDER_TO_TOPOLOGY,
    ],
);

/// `HullParams` in `shaders/inverted_hull.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct HullParams {
    smooth_normals: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

pub(crate) struct InvertedHull;

fn shader() -> Shader {
    use chamfer_shaders as wgsl;
    Shader::new(
        "inverted_hull.wgsl",
        &[wgsl::COMMON, wgsl::FLAT, wgsl::INVERTED_HULL],
        vec![Program::draw("hull_vertex", "flat_fragment", &BINDINGS)],
    )
}

/// The pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct HullPipelines {
    hull: wgpu::RenderPipeline,
}

impl PipelineSet for HullPipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            hull: compiled.render(
                "hull_vertex",
                Some("flat_fragment"),
                Raster {
                    buffers: &vertex_layouts(),
                    primitive: wgpu::PrimitiveState {
                        cull_mode: Some(wgpu::Face::Front),
                        ..Default::default()
                    },
                    ..Raster::over_mesh(cache.target())
                },
            )?,
        })
    }
}

impl Pull for InvertedHull {
    type Params = HullParams;
    type Pipelines = HullPipelines;
    type Draw = ();
    const BINDINGS: &'static Bindings = &BINDINGS;

    fn shaders(_target: &Target) -> Vec<Shader> {
        vec![shader()]
    }

    fn structs() -> Vec<Layout> {
        vec![layout!(
            "HullParams",
            HullParams,
            [smooth_normals, _pad0, _pad1, _pad2]
        )]
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<HullParams> {
        let Technique::InvertedHull { smooth_normals } = cx.style.technique else {
            return None;
        };
        Some(HullParams {
            smooth_normals: u32::from(smooth_normals),
            _pad0: 0,
            _pad1: 0,
            _pad2: 0,
        })
    }

    fn draw(set: &HullPipelines, _: (), pass: &mut wgpu::RenderPass<'_>, asset: &GpuAsset) {
        pass.set_pipeline(&set.hull);
        super::draw_mesh(pass, asset);
    }
}
