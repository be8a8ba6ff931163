//! [`Technique::McGuireHughes`](crate::render::Technique::McGuireHughes): McGuire and Hughes'
//! hardware-determined feature edges (thesis §8, `shaders/mcguire_hughes.wgsl`).
//!
//! The 2004 method stored four duplicated edge vertices per edge and classified the edge in the
//! vertex shader of each; wgpu lets the vertex shader pull the asset's own sections instead, so the
//! duplication is of work, not memory: per frame every edge runs the classification at each of the
//! quad's four vertices and each cap pass's three (§8.5 "high duplication of work"), and nothing is
//! compacted. Per-frame memory: one uniform block per instance.

use std::sync::Arc;

use super::{FrameContext, Pulled, TechniqueFrame, extra, pulled_pipeline};
use crate::render::pipelines::{Access, BindingSet};
use crate::render::{CapMethod, GpuAsset, Pipelines as Cache, RenderError, Technique, modules};

pub(crate) const SET: BindingSet = BindingSet {
    label: "vertex-classified edges",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[
        (0, Access::Instance),
        (1, Access::Read),
        (2, Access::Read),
        (3, Access::Read),
        (4, Access::Read),
    ],
};

/// The asset buffers of [`SET`].
pub(crate) fn buffers(
    asset: &GpuAsset,
    technique: &Technique,
) -> Result<Vec<(u32, wgpu::Buffer)>, RenderError> {
    let normals = extra(
        &asset.vertex_normals,
        technique,
        "AssetExtras::VERTEX_NORMALS",
    )?;
    Ok(vec![
        (1, asset.topology_positions.clone()),
        (2, asset.whole_edge_vertices()?.clone()),
        (3, asset.edge_attributes.clone()),
        (4, normals),
    ])
}

/// The edge pass and the two cap passes, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    edges: wgpu::RenderPipeline,
    cap0: wgpu::RenderPipeline,
    cap1: wgpu::RenderPipeline,
    /// The quad's two triangles over its four edge vertices.
    quad: wgpu::Buffer,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = cache.layout(&SET);
        let module = cache.module("mcguire_hughes.wgsl", &modules::mcguire_hughes())?;
        let pipeline = |label, vertex| {
            pulled_pipeline(cache, &layout, label, &module, vertex, "flat_fragment")
        };
        Ok(Self {
            edges: pipeline("mcguire-hughes edges", "mh_edge_vertex")?,
            cap0: pipeline("mcguire-hughes v0 caps", "mh_cap0_vertex")?,
            cap1: pipeline("mcguire-hughes v1 caps", "mh_cap1_vertex")?,
            quad: super::corner_indices(cache, "edge quad", &[0, 1, 2, 0, 2, 3]),
            layout,
        })
    }
}

/// A frame: the instances' blocks and the groups over their assets.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
    caps: bool,
}

impl Frame {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        Ok(Self {
            pipelines: cache.mcguire_hughes()?,
            pulled: Pulled::new(cache, "mcguire-hughes"),
            caps: true,
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        _encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        self.caps = cx.style.caps != CapMethod::None;
        let technique = cx.style.technique;
        self.pulled.prepare(
            cx,
            &self.pipelines.layout,
            &SET,
            |d, i| super::frame_uniform(cx, d, i, 0),
            |asset| buffers(asset, &technique),
        )
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let p = &self.pipelines;
        let caps = self.caps;
        self.pulled.each(pass, |pass, asset| {
            let edges = asset.edge_count;
            pass.set_pipeline(&p.edges);
            pass.set_index_buffer(p.quad.slice(..), wgpu::IndexFormat::Uint16);
            pass.draw_indexed(0..6, 0, 0..edges);
            if caps {
                pass.set_pipeline(&p.cap0);
                pass.draw(0..3, 0..edges);
                pass.set_pipeline(&p.cap1);
                pass.draw(0..3, 0..edges);
            }
        });
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
