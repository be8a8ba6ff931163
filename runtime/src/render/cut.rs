//! The cut faces of section planes (issue 43, `shaders/cut.wgsl`): where a plane cuts a closed mesh,
//! the cut is filled with a solid colour or a hatch, in screen or model space.
//!
//! **Stencil capping**, not cut polygons: the parity of the surface crossings along each pixel's ray
//! decides what lies inside, so the caps follow moving planes and posed meshes with no CPU pass
//! and no per-frame geometry, and are exact to the pixel where the mesh is closed. It costs two
//! extra draws of the instance's mesh and one quad per plane that crosses the instance (instances a
//! plane misses skip it), and needs a stencil aspect in the target (one bit). The cut polygons
//! would need the cut segments chained and triangulated every frame. **Open meshes** (any boundary
//! or non-manifold edge) get no cap: their parity means nothing, so a cut shows into them, their
//! back faces lit as the mesh pass lights both sides (what the section drawings do too).

use std::sync::Arc;

use super::bindings::{Binding, Bindings, Kind};
use super::gpu_asset::VERTEX_LAYOUTS;
use super::layout::CutFrame;
use super::modules::{Program, Shader};
use super::pipelines::{PipelineSet, Raster};
use super::techniques::Blocks;
use super::{Camera, Instance, Pipelines, RenderError};
use crate::section::ClipPlanes;

/// A hatch over a cut face: parallel lines.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapHatch {
    /// Straight-alpha RGBA.
    pub color: [f32; 4],
    /// From one line to the next: pixels, or model units when `in_model`.
    pub spacing: f32,
    /// Counter-clockwise from the screen's x axis, or from the plane's first axis in model space.
    pub angle_deg: f32,
    /// Line width in pixels.
    pub width_px: f32,
    /// Lines fixed to the model (they move with it) instead of the screen.
    pub in_model: bool,
}

/// How cut faces look.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapStyle {
    /// The fill, straight-alpha RGBA.
    pub color: [f32; 4],
    /// Lines over the fill; `None`: solid.
    pub hatch: Option<CapHatch>,
}

impl Default for CapStyle {
    fn default() -> Self {
        Self {
            color: [0.55, 0.2, 0.2, 1.0],
            hatch: None,
        }
    }
}

/// What [`CutRenderer::prepare`] draws: the section (world space, as the mesh's and the edges'
/// styles give it) and the caps' look; an [`Instance`] may have its own of either.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CutStyle {
    /// The section planes in world space.
    pub section: ClipPlanes,
    /// The cut faces' look.
    pub cap: CapStyle,
}

const CUT: Bindings = Bindings::draw("cut faces", &[Binding::new(0, "cut", Kind::Block)]);

/// The cut faces' module.
pub(crate) fn shader() -> Shader {
    Shader::new(
        "cut.wgsl",
        &[chamfer_shaders::CUT],
        vec![
            Program::draw("parity_vertex", "parity_fragment", &CUT),
            Program::draw("cap_face_vertex", "cap_face_fragment", &CUT),
        ],
    )
}

/// The stencil bit the parity draws flip.
const PARITY_BIT: u32 = 1;

/// The parity and cap pipelines, per device and target.
#[derive(Debug)]
pub(crate) struct CutPipelines {
    parity: wgpu::RenderPipeline,
    cap: wgpu::RenderPipeline,
}

impl PipelineSet for CutPipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let target = cache.target();
        if !target.has_stencil() {
            return Err(RenderError::TargetLacks {
                technique: "cut faces",
                needs: "a depth format with a stencil aspect",
            });
        }
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        let flip = wgpu::StencilFaceState {
            compare: wgpu::CompareFunction::Always,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Invert,
            pass_op: wgpu::StencilOperation::Invert,
        };
        let parity = compiled.render(
            "parity_vertex",
            Some("parity_fragment"),
            Raster {
                buffers: &VERTEX_LAYOUTS[..1],
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: target.depth_with_stencil(
                    false,
                    wgpu::CompareFunction::Always,
                    wgpu::StencilState {
                        front: flip,
                        back: flip,
                        read_mask: PARITY_BIT,
                        write_mask: PARITY_BIT,
                    },
                ),
                multisample: target.multisample(),
                color: Some(wgpu::ColorTargetState {
                    write_mask: wgpu::ColorWrites::empty(),
                    ..target.color(None)
                }),
            },
        )?;
        let inside = wgpu::StencilFaceState {
            compare: wgpu::CompareFunction::NotEqual,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op: wgpu::StencilOperation::Keep,
        };
        let cap = compiled.render(
            "cap_face_vertex",
            Some("cap_face_fragment"),
            Raster {
                buffers: &[],
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: target.depth_with_stencil(
                    true,
                    wgpu::CompareFunction::Less,
                    wgpu::StencilState {
                        front: inside,
                        back: inside,
                        read_mask: PARITY_BIT,
                        write_mask: 0,
                    },
                ),
                multisample: target.multisample(),
                color: Some(target.blended_color()),
            },
        )?;
        Ok(Self { parity, cap })
    }
}

/// Fills the cut faces of a frame's instances: draw it after the mesh pass (it tests and writes
/// depth, so the edges drawn after it are hidden behind the caps) and before the edges.
#[derive(Debug)]
pub struct CutRenderer {
    pipelines: Arc<CutPipelines>,
    cache: Pipelines,
    blocks: Blocks,
    group: Option<wgpu::BindGroup>,
    /// Per plane that crosses a closed instance: its block and the instance's asset.
    draws: Vec<(u32, super::GpuAsset)>,
}

impl CutRenderer {
    /// A cut-face pass for `pipelines`' target, which must have a stencil aspect.
    pub fn new(pipelines: &Pipelines) -> Result<Self, RenderError> {
        Ok(Self {
            pipelines: pipelines.get::<CutPipelines>()?,
            cache: pipelines.clone(),
            blocks: Blocks::new(pipelines, "cut faces", std::mem::size_of::<CutFrame>()),
            group: None,
            draws: Vec::new(),
        })
    }

    /// Sets this frame's camera, instances and style.
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        camera: &Camera,
        instances: &[Instance<'_>],
        style: &CutStyle,
    ) {
        let mut frames = Vec::new();
        let mut assets = Vec::new();
        for instance in instances.iter().filter(|i| i.asset.is_closed()) {
            let section = instance.model_section(&style.section);
            let [lo, hi] = instance.asset.bounds();
            let (gone, crossing) = section.against_box(lo, hi);
            if gone || crossing == 0 {
                continue;
            }
            let camera = Camera {
                model_view: camera.model_view * instance.transform,
                ..*camera
            };
            let cap = instance.cap.unwrap_or(style.cap);
            for plane in (0..section.planes().len()).filter(|k| crossing & (1 << k) != 0) {
                frames.push(cut_frame(&camera, instance, &section, &cap, plane as u32));
                assets.push(instance.asset.clone());
            }
        }
        if self.blocks.write(&self.cache, queue, &frames) {
            self.group = None;
        }
        if self.group.is_none() {
            let layout = self.cache.layout(&CUT);
            let blocks = &self.blocks;
            // A group of one block cannot fail to be made.
            self.group = CUT
                .group(self.cache.device(), &layout, |_| Ok(blocks.binding()))
                .ok();
        }
        self.draws = assets
            .into_iter()
            .enumerate()
            .map(|(i, asset)| (self.blocks.offset(i), asset))
            .collect();
    }

    /// Fills the cut faces into `pass` (whose depth attachment has the stencil aspect, cleared to 0
    /// or left at 0 by earlier cut passes).
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(group) = &self.group else {
            return;
        };
        pass.set_stencil_reference(0);
        for (offset, asset) in &self.draws {
            pass.set_bind_group(0, group, &[*offset]);
            pass.set_vertex_buffer(0, asset.render_positions.slice(..));
            pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
            pass.set_pipeline(&self.pipelines.parity);
            pass.draw_indexed(0..asset.index_count, 0, 0..1);
            pass.set_pipeline(&self.pipelines.cap);
            pass.draw(0..6, 0..1);
            // Flips the bits back: the next plane or instance starts from zero.
            pass.set_pipeline(&self.pipelines.parity);
            pass.draw_indexed(0..asset.index_count, 0, 0..1);
        }
    }
}

/// The cut uniform of plane `plane` of `instance` (camera already in its model space).
fn cut_frame(
    camera: &Camera,
    instance: &Instance<'_>,
    section: &ClipPlanes,
    cap: &CapStyle,
    plane: u32,
) -> CutFrame {
    let [lo, hi] = instance.asset.bounds().map(glam::Vec3::from);
    let centre = (lo + hi) * 0.5;
    let (hatch, hatch_color, in_model) = match cap.hatch {
        Some(h) => (
            [
                h.spacing.max(0.0),
                h.angle_deg.to_radians(),
                h.width_px.max(0.0),
                0.0,
            ],
            h.color,
            u32::from(h.in_model),
        ),
        None => ([0.0; 4], cap.color, 0),
    };
    CutFrame {
        mvp: camera.view_projection().to_cols_array_2d(),
        section: section.rows(),
        // A little wider than the box, so the quad's edge never falls inside it.
        bounds: centre
            .extend((hi - lo).length() * 0.5 * 1.01 + 1e-6)
            .to_array(),
        color: cap.color,
        hatch_color,
        hatch,
        plane,
        hatch_in_model: in_model,
        _pad0: 0,
        _pad1: 0,
    }
}
