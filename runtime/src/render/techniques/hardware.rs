//! [`Technique::Hardware`](crate::render::Technique::Hardware): the thesis' hardware contour methods
//! (§4.1–4.7), each a short configuration of passes over the mesh's triangles
//! (`shaders/hardware.wgsl`, pulled in the vertex shader: wgpu has no geometry shaders or wide lines).
//!
//! They draw inside the application's pass after its mesh, which is the thesis' "render the mesh
//! first" step; the stencil methods clear and use the pass's stencil (and leave its reference at 0),
//! Raskar's valleys read a second depth buffer of the back faces that the frame renders itself.

use std::sync::Arc;

use super::surface_angle::mesh_buffers;
use super::{FrameContext, PerAsset, Pulled, TechniqueFrame};
use crate::render::pipelines::{Access, BindingSet, RenderPipeline};
use crate::render::target::checked;
use crate::render::{HardwareContour, Pipelines as Cache, RenderError, Technique, modules};

const SET: BindingSet = BindingSet {
    label: "hardware contours",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Access::Instance), (5, Access::Read), (7, Access::Read)],
};

/// The format of the back faces' depth (Raskar's second depth buffer).
const BACK_DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Every pass of every method, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    valley_layout: wgpu::BindGroupLayout,
    /// The mesh into depth only (§4.1, Rossignac–van Emmerik's first step).
    depth_only: wgpu::RenderPipeline,
    wire: wgpu::RenderPipeline,
    back: wgpu::RenderPipeline,
    fat: wgpu::RenderPipeline,
    ridges: wgpu::RenderPipeline,
    valleys: wgpu::RenderPipeline,
    /// The back faces into the frame's own depth texture (Raskar's second depth buffer).
    back_depth: wgpu::RenderPipeline,
    /// Stencil passes, where the target has a stencil aspect.
    stencil: Option<StencilPipelines>,
}

#[derive(Debug)]
struct StencilPipelines {
    clear: wgpu::RenderPipeline,
    shifted: wgpu::RenderPipeline,
    shifted_cover: wgpu::RenderPipeline,
    lines: wgpu::RenderPipeline,
    lines_cover: wgpu::RenderPipeline,
}

/// A stencil state doing `op` where `compare` passes against the reference under `read_mask`.
fn stencil(
    compare: wgpu::CompareFunction,
    op: wgpu::StencilOperation,
    read_mask: u32,
) -> wgpu::StencilState {
    let face = wgpu::StencilFaceState {
        compare,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op: wgpu::StencilOperation::Keep,
        pass_op: op,
    };
    wgpu::StencilState {
        front: face,
        back: face,
        read_mask,
        write_mask: 0xff,
    }
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = cache.layout(&SET);
        let valley_layout =
            cache
                .device()
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some("raskar valleys"),
                    entries: &[
                        wgpu::BindGroupLayoutEntry {
                            binding: 0,
                            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                            ty: wgpu::BindingType::Buffer {
                                ty: wgpu::BufferBindingType::Uniform,
                                has_dynamic_offset: true,
                                min_binding_size: None,
                            },
                            count: None,
                        },
                        buffer_entry(5, wgpu::BufferBindingType::Storage { read_only: true }),
                        buffer_entry(7, wgpu::BufferBindingType::Storage { read_only: true }),
                        wgpu::BindGroupLayoutEntry {
                            binding: 9,
                            visibility: wgpu::ShaderStages::FRAGMENT,
                            ty: wgpu::BindingType::Texture {
                                sample_type: wgpu::TextureSampleType::Depth,
                                view_dimension: wgpu::TextureViewDimension::D2,
                                multisampled: false,
                            },
                            count: None,
                        },
                    ],
                });
        let module = cache.module("hardware.wgsl", &modules::hardware())?;
        let target = *cache.target();
        let no_color = wgpu::ColorTargetState {
            format: target.color_format,
            blend: None,
            write_mask: wgpu::ColorWrites::empty(),
        };
        let pipeline = |label,
                        layout: &wgpu::BindGroupLayout,
                        vertex,
                        fragment,
                        topology,
                        depth_stencil,
                        color| {
            cache.render_pipeline(
                &[layout],
                RenderPipeline {
                    label,
                    module: &module,
                    vertex,
                    fragment: Some(fragment),
                    buffers: &[],
                    primitive: wgpu::PrimitiveState {
                        topology,
                        ..Default::default()
                    },
                    depth_stencil,
                    multisample: target.multisample(),
                    color: Some(color),
                },
            )
        };
        let triangles = wgpu::PrimitiveTopology::TriangleList;
        let less_equal = target.depth(false, wgpu::CompareFunction::LessEqual);
        let drawn = target.blended_color();
        let depth_only = cache.render_pipeline(
            &[&layout],
            RenderPipeline {
                label: "mesh depth",
                module: &module,
                vertex: "hw_depth_vertex",
                fragment: Some("stencil_only"),
                buffers: &mesh_buffers()[..1],
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: target.depth(true, wgpu::CompareFunction::Less),
                multisample: target.multisample(),
                color: Some(no_color.clone()),
            },
        )?;
        let back_depth = cache.render_pipeline(
            &[&layout],
            RenderPipeline {
                label: "back faces' depth",
                module: &module,
                vertex: "hw_depth_vertex",
                fragment: None,
                buffers: &mesh_buffers()[..1],
                primitive: wgpu::PrimitiveState {
                    cull_mode: Some(wgpu::Face::Front),
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: BACK_DEPTH,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(target.nearer(wgpu::CompareFunction::Less)),
                    stencil: wgpu::StencilState::default(),
                    bias: wgpu::DepthBiasState::default(),
                }),
                multisample: wgpu::MultisampleState::default(),
                color: None,
            },
        )?;
        let stencil_pipelines = if target.has_stencil() {
            use wgpu::CompareFunction::{Always, Equal};
            use wgpu::StencilOperation::{IncrementClamp, Invert, Keep, Replace};
            let with = |compare, op, mask| {
                target.depth_with_stencil(false, Always, stencil(compare, op, mask))
            };
            Some(StencilPipelines {
                clear: pipeline(
                    "stencil clear",
                    &layout,
                    "fullscreen_vertex",
                    "stencil_only",
                    triangles,
                    with(Always, Replace, 0xff),
                    no_color.clone(),
                )?,
                shifted: pipeline(
                    "shifted mesh stencil",
                    &layout,
                    "hw_shift_vertex",
                    "stencil_only",
                    triangles,
                    with(Always, IncrementClamp, 0xff),
                    no_color.clone(),
                )?,
                shifted_cover: pipeline(
                    "shifted stencil cover",
                    &layout,
                    "fullscreen_vertex",
                    "flat_fragment",
                    triangles,
                    with(Equal, Keep, 2),
                    drawn.clone(),
                )?,
                lines: pipeline(
                    "front wireframe stencil",
                    &layout,
                    "hw_line_vertex",
                    "stencil_only",
                    wgpu::PrimitiveTopology::LineList,
                    target.depth_with_stencil(
                        false,
                        wgpu::CompareFunction::LessEqual,
                        stencil(Always, Invert, 0xff),
                    ),
                    no_color,
                )?,
                lines_cover: pipeline(
                    "inverted stencil cover",
                    &layout,
                    "fullscreen_vertex",
                    "flat_fragment",
                    triangles,
                    with(Equal, Keep, 1),
                    drawn.clone(),
                )?,
            })
        } else {
            None
        };
        Ok(Self {
            depth_only,
            wire: pipeline(
                "wireframe quads",
                &layout,
                "hw_wire_vertex",
                "flat_fragment",
                triangles,
                less_equal.clone(),
                drawn.clone(),
            )?,
            back: pipeline(
                "back faces",
                &layout,
                "hw_back_vertex",
                "flat_fragment",
                triangles,
                less_equal.clone(),
                drawn.clone(),
            )?,
            fat: pipeline(
                "fattened back faces",
                &layout,
                "hw_fat_vertex",
                "flat_fragment",
                triangles,
                less_equal.clone(),
                drawn.clone(),
            )?,
            ridges: pipeline(
                "ridge quads",
                &layout,
                "hw_crease_vertex",
                "flat_fragment",
                triangles,
                less_equal,
                drawn.clone(),
            )?,
            // Valleys draw where they lie behind the front surface: the depth test reversed.
            valleys: pipeline(
                "valley quads",
                &valley_layout,
                "hw_crease_vertex",
                "valley_fragment",
                triangles,
                target.depth(false, wgpu::CompareFunction::Greater),
                drawn,
            )?,
            back_depth,
            stencil: stencil_pipelines,
            layout,
            valley_layout,
        })
    }
}

fn buffer_entry(binding: u32, ty: wgpu::BufferBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Raskar's second depth buffer, sized to the viewport.
#[derive(Debug)]
struct BackDepth {
    size: [u32; 2],
    view: wgpu::TextureView,
}

/// A frame.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
    method: HardwareContour,
    back_depth: Option<BackDepth>,
    /// Per asset, its valley group over the back faces' depth (remade each frame: few assets).
    valley_groups: PerAsset<wgpu::BindGroup>,
    /// Per instance, its valley group and block.
    valleys: Vec<(usize, u32)>,
}

impl Frame {
    pub(crate) fn new(cache: &Cache, method: HardwareContour) -> Result<Self, RenderError> {
        let pipelines = cache.hardware()?;
        if method.needs_stencil() && pipelines.stencil.is_none() {
            return Err(RenderError::TargetLacks {
                technique: method.name(),
                needs: "a depth format with a stencil aspect",
            });
        }
        Ok(Self {
            pipelines,
            pulled: Pulled::new(cache, "hardware contours"),
            method,
            back_depth: None,
            valley_groups: PerAsset::default(),
            valleys: Vec::new(),
        })
    }

    /// Raskar's back-face depth for `size`, made or remade when the viewport changes.
    fn ensure_back_depth(&mut self, cache: &Cache, size: [u32; 2]) -> Result<(), RenderError> {
        if self.back_depth.as_ref().is_some_and(|b| b.size == size) {
            return Ok(());
        }
        let device = cache.device();
        let texture = checked(device, "the back faces' depth", || {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some("back faces' depth"),
                size: wgpu::Extent3d {
                    width: size[0],
                    height: size[1],
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: BACK_DEPTH,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
        })?;
        self.back_depth = Some(BackDepth {
            size,
            view: texture.create_view(&Default::default()),
        });
        Ok(())
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let Technique::Hardware(method) = cx.style.technique else {
            return Err(super::mismatch(cx));
        };
        self.method = method;
        let bias = cx.style.bias_px();
        let params = match method {
            HardwareContour::RossignacVanEmmerik => [0.0, bias, 0.0, 0.0],
            HardwareContour::GoochWireframe => [1.0, 0.0, 0.0, 0.0],
            HardwareContour::OffsetBackFaces => [0.0, bias, 0.0, 0.0],
            HardwareContour::Raskar { crease_deg } => {
                let angle = if crease_deg.is_finite() {
                    crease_deg.clamp(0.0, 180.0)
                } else {
                    30.0
                };
                [0.0, 0.0, 0.0, angle.to_radians()]
            }
            _ => [0.0; 4],
        };
        self.pulled.prepare(
            cx,
            &self.pipelines.layout,
            &SET,
            |d, i| {
                let mut uniform = super::frame_uniform(cx, d, i, 0);
                uniform.params = params;
                uniform
            },
            |asset| {
                Ok(vec![
                    (5, asset.render_positions.clone()),
                    (7, asset.mesh_indices.clone()),
                ])
            },
        )?;
        self.valley_groups.clear();
        self.valleys.clear();
        if let HardwareContour::Raskar { .. } = method {
            let size = cx.camera.viewport.map(|v| v.max(1));
            self.ensure_back_depth(cx.pipelines, size)?;
            let Some(back) = &self.back_depth else {
                return Err(super::mismatch(cx));
            };
            for (i, drawn) in cx.instances.iter().enumerate() {
                let blocks = &self.pulled.blocks;
                let layout = &self.pipelines.valley_layout;
                let group = self.valley_groups.index(drawn.asset, |asset| {
                    Ok(cx
                        .pipelines
                        .device()
                        .create_bind_group(&wgpu::BindGroupDescriptor {
                            label: Some("raskar valleys"),
                            layout,
                            entries: &[
                                wgpu::BindGroupEntry {
                                    binding: 0,
                                    resource: blocks.binding(),
                                },
                                wgpu::BindGroupEntry {
                                    binding: 5,
                                    resource: asset.render_positions.as_entire_binding(),
                                },
                                wgpu::BindGroupEntry {
                                    binding: 7,
                                    resource: asset.mesh_indices.as_entire_binding(),
                                },
                                wgpu::BindGroupEntry {
                                    binding: 9,
                                    resource: wgpu::BindingResource::TextureView(&back.view),
                                },
                            ],
                        }))
                })?;
                self.valleys.push((group, blocks.offset(i)));
            }
            let far = cx.pipelines.target().far_depth();
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("back faces' depth"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &back.view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(far),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipelines.back_depth);
            self.pulled.each(&mut pass, |pass, asset| {
                pass.set_vertex_buffer(0, asset.render_positions.slice(..));
                pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
                pass.draw_indexed(0..asset.index_count, 0, 0..1);
            });
        }
        Ok(())
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let p = &self.pipelines;
        match self.method {
            HardwareContour::RossignacVanEmmerik => self.pulled.each(pass, |pass, asset| {
                pass.set_pipeline(&p.depth_only);
                pass.set_vertex_buffer(0, asset.render_positions.slice(..));
                pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
                pass.draw_indexed(0..asset.index_count, 0, 0..1);
                pass.set_pipeline(&p.wire);
                pass.draw(0..18, 0..asset.index_count / 3);
            }),
            HardwareContour::GoochWireframe => self.pulled.each(pass, |pass, asset| {
                pass.set_pipeline(&p.wire);
                pass.draw(0..18, 0..asset.index_count / 3);
            }),
            HardwareContour::BackFaces | HardwareContour::OffsetBackFaces => {
                self.pulled.each(pass, |pass, asset| {
                    pass.set_pipeline(&p.back);
                    pass.draw(0..3, 0..asset.index_count / 3);
                })
            }
            HardwareContour::FattenedBackFaces => self.pulled.each(pass, |pass, asset| {
                pass.set_pipeline(&p.fat);
                pass.draw(0..18, 0..asset.index_count / 3);
            }),
            HardwareContour::StencilShifted => {
                if let Some(s) = &p.stencil {
                    // The stencil of every instance, then one cover: the method outlines the
                    // union of what it draws.
                    pass.set_stencil_reference(0);
                    let mut first = true;
                    self.pulled.each(pass, |pass, asset| {
                        if std::mem::take(&mut first) {
                            pass.set_pipeline(&s.clear);
                            pass.draw(0..3, 0..1);
                        }
                        let triangles = asset.index_count / 3;
                        pass.set_pipeline(&s.shifted);
                        // Four renders of the mesh, one per shift (instance / triangles).
                        for k in 0..4 {
                            pass.draw(0..3, k * triangles..(k + 1) * triangles);
                        }
                    });
                    if !first {
                        pass.set_stencil_reference(2);
                        pass.set_pipeline(&s.shifted_cover);
                        pass.draw(0..3, 0..1);
                        pass.set_stencil_reference(0);
                    }
                }
            }
            HardwareContour::InvertedStencil => {
                if let Some(s) = &p.stencil {
                    pass.set_stencil_reference(0);
                    let mut first = true;
                    self.pulled.each(pass, |pass, asset| {
                        if std::mem::take(&mut first) {
                            pass.set_pipeline(&s.clear);
                            pass.draw(0..3, 0..1);
                        }
                        pass.set_pipeline(&s.lines);
                        pass.draw(0..6, 0..asset.index_count / 3);
                    });
                    if !first {
                        pass.set_stencil_reference(1);
                        pass.set_pipeline(&s.lines_cover);
                        pass.draw(0..3, 0..1);
                        pass.set_stencil_reference(0);
                    }
                }
            }
            HardwareContour::Raskar { .. } => {
                self.pulled.each(pass, |pass, asset| {
                    let triangles = asset.index_count / 3;
                    pass.set_pipeline(&p.fat);
                    pass.draw(0..18, 0..triangles);
                    pass.set_pipeline(&p.ridges);
                    pass.draw(0..18, 0..triangles);
                });
                // Instances past the triangle count are the valley quads.
                for &(group, offset) in &self.valleys {
                    let (asset, bind_group) = self.valley_groups.get(group);
                    let triangles = asset.index_count / 3;
                    pass.set_bind_group(0, bind_group, &[offset]);
                    pass.set_pipeline(&p.valleys);
                    pass.draw(0..18, triangles..2 * triangles);
                }
            }
        }
    }

    fn gpu_bytes(&self) -> u64 {
        let back = self
            .back_depth
            .as_ref()
            .map_or(0, |b| 4 * u64::from(b.size[0]) * u64::from(b.size[1]));
        self.pulled.gpu_bytes() + back
    }
}
