//! [`Technique::McGuireHughes`](crate::render::Technique::McGuireHughes): McGuire and Hughes'
//! hardware-determined feature edges (thesis §8, `shaders/mcguire_hughes.wgsl`).
//!
//! The 2004 method stored four duplicated edge vertices per edge and classified the edge in the
//! vertex shader of each; wgpu lets the vertex shader pull the asset's own sections instead, so the
//! duplication is of work, not memory: per frame every edge runs the classification at each of the
//! quad's four vertices and each cap pass's three (§8.5 "high duplication of work"), and nothing is
//! compacted. Every instance of an asset is drawn by one draw sequence (a batch, issue 28). Per-frame
//! memory: a uniform block per batch and each instance's view.

use chamfer_shaders as wgsl;

use super::pulled::{Draws, Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, INSTANCE_FRAMES, asset};
use crate::render::layout::Layout;
use crate::render::modules::Program;
use crate::render::{CapMethod, GpuAsset, Pipelines, Technique};

pub(crate) static MODULE: PullModule<McGuireHughes> = PullModule::new();

#[derive(Debug)]
pub(crate) struct McGuireHughes;

const BINDINGS: Bindings = Bindings::draw(
    "mcguire-hughes",
    &[
        FRAME,
        asset::TOPOLOGY,
        asset::EDGE_VERTICES,
        asset::ATTRIBUTES,
        asset::VERTEX_NORMALS,
        INSTANCE_FRAMES,
    ],
);

impl Pull for McGuireHughes {
    const PRESETS: &'static [crate::render::Preset] = &[crate::render::Preset {
        name: "mcguire-hughes",
        summary: "McGuire-Hughes: every edge a quad classified per vertex, two cap passes (thesis §8)",
        technique: crate::render::Technique::McGuireHughes,
    }];

    type Params = ();
    /// Whether the two cap passes run.
    type Draw = bool;
    const BINDINGS: &'static Bindings = &BINDINGS;
    const SHADER: (&'static str, &'static [&'static str]) = (
        "mcguire_hughes.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::BATCH,
            wgsl::FLAT,
            wgsl::VERTEX_EDGES,
            wgsl::MCGUIRE_HUGHES,
        ],
    );
    /// The quad, six indexed vertices per edge (`draw` adds the caps).
    const BATCHED: bool = true;
    const DRAWS: Draws = Draws::PerEdge(6);
    /// The edge pass and the two cap passes.
    const PROGRAMS: &'static [Program] = &[
        Program::draw("mh_edge_vertex", "flat_fragment", &BINDINGS),
        Program::draw("mh_cap0_vertex", "flat_fragment", &BINDINGS),
        Program::draw("mh_cap1_vertex", "flat_fragment", &BINDINGS),
    ];
    const STRUCTS: &'static [Layout] = &[];

    /// The quad's two triangles over its four edge vertices.
    fn index_buffers(cache: &Pipelines) -> Vec<wgpu::Buffer> {
        vec![super::corner_indices(
            cache,
            "edge quad",
            &[0, 1, 2, 0, 2, 3],
        )]
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<()> {
        (cx.style.technique == Technique::McGuireHughes).then_some(())
    }

    fn draw_state(cx: &FrameContext<'_>) -> bool {
        cx.style.caps != CapMethod::None
    }

    fn draw(
        pipelines: &[wgpu::RenderPipeline],
        indices: &[wgpu::Buffer],
        caps: bool,
        pass: &mut wgpu::RenderPass<'_>,
        asset: &GpuAsset,
        copies: u32,
    ) {
        let ([edges, cap0, cap1], [quad]) = (pipelines, indices) else {
            return;
        };
        // Every instance of the batch: its edges one instance after another.
        let count = asset.edge_count * copies;
        pass.set_pipeline(edges);
        pass.set_index_buffer(quad.slice(..), wgpu::IndexFormat::Uint16);
        pass.draw_indexed(0..6, 0, 0..count);
        if caps {
            pass.set_pipeline(cap0);
            pass.draw(0..3, 0..count);
            pass.set_pipeline(cap1);
            pass.draw(0..3, 0..count);
        }
    }
}
