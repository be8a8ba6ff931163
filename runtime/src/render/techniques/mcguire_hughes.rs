//! [`Technique::McGuireHughes`](crate::render::Technique::McGuireHughes): McGuire and Hughes'
//! hardware-determined feature edges (thesis §8, `shaders/mcguire_hughes.wgsl`).
//!
//! The 2004 method stored four duplicated edge vertices per edge and classified the edge in the
//! vertex shader of each; wgpu lets the vertex shader pull the asset's own sections instead, so the
//! duplication is of work, not memory: per frame every edge runs the classification at each of the
//! quad's four vertices and each cap pass's three (§8.5 "high duplication of work"), and nothing is
//! compacted. Per-frame memory: one uniform block per instance.

use super::pulled::{Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, asset};
use crate::render::layout::Layout;
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::{CapMethod, GpuAsset, Pipelines, RenderError, Target, Technique};

pub(crate) static MODULE: PullModule<McGuireHughes> = PullModule::new();

const BINDINGS: Bindings = Bindings::draw(
    "mcguire-hughes",
    &[
        FRAME,
        asset::TOPOLOGY,
        asset::EDGE_VERTICES,
        asset::ATTRIBUTES,
        asset::VERTEX_NORMALS,
    ],
);

pub(crate) struct McGuireHughes;

fn shader() -> Shader {
    use chamfer_shaders as wgsl;
    let program = |vertex| Program::draw(vertex, "flat_fragment", &BINDINGS);
    Shader::new(
        "mcguire_hughes.wgsl",
        &[
            wgsl::COMMON,
            wgsl::FLAT,
            wgsl::VERTEX_EDGES,
            wgsl::MCGUIRE_HUGHES,
        ],
        vec![
            program("mh_edge_vertex"),
            program("mh_cap0_vertex"),
            program("mh_cap1_vertex"),
        ],
    )
}

/// The edge pass and the two cap passes, per device and target.
#[derive(Debug)]
pub(crate) struct McGuireHughesPipelines {
    edges: wgpu::RenderPipeline,
    cap0: wgpu::RenderPipeline,
    cap1: wgpu::RenderPipeline,
    /// The quad's two triangles over its four edge vertices.
    quad: wgpu::Buffer,
}

impl PipelineSet for McGuireHughesPipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        let pipeline = |vertex| {
            compiled.render(
                vertex,
                Some("flat_fragment"),
                Raster::over_mesh(cache.target()),
            )
        };
        Ok(Self {
            edges: pipeline("mh_edge_vertex")?,
            cap0: pipeline("mh_cap0_vertex")?,
            cap1: pipeline("mh_cap1_vertex")?,
            quad: super::corner_indices(cache, "edge quad", &[0, 1, 2, 0, 2, 3]),
        })
    }
}

impl Pull for McGuireHughes {
    type Params = ();
    type Pipelines = McGuireHughesPipelines;
    /// Whether the two cap passes run.
    type Draw = bool;
    const BINDINGS: &'static Bindings = &BINDINGS;

    fn shaders(_target: &Target) -> Vec<Shader> {
        vec![shader()]
    }

    fn structs() -> Vec<Layout> {
        Vec::new()
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<()> {
        (cx.style.technique == Technique::McGuireHughes).then_some(())
    }

    fn draw_state(cx: &FrameContext<'_>) -> bool {
        cx.style.caps != CapMethod::None
    }

    fn draw(
        set: &McGuireHughesPipelines,
        caps: bool,
        pass: &mut wgpu::RenderPass<'_>,
        asset: &GpuAsset,
    ) {
        let edges = asset.edge_count;
        pass.set_pipeline(&set.edges);
        pass.set_index_buffer(set.quad.slice(..), wgpu::IndexFormat::Uint16);
        pass.draw_indexed(0..6, 0, 0..edges);
        if caps {
            pass.set_pipeline(&set.cap0);
            pass.draw(0..3, 0..edges);
            pass.set_pipeline(&set.cap1);
            pass.draw(0..3, 0..edges);
        }
    }
}
