//! The chamfer highlight's outline pass (issue 39, `shaders/outline.wgsl`), recorded by
//! [`Prepared::finish`](crate::render::Prepared::finish) after the application's pass: where a chamfer
//! edge or a rounded corner lies on the silhouette, the pixels the sharp mesh covers beyond the rounded
//! outline are repainted with what lies just beyond the sharp outline beside them, so a rounded box's
//! outline runs where a filleted one's would and its corners are arcs.
//!
//! A pass after the mesh, not a change to the mesh pass: that pass is the application's (its own, or
//! Bevy's PBR pass), which Chamfer neither owns nor sees; repainting needs only the finished colour
//! and depth, which every front end can give. The cost of not knowing what lies behind the mesh: a
//! trimmed pixel takes the colour of the first pixel past the sharp outline, exact over a background of
//! one colour and within the band's width (under half the radius on a box) of it elsewhere.

use std::sync::Mutex;

use super::Frame;
use super::bindings::{OUTLINE_CORNERS, OUTLINE_STRIPS, SCENE_COLOR};
use crate::render::bindings::Bindings;
use crate::render::target::checked;
use crate::render::techniques::post;
use crate::render::{FrameViews, RenderError};

/// The copy of the application's colour the pass reads, kept while its size and format stay.
#[derive(Debug, Default)]
pub(super) struct Outline {
    copy: Mutex<Option<Copy>>,
}

#[derive(Debug)]
struct Copy {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

impl Outline {
    /// A copy of `color`'s first layer as it is now, recorded into `encoder`.
    fn copy(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::Texture,
    ) -> Result<wgpu::TextureView, RenderError> {
        if !color.usage().contains(wgpu::TextureUsages::COPY_SRC) {
            return Err(RenderError::TargetLacks {
                technique: "the chamfer highlight's rounded outline",
                needs: "a colour texture with COPY_SRC usage",
            });
        }
        let size = wgpu::Extent3d {
            depth_or_array_layers: 1,
            ..color.size()
        };
        let mut copy = self
            .copy
            .lock()
            .map_err(|_| RenderError::Internal("the outline's copy was poisoned".into()))?;
        let fits = copy
            .as_ref()
            .is_some_and(|c| c.texture.size() == size && c.texture.format() == color.format());
        if !fits {
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some("the colour under the highlight's outline"),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: color.format(),
                usage: wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            });
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            *copy = Some(Copy { texture, view });
        }
        let copy = copy
            .as_ref()
            .ok_or_else(|| RenderError::Internal("the outline's copy".into()))?;
        encoder.copy_texture_to_texture(color.as_image_copy(), copy.texture.as_image_copy(), size);
        Ok(copy.view.clone())
    }

    /// GPU bytes of the copy.
    pub(super) fn gpu_bytes(&self) -> u64 {
        self.copy
            .lock()
            .ok()
            .and_then(|c| {
                c.as_ref().map(|c| {
                    let size = c.texture.size();
                    u64::from(size.width)
                        * u64::from(size.height)
                        * u64::from(c.texture.format().block_copy_size(None).unwrap_or(4))
                })
            })
            .unwrap_or(0)
    }
}

/// Records the outline pass of `frame` over `views` (nothing where the frame draws no chamfer edges).
pub(super) fn record(
    frame: &Frame,
    encoder: &mut wgpu::CommandEncoder,
    views: &FrameViews<'_>,
) -> Result<(), RenderError> {
    let (Some(lists), Some(instances)) = (&frame.lists, &frame.instances) else {
        return Ok(());
    };
    if !frame.outlined {
        return Ok(());
    }
    let cache = &frame.cache;
    let device = cache.device();
    let copy = frame.outline.copy(device, encoder, views.color.texture())?;
    let shared = super::Resources {
        blocks: &frame.blocks,
        lists,
        instances,
        highlight: &frame.highlight,
        asset: None,
        window: None,
    };
    // The application's views are checked here: a depth view that cannot be sampled is a typed error.
    let group = |set: &'static Bindings, resources: &super::Resources<'_>| {
        checked(
            device,
            "the outline pass's bindings (is the depth TEXTURE_BINDING?)",
            || {
                set.group(device, &cache.layout(set), |binding| match binding {
                    SCENE_COLOR => Ok(wgpu::BindingResource::TextureView(&copy)),
                    post::DEPTH => Ok(wgpu::BindingResource::TextureView(views.depth)),
                    other => resources.get(other),
                })
            },
        )?
    };
    let strips = group(&OUTLINE_STRIPS, &shared)?;
    let mut corners = Vec::new();
    for &(asset, block) in &frame.instance_runs {
        let (gpu, _) = frame.assets.get(asset);
        if gpu.corner_count == 0 {
            continue;
        }
        let own = super::Resources {
            blocks: &frame.instance_blocks,
            lists,
            instances,
            highlight: &frame.highlight,
            asset: Some(gpu),
            window: None,
        };
        corners.push((group(&OUTLINE_CORNERS, &own)?, block, gpu.corner_count));
    }
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("chamfer highlight outline"),
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
    pass.set_pipeline(&frame.pipelines.outline_strips);
    pass.set_bind_group(0, &strips, &[0]);
    pass.draw_indirect(&lists.out, 0);
    pass.set_pipeline(&frame.pipelines.outline_corners);
    for (group, block, count) in &corners {
        pass.set_bind_group(0, group, &[*block]);
        pass.draw(0..6, 0..*count);
    }
    Ok(())
}
