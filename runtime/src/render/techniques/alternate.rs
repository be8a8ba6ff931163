//! The thesis' alternate drawable edge types (§9.3, `shaders/alternate.wgsl`):
//! [`Technique::HalfHex`], [`Technique::Plug`], [`Technique::HalfHexPlug`] and [`Technique::House`].
//! Each draws an edge and its caps in one pass of six points (four indexed triangles) per edge,
//! classified in the vertex shader like McGuire–Hughes (they share `shaders/vertex_edges.wgsl`); one
//! pipeline serves all four shapes, chosen by the parameters block.
//!
//! [`Technique::HalfHex`]: crate::render::Technique::HalfHex
//! [`Technique::Plug`]: crate::render::Technique::Plug
//! [`Technique::HalfHexPlug`]: crate::render::Technique::HalfHexPlug
//! [`Technique::House`]: crate::render::Technique::House

use super::pulled::{Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, PARAMS, asset};
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::{GpuAsset, Pipelines, RenderError, Target, Technique};

pub(crate) static MODULE: PullModule<Alternate> = PullModule::new();

const BINDINGS: Bindings = Bindings::draw(
    "alternate edges",
    &[
        FRAME,
        PARAMS,
        asset::TOPOLOGY,
        asset::EDGE_VERTICES,
        asset::ATTRIBUTES,
        asset::VERTEX_NORMALS,
    ],
);

/// `AlternateParams` in `shaders/alternate.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct AlternateParams {
    /// The shape `alternate.wgsl` switches on.
    shape: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

pub(crate) struct Alternate;

fn shader() -> Shader {
    use chamfer_shaders as wgsl;
    Shader::new(
        "alternate.wgsl",
        &[
            wgsl::COMMON,
            wgsl::FLAT,
            wgsl::VERTEX_EDGES,
            wgsl::ALTERNATE,
        ],
        vec![Program::draw(
            "alternate_vertex",
            "flat_fragment",
            &BINDINGS,
        )],
    )
}

/// The one pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct AlternatePipelines {
    shapes: wgpu::RenderPipeline,
    /// The four triangles of the half hex and the plug over their six points.
    hex_plug: wgpu::Buffer,
    /// The house's fan.
    house: wgpu::Buffer,
}

impl PipelineSet for AlternatePipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            shapes: compiled.render(
                "alternate_vertex",
                Some("flat_fragment"),
                Raster::over_mesh(cache.target()),
            )?,
            hex_plug: super::corner_indices(
                cache,
                "half hex, plug",
                &[0, 1, 2, 0, 2, 3, 0, 3, 4, 1, 5, 2],
            ),
            house: super::corner_indices(cache, "house", &[0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5]),
        })
    }
}

impl Pull for Alternate {
    type Params = AlternateParams;
    type Pipelines = AlternatePipelines;
    /// True for the house's fan of triangles.
    type Draw = bool;
    const BINDINGS: &'static Bindings = &BINDINGS;

    fn shaders(_target: &Target) -> Vec<Shader> {
        vec![shader()]
    }

    fn structs() -> Vec<Layout> {
        vec![layout!(
            "AlternateParams",
            AlternateParams,
            [shape, _pad0, _pad1, _pad2]
        )]
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<AlternateParams> {
        let shape = match cx.style.technique {
            Technique::HalfHex => 1,
            Technique::Plug => 2,
            Technique::HalfHexPlug => 3,
            Technique::House => 4,
            _ => return None,
        };
        Some(AlternateParams {
            shape,
            _pad0: 0,
            _pad1: 0,
            _pad2: 0,
        })
    }

    fn draw_state(cx: &FrameContext<'_>) -> bool {
        cx.style.technique == Technique::House
    }

    fn draw(
        set: &AlternatePipelines,
        house: bool,
        pass: &mut wgpu::RenderPass<'_>,
        asset: &GpuAsset,
    ) {
        let indices = if house { &set.house } else { &set.hex_plug };
        pass.set_pipeline(&set.shapes);
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint16);
        pass.draw_indexed(0..12, 0, 0..asset.edge_count);
    }
}
