//! [`Technique::InvertedHull`](crate::render::Technique::InvertedHull): the expanded inverted hull
//! (thesis §7.2, `shaders/inverted_hull.wgsl`): the mesh pushed out along its normals, front faces
//! culled, in the contour colour.

use std::sync::Arc;

use super::surface_angle::mesh_buffers;
use super::{FrameContext, Pulled, TechniqueFrame, extra};
use crate::render::pipelines::{Access, BindingSet, RenderPipeline};
use crate::render::{Pipelines as Cache, RenderError, Technique, modules};

const SET: BindingSet = BindingSet {
    label: "inverted hull",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Access::Instance), (4, Access::Read), (6, Access::Read)],
};

/// The pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    hull: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = cache.layout(&SET);
        let module = cache.module("inverted_hull.wgsl", &modules::inverted_hull())?;
        let target = cache.target();
        let hull = cache.render_pipeline(
            &[&layout],
            RenderPipeline {
                label: "inverted hull",
                module: &module,
                vertex: "hull_vertex",
                fragment: Some("flat_fragment"),
                buffers: &mesh_buffers(),
                primitive: wgpu::PrimitiveState {
                    cull_mode: Some(wgpu::Face::Front),
                    ..Default::default()
                },
                depth_stencil: target.depth(false, wgpu::CompareFunction::LessEqual),
                multisample: target.multisample(),
                color: Some(target.blended_color()),
            },
        )?;
        Ok(Self { layout, hull })
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
            pipelines: cache.inverted_hull()?,
            pulled: Pulled::new(cache, "inverted hull"),
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
        let Technique::InvertedHull { smooth_normals } = technique else {
            return Err(super::mismatch(cx));
        };
        self.pulled.prepare(
            cx,
            &self.pipelines.layout,
            &SET,
            |d, i| {
                let mut uniform = super::frame_uniform(cx, d, i, 0);
                uniform.params[0] = f32::from(u8::from(smooth_normals));
                uniform
            },
            |asset| {
                let needs = "AssetExtras::VERTEX_NORMALS";
                Ok(vec![
                    (4, extra(&asset.vertex_normals, &technique, needs)?),
                    (6, extra(&asset.render_to_topology, &technique, needs)?),
                ])
            },
        )
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let pipeline = &self.pipelines.hull;
        self.pulled.each(pass, |pass, asset| {
            pass.set_pipeline(pipeline);
            super::draw_mesh(pass, asset);
        });
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
