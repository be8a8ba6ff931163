//! [`Technique::Wireframe`](crate::render::Technique::Wireframe): the barycentric thick wireframe of
//! seed 001 (`shaders/wireframe.wgsl`). The article's geometry shader computed per-corner edge
//! coordinates from its triangle; here the vertex shader pulls the triangle's three corners from the
//! asset's render sections (instance = triangle, vertex = corner) and does the same.

use std::sync::Arc;

use super::{FrameContext, Pulled, TechniqueFrame, extra, pulled_pipeline};
use crate::render::pipelines::{Access, BindingSet};
use crate::render::{Pipelines as Cache, RenderError, Technique, modules};

const SET: BindingSet = BindingSet {
    label: "wireframe",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[
        (0, Access::Instance),
        (5, Access::Read),
        (7, Access::Read),
        (8, Access::Read),
    ],
};

/// The wireframe pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    wire: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = cache.layout(&SET);
        let module = cache.module("wireframe.wgsl", &modules::wireframe())?;
        let wire = pulled_pipeline(
            cache,
            &layout,
            "wireframe",
            &module,
            "wire_vertex",
            "wire_fragment",
        )?;
        Ok(Self { layout, wire })
    }
}

/// A frame.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
}

impl Frame {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        Ok(Self {
            pipelines: cache.wireframe()?,
            pulled: Pulled::new(cache, "wireframe"),
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        _encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let technique = cx.style.technique;
        let Technique::Wireframe {
            feature_only,
            smooth,
            naive_threshold,
        } = technique
        else {
            return Err(super::mismatch(cx));
        };
        let params = [
            f32::from(u8::from(naive_threshold.is_some())),
            f32::from(u8::from(smooth)),
            f32::from(u8::from(feature_only)),
            naive_threshold.unwrap_or(0.0),
        ];
        self.pulled.prepare(
            cx,
            &self.pipelines.layout,
            &SET,
            |d, i| {
                let mut uniform = super::frame_uniform(cx, d, i, 0);
                uniform.params = params;
                uniform
            },
            |asset| {
                // The masks are read only in feature-only mode; otherwise any buffer fills the
                // binding.
                let masks = if feature_only {
                    extra(
                        &asset.triangle_edges,
                        &technique,
                        "AssetExtras::TRIANGLE_EDGES",
                    )?
                } else {
                    asset
                        .triangle_edges
                        .clone()
                        .unwrap_or_else(|| asset.mesh_indices.clone())
                };
                Ok(vec![
                    (5, asset.render_positions.clone()),
                    (7, asset.mesh_indices.clone()),
                    (8, masks),
                ])
            },
        )
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let pipeline = &self.pipelines.wire;
        self.pulled.each(pass, |pass, asset| {
            pass.set_pipeline(pipeline);
            pass.draw(0..3, 0..asset.index_count / 3);
        });
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
