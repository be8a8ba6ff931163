//! [`Technique::InvertedHull`](crate::render::Technique::InvertedHull): the expanded inverted hull
//! (thesis §7.2, `shaders/inverted_hull.wgsl`): the mesh pushed out along its normals, front faces
//! culled, in the contour colour.

use std::sync::Arc;

use super::surface_angle::mesh_buffers;
use super::{FrameContext, Pulled, TechniqueFrame, extra};
use crate::render::pipelines::{Access, BindingSet, RenderPipeline};
use crate::render::{GpuAsset, Pipelines as Cache, RenderError, Technique, modules};

const SET: BindingSet = BindingSet {
    label: "inverted hull",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Access::Uniform), (4, Access::Read), (6, Access::Read)],
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

/// One asset's frame.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
    asset: GpuAsset,
}

impl Frame {
    pub(crate) fn new(
        cache: &Cache,
        asset: &GpuAsset,
        technique: &Technique,
    ) -> Result<Self, RenderError> {
        let pipelines = cache.inverted_hull()?;
        let needs = "AssetExtras::VERTEX_NORMALS";
        let normals = extra(&asset.vertex_normals, technique, needs)?;
        let map = extra(&asset.render_to_topology, technique, needs)?;
        let pulled = Pulled::new(cache, &pipelines.layout, &SET, &[(4, normals), (6, map)]);
        Ok(Self {
            pipelines,
            pulled,
            asset: asset.clone(),
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        _encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let Technique::InvertedHull { smooth_normals } = cx.style.technique else {
            return Err(super::mismatch(cx));
        };
        let mut uniform = super::frame_uniform(cx, 0);
        uniform.params[0] = f32::from(u8::from(smooth_normals));
        self.pulled.write(cx.queue, &uniform);
        Ok(())
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(0, &self.pulled.group, &[]);
        pass.set_pipeline(&self.pipelines.hull);
        super::draw_mesh(pass, &self.asset);
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
