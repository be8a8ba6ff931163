//! [`Technique::Hybrid`](crate::render::Technique::Hybrid): seed 004's hybrid shader for edges and
//! ambient shading (`shaders/hybrid.wgsl`), a post-process of the application's depth, multiplied
//! over its colour in [`Prepared::finish`](crate::render::Prepared::finish). With `object_only` the
//! frame first draws this asset white into a mask of its own (§3.1), whose Laplacian outlines it.

use std::sync::Arc;

use super::post::{self, Blend, DEPTH, MESH_PASS, Own, PARAMS, POST};
use super::{Blocks, FrameContext, FrameOptions, Module, TechniqueFrame};
use crate::render::bindings::{Binding, Bindings, Kind};
use crate::render::layout::{Layout, Post, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::PipelineSet;
use crate::render::{FrameViews, HybridDepth, Pipelines as Cache, RenderError, Target, Technique};

pub(crate) static MODULE: Hybrid = Hybrid;

/// The object mask of `object_only`.
const MASK: Binding = Binding::new(17, "mask", Kind::Texture);
const BINDINGS: Bindings = Bindings::draw("hybrid", &[POST, PARAMS, DEPTH, MASK]);
const MASK_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// `HybridParams` in `shaders/hybrid.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct HybridParams {
    step_px: f32,
    bleach: f32,
    contrast: f32,
    brightness: f32,
    range: f32,
    object_only: u32,
    _pad0: u32,
    _pad1: u32,
}

/// The module.
pub(crate) struct Hybrid;

fn shader(target: &Target) -> Shader {
    use chamfer_shaders as wgsl;
    Shader::new(
        "hybrid.wgsl",
        &[post::depth_source(target), wgsl::POST, wgsl::HYBRID],
        vec![
            Program::draw("post_vertex", "hybrid_fragment", &BINDINGS),
            Program::draw("mask_vertex", "mask_fragment", &MESH_PASS),
        ],
    )
}

impl Module for Hybrid {
    fn shaders(&self, target: &Target) -> Vec<Shader> {
        vec![shader(target)]
    }

    fn structs(&self) -> Vec<Layout> {
        vec![layout!(
            "HybridParams",
            HybridParams,
            [
                step_px,
                bleach,
                contrast,
                brightness,
                range,
                object_only,
                _pad0,
                _pad1
            ]
        )]
    }

    fn is_post_process(&self) -> bool {
        true
    }

    fn new_frame(
        &self,
        cache: &Cache,
        _options: &FrameOptions,
    ) -> Result<Box<dyn TechniqueFrame>, RenderError> {
        Ok(Box::new(Frame {
            pipelines: cache.get::<HybridPipelines>()?,
            cache: cache.clone(),
            uniform: post::uniform_buffer(cache, "hybrid", std::mem::size_of::<Post>()),
            params: post::uniform_buffer(
                cache,
                "hybrid parameters",
                std::mem::size_of::<HybridParams>(),
            ),
            blocks: Blocks::new(cache, "hybrid mask", std::mem::size_of::<Post>()),
            mask_group: None,
            mask: None,
            placeholder: Own::new(cache, "hybrid mask placeholder", [1, 1], MASK_FORMAT, false)?,
        }))
    }
}

/// The post-process and the mask pass, per device and target.
#[derive(Debug)]
pub(crate) struct HybridPipelines {
    hybrid: wgpu::RenderPipeline,
    mask: wgpu::RenderPipeline,
}

impl PipelineSet for HybridPipelines {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        let shader = shader(cache.target());
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            hybrid: post::pipeline(&compiled, cache, "hybrid_fragment", Blend::Multiply)?,
            mask: post::own_pipeline(
                &compiled,
                cache,
                ("mask_vertex", "mask_fragment"),
                MASK_FORMAT,
                false,
            )?,
        })
    }
}

/// A frame: the uniform, and the object mask while it is used.
#[derive(Debug)]
struct Frame {
    pipelines: Arc<HybridPipelines>,
    cache: Cache,
    uniform: wgpu::Buffer,
    params: wgpu::Buffer,
    /// Per instance, the mask pass's matrix.
    blocks: Blocks,
    mask_group: Option<wgpu::BindGroup>,
    mask: Option<Own>,
    /// Fills the mask binding when there is no mask (the shader reads it only with one).
    placeholder: Own,
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
        let share = if p.range.is_finite() && p.range > 0.0 {
            p.range
        } else {
            defaults.range
        };
        let params = HybridParams {
            step_px: finite(p.step_px, defaults.step_px).clamp(1.0, 64.0),
            bleach: finite(p.bleach, defaults.bleach).clamp(1e-4, 1.0),
            contrast: finite(p.contrast, defaults.contrast).clamp(0.0, 1000.0),
            brightness: finite(p.brightness, 0.0).clamp(0.0, 2.0),
            range: share * post::far_distance(cx),
            object_only: u32::from(p.object_only),
            _pad0: 0,
            _pad1: 0,
        };
        cx.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&post::uniform(cx)));
        cx.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        if p.object_only {
            let size = cx.camera.viewport.map(|v| v.max(1));
            if self.mask.as_ref().is_none_or(|m| m.size != size) {
                self.mask = Some(Own::new(
                    cx.pipelines,
                    "hybrid mask",
                    size,
                    MASK_FORMAT,
                    false,
                )?);
            }
            let meshes = post::instance_blocks(cx, &mut self.blocks, &mut self.mask_group);
            let group = post::block_group(cx.pipelines, &self.blocks, &mut self.mask_group)?;
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
            (&BINDINGS, &self.pipelines.hybrid),
            (&self.uniform, &self.params),
            (MASK, mask),
        )
    }

    fn gpu_bytes(&self) -> u64 {
        self.uniform.size() + self.params.size() + self.mask.as_ref().map_or(0, Own::bytes)
    }
}
