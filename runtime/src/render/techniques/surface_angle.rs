//! [`Technique::SurfaceAngle`](crate::render::Technique::SurfaceAngle): surface-angle contours
//! (thesis §7.1, `shaders/surface_angle.wgsl`): the mesh drawn once more over itself, inked where its
//! normal is nearly perpendicular to the view.

use std::sync::Arc;

use super::{FrameContext, Pulled, TechniqueFrame};
use crate::render::pipelines::{Access, BindingSet, RenderPipeline};
use crate::render::{Pipelines as Cache, RenderError, Technique, modules};

const SET: BindingSet = BindingSet {
    label: "surface angle",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Access::Instance)],
};

/// The position and normal vertex buffers of the mesh pass.
pub(crate) fn mesh_buffers() -> [Option<wgpu::VertexBufferLayout<'static>>; 2] {
    const POSITION: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x3];
    const NORMAL: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![1 => Float32x3];
    let layout = |attributes: &'static [wgpu::VertexAttribute]| {
        Some(wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes,
        })
    };
    [layout(&POSITION), layout(&NORMAL)]
}

/// The pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    angle: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = cache.layout(&SET);
        let module = cache.module("surface_angle.wgsl", &modules::surface_angle())?;
        let target = cache.target();
        let angle = cache.render_pipeline(
            &[&layout],
            RenderPipeline {
                label: "surface angle",
                module: &module,
                vertex: "angle_vertex",
                fragment: Some("angle_fragment"),
                buffers: &mesh_buffers(),
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: target.depth(false, wgpu::CompareFunction::LessEqual),
                multisample: target.multisample(),
                color: Some(target.blended_color()),
            },
        )?;
        Ok(Self { layout, angle })
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
            pipelines: cache.surface_angle()?,
            pulled: Pulled::new(cache, "surface angle"),
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        _encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let Technique::SurfaceAngle { threshold } = cx.style.technique else {
            return Err(super::mismatch(cx));
        };
        let threshold = if threshold.is_finite() {
            threshold.clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.pulled.prepare(
            cx,
            &self.pipelines.layout,
            &SET,
            |d, i| {
                let mut uniform = super::frame_uniform(cx, d, i, 0);
                uniform.params[0] = threshold;
                uniform
            },
            |_| Ok(Vec::new()),
        )
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let pipeline = &self.pipelines.angle;
        self.pulled.each(pass, |pass, asset| {
            pass.set_pipeline(pipeline);
            super::draw_mesh(pass, asset);
        });
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
