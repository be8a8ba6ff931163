//! [`Technique::Hardware`](crate::render::Technique::Hardware): the thesis' hardware contour methods
//! (§4.1–4.7), each a short configuration of passes over the mesh's triangles
//! (`shaders/hardware.wgsl`, pulled in the vertex shader: wgpu has no geometry shaders or wide lines).
//!
//! They draw inside the application's pass after its mesh, which is the thesis' "render the mesh
//! first" step; the stencil methods clear and use the pass's stencil (and leave its reference at 0),
//! Raskar's valleys read a second depth buffer of the back faces that the frame renders itself.

use std::sync::Arc;

use super::pulled::Instances;
use super::{FrameContext, FrameOptions, Module, PerAsset, TechniqueFrame};
use crate::render::bindings::{Binding, Bindings, FRAME, Kind, PARAMS, asset};
use crate::render::gpu_asset::VERTEX_LAYOUTS;
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::{
    AssetExtras, HardwareContour, Pipelines as Cache, RenderError, Target, Technique,
};

pub(crate) static MODULE: Hardware = Hardware;

/// One preset per method, in [`HardwareContour::ALL`]'s order, named as the method.
///
/// [`HardwareContour::ALL`]: crate::render::HardwareContour::ALL
static PRESETS: [crate::render::Preset; 8] = {
    const SUMMARIES: [&str; 8] = [
        "thick wireframe pushed behind the mesh's depth (thesis §4.1)",
        "back faces' wireframe over the front faces (thesis §4.1, Gooch)",
        "back faces filled with LessEqual (thesis §4.2)",
        "back faces pulled towards the camera (thesis §4.3)",
        "back faces fattened by the line width (thesis §4.4)",
        "stencil of the mesh shifted four ways (thesis §4.5)",
        "front-face wireframe inverting the stencil (thesis §4.6)",
        "Raskar's fattened back faces and rotated crease quads (thesis §4.7)",
    ];
    let methods = crate::render::HardwareContour::ALL;
    let mut presets = [crate::render::Preset {
        name: "",
        summary: "",
        technique: crate::render::Technique::Joined,
    }; 8];
    let mut k = 0;
    while k < 8 {
        presets[k] = crate::render::Preset {
            name: methods[k].name(),
            summary: SUMMARIES[k],
            technique: crate::render::Technique::Hardware(methods[k]),
        };
        k += 1;
    }
    presets
};

const BINDINGS: Bindings = Bindings::draw(
    "hardware contours",
    &[FRAME, PARAMS, asset::RENDER_POSITIONS, asset::MESH_INDICES],
);
/// The back faces' depth (Raskar's second depth buffer, the frame's own).
const BACK_DEPTH: Binding = Binding::new(16, "back_depth", Kind::Depth);
const VALLEY_BINDINGS: Bindings = Bindings::draw(
    "raskar valleys",
    &[
        FRAME,
        PARAMS,
        asset::RENDER_POSITIONS,
        asset::MESH_INDICES,
        BACK_DEPTH,
    ],
);

/// The format of the back faces' depth.
const BACK_DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// `HardwareParams` in `shaders/hardware.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct HardwareParams {
    back_only: u32,
    offset_px: f32,
    crease_angle: f32,
}

/// The module.
pub(crate) struct Hardware;

fn shader() -> Shader {
    use chamfer_shaders as wgsl;
    let flat = |vertex| Program::draw(vertex, "flat_fragment", &BINDINGS);
    let stencil = |vertex| Program::draw(vertex, "stencil_only", &BINDINGS);
    Shader::new(
        "hardware.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::FLAT,
            wgsl::TRIANGLES,
            wgsl::HARDWARE,
        ],
        vec![
            stencil("hw_depth_vertex"),
            flat("hw_wire_vertex"),
            flat("hw_back_vertex"),
            flat("hw_fat_vertex"),
            flat("hw_crease_vertex"),
            Program::draw("hw_crease_vertex", "valley_fragment", &VALLEY_BINDINGS),
            stencil("fullscreen_vertex"),
            flat("fullscreen_vertex"),
            stencil("hw_shift_vertex"),
            stencil("hw_line_vertex"),
        ],
    )
}

impl Module for Hardware {
    fn presets(&self) -> &'static [crate::render::Preset] {
        &PRESETS
    }

    /// By the method, whatever its parameters.
    fn preset(&self, technique: &crate::render::Technique) -> &'static crate::render::Preset {
        let index = match technique {
            crate::render::Technique::Hardware(method) => crate::render::HardwareContour::ALL
                .iter()
                .position(|m| m.name() == method.name()),
            _ => None,
        };
        &PRESETS[index.unwrap_or(0)]
    }

    fn shaders(&self, _target: &Target) -> Vec<Shader> {
        vec![shader()]
    }

    fn structs(&self) -> Vec<Layout> {
        vec![layout!(
            "HardwareParams",
            HardwareParams,
            [back_only, offset_px, crease_angle]
        )]
    }

    fn needs(&self, _technique: &Technique) -> AssetExtras {
        AssetExtras::NONE
    }

    fn needs_stencil(&self, technique: &Technique) -> bool {
        matches!(technique, Technique::Hardware(method) if method.needs_stencil())
    }

    fn new_frame(
        &self,
        cache: &Cache,
        _options: &FrameOptions,
    ) -> Result<Box<dyn TechniqueFrame>, RenderError> {
        Ok(Box::new(Frame::new(cache)?))
    }
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

/// Every pass of every method, per device and target.
#[derive(Debug)]
pub(crate) struct HardwarePipelines {
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

impl PipelineSet for HardwarePipelines {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        let target = *cache.target();
        let no_color = wgpu::ColorTargetState {
            format: target.color_format,
            blend: None,
            write_mask: wgpu::ColorWrites::empty(),
        };
        let triangles = |depth_stencil, color| Raster {
            depth_stencil,
            color: Some(color),
            ..Raster::over_mesh(&target)
        };
        let less_equal = || target.depth(false, wgpu::CompareFunction::LessEqual);
        let drawn = target.blended_color();
        let flat = |vertex, raster| compiled.render(vertex, Some("flat_fragment"), raster);
        let stencil_only = |vertex, raster| compiled.render(vertex, Some("stencil_only"), raster);
        let stencil_pipelines = if target.has_stencil() {
            use wgpu::CompareFunction::{Always, Equal};
            use wgpu::StencilOperation::{IncrementClamp, Invert, Keep, Replace};
            let with = |compare, op, mask| {
                target.depth_with_stencil(false, Always, stencil(compare, op, mask))
            };
            Some(StencilPipelines {
                clear: stencil_only(
                    "fullscreen_vertex",
                    triangles(with(Always, Replace, 0xff), no_color.clone()),
                )?,
                shifted: stencil_only(
                    "hw_shift_vertex",
                    triangles(with(Always, IncrementClamp, 0xff), no_color.clone()),
                )?,
                shifted_cover: flat(
                    "fullscreen_vertex",
                    triangles(with(Equal, Keep, 2), drawn.clone()),
                )?,
                lines: stencil_only(
                    "hw_line_vertex",
                    Raster {
                        primitive: wgpu::PrimitiveState {
                            topology: wgpu::PrimitiveTopology::LineList,
                            ..Default::default()
                        },
                        ..triangles(
                            target.depth_with_stencil(
                                false,
                                wgpu::CompareFunction::LessEqual,
                                stencil(Always, Invert, 0xff),
                            ),
                            no_color.clone(),
                        )
                    },
                )?,
                lines_cover: flat(
                    "fullscreen_vertex",
                    triangles(with(Equal, Keep, 1), drawn.clone()),
                )?,
            })
        } else {
            None
        };
        Ok(Self {
            depth_only: stencil_only(
                "hw_depth_vertex",
                Raster {
                    buffers: &VERTEX_LAYOUTS[..1],
                    ..triangles(target.depth(true, wgpu::CompareFunction::Less), no_color)
                },
            )?,
            wire: flat("hw_wire_vertex", triangles(less_equal(), drawn.clone()))?,
            back: flat("hw_back_vertex", triangles(less_equal(), drawn.clone()))?,
            fat: flat("hw_fat_vertex", triangles(less_equal(), drawn.clone()))?,
            ridges: flat("hw_crease_vertex", triangles(less_equal(), drawn.clone()))?,
            // Valleys draw where they lie behind the front surface: the depth test reversed.
            valleys: compiled.render(
                "hw_crease_vertex",
                Some("valley_fragment"),
                triangles(target.depth(false, wgpu::CompareFunction::Greater), drawn),
            )?,
            // Through the fragment that discards what the section cuts away.
            back_depth: compiled.render(
                "hw_depth_vertex",
                Some("stencil_only"),
                Raster {
                    buffers: &VERTEX_LAYOUTS[..1],
                    primitive: wgpu::PrimitiveState {
                        cull_mode: Some(wgpu::Face::Front),
                        ..Default::default()
                    },
                    depth_stencil: Some(wgpu::DepthStencilState {
                        format: BACK_DEPTH_FORMAT,
                        depth_write_enabled: Some(true),
                        depth_compare: Some(target.nearer(wgpu::CompareFunction::Less)),
                        stencil: wgpu::StencilState::default(),
                        bias: wgpu::DepthBiasState::default(),
                    }),
                    multisample: wgpu::MultisampleState::default(),
                    color: None,
                },
            )?,
            stencil: stencil_pipelines,
        })
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
struct Frame {
    pipelines: Arc<HardwarePipelines>,
    layout: wgpu::BindGroupLayout,
    valley_layout: wgpu::BindGroupLayout,
    instances: Instances<HardwareParams>,
    method: HardwareContour,
    back_depth: Option<BackDepth>,
    /// Per asset, its valley group over the back faces' depth (remade each frame: few assets).
    valley_groups: PerAsset<wgpu::BindGroup>,
    /// Per instance, its asset's valley group.
    valleys: Vec<usize>,
}

impl Frame {
    fn new(cache: &Cache) -> Result<Self, RenderError> {
        Ok(Self {
            pipelines: cache.get::<HardwarePipelines>()?,
            layout: cache.layout(&BINDINGS),
            valley_layout: cache.layout(&VALLEY_BINDINGS),
            instances: Instances::new(cache, "hardware contours"),
            method: HardwareContour::BackFaces,
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
        let view = super::texture(
            cache,
            "back faces' depth",
            size,
            BACK_DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        )?;
        self.back_depth = Some(BackDepth { size, view });
        Ok(())
    }

    /// Raskar's valleys: the groups over the back faces' depth, and the pass that renders it.
    fn prepare_valleys(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let size = cx.camera.viewport.map(|v| v.max(1));
        self.ensure_back_depth(cx.pipelines, size)?;
        let Some(back) = &self.back_depth else {
            return Err(super::mismatch(cx));
        };
        let technique = cx.style.technique.name();
        for drawn in cx.instances {
            let instances = &self.instances;
            let layout = &self.valley_layout;
            let group = self.valley_groups.index(drawn.asset, |asset| {
                VALLEY_BINDINGS.group(cx.pipelines.device(), layout, |binding| {
                    if binding == BACK_DEPTH {
                        return Ok(wgpu::BindingResource::TextureView(&back.view));
                    }
                    match instances.block(binding) {
                        Some(block) => Ok(block),
                        None => asset.resource(binding, technique),
                    }
                })
            })?;
            self.valleys.push(group);
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
        self.instances.each(&mut pass, |pass, asset| {
            pass.set_vertex_buffer(0, asset.render_positions.slice(..));
            pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
            pass.draw_indexed(0..asset.index_count, 0, 0..1);
        });
        Ok(())
    }
}

impl Frame {
    /// A stencil method's passes: the stencil cleared, `draw` of every instance into it, then one
    /// cover where it equals `reference` (the methods outline the union of what they draw); the
    /// pass's stencil reference is left at 0.
    fn stencil_outline(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        stencil: &StencilPipelines,
        (cover, reference): (&wgpu::RenderPipeline, u32),
        mut draw: impl FnMut(&mut wgpu::RenderPass<'_>, &crate::render::GpuAsset),
    ) {
        pass.set_stencil_reference(0);
        let mut first = true;
        self.instances.each(pass, |pass, asset| {
            if std::mem::take(&mut first) {
                pass.set_pipeline(&stencil.clear);
                pass.draw(0..3, 0..1);
            }
            draw(pass, asset);
        });
        if !first {
            pass.set_stencil_reference(reference);
            pass.set_pipeline(cover);
            pass.draw(0..3, 0..1);
            pass.set_stencil_reference(0);
        }
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
        let mut params = HardwareParams {
            back_only: 0,
            offset_px: 0.0,
            crease_angle: 0.0,
        };
        match method {
            HardwareContour::RossignacVanEmmerik | HardwareContour::OffsetBackFaces => {
                params.offset_px = bias;
            }
            HardwareContour::GoochWireframe => params.back_only = 1,
            HardwareContour::Raskar { crease_deg } => {
                let angle = if crease_deg.is_finite() {
                    crease_deg.clamp(0.0, 180.0)
                } else {
                    30.0
                };
                params.crease_angle = angle.to_radians();
            }
            _ => {}
        }
        self.instances.prepare(
            cx,
            &BINDINGS,
            &self.layout,
            |_| Some(params),
            |asset, binding| asset.resource(binding, method.name()),
        )?;
        self.valley_groups.clear();
        self.valleys.clear();
        if let HardwareContour::Raskar { .. } = method {
            self.prepare_valleys(cx, encoder)?;
        }
        Ok(())
    }

    fn gpu_bytes(&self) -> u64 {
        let back = self
            .back_depth
            .as_ref()
            .map_or(0, |b| 4 * u64::from(b.size[0]) * u64::from(b.size[1]));
        self.instances.gpu_bytes() + back
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let p = &self.pipelines;
        match self.method {
            HardwareContour::RossignacVanEmmerik => self.instances.each(pass, |pass, asset| {
                pass.set_pipeline(&p.depth_only);
                pass.set_vertex_buffer(0, asset.render_positions.slice(..));
                pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
                pass.draw_indexed(0..asset.index_count, 0, 0..1);
                pass.set_pipeline(&p.wire);
                pass.draw(0..18, 0..asset.index_count / 3);
            }),
            HardwareContour::GoochWireframe => self.instances.each(pass, |pass, asset| {
                pass.set_pipeline(&p.wire);
                pass.draw(0..18, 0..asset.index_count / 3);
            }),
            HardwareContour::BackFaces | HardwareContour::OffsetBackFaces => {
                self.instances.each(pass, |pass, asset| {
                    pass.set_pipeline(&p.back);
                    pass.draw(0..3, 0..asset.index_count / 3);
                })
            }
            HardwareContour::FattenedBackFaces => self.instances.each(pass, |pass, asset| {
                pass.set_pipeline(&p.fat);
                pass.draw(0..18, 0..asset.index_count / 3);
            }),
            HardwareContour::StencilShifted => {
                if let Some(s) = &p.stencil {
                    self.stencil_outline(pass, s, (&s.shifted_cover, 2), |pass, asset| {
                        let triangles = asset.index_count / 3;
                        pass.set_pipeline(&s.shifted);
                        // Four renders of the mesh, one per shift (instance / triangles).
                        for k in 0..4 {
                            pass.draw(0..3, k * triangles..(k + 1) * triangles);
                        }
                    });
                }
            }
            HardwareContour::InvertedStencil => {
                if let Some(s) = &p.stencil {
                    self.stencil_outline(pass, s, (&s.lines_cover, 1), |pass, asset| {
                        pass.set_pipeline(&s.lines);
                        pass.draw(0..6, 0..asset.index_count / 3);
                    });
                }
            }
            HardwareContour::Raskar { .. } => {
                self.instances.each(pass, |pass, asset| {
                    let triangles = asset.index_count / 3;
                    pass.set_pipeline(&p.fat);
                    pass.draw(0..18, 0..triangles);
                    pass.set_pipeline(&p.ridges);
                    pass.draw(0..18, 0..triangles);
                });
                // Instances past the triangle count are the valley quads.
                for ((_, offsets), &group) in self.instances.draws().zip(&self.valleys) {
                    let (asset, bind_group) = self.valley_groups.get(group);
                    let triangles = asset.index_count / 3;
                    pass.set_bind_group(0, bind_group, offsets);
                    pass.set_pipeline(&p.valleys);
                    pass.draw(0..18, triangles..2 * triangles);
                }
            }
        }
    }
}
