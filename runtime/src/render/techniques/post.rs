//! What the post-processes share (`shaders/post.wgsl`): a full-screen pass after the application's
//! pass into its finished colour, reading its depth; textures of their own sized to the viewport;
//! the `Post` uniform.

use crate::render::bindings::{Binding, Bindings, Kind};
use crate::render::gpu_asset::VERTEX_LAYOUTS;
use crate::render::layout::Post;
use crate::render::pipelines::{Compiled, Raster};
use crate::render::target::checked;
use crate::render::{FrameViews, GpuAsset, Pipelines as Cache, RenderError};

use super::FrameContext;

/// The frame's [`Post`] uniform, in the full-screen pass.
pub(crate) const POST: Binding = Binding::new(0, "post", Kind::Uniform);
/// One [`Post`] block per instance, in the passes that draw the instances' meshes into the frame's
/// own textures.
pub(crate) const POST_BLOCK: Binding = Binding::new(0, "post", Kind::Block);
/// The technique's parameters (its own struct, one per frame).
pub(crate) const PARAMS: Binding = Binding::new(15, "params", Kind::Uniform);
/// The application's depth.
pub(crate) const DEPTH: Binding = Binding::new(16, "depth_texture", Kind::TargetDepth);
/// The bindings of a mesh pass into the frame's own textures.
pub(crate) const MESH_PASS: Bindings = Bindings::draw("post-process mesh pass", &[POST_BLOCK]);

/// How a post-process's output meets the scene colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Blend {
    /// Multiplied over it (shading factors, seed 004 §3.1).
    Multiply,
    /// Alpha-blended over it (coloured lines).
    Alpha,
}

/// The full-screen pipeline of `fragment` (a program of `compiled` with `post_vertex`), drawing into
/// the single-sample finished colour.
pub(crate) fn pipeline(
    compiled: &Compiled<'_>,
    cache: &Cache,
    fragment: &str,
    blend: Blend,
) -> Result<wgpu::RenderPipeline, RenderError> {
    let blend = match blend {
        Blend::Multiply => wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Dst,
                dst_factor: wgpu::BlendFactor::Zero,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
        },
        Blend::Alpha => wgpu::BlendState::ALPHA_BLENDING,
    };
    compiled.render(
        "post_vertex",
        Some(fragment),
        Raster {
            buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            color: Some(cache.target().color(Some(blend))),
        },
    )
}

/// The uniform of this frame (its mesh pass: the first instance's).
pub(crate) fn uniform(cx: &FrameContext<'_>) -> Post {
    let camera = cx.camera;
    let mvp = cx
        .instances
        .first()
        .map_or(camera.view_projection(), |d| d.camera.view_projection());
    // Depth-scaled steps are relative to the first instance's centre.
    let depth_ref = match cx.instances.first() {
        Some(d) if cx.style.depth_scaled => {
            let c = d.camera.model_view * d.asset.center().extend(1.0);
            (-c.z).max(1e-6)
        }
        _ => 0.0,
    };
    Post {
        inv_projection: camera.projection.inverse().to_cols_array_2d(),
        mvp: mvp.to_cols_array_2d(),
        color: cx.style.colors.contour,
        viewport: camera.viewport.map(|v| v.max(1) as f32),
        depth_ref,
        _pad: 0,
        section: cx
            .instances
            .first()
            .map_or(crate::section::ClipPlanes::NONE, |d| d.section)
            .rows(),
    }
}

/// The distance to the camera's far plane, view units (from the inverse projection), or a finite
/// stand-in for an infinite one: twice the distance to the model's far side.
pub(crate) fn far_distance(cx: &FrameContext<'_>) -> f32 {
    let far_depth = cx.pipelines.target().far_depth();
    let v = cx.camera.projection.inverse() * glam::Vec4::new(0.0, 0.0, far_depth, 1.0);
    let far = -v.z / v.w;
    if far.is_finite() && far > 0.0 {
        return far;
    }
    let farthest = cx
        .instances
        .iter()
        .map(|d| {
            let [lo, hi] = d.asset.bounds().map(glam::Vec3::from);
            -(d.camera.model_view * d.asset.center().extend(1.0)).z + 0.5 * (hi - lo).length()
        })
        .fold(1e-3f32, f32::max);
    2.0 * farthest
}

/// A texture of the frame's own, sized to the viewport, remade when the viewport changes.
#[derive(Debug)]
pub(crate) struct Own {
    pub(crate) size: [u32; 2],
    pub(crate) view: wgpu::TextureView,
    pub(crate) depth: Option<wgpu::TextureView>,
    pub(crate) format: wgpu::TextureFormat,
}

impl Own {
    /// A `format` colour texture (and a depth texture if `with_depth`) of `size`.
    pub(crate) fn new(
        cache: &Cache,
        label: &str,
        size: [u32; 2],
        format: wgpu::TextureFormat,
        with_depth: bool,
    ) -> Result<Self, RenderError> {
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let view = super::texture(
            cache,
            label,
            size,
            format,
            attachment | wgpu::TextureUsages::TEXTURE_BINDING,
        )?;
        let depth = if with_depth {
            Some(super::texture(cache, label, size, OWN_DEPTH, attachment)?)
        } else {
            None
        };
        Ok(Self {
            size,
            view,
            depth,
            format,
        })
    }

    /// GPU bytes of the textures.
    pub(crate) fn bytes(&self) -> u64 {
        let pixels = u64::from(self.size[0]) * u64::from(self.size[1]);
        let per_pixel = self.format.block_copy_size(None).unwrap_or(4);
        pixels * u64::from(per_pixel) + if self.depth.is_some() { 4 * pixels } else { 0 }
    }

    /// Records a pass that clears the texture to zero and draws each of `meshes` (an asset and
    /// its block's dynamic offset in `group`) with `pipeline`.
    pub(crate) fn draw_meshes(
        &self,
        cache: &Cache,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::RenderPipeline,
        group: &wgpu::BindGroup,
        meshes: &[(u32, GpuAsset)],
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("post-process buffer"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &self.view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: self.depth.as_ref().map(|view| {
                wgpu::RenderPassDepthStencilAttachment {
                    view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(cache.target().far_depth()),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        for (offset, asset) in meshes {
            pass.set_bind_group(0, group, &[*offset]);
            super::draw_mesh(&mut pass, asset);
        }
    }
}

/// The depth format of the frame's own mesh passes (the target's depth convention).
pub(crate) const OWN_DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A pipeline of `compiled`'s program `vertex` + `fragment` drawing the instances' meshes into an
/// [`Own`] texture of `format` (with depth if `depth`).
pub(crate) fn own_pipeline(
    compiled: &Compiled<'_>,
    cache: &Cache,
    (vertex, fragment): (&str, &str),
    format: wgpu::TextureFormat,
    depth: bool,
) -> Result<wgpu::RenderPipeline, RenderError> {
    compiled.render(
        vertex,
        Some(fragment),
        Raster {
            buffers: &VERTEX_LAYOUTS,
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: depth.then_some(wgpu::DepthStencilState {
                format: OWN_DEPTH,
                depth_write_enabled: Some(true),
                depth_compare: Some(cache.target().nearer(wgpu::CompareFunction::Less)),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState::default(),
            color: Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            }),
        },
    )
}

/// Records the full-screen pass of `pipeline` over `views.color`, its group over `bindings`: the
/// uniform ([`POST`]), the parameters ([`PARAMS`]), the application's depth ([`DEPTH`]) and `own`,
/// the frame's own texture at its binding.
pub(crate) fn full_screen(
    cache: &Cache,
    encoder: &mut wgpu::CommandEncoder,
    views: &FrameViews<'_>,
    (bindings, pipeline): (&'static Bindings, &wgpu::RenderPipeline),
    (uniform, params): (&wgpu::Buffer, &wgpu::Buffer),
    own: (Binding, &wgpu::TextureView),
) -> Result<(), RenderError> {
    let device = cache.device();
    let layout = cache.layout(bindings);
    // The application's views are checked here: a depth view that cannot be sampled is a typed
    // error, not a panic.
    let group = checked(
        device,
        "the post-process bindings (is the depth TEXTURE_BINDING?)",
        || {
            bindings.group(device, &layout, |binding| match binding {
                POST => Ok(uniform.as_entire_binding()),
                PARAMS => Ok(params.as_entire_binding()),
                DEPTH => Ok(wgpu::BindingResource::TextureView(views.depth)),
                b if b == own.0 => Ok(wgpu::BindingResource::TextureView(own.1)),
                other => Err(crate::render::bindings::unbound(bindings, other)),
            })
        },
    )??;
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("post-process"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: views.color,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, &group, &[]);
    pass.draw(0..3, 0..1);
    Ok(())
}

/// A uniform buffer of `size` bytes (for [`Post`] or a technique's parameters).
pub(crate) fn uniform_buffer(cache: &Cache, label: &str, size: usize) -> wgpu::Buffer {
    cache.device().create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// One [`Post`] block per instance (its mesh pass's matrix), written to `blocks`; forgets `group`
/// if the blocks were remade. Returns each instance's dynamic offset and asset.
pub(crate) fn instance_blocks(
    cx: &FrameContext<'_>,
    blocks: &mut super::Blocks,
    group: &mut Option<wgpu::BindGroup>,
) -> Vec<(u32, GpuAsset)> {
    let posts: Vec<Post> = cx
        .instances
        .iter()
        .map(|d| {
            let mut post = uniform(cx);
            post.mvp = d.camera.view_projection().to_cols_array_2d();
            post
        })
        .collect();
    if blocks.write(cx.pipelines, cx.queue, &posts) {
        *group = None;
    }
    cx.instances
        .iter()
        .enumerate()
        .map(|(i, d)| (blocks.offset(i), d.asset.clone()))
        .collect()
}

/// The bind group of a mesh pass over `blocks` ([`MESH_PASS`]), made once.
pub(crate) fn block_group<'g>(
    cache: &Cache,
    blocks: &super::Blocks,
    group: &'g mut Option<wgpu::BindGroup>,
) -> Result<&'g wgpu::BindGroup, RenderError> {
    if group.is_none() {
        let layout = cache.layout(&MESH_PASS);
        *group = Some(MESH_PASS.group(cache.device(), &layout, |_| Ok(blocks.binding()))?);
    }
    group
        .as_ref()
        .ok_or_else(|| RenderError::Internal("the mesh pass group was not made".into()))
}

/// The WGSL that reads the application's depth, as `target` samples it.
pub(crate) fn depth_source(target: &crate::render::Target) -> &'static str {
    if target.sample_count > 1 {
        chamfer_shaders::DEPTH_MULTI
    } else {
        chamfer_shaders::DEPTH_SINGLE
    }
}

/// What a post-process declares; the rest is [`PostModule`]'s: a frame that, before the
/// application's pass, draws the instances' meshes into a texture of its own (when
/// [`PostProcess::params`] asks), and after it runs one full-screen pass over the finished colour,
/// reading the application's depth and that texture.
pub(crate) trait PostProcess: std::fmt::Debug + Send + Sync + 'static {
    /// The techniques of this module ([`Module::presets`](super::Module::presets)).
    const PRESETS: &'static [crate::render::Preset];

    /// [`Module::preset`](super::Module::preset): the preset equal to `technique`, else the first.
    fn preset(technique: &crate::render::Technique) -> &'static crate::render::Preset {
        crate::render::technique::preset_of(Self::PRESETS, technique)
    }

    /// The parameters (`#[repr(C)]`, its WGSL twin named in [`PostProcess::structs`]), at
    /// [`PARAMS`].
    type Params: bytemuck::Pod + std::fmt::Debug + Send + Sync;
    /// The full-screen pass's bindings: [`POST`], [`PARAMS`], [`DEPTH`] and [`PostProcess::OWN`].
    const BINDINGS: &'static Bindings;
    /// The frame's own texture, as the full-screen pass binds it.
    const OWN: Binding;
    const OWN_FORMAT: wgpu::TextureFormat;
    /// The mesh pass into the own texture tests depth (against a depth texture of its own).
    const OWN_DEPTH: bool;
    /// How the full-screen pass meets the scene colour.
    const BLEND: Blend;

    /// The module: its first program the full-screen pass (`post_vertex` + its fragment, with
    /// [`PostProcess::BINDINGS`]), its second the mesh pass into the own texture (with
    /// [`MESH_PASS`]).
    fn shader(target: &crate::render::Target) -> crate::render::modules::Shader;

    /// The Rust twins of its WGSL structs.
    #[cfg_attr(not(test), allow(dead_code))]
    fn structs() -> Vec<crate::render::layout::Layout>;

    /// This frame's parameters, and whether it draws the own texture; `None` if the style's
    /// technique is not this module's.
    fn params(cx: &FrameContext<'_>) -> Option<(Self::Params, bool)>;
}

/// The [`Module`](super::Module) of a [`PostProcess`].
pub(crate) struct PostModule<T>(std::marker::PhantomData<fn() -> T>);

impl<T> PostModule<T> {
    pub(crate) const fn new() -> Self {
        Self(std::marker::PhantomData)
    }
}

impl<T: PostProcess> super::Module for PostModule<T> {
    fn presets(&self) -> &'static [crate::render::Preset] {
        T::PRESETS
    }

    fn preset(&self, technique: &crate::render::Technique) -> &'static crate::render::Preset {
        T::preset(technique)
    }

    fn shaders(&self, target: &crate::render::Target) -> Vec<crate::render::modules::Shader> {
        vec![T::shader(target)]
    }

    fn structs(&self) -> Vec<crate::render::layout::Layout> {
        T::structs()
    }

    fn is_post_process(&self) -> bool {
        true
    }

    fn new_frame(
        &self,
        cache: &Cache,
        _options: &super::FrameOptions,
    ) -> Result<Box<dyn super::TechniqueFrame>, RenderError> {
        let label = T::BINDINGS.label;
        Ok(Box::new(PostFrame::<T> {
            pipelines: cache.get::<PostPipelines<T>>()?,
            cache: cache.clone(),
            uniform: uniform_buffer(cache, label, std::mem::size_of::<Post>()),
            params: uniform_buffer(cache, label, std::mem::size_of::<T::Params>()),
            blocks: super::Blocks::new(cache, label, std::mem::size_of::<Post>()),
            group: None,
            own: None,
            placeholder: Own::new(cache, label, [1, 1], T::OWN_FORMAT, T::OWN_DEPTH)?,
        }))
    }
}

/// A post-process's full-screen pass and mesh pass, per device and target.
#[derive(Debug)]
pub(crate) struct PostPipelines<T> {
    full_screen: wgpu::RenderPipeline,
    mesh: wgpu::RenderPipeline,
    _technique: std::marker::PhantomData<fn() -> T>,
}

impl<T: PostProcess> crate::render::pipelines::PipelineSet for PostPipelines<T> {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        let shader = T::shader(cache.target());
        let compiled = cache.compile(&shader)?;
        let [full_screen, mesh] = [0, 1].map(|i| shader.programs.get(i));
        let missing = || RenderError::Internal(format!("{} declares two programs", shader.label));
        let (full_screen, mesh) = (full_screen.ok_or_else(missing)?, mesh.ok_or_else(missing)?);
        Ok(Self {
            full_screen: pipeline(
                &compiled,
                cache,
                full_screen.fragment.ok_or_else(missing)?,
                T::BLEND,
            )?,
            mesh: own_pipeline(
                &compiled,
                cache,
                (mesh.entry, mesh.fragment.ok_or_else(missing)?),
                T::OWN_FORMAT,
                T::OWN_DEPTH,
            )?,
            _technique: std::marker::PhantomData,
        })
    }
}

/// A post-process's frame: the uniforms, the instances' blocks of the mesh pass, the own texture
/// while it is drawn.
#[derive(Debug)]
struct PostFrame<T: PostProcess> {
    pipelines: std::sync::Arc<PostPipelines<T>>,
    cache: Cache,
    uniform: wgpu::Buffer,
    params: wgpu::Buffer,
    /// Per instance, the mesh pass's matrix.
    blocks: super::Blocks,
    group: Option<wgpu::BindGroup>,
    own: Option<Own>,
    /// Fills the own texture's binding on frames that do not draw it (the shader reads it only
    /// when they do).
    placeholder: Own,
}

impl<T: PostProcess> super::TechniqueFrame for PostFrame<T> {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let (params, draws_own) = T::params(cx).ok_or_else(|| super::mismatch(cx))?;
        cx.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform(cx)));
        cx.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        if !draws_own {
            self.own = None;
            return Ok(());
        }
        let size = cx.camera.viewport.map(|v| v.max(1));
        if self.own.as_ref().is_none_or(|own| own.size != size) {
            let own = Own::new(
                cx.pipelines,
                T::BINDINGS.label,
                size,
                T::OWN_FORMAT,
                T::OWN_DEPTH,
            )?;
            self.own = Some(own);
        }
        let meshes = instance_blocks(cx, &mut self.blocks, &mut self.group);
        let group = block_group(cx.pipelines, &self.blocks, &mut self.group)?;
        if let Some(own) = &self.own {
            own.draw_meshes(cx.pipelines, encoder, &self.pipelines.mesh, group, &meshes);
        }
        Ok(())
    }

    fn render(&self, _pass: &mut wgpu::RenderPass<'_>) {}

    fn finish(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        views: &FrameViews<'_>,
    ) -> Result<(), RenderError> {
        let own = &self.own.as_ref().unwrap_or(&self.placeholder).view;
        full_screen(
            &self.cache,
            encoder,
            views,
            (T::BINDINGS, &self.pipelines.full_screen),
            (&self.uniform, &self.params),
            (T::OWN, own),
        )
    }

    fn gpu_bytes(&self) -> u64 {
        self.uniform.size() + self.params.size() + self.own.as_ref().map_or(0, Own::bytes)
    }
}
