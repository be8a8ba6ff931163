//! [`Technique::ImageSpace`](crate::render::Technique::ImageSpace): gradient operators over the
//! application's depth and a normal buffer (thesis §5, `shaders/image_space.wgsl`). The frame draws
//! this asset's normals into a buffer of its own before the application's pass (§5.4's first pass),
//! and runs the operator over both in [`Prepared::finish`](crate::render::Prepared::finish).

use std::sync::Arc;

use super::post::{self, Blend, DEPTH, MESH_PASS, Own, PARAMS, POST};
use super::{Blocks, FrameContext, FrameOptions, Module, TechniqueFrame};
use crate::render::bindings::{Binding, Bindings, Kind};
use crate::render::layout::{Layout, Post, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::PipelineSet;
use crate::render::{FrameViews, Operator, Pipelines as Cache, RenderError, Target, Technique};

pub(crate) static MODULE: ImageSpace = ImageSpace;

/// The normal buffer the frame draws.
const NORMALS: Binding = Binding::new(17, "normals", Kind::Texture);
const BINDINGS: Bindings = Bindings::draw("image-space edges", &[POST, PARAMS, DEPTH, NORMALS]);
const NORMALS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// `ImageParams` in `shaders/image_space.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ImageParams {
    kernel: u32,
    depth_threshold: f32,
    normal_threshold: f32,
    step_px: f32,
    depth_scaled: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

/// The module.
pub(crate) struct ImageSpace;

fn shader(target: &Target) -> Shader {
    use chamfer_shaders as wgsl;
    Shader::new(
        "image_space.wgsl",
        &[post::depth_source(target), wgsl::POST, wgsl::IMAGE_SPACE],
        vec![
            Program::draw("post_vertex", "image_fragment", &BINDINGS),
            Program::draw("normal_vertex", "normal_fragment", &MESH_PASS),
        ],
    )
}

impl Module for ImageSpace {
    fn shaders(&self, target: &Target) -> Vec<Shader> {
        vec![shader(target)]
    }

    fn structs(&self) -> Vec<Layout> {
        vec![layout!(
            "ImageParams",
            ImageParams,
            [
                kernel,
                depth_threshold,
                normal_threshold,
                step_px,
                depth_scaled,
                _pad0,
                _pad1,
                _pad2
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
            pipelines: cache.get::<ImagePipelines>()?,
            cache: cache.clone(),
            uniform: post::uniform_buffer(cache, "image-space edges", std::mem::size_of::<Post>()),
            params: post::uniform_buffer(
                cache,
                "image-space parameters",
                std::mem::size_of::<ImageParams>(),
            ),
            blocks: Blocks::new(cache, "normal buffer", std::mem::size_of::<Post>()),
            normal_group: None,
            normals: Own::new(cache, "normal buffer", [1, 1], NORMALS_FORMAT, true)?,
        }))
    }
}

/// The operator pass and the normal pass, per device and target.
#[derive(Debug)]
pub(crate) struct ImagePipelines {
    operator: wgpu::RenderPipeline,
    normals: wgpu::RenderPipeline,
}

impl PipelineSet for ImagePipelines {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        let shader = shader(cache.target());
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            operator: post::pipeline(&compiled, cache, "image_fragment", Blend::Alpha)?,
            normals: post::own_pipeline(
                &compiled,
                cache,
                ("normal_vertex", "normal_fragment"),
                NORMALS_FORMAT,
                true,
            )?,
        })
    }
}

/// A frame: the uniforms and the normal buffer.
#[derive(Debug)]
struct Frame {
    pipelines: Arc<ImagePipelines>,
    cache: Cache,
    uniform: wgpu::Buffer,
    params: wgpu::Buffer,
    /// Per instance, the normal pass's matrix.
    blocks: Blocks,
    normal_group: Option<wgpu::BindGroup>,
    normals: Own,
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
        let threshold = |t: f32| if t.is_finite() { t.max(0.0) } else { 0.0 };
        let params = ImageParams {
            kernel: match p.operator {
                Operator::Sobel => 0,
                Operator::Prewitt => 1,
                Operator::Scharr => 2,
                Operator::Roberts => 3,
            },
            depth_threshold: threshold(p.depth_threshold),
            normal_threshold: threshold(p.normal_threshold),
            step_px: (0.5 * cx.style.width()).max(1.0),
            depth_scaled: u32::from(cx.style.depth_scaled),
            _pad0: 0,
            _pad1: 0,
            _pad2: 0,
        };
        cx.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&post::uniform(cx)));
        cx.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let size = cx.camera.viewport.map(|v| v.max(1));
        if self.normals.size != size {
            self.normals = Own::new(cx.pipelines, "normal buffer", size, NORMALS_FORMAT, true)?;
        }
        let meshes = post::instance_blocks(cx, &mut self.blocks, &mut self.normal_group);
        let group = post::block_group(cx.pipelines, &self.blocks, &mut self.normal_group)?;
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
            (&BINDINGS, &self.pipelines.operator),
            (&self.uniform, &self.params),
            (NORMALS, &self.normals.view),
        )
    }

    fn gpu_bytes(&self) -> u64 {
        self.uniform.size() + self.params.size() + self.normals.bytes()
    }
}
