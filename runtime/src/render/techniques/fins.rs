//! [`Technique::Fins`](crate::render::Technique::Fins): seed 003's geometry-shader inking, in the
//! vertex shader (`shaders/fins.wgsl`): per edge instance, twelve vertices, a fin per front-facing
//! face whose edge is a silhouette or a crease, extruded along that face's corner normals, crease
//! fins biased towards the camera (Listing 3).

use std::sync::Arc;

use super::{FrameContext, Pulled, TechniqueFrame, extra, pulled_pipeline};
use crate::render::pipelines::{Access, BindingSet};
use crate::render::{Pipelines as Cache, RenderError, Technique, modules};

const SET: BindingSet = BindingSet {
    label: "fins",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[
        (0, Access::Instance),
        (1, Access::Read),
        (2, Access::Read),
        (3, Access::Read),
        (5, Access::Read),
        (6, Access::Read),
    ],
};

/// The fin pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    fins: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = cache.layout(&SET);
        let module = cache.module("fins.wgsl", &modules::fins())?;
        let fins = pulled_pipeline(
            cache,
            &layout,
            "fins",
            &module,
            "fin_vertex",
            "flat_fragment",
        )?;
        Ok(Self { layout, fins })
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
            pipelines: cache.fins()?,
            pulled: Pulled::new(cache, "fins"),
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
        let Technique::Fins {
            world_thickness,
            z_bias,
        } = technique
        else {
            return Err(super::mismatch(cx));
        };
        let finite = |v: f32| if v.is_finite() { v } else { 0.0 };
        self.pulled.prepare(
            cx,
            &self.pipelines.layout,
            &SET,
            |d, i| {
                let [lo, hi] = d.asset.bounds().map(glam::Vec3::from);
                let mut uniform = super::frame_uniform(cx, d, i, 0);
                uniform.params = match world_thickness {
                    Some(t) => [finite(t), 0.0, 0.0, 0.0],
                    None => [cx.style.width(), 1.0, 0.0, 0.0],
                };
                uniform.params[2] = finite(z_bias.unwrap_or(2e-3 * (hi - lo).length()));
                uniform
            },
            |asset| {
                let corners = extra(&asset.fin_corners, &technique, "AssetExtras::FIN_CORNERS")?;
                Ok(vec![
                    (1, asset.topology_positions.clone()),
                    (2, asset.whole_edge_vertices()?.clone()),
                    (3, asset.edge_attributes.clone()),
                    (5, asset.render_normals.clone()),
                    (6, corners),
                ])
            },
        )
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let pipeline = &self.pipelines.fins;
        self.pulled.each(pass, |pass, asset| {
            pass.set_pipeline(pipeline);
            pass.draw(0..12, 0..asset.edge_count);
        });
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
