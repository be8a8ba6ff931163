//! Section planes in Bevy (issue 43): [`ChamferSection`] on an entity cuts it open. Its Chamfer
//! edges are clipped and its cut outline drawn by the runtime (`render.rs`); its mesh is clipped by
//! a [`SectionMaterial`], a `StandardMaterial` with the same look that discards what the planes cut
//! away and fills the cut faces of a closed mesh (`material.wesl`). The plugin swaps the entity's
//! `MeshMaterial3d<StandardMaterial>` for it while the section is there, keeps its uniform in step
//! with the section and the entity's transform, and gives the material back when the section goes.
//!
//! Bevy's depth has no stencil aspect, so the caps cannot be the runtime's stencil caps: the
//! material draws the back faces seen through the cut as the cap (at their own depth). For a closed
//! mesh and a viewer outside it both are the same pixels. Open meshes (an asset with a boundary
//! edge) get no cap, as in the runtime. Left for later: the depth prepass and shadow maps see the
//! whole mesh (a cut model's shadow is whole), and the deferred path is not clipped.

use bevy::asset::uuid_handle;
use bevy::pbr::{ExtendedMaterial, MaterialExtension, MaterialPlugin};
use bevy::prelude::*;
use bevy::render::RenderApp;
use bevy::render::render_resource::{AsBindGroup, ShaderType};
use bevy::shader::ShaderRef;
use chamfer_runtime::render::{CapStyle, CutStyle};
use chamfer_runtime::schema::SchemaError;
use chamfer_runtime::section::{ClipPlanes, CutSettings, MAX_PLANES, Section};

use crate::{ChamferAsset, ChamferEdges};

/// Cuts an entity by section planes: its [`ChamferEdges`] are clipped and the cut's outline drawn,
/// its mesh (with a `MeshMaterial3d<StandardMaterial>`) is clipped and the cut faces of a closed
/// mesh are filled, solid or hatched, on the screen or on the model. Remove it and the entity is
/// whole again, with its own material.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct ChamferSection {
    /// The planes, in world space (`cut.section`), and how the cut looks: the caps (only the
    /// entity's mesh material fills them) and the outline (drawn along the edges' asset).
    pub cut: CutStyle,
}

impl ChamferSection {
    /// A cut by `planes` (world space) in the default look: capped, outlined.
    pub fn new(planes: ClipPlanes) -> Self {
        Self {
            cut: CutStyle {
                section: planes,
                ..CutStyle::default()
            },
        }
    }

    /// The section and cut look of the shared schema (`chamfer render --section ... --cap-color
    /// ...`, Python's and the page's section settings), in world space.
    pub fn from_settings(section: &Section, settings: &CutSettings) -> Result<Self, SchemaError> {
        settings.check()?;
        let planes = ClipPlanes::from_section(section)?;
        Ok(Self {
            cut: CutStyle::from_settings(planes, settings),
        })
    }
}

/// A `StandardMaterial` cut by a section: what [`ChamferSection`] swaps in.
pub type SectionMaterial = ExtendedMaterial<StandardMaterial, SectionExtension>;

/// The section part of [`SectionMaterial`].
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone, Default)]
pub struct SectionExtension {
    /// The planes and the cap's look.
    #[uniform(100)]
    pub section: SectionUniform,
}

/// `material.wesl`'s `SectionUniform`.
#[derive(Clone, Copy, Debug, Default, PartialEq, ShaderType, Reflect)]
pub struct SectionUniform {
    /// The planes in the entity's model space (`ClipPlanes::rows`).
    pub planes: [Vec4; MAX_PLANES],
    /// World to the entity's model space.
    pub model_from_world: Mat4,
    /// The cap's fill, straight-alpha linear RGBA.
    pub cap_color: Vec4,
    /// The hatch lines' colour.
    pub hatch_color: Vec4,
    /// Hatch spacing (0: solid), angle (radians), line width (pixels), 1 if on the model.
    pub hatch: Vec4,
    /// x: 1 if the cut faces are filled.
    pub capped: Vec4,
}

impl SectionUniform {
    /// The uniform of `section` on an entity placed by `world_from_model`; `closed`: its mesh
    /// has no boundary edge.
    pub fn new(section: &ChamferSection, world_from_model: Mat4, closed: bool) -> Self {
        let model = section.cut.section.to_model(glam::Mat4::from_cols_array(
            &world_from_model.to_cols_array(),
        ));
        let CapStyle { color, hatch } = section.cut.cap;
        let (hatch, hatch_color) = match hatch {
            Some(h) => (
                Vec4::new(
                    h.spacing.max(0.0),
                    h.angle_deg.to_radians(),
                    h.width_px.max(0.0),
                    f32::from(u8::from(h.in_model)),
                ),
                h.color,
            ),
            None => (Vec4::ZERO, color),
        };
        Self {
            planes: model.rows().map(Vec4::from_array),
            model_from_world: world_from_model.inverse(),
            cap_color: Vec4::from_array(color),
            hatch_color: Vec4::from_array(hatch_color),
            hatch,
            capped: Vec4::new(
                f32::from(u8::from(section.cut.caps && closed)),
                0.0,
                0.0,
                0.0,
            ),
        }
    }
}

const SHADER: Handle<Shader> = uuid_handle!("5a0c8e0e-43a1-4d1b-9a43-c0ffee5ec710");

impl MaterialExtension for SectionExtension {
    fn fragment_shader() -> ShaderRef {
        SHADER.into()
    }
}

/// The material a sectioned entity had, given back when its section goes, and what its uniform
/// was last made from.
#[derive(Component, Debug)]
struct Sectioned {
    base: Handle<StandardMaterial>,
    /// Whether its edges' asset is closed, once it has loaded (an entity without
    /// [`ChamferEdges`] counts as closed).
    closed: Option<bool>,
}

/// Registers the material and the systems that keep sectioned entities' materials.
pub(crate) fn build(app: &mut App) {
    if app.get_sub_app(RenderApp).is_none() {
        return; // no renderer (the asset processor alone): nothing to draw
    }
    let source = format!(
        "{}\n{}",
        include_str!("material.wesl"),
        chamfer_runtime::render::section_wgsl()
    );
    let shader = Shader::from_wesl(source, "embedded://chamfer_bevy/section.wesl");
    if let Some(mut shaders) = app.world_mut().get_resource_mut::<Assets<Shader>>()
        && let Err(e) = shaders.insert(&SHADER, shader)
    {
        error!("chamfer: cannot add the section shader: {e}");
    }
    app.add_plugins(MaterialPlugin::<SectionMaterial>::default())
        .add_systems(
            PostUpdate,
            (give_materials_back, swap_materials, update_materials)
                .chain()
                .after(TransformSystems::Propagate),
        );
}

/// A sectioned entity's `StandardMaterial` becomes a [`SectionMaterial`] with the same look,
/// both sides drawn (the back faces seen through the cut are the caps).
fn swap_materials(
    mut commands: Commands,
    added: Query<
        (Entity, &MeshMaterial3d<StandardMaterial>),
        (With<ChamferSection>, Without<Sectioned>),
    >,
    standard: Res<Assets<StandardMaterial>>,
    mut sectioned: ResMut<Assets<SectionMaterial>>,
) {
    for (entity, material) in &added {
        let Some(base) = standard.get(&material.0) else {
            continue; // still loading
        };
        let cut = sectioned.add(SectionMaterial {
            base: double_sided(base),
            extension: SectionExtension::default(),
        });
        commands
            .entity(entity)
            .remove::<MeshMaterial3d<StandardMaterial>>()
            .insert((
                MeshMaterial3d(cut),
                Sectioned {
                    base: material.0.clone(),
                    closed: None,
                },
            ));
    }
}

fn double_sided(base: &StandardMaterial) -> StandardMaterial {
    StandardMaterial {
        double_sided: true,
        cull_mode: None,
        ..base.clone()
    }
}

/// Writes a sectioned entity's uniform when its section, its place, its mesh's closedness (once
/// the asset loads) or its own material changed.
fn update_materials(
    mut entities: Query<(
        Ref<ChamferSection>,
        Ref<GlobalTransform>,
        &mut Sectioned,
        &MeshMaterial3d<SectionMaterial>,
        Option<&ChamferEdges>,
    )>,
    assets: Res<Assets<ChamferAsset>>,
    standard: Res<Assets<StandardMaterial>>,
    mut base_events: MessageReader<AssetEvent<StandardMaterial>>,
    mut materials: ResMut<Assets<SectionMaterial>>,
) {
    let modified: Vec<AssetId<StandardMaterial>> = base_events
        .read()
        .filter_map(|event| match *event {
            AssetEvent::Modified { id } => Some(id),
            _ => None,
        })
        .collect();
    for (section, transform, mut state, material, edges) in &mut entities {
        // One pass over the asset's edges, once.
        let closed_now = state.closed.is_none() && {
            state.closed = match edges {
                Some(edges) => assets.get(&edges.asset).map(|a| a.asset.is_closed()),
                None => Some(true),
            };
            state.closed.is_some()
        };
        let base_changed = modified.contains(&state.base.id());
        if !(section.is_changed() || transform.is_changed() || closed_now || base_changed) {
            continue;
        }
        let Some(mut cut) = materials.get_mut(&material.0) else {
            continue;
        };
        if base_changed && let Some(base) = standard.get(&state.base) {
            cut.base = double_sided(base);
        }
        cut.extension.section = SectionUniform::new(
            &section,
            transform.to_matrix(),
            state.closed.unwrap_or(false),
        );
    }
}

/// An entity whose section went waits one frame without a material, then gets its own back: Bevy
/// 0.20 keeps drawing an entity with the pipeline of the material type it had when that type is
/// swapped for another within one frame (a validation error that stops the renderer).
#[derive(Component, Debug)]
struct GivingBack(Handle<StandardMaterial>);

/// An entity whose section went gets its own material back (the frame after).
fn give_materials_back(
    mut commands: Commands,
    mut removed: RemovedComponents<ChamferSection>,
    sectioned: Query<&Sectioned>,
    giving_back: Query<(Entity, &GivingBack)>,
) {
    for (entity, base) in &giving_back {
        commands
            .entity(entity)
            .remove::<GivingBack>()
            .insert(MeshMaterial3d(base.0.clone()));
    }
    for entity in removed.read() {
        let Ok(state) = sectioned.get(entity) else {
            continue;
        };
        commands
            .entity(entity)
            .remove::<(MeshMaterial3d<SectionMaterial>, Sectioned)>()
            .insert(GivingBack(state.base.clone()));
    }
}
