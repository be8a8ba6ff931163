//! Drawing the edges in Bevy's 3D pass: every entity with [`ChamferEdges`] whose Bevy visibility
//! says it is seen is extracted with its `GlobalTransform`; each 3D camera then draws them through
//! one `SceneRenderer` of its own after Bevy's opaque and transparent passes, into the camera's own
//! colour and depth (its MSAA sample count, its HDR or LDR format, Bevy's reverse-Z depth), so
//! edges are hidden by everything the camera drew, Chamfer asset or not.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;

use bevy::platform::time::Instant;

use bevy::core_pipeline::Core3dSystems;
use bevy::core_pipeline::schedule::Core3d;
use bevy::prelude::*;
use bevy::render::camera::ExtractedCamera;
use bevy::render::renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery};
use bevy::render::view::{
    ExtractedView, Msaa, RetainedViewEntity, ViewDepthStencilTexture, ViewTarget,
};
use bevy::render::{Extract, ExtractSchedule, Render, RenderApp, RenderSystems};
use chamfer_runtime::asset::Asset as EdgeAsset;
use chamfer_runtime::render::{
    Camera as EdgeCamera, CutRenderer, CutStyle, DisplaySettings, EdgeStyle, FrameViews, GpuAsset,
    Instance, Light, Pipelines, SceneRenderer, Shading, Target,
};
use chamfer_runtime::schema::SchemaError;
use chamfer_runtime::section::ClipPlanes;

use crate::asset::ChamferAsset;
use crate::section::ChamferSection;

/// Draws an entity's baked edges in every 3D camera, placed by its `GlobalTransform`. Hidden
/// entities (Bevy's `Visibility`) draw nothing.
#[derive(Component, Clone, Debug)]
#[require(Transform, Visibility)]
pub struct ChamferEdges {
    /// The baked asset.
    pub asset: Handle<ChamferAsset>,
    /// How its edges are drawn (technique, classes, width, colours, highlight).
    pub style: EdgeStyle,
    /// Light the chamfer highlight (when the style has one) with the visible `DirectionalLight`,
    /// `PointLight` or `SpotLight` that lights the entity's origin most, as Bevy lights its meshes:
    /// the light's linear colour × its illuminance (lux; a point or spot light's lumens / 4π, the
    /// candela Bevy's shaders use, falling off as 1/d²) × the camera's exposure is the highlight's
    /// colour under PBR shading, and that over π under the seed's Blinn shading (whose diffuse
    /// term has no 1/π; its point and spot lights do not fall off, so they take their strength at
    /// the entity's origin). Default true; with false, or with no light, the style's own light is
    /// used (in the entity's model space).
    pub scene_light: bool,
}

impl ChamferEdges {
    /// The asset's edges in the default style (the joined technique, every class, 2 px).
    pub fn new(asset: Handle<ChamferAsset>) -> Self {
        Self {
            asset,
            style: EdgeStyle::default(),
            scene_light: true,
        }
    }

    /// These edges in `style`.
    pub fn with_style(self, style: EdgeStyle) -> Self {
        Self { style, ..self }
    }

    /// These edges with the hidden edges' style and the distance fade of `display` (the display
    /// schema, `chamfer render`'s `--hidden-*` and `--fade-*` flags): the hidden part of each edge,
    /// behind anything in Bevy's depth, drawn in its own style. Refused as `chamfer render`
    /// refuses it (a technique without hidden edges, a hidden line wider than the edges). The
    /// face modes are the entity's material's: Bevy draws its faces.
    pub fn with_display(mut self, display: &DisplaySettings) -> Result<Self, SchemaError> {
        display.check_for(&self.style.technique, self.style.width_px)?;
        self.style.display = display.display();
        Ok(self)
    }
}

/// The CPU time the plugin took in the last frame, in the render world
/// (`app.sub_app(RenderApp).world().resource::<ChamferTimings>()`): what it adds to a frame
/// besides the GPU's work.
#[derive(Resource, Clone, Copy, Debug, Default)]
pub struct ChamferTimings {
    /// Copying the visible entities, the scene's light and changed assets out of the main world.
    pub extract: Duration,
    /// Uploading assets (first use, or a technique needing more of them) and forgetting stale ones.
    pub prepare: Duration,
    /// Recording every camera's edge passes (culling, uniforms, compute and draw commands).
    pub draw: Duration,
}

/// Registers the extraction and the per-camera draw.
pub(crate) fn build(app: &mut App) {
    app.add_systems(PostUpdate, let_edges_read_depth);
    let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
        return;
    };
    render_app
        .init_resource::<Extracted>()
        .init_resource::<Uploaded>()
        .init_resource::<ViewRenderers>()
        .init_resource::<ChamferTimings>()
        .add_systems(ExtractSchedule, extract)
        .add_systems(
            Render,
            (upload, forget_views).in_set(RenderSystems::PrepareResources),
        )
        .add_systems(
            Core3d,
            draw.after(Core3dSystems::MainPass)
                .before(Core3dSystems::EarlyPostProcess),
        );
}

/// The post-process techniques read the camera's depth: every 3D camera's depth texture can be
/// bound.
fn let_edges_read_depth(mut cameras: Query<&mut Camera3d, Added<Camera3d>>) {
    for mut camera in &mut cameras {
        let usages =
            bevy::render::render_resource::TextureUsages::from(camera.depth_texture_usages)
                | bevy::render::render_resource::TextureUsages::TEXTURE_BINDING;
        camera.depth_texture_usages = usages.into();
    }
}

/// One visible entity's edges, in the render world.
struct Drawn {
    asset: AssetId<ChamferAsset>,
    transform: glam::Mat4,
    style: EdgeStyle,
    scene_light: bool,
    /// Its section, if it has one (planes in world space).
    cut: Option<CutStyle>,
}

/// A visible light of the scene, in world space.
#[derive(Clone, Copy, Debug)]
struct SceneLight {
    /// Which and where: towards a directional light, a point light's position, a spot's position,
    /// direction and cone (degrees).
    light: Light,
    /// Linear colour × strength: illuminance (lux) for a directional light, luminous intensity
    /// (candela: lumens / 4π, as Bevy's shaders take it) for a point or spot light.
    strength: glam::Vec3,
}

impl SceneLight {
    /// Linear colour × illuminance (lux) at `point`: a point or spot light's falls off as 1/d²
    /// (Bevy's range cut-off aside), a spot's also over its cone as KHR_lights_punctual's.
    fn illuminance_at(&self, point: glam::Vec3) -> glam::Vec3 {
        let falloff = |position: [f32; 3]| {
            1.0 / glam::Vec3::from(position)
                .distance_squared(point)
                .max(1e-12)
        };
        match self.light {
            Light::Directional(_) => self.strength,
            Light::Point(position) => self.strength * falloff(position),
            Light::Spot {
                position,
                direction,
                inner_deg,
                outer_deg,
            } => {
                let to_point = (point - glam::Vec3::from(position)).normalize_or_zero();
                let (cos_inner, cos_outer) =
                    (inner_deg.to_radians().cos(), outer_deg.to_radians().cos());
                let cone = ((to_point.dot(glam::Vec3::from(direction)) - cos_outer)
                    / (cos_inner - cos_outer).max(1e-4))
                .clamp(0.0, 1.0);
                self.strength * falloff(position) * cone * cone
            }
        }
    }
}

/// This frame's visible entities, the decoded assets they draw and the scene's light.
#[derive(Resource, Default)]
struct Extracted {
    drawn: Vec<Drawn>,
    assets: HashMap<AssetId<ChamferAsset>, Arc<EdgeAsset>>,
    /// Assets changed (re-baked, reloaded) or no longer used since the last frame: their uploads
    /// go.
    stale: Vec<AssetId<ChamferAsset>>,
    lights: Vec<SceneLight>,
}

fn extract(
    mut extracted: ResMut<Extracted>,
    entities: Extract<
        Query<(
            &ChamferEdges,
            &GlobalTransform,
            &ViewVisibility,
            Option<&ChamferSection>,
        )>,
    >,
    suns: Extract<Query<(&DirectionalLight, &GlobalTransform, &InheritedVisibility)>>,
    points: Extract<Query<(&PointLight, &GlobalTransform, &InheritedVisibility)>>,
    spots: Extract<Query<(&SpotLight, &GlobalTransform, &InheritedVisibility)>>,
    assets: Extract<Res<Assets<ChamferAsset>>>,
    mut events: Extract<MessageReader<AssetEvent<ChamferAsset>>>,
    mut timings: ResMut<ChamferTimings>,
) {
    let start = Instant::now();
    for event in events.read() {
        if let AssetEvent::Modified { id }
        | AssetEvent::Unused { id }
        | AssetEvent::Removed { id } = *event
        {
            extracted.assets.remove(&id);
            extracted.stale.push(id);
        }
    }
    let linear = |color: Color| glam::Vec3::from_array(color.to_linear().to_f32_array_no_alpha());
    let at =
        |transform: &GlobalTransform| glam::Vec3::from_array(transform.translation().to_array());
    let forward =
        |transform: &GlobalTransform| glam::Vec3::from_array(transform.forward().to_array());
    let candela = 1.0 / (4.0 * std::f32::consts::PI);
    extracted.lights.clear();
    let suns = suns.iter().filter(|(_, _, visible)| visible.get());
    extracted
        .lights
        .extend(suns.map(|(light, transform, _)| SceneLight {
            light: Light::Directional((-forward(transform)).to_array()),
            strength: linear(light.color) * light.illuminance,
        }));
    let points = points.iter().filter(|(_, _, visible)| visible.get());
    extracted
        .lights
        .extend(points.map(|(light, transform, _)| SceneLight {
            light: Light::Point(at(transform).to_array()),
            strength: linear(light.color) * light.intensity * candela,
        }));
    let spots = spots.iter().filter(|(_, _, visible)| visible.get());
    extracted
        .lights
        .extend(spots.map(|(light, transform, _)| SceneLight {
            light: Light::Spot {
                position: at(transform).to_array(),
                direction: forward(transform).to_array(),
                inner_deg: light.inner_angle.to_degrees(),
                outer_deg: light.outer_angle.to_degrees(),
            },
            strength: linear(light.color) * light.intensity * candela,
        }));
    extracted.drawn.clear();
    for (edges, transform, visibility, section) in &entities {
        if !visibility.get() {
            continue;
        }
        let Some(asset) = assets.get(&edges.asset) else {
            continue; // still loading
        };
        let id = edges.asset.id();
        extracted
            .assets
            .entry(id)
            .or_insert_with(|| Arc::clone(&asset.asset));
        extracted.drawn.push(Drawn {
            asset: id,
            transform: to_glam(transform.to_matrix()),
            style: edges.style,
            scene_light: edges.scene_light,
            cut: section.map(|s| s.cut),
        });
    }
    *timings = ChamferTimings {
        extract: start.elapsed(),
        ..ChamferTimings::default()
    };
}

/// The assets on the GPU, with the extras their techniques needed so far.
#[derive(Resource, Default)]
struct Uploaded {
    assets: HashMap<AssetId<ChamferAsset>, GpuAsset>,
}

fn upload(
    mut extracted: ResMut<Extracted>,
    mut uploaded: ResMut<Uploaded>,
    device: Res<RenderDevice>,
    mut timings: ResMut<ChamferTimings>,
) {
    let start = Instant::now();
    for id in std::mem::take(&mut extracted.stale) {
        uploaded.assets.remove(&id);
    }
    for drawn in &extracted.drawn {
        let needs = drawn.style.technique.needs();
        let current = uploaded.assets.get(&drawn.asset).map(GpuAsset::extras);
        if current.is_some_and(|extras| extras.contains(needs)) {
            continue;
        }
        let Some(asset) = extracted.assets.get(&drawn.asset) else {
            continue;
        };
        let extras = current.map_or(needs, |extras| extras | needs);
        match GpuAsset::with_extras(device.wgpu_device(), asset, extras) {
            Ok(gpu) => {
                uploaded.assets.insert(drawn.asset, gpu);
            }
            Err(e) => error!("chamfer: {}: cannot upload: {e}", asset.header.source),
        }
    }
    timings.prepare = start.elapsed();
}

/// Adds the time from its making to its drop to a total (a system with several ways out).
struct Timed<'a>(&'a mut Duration, Instant);

impl<'a> Timed<'a> {
    fn start(total: &'a mut Duration) -> Self {
        Self(total, Instant::now())
    }
}

impl Drop for Timed<'_> {
    fn drop(&mut self) {
        *self.0 += self.1.elapsed();
    }
}

/// Each camera's renderer, by the camera's lasting identity.
#[derive(Resource, Default)]
struct ViewRenderers(HashMap<RetainedViewEntity, ViewRenderer>);

/// Drops the renderers of cameras that are gone.
fn forget_views(mut renderers: ResMut<ViewRenderers>, views: Query<&ExtractedView>) {
    if renderers.0.is_empty() {
        return;
    }
    let live: Vec<RetainedViewEntity> = views.iter().map(|v| v.retained_view_entity).collect();
    renderers.0.retain(|view, _| live.contains(view));
}

/// A camera's renderer: pipelines for its target, a scene renderer per style drawn, a cut
/// renderer per outline style of the sectioned entities.
struct ViewRenderer {
    target: Target,
    pipelines: Pipelines,
    scenes: Vec<SceneRenderer>,
    cuts: Vec<CutRenderer>,
}

fn draw(
    view: ViewQuery<(
        &ExtractedCamera,
        &ExtractedView,
        &ViewTarget,
        &ViewDepthStencilTexture,
        &Msaa,
    )>,
    extracted: Res<Extracted>,
    uploaded: Res<Uploaded>,
    queue: Res<RenderQueue>,
    mut renderers: ResMut<ViewRenderers>,
    mut timings: ResMut<ChamferTimings>,
    mut ctx: RenderContext,
) {
    let _timed = Timed::start(&mut timings.draw);
    if extracted.drawn.is_empty() {
        return;
    }
    let (camera, view, target, depth, msaa) = view.into_inner();
    let formats = Target::new(
        view.target_format,
        Some(bevy::core_pipeline::core_3d::CORE_3D_DEPTH_FORMAT),
        msaa.samples(),
    )
    .with_reverse_z(true);
    let device = ctx.render_device().wgpu_device().clone();
    let renderer = match renderers.0.get_mut(&view.retained_view_entity) {
        Some(r) if r.target == formats => r,
        _ => match Pipelines::new(&device, &formats) {
            Ok(pipelines) => renderers
                .0
                .entry(view.retained_view_entity)
                .insert_entry(ViewRenderer {
                    target: formats,
                    pipelines,
                    scenes: Vec::new(),
                    cuts: Vec::new(),
                })
                .into_mut(),
            Err(e) => {
                error!("chamfer: cannot build the pipelines for a camera: {e}");
                return;
            }
        },
    };
    let size = view.viewport.zw();
    let edge_camera = EdgeCamera {
        model_view: to_glam(view.world_from_view.to_matrix().inverse()),
        projection: to_glam(view.clip_from_view),
        viewport: [size.x.max(1), size.y.max(1)],
    };
    // One draw per distinct style, in the order styles first appear; the scene's light reaches each
    // entity in its own model space.
    let mut groups: Vec<(EdgeStyle, Vec<Instance<'_>>)> = Vec::new();
    let mut cut_groups: Vec<(CutStyle, Vec<Instance<'_>>)> = Vec::new();
    for drawn in &extracted.drawn {
        let Some(gpu) = uploaded.assets.get(&drawn.asset) else {
            continue;
        };
        let (style, light) = match brightest_at(&extracted.lights, drawn.transform) {
            Some(light) if drawn.scene_light => {
                lit_by(drawn.style, light, drawn.transform, camera.exposure)
            }
            _ => (drawn.style, None),
        };
        let mut instance = Instance::new(gpu).with_transform(drawn.transform);
        if let Some(light) = light {
            instance = instance.with_light(light);
        }
        if let Some(cut) = drawn.cut {
            instance = instance.with_section(cut.section).with_cap(cut.cap);
            // Grouped by the rest of the style: the planes and caps go with each instance.
            let rest = CutStyle {
                section: ClipPlanes::NONE,
                cap: Default::default(),
                ..cut
            };
            match cut_groups.iter_mut().find(|(s, _)| *s == rest) {
                Some((_, instances)) => instances.push(instance),
                None => cut_groups.push((rest, vec![instance])),
            }
        }
        match groups.iter_mut().find(|(s, _)| *s == style) {
            Some((_, instances)) => instances.push(instance),
            None => groups.push((style, vec![instance])),
        }
    }
    let encoder = ctx.command_encoder();
    draw_cuts(
        renderer,
        &queue,
        encoder,
        &edge_camera,
        &cut_groups,
        camera,
        target,
        depth,
    );
    // Scene renderers are kept by position, so a style changed at run time keeps its state.
    renderer.scenes.truncate(groups.len());
    while renderer.scenes.len() < groups.len() {
        renderer
            .scenes
            .push(SceneRenderer::new(&renderer.pipelines));
    }
    for ((style, instances), scene) in groups.iter().zip(&mut renderer.scenes) {
        let prepared = match scene.prepare(&queue, encoder, &edge_camera, instances, style) {
            Ok(prepared) => prepared,
            Err(e) => {
                error!("chamfer: cannot draw the edges: {e}");
                continue;
            }
        };
        {
            let mut pass = camera_pass(encoder, "chamfer edges", camera, target, depth);
            prepared.render(&mut pass);
        }
        let views = FrameViews {
            color: target.main_texture_view(),
            depth: &depth.attachment.texture.default_view,
        };
        if let Err(e) = prepared.finish(encoder, &views) {
            error!("chamfer: cannot finish the edges: {e}");
        }
    }
}

/// The cut outlines of the sectioned entities, before the edges (which they hide where they
/// cross). Bevy's depth has no stencil aspect: the caps are the section material's.
#[allow(clippy::too_many_arguments)]
fn draw_cuts(
    renderer: &mut ViewRenderer,
    queue: &RenderQueue,
    encoder: &mut wgpu::CommandEncoder,
    edge_camera: &EdgeCamera,
    groups: &[(CutStyle, Vec<Instance<'_>>)],
    camera: &ExtractedCamera,
    target: &ViewTarget,
    depth: &ViewDepthStencilTexture,
) {
    let outlined: Vec<_> = groups.iter().filter(|(s, _)| s.outline.is_some()).collect();
    renderer.cuts.truncate(outlined.len());
    while renderer.cuts.len() < outlined.len() {
        match CutRenderer::new(&renderer.pipelines) {
            Ok(cut) => renderer.cuts.push(cut),
            Err(e) => {
                error!("chamfer: cannot build the cut outline pass: {e}");
                return;
            }
        }
    }
    for ((style, instances), cut) in outlined.into_iter().zip(&mut renderer.cuts) {
        cut.prepare(queue, edge_camera, instances, style);
        let mut pass = camera_pass(encoder, "chamfer cut outlines", camera, target, depth);
        cut.render(&mut pass);
    }
}

/// A pass into the camera's colour and depth (kept), on its viewport if it has one.
fn camera_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    camera: &ExtractedCamera,
    target: &ViewTarget,
    depth: &ViewDepthStencilTexture,
) -> wgpu::RenderPass<'e> {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(target.get_color_attachment())],
        depth_stencil_attachment: Some(depth.get_attachment(wgpu::StoreOp::Store)),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    if let Some(viewport) = camera.viewport.as_ref() {
        let [x, y] = viewport.physical_position.to_array().map(|v| v as f32);
        let [w, h] = viewport.physical_size.to_array().map(|v| v as f32);
        pass.set_viewport(x, y, w, h, 0.0, 1.0);
    }
    pass
}

/// Of `lights`, the one that lights the origin of an entity placed by `transform` most (by the sum
/// of its colour channels).
fn brightest_at(lights: &[SceneLight], transform: glam::Mat4) -> Option<SceneLight> {
    let origin = transform.w_axis.truncate();
    let strength = |light: &SceneLight| light.illuminance_at(origin).element_sum();
    lights
        .iter()
        .max_by(|a, b| strength(a).total_cmp(&strength(b)))
        .copied()
}

/// `style` with its highlight (if any) lit by `light` as Bevy lights a `StandardMaterial` seen by
/// a camera of this `exposure`, and the light as an entity placed by `transform` sees it (in its
/// model space, where the runtime's lights live): the style is the same for every entity lit alike,
/// so differently turned entities are still drawn together.
fn lit_by(
    style: EdgeStyle,
    light: SceneLight,
    transform: glam::Mat4,
    exposure: f32,
) -> (EdgeStyle, Option<Light>) {
    let Some(mut highlight) = style.highlight else {
        return (style, None);
    };
    let model = transform.inverse();
    let direction = |d: [f32; 3]| {
        let d = glam::Vec3::from(d);
        model.transform_vector3(d).normalize_or(d).to_array()
    };
    let point = |p: [f32; 3]| model.transform_point3(glam::Vec3::from(p)).to_array();
    let seen = match light.light {
        Light::Directional(towards) => Light::Directional(direction(towards)),
        Light::Point(position) => Light::Point(point(position)),
        Light::Spot {
            position,
            direction: along,
            inner_deg,
            outer_deg,
        } => Light::Spot {
            position: point(position),
            direction: direction(along),
            inner_deg,
            outer_deg,
        },
    };
    let color = match (highlight.shading, light.light) {
        (Shading::Pbr(_), Light::Directional(_)) => light.strength * exposure,
        // The runtime's 1/d² is in model units: a scaled entity's are not the world's.
        (Shading::Pbr(_), _) => {
            let scale = transform.determinant().abs().cbrt().max(1e-12);
            light.strength * exposure / (scale * scale)
        }
        (Shading::Blinn(_), _) => {
            light.illuminance_at(transform.w_axis.truncate()) * exposure / std::f32::consts::PI
        }
    };
    highlight.light = light.light;
    highlight.color = color.to_array();
    let style = EdgeStyle {
        highlight: Some(highlight),
        ..style
    };
    (style, Some(seen))
}

/// Bevy's glam (0.33) to the runtime's (0.34): the same column-major floats.
fn to_glam(m: Mat4) -> glam::Mat4 {
    glam::Mat4::from_cols_array(&m.to_cols_array())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn highlight(shading: Shading) -> EdgeStyle {
        EdgeStyle {
            highlight: Some(chamfer_runtime::render::Highlight {
                shading,
                ..Default::default()
            }),
            ..EdgeStyle::default()
        }
    }

    #[test]
    fn the_sun_is_mapped_as_bevy_lights_a_standard_material() {
        let sun = SceneLight {
            light: Light::Directional([1.0, 0.0, 0.0]),
            strength: glam::Vec3::new(10_000.0, 5_000.0, 0.0),
        };
        // An entity turned 90° about +Y: its model +Z is world +X, where the light comes from.
        let turned = glam::Mat4::from_rotation_y(std::f32::consts::FRAC_PI_2);
        let exposure = 1e-3;
        let (pbr, seen) = lit_by(
            highlight(Shading::Pbr(Default::default())),
            sun,
            turned,
            exposure,
        );
        let lit = pbr.highlight.expect("highlight");
        assert_eq!(
            lit.light,
            Light::Directional([1.0, 0.0, 0.0]),
            "the style's: world"
        );
        let Some(Light::Directional(towards)) = seen else {
            panic!("directional");
        };
        assert!(
            glam::Vec3::from(towards).abs_diff_eq(glam::Vec3::Z, 1e-6),
            "{towards:?}"
        );
        assert_eq!(lit.color, [10.0, 5.0, 0.0]);
        let blinn = lit_by(
            EdgeStyle {
                highlight: Some(Default::default()), // Blinn
                ..EdgeStyle::default()
            },
            sun,
            turned,
            exposure,
        );
        let color = blinn.0.highlight.expect("highlight").color;
        assert!(
            (color[0] - 10.0 / std::f32::consts::PI).abs() < 1e-5,
            "{color:?}"
        );
        let plain = EdgeStyle::default();
        assert_eq!(lit_by(plain, sun, turned, exposure), (plain, None));
    }

    #[test]
    fn a_point_light_is_placed_in_model_space_and_falls_off_with_the_worlds_distance() {
        let bulb = SceneLight {
            light: Light::Point([0.0, 0.0, 4.0]),
            strength: glam::Vec3::splat(1000.0),
        };
        // Moved 2 along +X and scaled 2: the bulb is at (-1, 0, 2) in model units, 4.47 world
        // units from the entity's origin.
        let placed = glam::Mat4::from_scale_rotation_translation(
            glam::Vec3::splat(2.0),
            glam::Quat::IDENTITY,
            glam::Vec3::new(2.0, 0.0, 0.0),
        );
        let (pbr, seen) = lit_by(
            highlight(Shading::Pbr(Default::default())),
            bulb,
            placed,
            1.0,
        );
        let Some(Light::Point(position)) = seen else {
            panic!("point: {seen:?}");
        };
        assert!(glam::Vec3::from(position).abs_diff_eq(glam::Vec3::new(-1.0, 0.0, 2.0), 1e-5));
        // PBR: the runtime's 1/d² over model units, d_model = d_world / 2, so the colour is a
        // quarter of the candela for the same illuminance.
        let color = pbr.highlight.expect("highlight").color;
        assert!((color[0] - 250.0).abs() < 1e-2, "{color:?}");
        // Blinn has no falloff: the illuminance at the origin, over π.
        let (blinn, _) = lit_by(
            highlight(chamfer_runtime::render::Highlight::default().shading),
            bulb,
            placed,
            1.0,
        );
        let color = blinn.highlight.expect("highlight").color;
        let expected = 1000.0 / 20.0 / std::f32::consts::PI;
        assert!(
            (color[0] - expected).abs() < 1e-3,
            "{color:?} vs {expected}"
        );
    }

    #[test]
    fn a_spot_light_keeps_its_cone_and_lights_only_inside_it() {
        let spot = SceneLight {
            light: Light::Spot {
                position: [0.0, 5.0, 0.0],
                direction: [0.0, -1.0, 0.0],
                inner_deg: 10.0,
                outer_deg: 20.0,
            },
            strength: glam::Vec3::splat(500.0),
        };
        let turned = glam::Mat4::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let (style, seen) = lit_by(
            highlight(Shading::Pbr(Default::default())),
            spot,
            turned,
            1.0,
        );
        let Some(Light::Spot {
            position,
            direction,
            inner_deg,
            outer_deg,
        }) = seen
        else {
            panic!("spot: {seen:?}");
        };
        // World +Y is the turned entity's model +X.
        assert!(glam::Vec3::from(position).abs_diff_eq(glam::Vec3::new(5.0, 0.0, 0.0), 1e-5));
        assert!(glam::Vec3::from(direction).abs_diff_eq(glam::Vec3::new(-1.0, 0.0, 0.0), 1e-5));
        assert_eq!((inner_deg, outer_deg), (10.0, 20.0));
        assert_eq!(style.highlight.expect("highlight").color, [500.0; 3]);
        // Under the spot it lights 500 / 25 lux; beside it (45° off its axis) nothing.
        assert!((spot.illuminance_at(glam::Vec3::ZERO).x - 20.0).abs() < 1e-3);
        assert_eq!(spot.illuminance_at(glam::Vec3::new(5.0, 0.0, 0.0)).x, 0.0);
    }

    #[test]
    fn the_light_that_lights_an_entity_most_is_chosen() {
        let sun = SceneLight {
            light: Light::Directional([0.0, 1.0, 0.0]),
            strength: glam::Vec3::splat(100.0),
        };
        let bulb = SceneLight {
            light: Light::Point([0.0, 1.0, 0.0]),
            strength: glam::Vec3::splat(1000.0),
        };
        let lights = [sun, bulb];
        let near = glam::Mat4::IDENTITY; // 1,000 lux from the bulb
        let far = glam::Mat4::from_translation(glam::Vec3::new(0.0, 1.0, 10.0)); // 10 lux
        let chosen = |transform| brightest_at(&lights, transform).map(|l| l.light);
        assert_eq!(chosen(near), Some(bulb.light));
        assert_eq!(chosen(far), Some(sun.light));
        assert_eq!(brightest_at(&[], near).map(|l| l.light), None);
    }
}
