//! [`Technique::Wireframe`](crate::render::Technique::Wireframe): the barycentric thick wireframe of
//! seed 001 (`shaders/wireframe.wgsl`). The article's geometry shader computed per-corner edge
//! coordinates from its triangle; here the vertex shader pulls the triangle's three corners from the
//! asset's render sections (instance = triangle, vertex = corner) and does the same.

use std::sync::Arc;

use super::{FrameContext, Pulled, TechniqueFrame, extra, pulled_pipeline};
use crate::render::pipelines::{Access, BindingSet};
use crate::render::{GpuAsset, Pipelines as Cache, RenderError, Technique, modules};

const SET: BindingSet = BindingSet {
    label: "wireframe",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[
        (0, Access::Uniform),
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

/// One asset's frame.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
    triangle_count: u32,
}

impl Frame {
    pub(crate) fn new(
        cache: &Cache,
        asset: &GpuAsset,
        technique: &Technique,
    ) -> Result<Self, RenderError> {
        let pipelines = cache.wireframe()?;
        let feature_only = matches!(
            technique,
            Technique::Wireframe {
                feature_only: true,
                ..
            }
        );
        // The masks are read only in feature-only mode; otherwise any buffer fills the binding.
        let masks = if feature_only {
            extra(
                &asset.triangle_edges,
                technique,
                "AssetExtras::TRIANGLE_EDGES",
            )?
        } else {
            asset.triangle_edges.as_ref().unwrap_or(&asset.mesh_indices)
        };
        let pulled = Pulled::new(
            cache,
            &pipelines.layout,
            &SET,
            &[
                (5, &asset.render_positions),
                (7, &asset.mesh_indices),
                (8, masks),
            ],
        );
        Ok(Self {
            pipelines,
            pulled,
            triangle_count: asset.index_count / 3,
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        _encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let Technique::Wireframe {
            feature_only,
            smooth,
            naive_threshold,
        } = cx.style.technique
        else {
            return Err(super::mismatch(cx));
        };
        let mut uniform = super::frame_uniform(cx, 0);
        uniform.params = [
            f32::from(u8::from(naive_threshold.is_some())),
            f32::from(u8::from(smooth)),
            f32::from(u8::from(feature_only)),
            naive_threshold.unwrap_or(0.0),
        ];
        self.pulled.write(cx.queue, &uniform);
        Ok(())
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(0, &self.pulled.group, &[]);
        pass.set_pipeline(&self.pipelines.wire);
        pass.draw(0..3, 0..self.triangle_count);
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
