//! The cut faces and cut outlines of section planes (issue 43, `shaders/cut.wgsl`): where a plane
//! cuts a closed mesh, the cut is filled with a solid colour or a hatch, in screen or model space;
//! where it cuts any mesh, the cut's outline is drawn as a thick line.
//!
//! **Stencil capping**, not cut polygons: the parity of the surface crossings along each pixel's ray
//! decides what lies inside, so the caps follow moving planes and posed meshes with no CPU pass
//! and no per-frame geometry, and are exact to the pixel where the mesh is closed. It costs two
//! extra draws of the instance's mesh and one quad per plane that crosses the instance (instances a
//! plane misses skip it), and needs a stencil aspect in the target (one bit; on a target without
//! one only the outlines are drawn, and the Bevy crate fills the caps in its material). The cut polygons
//! would need the cut segments chained and triangulated every frame. **Open meshes** (any boundary
//! edge) get no cap: their parity means nothing, so a cut shows into them, their
//! back faces lit as the mesh pass lights both sides (what the section drawings do too); they keep
//! their outline.
//!
//! **Outlines** are found in the vertex shader, one instanced draw per plane and instance over the
//! mesh's triangles: a triangle the plane crosses emits the capsule of its segment (the vertices of
//! the others fall outside the view), so the outline follows the plane each frame with no list, no
//! counter and no capacity to outgrow. The capsules' round ends join neighbouring segments at any
//! angle (as baked intersection lines join), so the segments are not chained.

use std::sync::Arc;

use super::bindings::{Binding, Bindings, Kind};
use super::gpu_asset::VERTEX_LAYOUTS;
use super::layout::CutFrame;
use super::modules::{Program, Shader};
use super::pipelines::{PipelineSet, Raster};
use super::techniques::Blocks;
use super::{Camera, Instance, Pipelines, RenderError};
use crate::section::{ClipPlanes, CutSettings};

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

/// How cut outlines look.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutOutline {
    /// Straight-alpha RGBA.
    pub color: [f32; 4],
    /// Line width in pixels.
    pub width_px: f32,
}

impl Default for CutOutline {
    fn default() -> Self {
        Self {
            color: [0.05, 0.05, 0.05, 1.0],
            width_px: 2.5,
        }
    }
}

/// What [`CutRenderer::prepare`] draws: the section (world space, as the mesh's and the edges'
/// styles give it), the caps' look (an [`Instance`] may have its own of either) and the outline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutStyle {
    /// The section planes in world space.
    pub section: ClipPlanes,
    /// The cut faces' look.
    pub cap: CapStyle,
    /// The cut outline; `None`: not drawn.
    pub outline: Option<CutOutline>,
    /// Fill the cut faces of closed meshes.
    pub caps: bool,
}

impl Default for CutStyle {
    fn default() -> Self {
        Self {
            section: ClipPlanes::NONE,
            cap: CapStyle::default(),
            outline: Some(CutOutline::default()),
            caps: true,
        }
    }
}

impl CutStyle {
    /// The style `settings` describe, cutting with `section` (world space).
    pub fn from_settings(section: ClipPlanes, settings: &CutSettings) -> Self {
        let [cap, hatch, outline] = settings.colors();
        let hatch = (settings.cap_hatch_spacing > 0.0).then_some(CapHatch {
            color: hatch,
            spacing: settings.cap_hatch_spacing,
            angle_deg: settings.cap_hatch_angle,
            width_px: settings.cap_hatch_width,
            in_model: settings.cap_hatch_in_model,
        });
        Self {
            section,
            cap: CapStyle { color: cap, hatch },
            outline: (settings.cut_outline_width > 0.0).then_some(CutOutline {
                color: outline,
                width_px: settings.cut_outline_width,
            }),
            caps: !settings.no_caps,
        }
    }
}

const CUT_BLOCK: Binding = Binding::new(0, "cut", Kind::Block);
const CUT: Bindings = Bindings::draw("cut faces", &[CUT_BLOCK]);
const OUTLINE: Bindings = Bindings::draw(
    "cut outlines",
    &[
        CUT_BLOCK,
        super::bindings::asset::RENDER_POSITIONS,
        super::bindings::asset::MESH_INDICES,
    ],
);

/// Section.wgsl for a host outside the runtime (the Bevy crate's section material): the section
/// tests and the cap fill, after the `SECTION_PLANES` constant. The host defines
/// `view_section(k)`, plane k in the space of the points it tests.
pub fn section_wgsl() -> String {
    format!(
        "const SECTION_PLANES: u32 = {}u;\n{}",
        crate::section::MAX_PLANES,
        chamfer_shaders::SECTION
    )
}

/// The cut faces' module.
pub(crate) fn shader() -> Shader {
    Shader::new(
        "cut.wgsl",
        &[chamfer_shaders::SECTION, chamfer_shaders::CUT],
        vec![
            Program::draw("parity_vertex", "parity_fragment", &CUT),
            Program::draw("cap_face_vertex", "cap_face_fragment", &CUT),
            Program::draw("outline_vertex", "outline_fragment", &OUTLINE),
        ],
    )
}

/// The stencil bit the parity draws flip.
const PARITY_BIT: u32 = 1;

/// The parity and cap pipelines, per device and target.
#[derive(Debug)]
pub(crate) struct CutPipelines {
    /// The parity draw and the cap quad: only on targets with a stencil aspect.
    caps: Option<CapPipelines>,
    outline: wgpu::RenderPipeline,
}

#[derive(Debug)]
struct CapPipelines {
    parity: wgpu::RenderPipeline,
    cap: wgpu::RenderPipeline,
}

impl PipelineSet for CutPipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let target = cache.target();
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        let outline = compiled.render(
            "outline_vertex",
            Some("outline_fragment"),
            Raster::over_mesh(target),
        )?;
        if !target.has_stencil() {
            return Ok(Self {
                caps: None,
                outline,
            });
        }
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
        Ok(Self {
            caps: Some(CapPipelines { parity, cap }),
            outline,
        })
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
    /// Per asset drawn, the outline pass's group over its mesh (and the blocks).
    outline_groups: Vec<(Arc<()>, wgpu::BindGroup)>,
    /// Per plane that crosses an instance: its block, the instance's asset, and whether it is capped.
    draws: Vec<(u32, super::GpuAsset, bool)>,
    outlined: bool,
}

impl CutRenderer {
    /// A cut-face pass for `pipelines`' target. Cut faces need a stencil aspect in its depth
    /// format: without one (Bevy's cameras have none) only the outlines are drawn, and
    /// [`CutRenderer::fills_caps`] is false.
    pub fn new(pipelines: &Pipelines) -> Result<Self, RenderError> {
        Ok(Self {
            pipelines: pipelines.get::<CutPipelines>()?,
            cache: pipelines.clone(),
            blocks: Blocks::new(pipelines, "cut faces", std::mem::size_of::<CutFrame>()),
            group: None,
            outline_groups: Vec::new(),
            draws: Vec::new(),
            outlined: false,
        })
    }

    /// True if this pass fills cut faces: its target has a stencil aspect.
    pub fn fills_caps(&self) -> bool {
        self.pipelines.caps.is_some()
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
        let mut draws = Vec::new();
        for instance in instances {
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
                let target = self.cache.target();
                frames.push(cut_frame(
                    &camera,
                    instance,
                    &section,
                    &cap,
                    style,
                    target,
                    plane as u32,
                ));
                draws.push((
                    instance.asset.clone(),
                    style.caps && instance.asset.is_closed(),
                ));
            }
        }
        if self.blocks.write(&self.cache, queue, &frames) {
            self.group = None;
            self.outline_groups.clear();
        }
        self.outlined = style.outline.is_some();
        if self.outlined {
            for (asset, _) in &draws {
                if self
                    .outline_groups
                    .iter()
                    .any(|(key, _)| Arc::ptr_eq(key, &asset.key))
                {
                    continue;
                }
                let layout = self.cache.layout(&OUTLINE);
                let blocks = &self.blocks;
                let group = OUTLINE.group(self.cache.device(), &layout, |binding| {
                    Ok(match binding.index {
                        0 => blocks.binding(),
                        7 => asset.render_positions.as_entire_binding(),
                        _ => asset.mesh_indices.as_entire_binding(),
                    })
                });
                // A group of a block and two of the asset's buffers cannot fail to be made.
                if let Ok(group) = group {
                    self.outline_groups.push((asset.key.clone(), group));
                }
            }
        }
        if self.group.is_none() {
            let layout = self.cache.layout(&CUT);
            let blocks = &self.blocks;
            // A group of one block cannot fail to be made.
            self.group = CUT
                .group(self.cache.device(), &layout, |_| Ok(blocks.binding()))
                .ok();
        }
        self.draws = draws
            .into_iter()
            .enumerate()
            .map(|(i, (asset, capped))| (self.blocks.offset(i), asset, capped))
            .collect();
    }

    /// Fills the cut faces into `pass` (whose depth attachment's stencil aspect, if the target has
    /// one, is cleared to 0 or left at 0 by earlier cut passes) and draws the outlines.
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(group) = &self.group else {
            return;
        };
        let caps = self.pipelines.caps.as_ref();
        if caps.is_some() {
            pass.set_stencil_reference(0);
        }
        for (offset, asset, capped) in &self.draws {
            if let (true, Some(caps)) = (*capped, caps) {
                pass.set_bind_group(0, group, &[*offset]);
                pass.set_vertex_buffer(0, asset.render_positions.slice(..));
                pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
                pass.set_pipeline(&caps.parity);
                pass.draw_indexed(0..asset.index_count, 0, 0..1);
                pass.set_pipeline(&caps.cap);
                pass.draw(0..6, 0..1);
                // Flips the bits back: the next plane or instance starts from zero.
                pass.set_pipeline(&caps.parity);
                pass.draw_indexed(0..asset.index_count, 0, 0..1);
            }
            let outline = self
                .outline_groups
                .iter()
                .find(|(key, _)| Arc::ptr_eq(key, &asset.key));
            if let (true, Some((_, outline))) = (self.outlined, outline) {
                pass.set_pipeline(&self.pipelines.outline);
                pass.set_bind_group(0, outline, &[*offset]);
                pass.draw(0..6, 0..asset.index_count / 3);
            }
        }
    }
}

/// The cut uniform of plane `plane` of `instance` (camera already in its model space).
fn cut_frame(
    camera: &Camera,
    instance: &Instance<'_>,
    section: &ClipPlanes,
    cap: &CapStyle,
    style: &CutStyle,
    target: &super::Target,
    plane: u32,
) -> CutFrame {
    let outline = style.outline.unwrap_or_default();
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
        indices_u16: u32::from(instance.asset.index_format == wgpu::IndexFormat::Uint16),
        reverse_z: u32::from(target.reverse_z),
        outline: outline.color,
        screen: [
            camera.viewport[0].max(1) as f32,
            camera.viewport[1].max(1) as f32,
            camera.pixel_scale(),
            0.5 * outline.width_px.clamp(0.0, 1000.0),
        ],
        proj_z: camera.projection.z_axis.to_array(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schema::{Numbers, Schema};

    /// Each entry's example is valid and changes the style made from the settings (with a hatch
    /// in the base, so its angle, width and colour count); wrong values are refused by name.
    #[test]
    fn every_cut_setting_reaches_the_style_and_bad_values_are_refused() {
        let base = CutSettings {
            cap_hatch_spacing: 4.0,
            ..CutSettings::default()
        };
        let style = |s: &CutSettings| CutStyle::from_settings(ClipPlanes::NONE, s);
        assert_eq!(base.check(), Ok(()));
        for entry in CutSettings::ENTRIES {
            let mut settings = base;
            entry.set_example(&mut settings);
            assert_eq!(settings.check(), Ok(()), "{}", entry.name);
            assert_ne!(style(&settings), style(&base), "{}", entry.name);
        }
        assert!(
            CutStyle::from_settings(ClipPlanes::NONE, &CutSettings::default())
                .cap
                .hatch
                .is_none()
        );
        let two = CutSettings {
            cap_color: Numbers::from_array([0.5, 0.5]),
            ..CutSettings::default()
        };
        assert!(
            two.check()
                .expect_err("two numbers")
                .to_string()
                .contains("cap_color")
        );
        let negative = CutSettings {
            cut_outline_width: -1.0,
            ..CutSettings::default()
        };
        assert!(negative.check().is_err());
    }
}
