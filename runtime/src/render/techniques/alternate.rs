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

use chamfer_shaders as wgsl;

use super::pulled::{Draws, Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, PARAMS, asset};
use crate::render::layout::{Layout, layout};
use crate::render::modules::Program;
use crate::render::{GpuAsset, Pipelines, Technique};

pub(crate) static MODULE: PullModule<Alternate> = PullModule::new();

#[derive(Debug)]
pub(crate) struct Alternate;

/// `AlternateParams` in `shaders/alternate.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct AlternateParams {
    /// The shape `alternate.wgsl` switches on.
    shape: u32,
}

impl Pull for Alternate {
    const PRESETS: &'static [crate::render::Preset] = &[
        crate::render::Preset {
            name: "half-hex",
            summary: "half-hex contours: half quad and caps in one pass (thesis §9.3)",
            technique: crate::render::Technique::HalfHex,
        },
        crate::render::Preset {
            name: "plug",
            summary: "plug edges: full quad and end caps in one pass (thesis §9.3)",
            technique: crate::render::Technique::Plug,
        },
        crate::render::Preset {
            name: "half-hex-plug",
            summary: "half-hex contours with plug edges for the rest (thesis §9.3)",
            technique: crate::render::Technique::HalfHexPlug,
        },
        crate::render::Preset {
            name: "house",
            summary: "house edges, for their artifacts (thesis §9.3)",
            technique: crate::render::Technique::House,
        },
    ];

    type Params = AlternateParams;
    /// True for the house's fan of triangles.
    type Draw = bool;
    const BINDINGS: &'static Bindings = &Bindings::draw(
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
    const SHADER: (&'static str, &'static [&'static str]) = (
        "alternate.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::FLAT,
            wgsl::VERTEX_EDGES,
            wgsl::ALTERNATE,
        ],
    );
    /// Twelve indexed vertices per edge (`draw` picks the shape's indices).
    const DRAWS: Draws = Draws::PerEdge(12);
    const PROGRAMS: &'static [Program] = &[Program::draw(
        "alternate_vertex",
        "flat_fragment",
        Self::BINDINGS,
    )];
    const STRUCTS: &'static [Layout] = &[layout!("AlternateParams", AlternateParams, [shape])];

    /// The four triangles of the half hex and the plug over their six points, and the house's fan.
    fn index_buffers(cache: &Pipelines) -> Vec<wgpu::Buffer> {
        vec![
            super::corner_indices(
                cache,
                "half hex, plug",
                &[0, 1, 2, 0, 2, 3, 0, 3, 4, 1, 5, 2],
            ),
            super::corner_indices(cache, "house", &[0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5]),
        ]
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<AlternateParams> {
        let shape = match cx.style.technique {
            Technique::HalfHex => 1,
            Technique::Plug => 2,
            Technique::HalfHexPlug => 3,
            Technique::House => 4,
            _ => return None,
        };
        Some(AlternateParams { shape })
    }

    fn draw_state(cx: &FrameContext<'_>) -> bool {
        cx.style.technique == Technique::House
    }

    fn draw(
        pipelines: &[wgpu::RenderPipeline],
        indices: &[wgpu::Buffer],
        house: bool,
        pass: &mut wgpu::RenderPass<'_>,
        asset: &GpuAsset,
        copies: u32,
    ) {
        let ([shapes], [hex_plug, house_fan]) = (pipelines, indices) else {
            return;
        };
        let indices = if house { house_fan } else { hex_plug };
        pass.set_pipeline(shapes);
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint16);
        pass.draw_indexed(0..12, 0, 0..asset.edge_count * copies);
    }
}
