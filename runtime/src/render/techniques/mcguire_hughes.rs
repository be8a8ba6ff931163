//! [`Technique::McGuireHughes`](crate::render::Technique::McGuireHughes): McGuire and Hughes'
//! hardware-determined feature edges (thesis §8, `shaders/mcguire_hughes.wgsl`).
//!
//! The 2004 method stored four duplicated edge vertices per edge and classified the edge in the
//! vertex shader of each; wgpu lets the vertex shader pull the asset's own sections instead, so the
//! duplication is of work, not memory: per frame every edge runs the classification at each of the
//! quad's six vertices and each cap pass's three (§8.5 "high duplication of work"), and nothing is
//! compacted. Per-frame memory: one uniform.

use std::sync::Arc;

use super::{FrameContext, Pulled, TechniqueFrame, extra, pulled_pipeline};
use crate::render::pipelines::{Access, BindingSet};
use crate::render::{CapMethod, GpuAsset, Pipelines as Cache, RenderError, Technique, modules};

pub(crate) const SET: BindingSet = BindingSet {
    label: "vertex-classified edges",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[
        (0, Access::Uniform),
        (1, Access::Read),
        (2, Access::Read),
        (3, Access::Read),
        (4, Access::Read),
    ],
};

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

/// One asset's frame: the uniform and the group over the asset's sections.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
    edge_count: u32,
    caps: bool,
}

impl Frame {
    pub(crate) fn new(cache: &Cache, asset: &GpuAsset) -> Result<Self, RenderError> {
        let pipelines = cache.mcguire_hughes()?;
        let normals = extra(
            &asset.vertex_normals,
            &Technique::McGuireHughes,
            "AssetExtras::VERTEX_NORMALS",
        )?;
        let pulled = Pulled::new(
            cache,
            &pipelines.layout,
            &SET,
            &[
                (1, &asset.topology_positions),
                (2, &asset.edge_vertices),
                (3, &asset.edge_attributes),
                (4, normals),
            ],
        );
        Ok(Self {
            pipelines,
            pulled,
            edge_count: asset.edge_count,
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
        self.pulled.write(cx.queue, &super::frame_uniform(cx, 0));
        self.caps = cx.style.caps != CapMethod::None;
        Ok(())
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(0, &self.pulled.group, &[]);
        pass.set_pipeline(&self.pipelines.edges);
        pass.set_index_buffer(self.pipelines.quad.slice(..), wgpu::IndexFormat::Uint16);
        pass.draw_indexed(0..6, 0, 0..self.edge_count);
        if self.caps {
            pass.set_pipeline(&self.pipelines.cap0);
            pass.draw(0..3, 0..self.edge_count);
            pass.set_pipeline(&self.pipelines.cap1);
            pass.draw(0..3, 0..self.edge_count);
        }
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
