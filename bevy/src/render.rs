//! Drawing the edges in Bevy's 3D pass: every entity with [`ChamferEdges`] whose Bevy visibility
//! says it is seen is extracted with its `GlobalTransform`; each 3D camera then draws them through
//! one `SceneRenderer` of its own after Bevy's opaque and transparent passes, into the camera's own
//! colour and depth (its MSAA sample count, its HDR or LDR format, Bevy's reverse-Z depth), so
//! edges are hidden by everything the camera drew, Chamfer asset or not.

use std::collections::HashMap;
use std::sync::Arc;

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
    Camera as EdgeCamera, EdgeStyle, FrameViews, GpuAsset, Instance, Pipelines, SceneRenderer,
    Target,
};

use crate::asset::ChamferAsset;

/// Draws an entity's baked edges in every 3D camera, placed by its `GlobalTransform`. Hidden
/// entities (Bevy's `Visibility`) draw nothing.
#[derive(Component, Clone, Debug)]
#[require(Transform, Visibility)]
pub struct ChamferEdges {
    /// The baked asset.
    pub asset: Handle<ChamferAsset>,
    /// How its edges are drawn (technique, classes, width, colours, highlight).
    pub style: EdgeStyle,
}

impl ChamferEdges {
    /// The asset's edges in the default style (the joined technique, every class, 2 px).
    pub fn new(asset: Handle<ChamferAsset>) -> Self {
        Self {
            asset,
            style: EdgeStyle::default(),
        }
    }
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
        .add_systems(ExtractSchedule, extract)
        .add_systems(Render, upload.in_set(RenderSystems::PrepareResources))
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
}

/// This frame's visible entities, and the decoded assets they draw.
#[derive(Resource, Default)]
struct Extracted {
    drawn: Vec<Drawn>,
    assets: HashMap<AssetId<ChamferAsset>, Arc<EdgeAsset>>,
}

fn extract(
    mut extracted: ResMut<Extracted>,
    entities: Extract<Query<(&ChamferEdges, &GlobalTransform, &ViewVisibility)>>,
    assets: Extract<Res<Assets<ChamferAsset>>>,
) {
    extracted.drawn.clear();
    for (edges, transform, visibility) in &entities {
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
        });
    }
}

/// The assets on the GPU, with the extras their techniques needed so far.
#[derive(Resource, Default)]
struct Uploaded {
    assets: HashMap<AssetId<ChamferAsset>, GpuAsset>,
}

fn upload(extracted: Res<Extracted>, mut uploaded: ResMut<Uploaded>, device: Res<RenderDevice>) {
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
}

/// A camera's renderer: pipelines for its target, a scene renderer per style drawn.
struct ViewRenderer {
    target: Target,
    pipelines: Pipelines,
    scenes: Vec<SceneRenderer>,
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
    mut renderers: Local<HashMap<RetainedViewEntity, ViewRenderer>>,
    mut ctx: RenderContext,
) {
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
    let renderer = match renderers.get_mut(&view.retained_view_entity) {
        Some(r) if r.target == formats => r,
        _ => match Pipelines::new(&device, &formats) {
            Ok(pipelines) => renderers
                .entry(view.retained_view_entity)
                .insert_entry(ViewRenderer {
                    target: formats,
                    pipelines,
                    scenes: Vec::new(),
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
    // One draw per distinct style, in the order styles first appear.
    let mut styles: Vec<&EdgeStyle> = Vec::new();
    for drawn in &extracted.drawn {
        if !styles.contains(&&drawn.style) {
            styles.push(&drawn.style);
        }
    }
    while renderer.scenes.len() < styles.len() {
        renderer
            .scenes
            .push(SceneRenderer::new(&renderer.pipelines));
    }
    let encoder = ctx.command_encoder();
    for (style, scene) in styles.iter().zip(&mut renderer.scenes) {
        let instances: Vec<Instance<'_>> = extracted
            .drawn
            .iter()
            .filter(|d| &&d.style == style)
            .filter_map(|d| {
                let gpu = uploaded.assets.get(&d.asset)?;
                Some(Instance::new(gpu).with_transform(d.transform))
            })
            .collect();
        if instances.is_empty() {
            continue;
        }
        let prepared = match scene.prepare(&queue, encoder, &edge_camera, &instances, style) {
            Ok(prepared) => prepared,
            Err(e) => {
                error!("chamfer: cannot draw the edges: {e}");
                continue;
            }
        };
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("chamfer edges"),
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

/// Bevy's glam (0.33) to the runtime's (0.34): the same column-major floats.
fn to_glam(m: Mat4) -> glam::Mat4 {
    glam::Mat4::from_cols_array(&m.to_cols_array())
}
