//! What the post-processes share (`shaders/post.wgsl`): a full-screen pass after the application's
//! pass into its finished colour, reading its depth; textures of their own sized to the viewport;
//! the `Post` uniform.

use crate::render::bindings::{Binding, Bindings, Kind};
use crate::render::gpu_asset::vertex_layouts;
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
        let device = cache.device();
        let texture = |format, usage| {
            checked(device, label, || {
                device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: size[0],
                        height: size[1],
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
            })
        };
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let view = texture(format, attachment | wgpu::TextureUsages::TEXTURE_BINDING)?
            .create_view(&Default::default());
        let depth = if with_depth {
            Some(texture(OWN_DEPTH, attachment)?.create_view(&Default::default()))
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
            buffers: &vertex_layouts(),
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
