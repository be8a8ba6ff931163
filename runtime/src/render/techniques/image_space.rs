//! [`Technique::ImageSpace`](crate::render::Technique::ImageSpace): gradient operators over the
//! application's depth and a normal buffer (thesis §5, `shaders/image_space.wgsl`). The frame draws
//! this asset's normals into a buffer of its own before the application's pass (§5.4's first pass),
//! and runs the operator over both in [`Prepared::finish`](crate::render::Prepared::finish).

use std::sync::Arc;

use super::post::{self, Blend, Own};
use super::{Blocks, FrameContext, TechniqueFrame};
use crate::render::layout::Post;
use crate::render::pipelines::{Access, BindingSet};
use crate::render::{FrameViews, Operator, Pipelines as Cache, RenderError, Technique, modules};

const NORMAL_SET: BindingSet = BindingSet {
    label: "normal buffer",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Access::Instance)],
};
const NORMALS: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The operator pass and the normal pass, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    normal_layout: wgpu::BindGroupLayout,
    operator: wgpu::RenderPipeline,
    normals: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = post::layout(cache, "image-space edges", &[2]);
        let normal_layout = cache.layout(&NORMAL_SET);
        let multisampled = cache.target().sample_count > 1;
        let module = cache.module("image_space.wgsl", &modules::image_space(multisampled))?;
        Ok(Self {
            operator: post::pipeline(
                cache,
                &layout,
                "image-space edges",
                &module,
                "image_fragment",
                Blend::Alpha,
            )?,
            normals: post::own_pipeline(
                cache,
                &normal_layout,
                "normal buffer",
                &module,
                ("normal_vertex", "normal_fragment"),
                NORMALS,
                true,
            )?,
            layout,
            normal_layout,
        })
    }
}

/// A frame: the uniform and the normal buffer.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    cache: Cache,
    uniform: wgpu::Buffer,
    /// Per instance, the normal pass's matrix.
    blocks: Blocks,
    normal_group: Option<wgpu::BindGroup>,
    normals: Own,
}

impl Frame {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let pipelines = cache.image_space()?;
        let uniform = post::uniform_buffer(cache, "image-space edges");
        Ok(Self {
            normals: Own::new(cache, "normal buffer", [1, 1], NORMALS, true)?,
            pipelines,
            cache: cache.clone(),
            uniform,
            blocks: Blocks::new(cache, "normal buffer", std::mem::size_of::<Post>()),
            normal_group: None,
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let Technique::ImageSpace(p) = cx.style.technique else {
            return Err(super::mismatch(cx));
        };
        let operator = match p.operator {
            Operator::Sobel => 0,
            Operator::Prewitt => 1,
            Operator::Scharr => 2,
            Operator::Roberts => 3,
        };
        let threshold = |t: f32| if t.is_finite() { t.max(0.0) } else { 0.0 };
        let mut uniform = post::uniform(cx, operator);
        uniform.params = [
            threshold(p.depth_threshold),
            threshold(p.normal_threshold),
            (0.5 * cx.style.width()).max(1.0),
            f32::from(u8::from(cx.style.depth_scaled)),
        ];
        cx.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let size = cx.camera.viewport.map(|v| v.max(1));
        if self.normals.size != size {
            self.normals = Own::new(cx.pipelines, "normal buffer", size, NORMALS, true)?;
        }
        let meshes = post::instance_blocks(cx, &mut self.blocks, &mut self.normal_group);
        let group = post::block_group(
            cx.pipelines,
            &self.pipelines.normal_layout,
            &self.blocks,
            &mut self.normal_group,
        );
        self.normals.draw_meshes(
            cx.pipelines,
            encoder,
            &self.pipelines.normals,
            group,
            &meshes,
        );
        Ok(())
    }

    fn render(&self, _pass: &mut wgpu::RenderPass<'_>) {}

    fn finish(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        views: &FrameViews<'_>,
    ) -> Result<(), RenderError> {
        post::full_screen(
            &self.cache,
            encoder,
            views,
            &self.pipelines.layout,
            &self.pipelines.operator,
            &self.uniform,
            &[(2, &self.normals.view)],
        )
    }

    fn gpu_bytes(&self) -> u64 {
        self.uniform.size() + self.normals.bytes()
    }
}
