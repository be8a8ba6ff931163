//! [`Technique::Hybrid`](crate::render::Technique::Hybrid): seed 004's hybrid shader for edges and
//! ambient shading (`shaders/hybrid.wgsl`), a post-process of the application's depth, multiplied
//! over its colour in [`Prepared::finish`](crate::render::Prepared::finish). With `object_only` the
//! frame first draws this asset white into a mask of its own (§3.1), whose Laplacian outlines it.

use std::sync::Arc;

use super::post::{self, Blend, Own};
use super::{Blocks, FrameContext, TechniqueFrame};
use crate::render::layout::Post;
use crate::render::pipelines::{Access, BindingSet};
use crate::render::{FrameViews, HybridDepth, Pipelines as Cache, RenderError, Technique, modules};

const MASK_SET: BindingSet = BindingSet {
    label: "hybrid mask",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Access::Instance)],
};
const MASK: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// The post-process and the mask pass, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    mask_layout: wgpu::BindGroupLayout,
    hybrid: wgpu::RenderPipeline,
    mask: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = post::layout(cache, "hybrid", &[3]);
        let mask_layout = cache.layout(&MASK_SET);
        let multisampled = cache.target().sample_count > 1;
        let module = cache.module("hybrid.wgsl", &modules::hybrid(multisampled))?;
        Ok(Self {
            hybrid: post::pipeline(
                cache,
                &layout,
                "hybrid",
                &module,
                "hybrid_fragment",
                Blend::Multiply,
            )?,
            mask: post::own_pipeline(
                cache,
                &mask_layout,
                "hybrid mask",
                &module,
                ("mask_vertex", "mask_fragment"),
                MASK,
                false,
            )?,
            layout,
            mask_layout,
        })
    }
}

/// A frame: the uniform, and the object mask while it is used.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    cache: Cache,
    uniform: wgpu::Buffer,
    /// Per instance, the mask pass's matrix.
    blocks: Blocks,
    mask_group: Option<wgpu::BindGroup>,
    mask: Option<Own>,
    /// Fills the mask binding when there is no mask (the shader reads it only with one).
    placeholder: Own,
}

impl Frame {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let pipelines = cache.hybrid()?;
        let uniform = post::uniform_buffer(cache, "hybrid");
        Ok(Self {
            pipelines,
            cache: cache.clone(),
            uniform,
            blocks: Blocks::new(cache, "hybrid mask", std::mem::size_of::<Post>()),
            mask_group: None,
            mask: None,
            placeholder: Own::new(cache, "hybrid mask placeholder", [1, 1], MASK, false)?,
        })
    }
}

fn finite(value: f32, fallback: f32) -> f32 {
    if value.is_finite() { value } else { fallback }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let Technique::Hybrid(p) = cx.style.technique else {
            return Err(super::mismatch(cx));
        };
        let defaults = HybridDepth::EDGES;
        let mut uniform = post::uniform(cx, u32::from(p.object_only));
        uniform.params = [
            finite(p.step_px, defaults.step_px).clamp(1.0, 64.0),
            finite(p.bleach, defaults.bleach).clamp(1e-4, 1.0),
            finite(p.contrast, defaults.contrast).clamp(0.0, 1000.0),
            finite(p.brightness, 0.0).clamp(0.0, 2.0),
        ];
        let share = if p.range.is_finite() && p.range > 0.0 {
            p.range
        } else {
            defaults.range
        };
        let range = share * post::far_distance(cx);
        uniform.more = [range, 0.0, 0.0, 0.0];
        cx.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        if p.object_only {
            let size = cx.camera.viewport.map(|v| v.max(1));
            if self.mask.as_ref().is_none_or(|m| m.size != size) {
                self.mask = Some(Own::new(cx.pipelines, "hybrid mask", size, MASK, false)?);
            }
            let meshes = post::instance_blocks(cx, &mut self.blocks, &mut self.mask_group);
            let group = post::block_group(
                cx.pipelines,
                &self.pipelines.mask_layout,
                &self.blocks,
                &mut self.mask_group,
            );
            if let Some(mask) = &self.mask {
                mask.draw_meshes(cx.pipelines, encoder, &self.pipelines.mask, group, &meshes);
            }
        } else {
            self.mask = None;
        }
        Ok(())
    }

    fn render(&self, _pass: &mut wgpu::RenderPass<'_>) {}

    fn finish(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        views: &FrameViews<'_>,
    ) -> Result<(), RenderError> {
        let mask = &self.mask.as_ref().unwrap_or(&self.placeholder).view;
        post::full_screen(
            &self.cache,
            encoder,
            views,
            &self.pipelines.layout,
            &self.pipelines.hybrid,
            &self.uniform,
            &[(3, mask)],
        )
    }

    fn gpu_bytes(&self) -> u64 {
        self.uniform.size() + self.mask.as_ref().map_or(0, Own::bytes)
    }
}
