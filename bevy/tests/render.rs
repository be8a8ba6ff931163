//! The plugin in a headless Bevy app on lavapipe: a camera renders into an `Image` that is read
//! back; edge pixels are where a frame with the edges differs from the same frame without them.

use std::path::Path;
use std::sync::{Arc, Mutex};

use bevy::asset::AssetPlugin;
use bevy::camera::RenderTarget;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::render_resource::{TextureFormat, TextureUsages};
use bevy::render::view::{Msaa, Tonemapping};
use bevy::window::{ExitCondition, WindowPlugin};
use chamfer_bevy::{ChamferAsset, ChamferEdges, ChamferPlugin};
use chamfer_preprocess::{BakeOptions, bake_file};
use chamfer_runtime::render::{
    Camera as EdgeCamera, EdgeStyle, GpuAsset, Instance, MeshRenderer, MeshStyle, Offscreen, Orbit,
    Pipelines, SceneRenderer,
};
use chamfer_tests::fixture;

const SIZE: [u32; 2] = [320, 240];

/// A folder of assets: `name.chamfer` baked from each fixture.
fn assets(meshes: &[(&str, &str)]) -> tempfile::TempDir {
    assets_baked_with(meshes, &BakeOptions::DEFAULT)
}

/// [`assets`] baked with chamfer radii (ridges get `radius_rel` of the diagonal), so the
/// highlight has strips to shade.
fn rounded_assets(meshes: &[(&str, &str)], radius_rel: f32) -> tempfile::TempDir {
    let options =
        BakeOptions::DEFAULT.with_radius(chamfer_preprocess::Radius::Relative(radius_rel));
    assets_baked_with(meshes, &options)
}

fn assets_baked_with(meshes: &[(&str, &str)], options: &BakeOptions) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    for (name, mesh) in meshes {
        let baked = bake_file(&fixture(mesh), options).expect("bake");
        std::fs::write(
            dir.path().join(format!("{name}.chamfer")),
            baked.asset.encode_to_vec(),
        )
        .expect("write");
    }
    dir
}

/// A headless app with the plugin, its assets read from `folder`.
fn app(folder: &Path) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(AssetPlugin {
                file_path: folder.to_string_lossy().into_owned(),
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            })
            // One global logger per test process: the tests make many apps.
            .disable::<bevy::log::LogPlugin>(),
    )
    .add_plugins(ChamferPlugin);
    app.finish();
    app.cleanup();
    app
}

/// The orbit camera `chamfer render` frames `bounds` with, as a Bevy camera's transform and
/// projection (the same view and field of view; Bevy's depth is reverse-Z and infinite).
fn orbit_camera(
    bounds: [[f32; 3]; 2],
    azimuth: f32,
    elevation: f32,
) -> (Transform, Projection, EdgeCamera) {
    let orbit = Orbit {
        azimuth,
        elevation,
        ..Orbit::default()
    };
    let camera = EdgeCamera::orbit(bounds, &orbit, SIZE);
    let eye = camera.model_view.inverse().w_axis.truncate();
    let [lo, hi] = bounds.map(glam::Vec3::from);
    let center = (lo + hi) * 0.5;
    let transform = Transform::from_translation(Vec3::from_array(eye.to_array()))
        .looking_at(Vec3::from_array(center.to_array()), Vec3::Y);
    let projection = Projection::Perspective(PerspectiveProjection {
        fov: orbit.fov_y.to_radians(),
        near: 0.01,
        ..default()
    });
    (transform, projection, camera)
}

/// Renders frames until the image has been read back after the asset loaded; returns RGBA8 rows
/// (an HDR target's half floats clamped to 0..1 and sRGB-encoded; alpha too, unused).
fn render(app: &mut App, image: &Handle<Image>) -> Vec<u8> {
    let hdr = {
        let images = app.world().resource::<Assets<Image>>();
        images.get(image).map(|i| i.texture_descriptor.format) == Some(TextureFormat::Rgba16Float)
    };
    let raw = render_raw(app, image, if hdr { 8 } else { 4 });
    if !hdr {
        return raw;
    }
    // Linear values, encoded as a display would show them (sRGB), so dark faces stay apart from
    // black edges as in the LDR frames.
    raw.chunks(2)
        .map(|h| {
            let linear = half::f16::from_le_bytes([h[0], h[1]])
                .to_f32()
                .clamp(0.0, 1.0);
            let encoded = if linear <= 0.003_130_8 {
                12.92 * linear
            } else {
                1.055 * linear.powf(1.0 / 2.4) - 0.055
            };
            (encoded * 255.0).round() as u8
        })
        .collect()
}

fn render_raw(app: &mut App, image: &Handle<Image>, bytes_per_pixel: usize) -> Vec<u8> {
    let received: Arc<Mutex<Option<Vec<u8>>>> = Arc::default();
    for _ in 0..300 {
        app.update();
        let loaded = {
            let world = app.world();
            !world.resource::<Assets<ChamferAsset>>().is_empty()
        };
        if loaded {
            break;
        }
    }
    // A few frames so the joined technique's lists settle, then one read back.
    for _ in 0..4 {
        app.update();
    }
    let sink = Arc::clone(&received);
    app.world_mut()
        .spawn(Readback::texture(image.clone()))
        .observe(move |event: On<ReadbackComplete>| {
            if let Ok(mut slot) = sink.lock() {
                slot.get_or_insert_with(|| event.data.clone());
            }
        });
    for _ in 0..20 {
        app.update();
        if let Some(bytes) = received.lock().ok().and_then(|r| r.clone()) {
            return unpad(&bytes, bytes_per_pixel);
        }
    }
    panic!("no readback");
}

/// Rows padded to 256 bytes, as the readback gives them, to tight rows.
fn unpad(bytes: &[u8], bytes_per_pixel: usize) -> Vec<u8> {
    let row = bytes_per_pixel * SIZE[0] as usize;
    let padded = row.next_multiple_of(256);
    (0..SIZE[1] as usize)
        .flat_map(|y| bytes[y * padded..y * padded + row].iter().copied())
        .collect()
}

fn differing(a: &[u8], b: &[u8]) -> Vec<bool> {
    a.chunks(4)
        .zip(b.chunks(4))
        .map(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 40))
        .collect()
}

/// Share of `from`'s pixels with a pixel of `to` within one pixel.
fn covered(from: &[bool], to: &[bool]) -> f64 {
    let [w, h] = SIZE.map(|v| v as i64);
    let (mut hits, mut total) = (0u64, 0u64);
    for y in 0..h {
        for x in 0..w {
            if !from[(y * w + x) as usize] {
                continue;
            }
            total += 1;
            let near = (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (u, v) = (x + dx, y + dy);
                    u >= 0 && v >= 0 && u < w && v < h && to[(v * w + u) as usize]
                })
            });
            hits += u64::from(near);
        }
    }
    if total == 0 {
        0.0
    } else {
        hits as f64 / total as f64
    }
}

/// `chamfer render`'s picture (mesh + edges, and mesh alone) of `mesh` from `camera`, as the
/// command draws it (the runtime's renderers on an offscreen target, 4× MSAA).
fn reference(mesh: &str, camera: &EdgeCamera) -> Vec<bool> {
    reference_at(mesh, camera, glam::Mat4::IDENTITY)
}

/// [`reference`] with the mesh moved by `transform`.
fn reference_at(mesh: &str, camera: &EdgeCamera, transform: glam::Mat4) -> Vec<bool> {
    let baked = bake_file(&fixture(mesh), &BakeOptions::DEFAULT).expect("bake");
    let gpu = Offscreen::new().expect("a wgpu adapter (lavapipe)");
    let target = gpu.target(SIZE[0], SIZE[1], 4).expect("target");
    let pipelines = Pipelines::new(&gpu.device, &target.formats()).expect("pipelines");
    let asset = GpuAsset::new(&gpu.device, &baked.asset).expect("upload");
    let drawn = [Instance::new(&asset).with_transform(transform)];
    let mut pictures = Vec::new();
    for with_edges in [true, false] {
        let mut mesh = MeshRenderer::for_scenes(&pipelines).expect("mesh");
        mesh.prepare_scene(&gpu.queue, camera, &drawn, &MeshStyle::default());
        let mut edges = SceneRenderer::new(&pipelines);
        let mut encoder = gpu.encoder();
        let prepared = with_edges.then(|| {
            edges
                .prepare(
                    &gpu.queue,
                    &mut encoder,
                    camera,
                    &drawn,
                    &EdgeStyle::default(),
                )
                .expect("prepare")
        });
        {
            let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
            mesh.render(&mut pass);
            if let Some(p) = &prepared {
                p.render(&mut pass);
            }
        }
        if let Some(p) = &prepared {
            p.finish(&mut encoder, &target.views()).expect("finish");
        }
        gpu.submit(encoder).expect("submit");
        pictures.push(target.read(&gpu).expect("read").rgba);
    }
    differing(&pictures[0], &pictures[1])
}

/// The scene: `name.chamfer` drawn by Bevy (its mesh, a light) with or without edges, from
/// `transform`; returns the edge pixels.
struct Scene {
    app: App,
    image: Handle<Image>,
    part: Entity,
}

impl Scene {
    fn new(
        folder: &Path,
        name: &str,
        camera: (Transform, Projection),
        msaa: Msaa,
        hdr: bool,
    ) -> Self {
        let mut app = app(folder);
        let world = app.world_mut();
        let format = if hdr {
            TextureFormat::Rgba16Float
        } else {
            TextureFormat::Rgba8UnormSrgb
        };
        let mut target = Image::new_target_texture(SIZE[0], SIZE[1], format, None);
        target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
        let image = world.resource_mut::<Assets<Image>>().add(target);
        let server = world.resource::<AssetServer>().clone();
        let part: Handle<ChamferAsset> = server.load(format!("{name}.chamfer"));
        let mesh: Handle<Mesh> = server.load(format!("{name}.chamfer#mesh"));
        let material = world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial::from(Color::srgb(0.8, 0.8, 0.78)));
        let part = world
            .spawn((
                Mesh3d(mesh),
                MeshMaterial3d(material),
                ChamferEdges::new(part),
            ))
            .id();
        world.spawn((
            DirectionalLight::default(),
            Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        let mut camera_entity = world.spawn((
            Camera3d::default(),
            RenderTarget::Image(image.clone().into()),
            Tonemapping::None,
            msaa,
            camera.0,
            camera.1,
        ));
        if hdr {
            camera_entity.insert(bevy::camera::Hdr);
        }
        Self { app, image, part }
    }

    /// The frame with the part's edges and without them.
    fn edge_pixels(&mut self) -> Vec<bool> {
        let with = render(&mut self.app, &self.image);
        let edges = self
            .app
            .world_mut()
            .entity_mut(self.part)
            .take::<ChamferEdges>()
            .expect("edges");
        let without = render(&mut self.app, &self.image);
        self.app.world_mut().entity_mut(self.part).insert(edges);
        differing(&with, &without)
    }
}

#[test]
fn the_cube_and_the_fandisk_are_drawn_where_chamfer_render_draws_them() {
    let folder = assets(&[
        ("cube", "shapes/cube.obj"),
        ("fandisk", "meshes/fandisk.obj"),
    ]);
    for (name, mesh) in [
        ("cube", "shapes/cube.obj"),
        ("fandisk", "meshes/fandisk.obj"),
    ] {
        let bounds = {
            let baked = bake_file(&fixture(mesh), &BakeOptions::DEFAULT).expect("bake");
            [baked.asset.header.bounds_min, baked.asset.header.bounds_max]
        };
        let (transform, projection, camera) = orbit_camera(bounds, -50.0, 30.0);
        let mut scene = Scene::new(
            folder.path(),
            name,
            (transform, projection),
            Msaa::Sample4,
            false,
        );
        let bevy = scene.edge_pixels();
        let cli = reference(mesh, &camera);
        let (_, _, control_camera) = orbit_camera(bounds, -35.0, 30.0);
        let control = reference(mesh, &control_camera);
        let (a, b) = (covered(&bevy, &cli), covered(&cli, &bevy));
        let (c, d) = (covered(&bevy, &control), covered(&control, &bevy));
        let count = bevy.iter().filter(|&&e| e).count();
        eprintln!(
            "{name}: {count} edge pixels; within 1 px {a:.4} / {b:.4}; control {c:.4} / {d:.4}"
        );
        assert!(count > 100, "{name}: {count} edge pixels");
        assert!(a >= 0.95 && b >= 0.95, "{name}: {a} / {b}");
        assert!(c.min(d) < 0.95, "{name}: the control passes: {c} / {d}");
    }
}

/// The cube's bounds and the test camera (`chamfer render --azimuth -50 --elevation 30`).
fn cube_view() -> ([[f32; 3]; 2], (Transform, Projection), EdgeCamera) {
    let baked = bake_file(&fixture("shapes/cube.obj"), &BakeOptions::DEFAULT).expect("bake");
    let bounds = [baked.asset.header.bounds_min, baked.asset.header.bounds_max];
    let (transform, projection, camera) = orbit_camera(bounds, -50.0, 30.0);
    (bounds, (transform, projection), camera)
}

fn overlaps(bevy: &[bool], reference: &[bool]) -> (f64, f64, usize) {
    (
        covered(bevy, reference),
        covered(reference, bevy),
        bevy.iter().filter(|&&e| e).count(),
    )
}

#[test]
fn single_sample_and_hdr_cameras_draw_the_same_edges() {
    let folder = assets(&[("cube", "shapes/cube.obj")]);
    let (_, view, camera) = cube_view();
    let cli = reference("shapes/cube.obj", &camera);
    for (msaa, hdr) in [(Msaa::Off, false), (Msaa::Sample4, true), (Msaa::Off, true)] {
        let mut scene = Scene::new(folder.path(), "cube", view.clone(), msaa, hdr);
        let (a, b, count) = overlaps(&scene.edge_pixels(), &cli);
        eprintln!("{msaa:?} hdr {hdr}: {count} edge pixels, within 1 px {a:.4} / {b:.4}");
        assert!(
            count > 100 && a >= 0.95 && b >= 0.95,
            "{msaa:?} hdr {hdr}: {a} / {b}"
        );
    }
}

#[test]
fn a_moved_entity_is_drawn_at_its_new_place() {
    let folder = assets(&[("cube", "shapes/cube.obj")]);
    let (_, view, camera) = cube_view();
    let mut scene = Scene::new(folder.path(), "cube", view, Msaa::Sample4, false);
    let before = scene.edge_pixels();
    let shift = Vec3::new(0.3, 0.1, -0.2);
    scene
        .app
        .world_mut()
        .entity_mut(scene.part)
        .insert(Transform::from_translation(shift));
    let after = scene.edge_pixels();
    let moved = reference_at(
        "shapes/cube.obj",
        &camera,
        glam::Mat4::from_translation(glam::Vec3::from_array(shift.to_array())),
    );
    let (a, b, count) = overlaps(&after, &moved);
    let (c, d, _) = overlaps(&after, &before);
    eprintln!(
        "moved: {count} edge pixels, within 1 px of the moved reference {a:.4} / {b:.4}, of the old place {c:.4} / {d:.4}"
    );
    assert!(a >= 0.95 && b >= 0.95, "{a} / {b}");
    assert!(c.min(d) < 0.9, "the edges did not move: {c} / {d}");
}

#[test]
fn a_changed_asset_is_uploaded_again() {
    let folder = assets(&[("cube", "shapes/cube.obj")]);
    let (_, view, _) = cube_view();
    let mut scene = Scene::new(folder.path(), "cube", view, Msaa::Sample4, false);
    let cube = scene.edge_pixels();
    let replace = |scene: &mut Scene, mesh: &str| {
        let baked = bake_file(&fixture(mesh), &BakeOptions::DEFAULT).expect("bake");
        let world = scene.app.world_mut();
        let handle = world
            .entity(scene.part)
            .get::<ChamferEdges>()
            .expect("edges")
            .asset
            .clone();
        // As a hot reload or a re-bake does: the asset changes in place.
        world
            .resource_mut::<Assets<ChamferAsset>>()
            .get_mut(&handle)
            .expect("loaded")
            .asset = Arc::new(baked.asset);
    };
    replace(&mut scene, "meshes/fandisk.obj");
    let fandisk = scene.edge_pixels();
    replace(&mut scene, "shapes/cube.obj");
    let cube_again = scene.edge_pixels();
    let changed = cube.iter().zip(&fandisk).filter(|(a, b)| a != b).count();
    let (a, b, count) = overlaps(&cube_again, &cube);
    eprintln!(
        "the fandisk's edges in place of the cube's: {changed} pixels changed; the cube again: {count} edge pixels, {a:.4} / {b:.4}"
    );
    assert!(changed > 200, "{changed}");
    assert!(a >= 0.99 && b >= 0.99, "{a} / {b}");
}

#[test]
fn a_hidden_entity_draws_no_edges() {
    let folder = assets(&[("cube", "shapes/cube.obj")]);
    let (_, view, _) = cube_view();
    let mut scene = Scene::new(folder.path(), "cube", view, Msaa::Sample4, false);
    let shown = scene.edge_pixels().iter().filter(|&&e| e).count();
    scene
        .app
        .world_mut()
        .entity_mut(scene.part)
        .insert(Visibility::Hidden);
    let hidden = scene.edge_pixels().iter().filter(|&&e| e).count();
    assert!(shown > 100, "{shown} edge pixels when shown");
    assert_eq!(hidden, 0, "a hidden entity drew {hidden} edge pixels");
}

/// A plain Bevy box (not a Chamfer asset) between the camera `view` and the part in `bounds`,
/// filling the view.
fn plain_box_in_front(scene: &mut Scene, bounds: [[f32; 3]; 2], view: &(Transform, Projection)) {
    let [lo, hi] = bounds.map(Vec3::from_array);
    let center = (lo + hi) * 0.5;
    let eye = view.0.translation;
    let between = center + (eye - center) * 0.6;
    let world = scene.app.world_mut();
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Cuboid::new(4.0, 4.0, 0.05));
    let material = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial::from(Color::srgb(0.2, 0.4, 0.8)));
    world.spawn((
        Mesh3d(mesh),
        MeshMaterial3d(material),
        Transform::from_translation(between).looking_at(eye, Vec3::Y),
    ));
}

#[test]
fn edges_behind_a_plain_bevy_cube_are_hidden() {
    let folder = assets(&[("cube", "shapes/cube.obj")]);
    let (bounds, view, _) = cube_view();
    let mut scene = Scene::new(folder.path(), "cube", view.clone(), Msaa::Sample4, false);
    let open = scene.edge_pixels().iter().filter(|&&e| e).count();
    plain_box_in_front(&mut scene, bounds, &view);
    let behind = scene.edge_pixels().iter().filter(|&&e| e).count();
    assert!(open > 100, "{open} edge pixels without the box");
    assert_eq!(behind, 0, "{behind} edge pixels show through the box");
}

/// Issue 42: with the display schema's hidden edges, the part's edges behind the plain Bevy box
/// (another entity, in Bevy's depth) are drawn in the hidden style: green, solid, where the control
/// without it draws none; a hidden line wider than the edges is refused.
#[test]
fn edges_behind_a_plain_bevy_cube_are_drawn_in_the_hidden_style() {
    use chamfer_bevy::DisplaySettings;
    use chamfer_runtime::schema::Numbers;
    let folder = assets(&[("cube", "shapes/cube.obj")]);
    let (bounds, view, _) = cube_view();
    let mut scene = Scene::new(folder.path(), "cube", view.clone(), Msaa::Sample4, false);
    plain_box_in_front(&mut scene, bounds, &view);
    let green_pixels = |frame: &[u8]| {
        frame
            .chunks(4)
            .filter(|p| p[1] > 150 && p[0] < 110 && p[2] < 110)
            .count()
    };
    let plain = render(&mut scene.app, &scene.image);
    let display = DisplaySettings {
        hidden_edges: true,
        hidden_color: Some(Numbers::from_array([0.0, 1.0, 0.0])),
        hidden_opacity: 1.0,
        hidden_width: 2.0,
        hidden_dash: Numbers::from_array([1.0, 0.0]),
        ..DisplaySettings::default()
    };
    let mut entity = scene.app.world_mut().entity_mut(scene.part);
    let edges = entity.take::<ChamferEdges>().expect("edges");
    let wider = DisplaySettings {
        hidden_width: 3.0,
        ..display
    };
    let refused = edges.clone().with_display(&wider).expect_err("wider");
    assert!(refused.to_string().contains("hidden_width"), "{refused}");
    entity.insert(edges.with_display(&display).expect("valid"));
    let hidden = render(&mut scene.app, &scene.image);
    keep(&hidden, "hidden-edges");
    assert_eq!(green_pixels(&plain), 0, "green without hidden edges");
    // The cube's three hidden edges and its nine visible ones, all behind the box: 12 edges of
    // about 60 px at 2 px.
    assert!(
        green_pixels(&hidden) > 400,
        "{} hidden edge pixels",
        green_pixels(&hidden)
    );
}

#[test]
fn two_cameras_both_draw_the_edges() {
    let folder = assets(&[("cube", "shapes/cube.obj")]);
    let (bounds, view, camera) = cube_view();
    let (other_transform, other_projection, other_camera) = orbit_camera(bounds, 40.0, 20.0);
    let mut scene = Scene::new(folder.path(), "cube", view, Msaa::Sample4, false);
    let world = scene.app.world_mut();
    let mut target =
        Image::new_target_texture(SIZE[0], SIZE[1], TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let second = world.resource_mut::<Assets<Image>>().add(target);
    world.spawn((
        Camera3d::default(),
        Camera {
            order: 1,
            ..default()
        },
        RenderTarget::Image(second.clone().into()),
        Tonemapping::None,
        other_transform,
        other_projection,
    ));
    let first_edges = scene.edge_pixels();
    let with = render(&mut scene.app, &second);
    let edges = scene
        .app
        .world_mut()
        .entity_mut(scene.part)
        .take::<ChamferEdges>()
        .expect("edges");
    let without = render(&mut scene.app, &second);
    scene.app.world_mut().entity_mut(scene.part).insert(edges);
    let second_edges = differing(&with, &without);
    for (name, pixels, reference) in [
        (
            "first",
            &first_edges,
            crate::reference("shapes/cube.obj", &camera),
        ),
        (
            "second",
            &second_edges,
            crate::reference("shapes/cube.obj", &other_camera),
        ),
    ] {
        let (a, b, count) = overlaps(pixels, &reference);
        eprintln!("{name} camera: {count} edge pixels, within 1 px {a:.4} / {b:.4}");
        assert!(count > 100 && a >= 0.95 && b >= 0.95, "{name}: {a} / {b}");
    }
}

#[test]
fn a_broken_asset_is_a_load_error_naming_the_file() {
    let folder = tempfile::tempdir().expect("tempdir");
    std::fs::write(
        folder.path().join("broken.chamfer"),
        b"CHAMFER but not really",
    )
    .expect("write");
    let mut app = app(folder.path());
    let handle: Handle<ChamferAsset> = app.world().resource::<AssetServer>().load("broken.chamfer");
    for _ in 0..200 {
        app.update();
        let server = app.world().resource::<AssetServer>();
        if let Some(bevy::asset::LoadState::Failed(error)) = server.get_load_state(&handle) {
            let text = error.to_string();
            assert!(
                text.contains("broken.chamfer") && text.contains("not a valid .chamfer asset"),
                "{text}"
            );
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    panic!("the broken asset neither failed nor loaded");
}

/// The fandisk of `folder` seen from the side its creases show best, 4× MSAA.
fn fandisk_scene(folder: &Path) -> Scene {
    let baked = bake_file(&fixture("meshes/fandisk.obj"), &BakeOptions::DEFAULT).expect("bake");
    let bounds = [baked.asset.header.bounds_min, baked.asset.header.bounds_max];
    let (transform, projection, _) = orbit_camera(bounds, -50.0, 30.0);
    Scene::new(
        folder,
        "fandisk",
        (transform, projection),
        Msaa::Sample4,
        false,
    )
}

#[test]
fn the_technique_changes_at_run_time() {
    let folder = assets(&[("fandisk", "meshes/fandisk.obj")]);
    let mut scene = fandisk_scene(folder.path());
    let joined = scene.edge_pixels();
    for technique in [
        chamfer_bevy::Technique::Fins(chamfer_bevy::FinSettings::default()),
        chamfer_bevy::Technique::from_name("image-sobel").expect("sobel"),
    ] {
        scene
            .app
            .world_mut()
            .entity_mut(scene.part)
            .get_mut::<ChamferEdges>()
            .expect("edges")
            .style
            .technique = technique;
        let switched = scene.edge_pixels();
        let count = switched.iter().filter(|&&e| e).count();
        let changed = joined.iter().zip(&switched).filter(|(a, b)| a != b).count();
        eprintln!(
            "{}: {count} edge pixels, {changed} differ from joined",
            technique.name()
        );
        assert!(
            count > 100 && changed > 100,
            "{}: {count} / {changed}",
            technique.name()
        );
    }
}

/// Moves the scene's only light (`light`, put where `from` is and looking at the part) from one side to
/// the other: lit by the scene, the strips change; with the style's own light, they stay.
/// `light` is made (from the distance it will be at) by `make`: point and spot lights are placed three
/// diagonals from the part's centre, so every face sees them from outside.
fn strips_follow_the_scenes_light<L: Component + Clone>(make: impl Fn(f32) -> L) {
    let folder = rounded_assets(&[("fandisk", "meshes/fandisk.obj")], 0.01);
    let mut scene = fandisk_scene(folder.path());
    let baked = bake_file(&fixture("meshes/fandisk.obj"), &BakeOptions::DEFAULT).expect("bake");
    let [lo, hi] =
        [baked.asset.header.bounds_min, baked.asset.header.bounds_max].map(Vec3::from_array);
    let (centre, diagonal) = ((lo + hi) * 0.5, (hi - lo).length());
    let place = |side: Vec3| centre + side.normalize() * 3.0 * diagonal;
    let light = make(3.0 * diagonal);
    let highlight = chamfer_bevy::Highlight {
        shading: chamfer_bevy::Shading::Pbr(chamfer_bevy::PbrMaterial::default()),
        ..chamfer_bevy::Highlight::default()
    };
    {
        let world = scene.app.world_mut();
        let suns: Vec<Entity> = world
            .query_filtered::<Entity, With<DirectionalLight>>()
            .iter(world)
            .collect();
        for sun in suns {
            world.despawn(sun);
        }
        world.spawn((light, Transform::default()));
        let mut edges = world.entity_mut(scene.part);
        let mut edges = edges.get_mut::<ChamferEdges>().expect("edges");
        edges.style.highlight = Some(highlight);
        // An unlit mesh: only the strips can change with the light.
        let material = edges_material(world, scene.part);
        world
            .resource_mut::<Assets<StandardMaterial>>()
            .get_mut(&material)
            .expect("material")
            .unlit = true;
    }
    let frame_lit_from = |scene: &mut Scene, from: Vec3, scene_light: bool| {
        let world = scene.app.world_mut();
        world
            .entity_mut(scene.part)
            .get_mut::<ChamferEdges>()
            .expect("edges")
            .scene_light = scene_light;
        let mut lights = world.query_filtered::<&mut Transform, With<L>>();
        for mut light in lights.iter_mut(world) {
            *light = Transform::from_translation(from).looking_at(centre, Vec3::Y);
        }
        render(&mut scene.app, &scene.image)
    };
    let differ = |a: &[u8], b: &[u8], only: &[bool]| {
        differing(a, b)
            .iter()
            .zip(only)
            .filter(|(d, strip)| **d && **strip)
            .count()
    };
    let strips = scene.edge_pixels();
    let strip_count = strips.iter().filter(|&&s| s).count();
    let (from_left, from_right) = (
        place(Vec3::new(-2.0, 1.0, 0.5)),
        place(Vec3::new(2.0, 1.0, -0.5)),
    );
    let left = frame_lit_from(&mut scene, from_left, true);
    let right = frame_lit_from(&mut scene, from_right, true);
    let moved = differ(&left, &right, &strips);
    // With the style's own light, the strips stay (a few pixels of the joined technique's
    // ties aside: 5 of 1,669 measured).
    let own_left = frame_lit_from(&mut scene, from_left, false);
    let own_right = frame_lit_from(&mut scene, from_right, false);
    let own_moved = differ(&own_left, &own_right, &strips);
    eprintln!(
        "{}: {strip_count} strip pixels; the scene's light moved: {moved} differ lit by it, {own_moved} with the style's own light",
        std::any::type_name::<L>()
    );
    assert!(strip_count > 500, "{strip_count}");
    assert!(moved > strip_count / 4, "{moved} of {strip_count}");
    assert!(own_moved * 50 < moved, "{own_moved} vs {moved}");
}

#[test]
fn the_highlight_takes_its_light_from_the_scenes_directional_light() {
    strips_follow_the_scenes_light(|_| DirectionalLight::default());
}

/// The lumens that light a surface `distance` away as the default directional light does.
fn lumens_like_the_sun(distance: f32) -> f32 {
    DirectionalLight::default().illuminance * distance * distance * 4.0 * std::f32::consts::PI
}

#[test]
fn the_highlight_takes_its_light_from_the_scenes_point_light() {
    strips_follow_the_scenes_light(|distance| PointLight {
        intensity: lumens_like_the_sun(distance),
        range: 2.0 * distance,
        ..PointLight::default()
    });
}

#[test]
fn the_highlight_takes_its_light_from_the_scenes_spot_light() {
    strips_follow_the_scenes_light(|distance| SpotLight {
        intensity: lumens_like_the_sun(distance),
        range: 2.0 * distance,
        outer_angle: 0.6,
        inner_angle: 0.5,
        ..SpotLight::default()
    });
}

/// Issue 39: the highlight draws on every asset: a cube baked without a radius (no chamfer edges:
/// the frame is the one without the highlight), a cylinder (chamfer edges without corners) and the
/// cube with a radius (corners).
#[test]
fn the_highlight_draws_with_and_without_chamfer_edges_and_corners() {
    let plain = assets(&[("cube", "shapes/cube.obj")]);
    let rounded = rounded_assets(
        &[
            ("cube", "shapes/cube.obj"),
            ("cylinder", "meshes/cylinder.obj"),
        ],
        0.02,
    );
    for (folder, name, strips) in [
        (plain.path(), "cube", false),
        (rounded.path(), "cylinder", true),
        (rounded.path(), "cube", true),
    ] {
        let bytes = std::fs::read(folder.join(format!("{name}.chamfer"))).expect("asset");
        let asset = chamfer_runtime::asset::Asset::decode(&bytes).expect("decode");
        let bounds = [asset.header.bounds_min, asset.header.bounds_max];
        let (transform, projection, _) = orbit_camera(bounds, 35.0, 25.0);
        let mut scene = Scene::new(folder, name, (transform, projection), Msaa::Sample4, false);
        let plain_frame = render(&mut scene.app, &scene.image);
        scene
            .app
            .world_mut()
            .entity_mut(scene.part)
            .get_mut::<ChamferEdges>()
            .expect("edges")
            .style
            .highlight = Some(chamfer_bevy::Highlight::default());
        let lit = render(&mut scene.app, &scene.image);
        let changed = differing(&plain_frame, &lit).iter().filter(|&&d| d).count();
        eprintln!("{name}: {changed} pixels changed by the highlight");
        if strips {
            assert!(changed > 100, "{name}: {changed}");
        } else {
            assert_eq!(changed, 0, "{name}");
        }
    }
}

fn edges_material(world: &World, part: Entity) -> Handle<StandardMaterial> {
    world
        .entity(part)
        .get::<MeshMaterial3d<StandardMaterial>>()
        .expect("material")
        .0
        .clone()
}

/// Saves `frame` as `name`.png where `CHAMFER_TEST_IMAGES` names a folder (to look at what a test
/// saw).
fn keep(frame: &[u8], name: &str) {
    if let Ok(dir) = std::env::var("CHAMFER_TEST_IMAGES") {
        let image = chamfer_runtime::render::Image {
            width: SIZE[0],
            height: SIZE[1],
            rgba: frame.to_vec(),
        };
        chamfer_tests::save_png(&image, &Path::new(&dir).join(format!("bevy-{name}.png")));
    }
}

/// A pixel within `tolerance` of `color` (RGB, 0–255).
fn near(p: &[u8], color: [u8; 3], tolerance: u8) -> bool {
    (0..3).all(|c| p[c].abs_diff(color[c]) <= tolerance)
}

/// The plane through the centre of `bounds` across the axis that points most at `eye`, its normal
/// towards the eye: the half nearer the camera is cut away and the cut face looks at it.
fn plane_facing(bounds: [[f32; 3]; 2], eye: Vec3) -> chamfer_bevy::ClipPlanes {
    let center = (Vec3::from(bounds[0]) + Vec3::from(bounds[1])) * 0.5;
    let to_eye = eye - center;
    let axis = (0..3)
        .max_by(|&a, &b| to_eye[a].abs().total_cmp(&to_eye[b].abs()))
        .expect("three axes");
    let mut normal = [0.0f64; 3];
    normal[axis] = f64::from(to_eye[axis].signum());
    let offset = normal[axis] * f64::from(center[axis]);
    chamfer_bevy::ClipPlanes::new(&[chamfer_bevy::Plane { normal, offset }])
}

const CAP_BLUE: [u8; 3] = [0, 0, 255];
const OUTLINE_RED: [u8; 3] = [255, 0, 0];
const HATCH_GREEN: [u8; 3] = [0, 255, 0];

fn section_in(planes: chamfer_bevy::ClipPlanes, hatch: bool) -> chamfer_bevy::ChamferSection {
    use chamfer_bevy::{CapHatch, CapStyle, CutOutline, CutStyle};
    chamfer_bevy::ChamferSection {
        cut: CutStyle {
            section: planes,
            cap: CapStyle {
                color: [0.0, 0.0, 1.0, 1.0],
                hatch: hatch.then_some(CapHatch {
                    color: [0.0, 1.0, 0.0, 1.0],
                    spacing: 8.0,
                    angle_deg: 45.0,
                    width_px: 2.0,
                    in_model: false,
                }),
            },
            outline: Some(CutOutline {
                color: [1.0, 0.0, 0.0, 1.0],
                width_px: 3.0,
            }),
            caps: true,
        },
    }
}

/// Counts of a frame's pixels: not the background, the cap's blue, the outline's red, the hatch's
/// green.
fn tally(frame: &[u8]) -> (usize, usize, usize, usize) {
    let background = [frame[0], frame[1], frame[2]];
    let count = |f: &dyn Fn(&[u8]) -> bool| frame.chunks(4).filter(|p| f(p)).count();
    (
        count(&|p| !near(p, background, 8)),
        count(&|p| near(p, CAP_BLUE, 40)),
        count(&|p| near(p, OUTLINE_RED, 60)),
        count(&|p| near(p, HATCH_GREEN, 60)),
    )
}

#[test]
fn a_section_component_cuts_the_cube_caps_the_cut_and_outlines_it() {
    let folder = assets(&[("cube", "shapes/cube.obj"), ("open", "shapes/open-box.obj")]);
    let (bounds, view, _) = cube_view();
    let planes = plane_facing(bounds, view.0.translation);
    // A clear colour no face is shaded in (the default is as dark as the cube's shaded side).
    let clear = ClearColor(Color::srgb(1.0, 0.0, 1.0));
    let mut scene = Scene::new(folder.path(), "cube", view.clone(), Msaa::Off, false);
    scene.app.insert_resource(clear.clone());
    let whole = render(&mut scene.app, &scene.image);
    let background = [whole[0], whole[1], whole[2]];
    let (mesh, blue, ..) = tally(&whole);
    assert!(mesh > 5000 && blue == 0, "the whole cube: {mesh} pixels");
    let own_material = edges_material(scene.app.world(), scene.part);

    scene
        .app
        .world_mut()
        .entity_mut(scene.part)
        .insert(section_in(planes, false));
    let cut = render(&mut scene.app, &scene.image);
    keep(&whole, "section-whole");
    keep(&cut, "section-cut");
    let (cut_mesh, cap, outline, _) = tally(&cut);
    eprintln!("whole {mesh}, cut {cut_mesh}: cap {cap}, outline {outline}");
    // The near half is gone: what it covered alone is background now, and nothing is drawn where
    // the whole cube was not (the outline's half width aside).
    let gone = whole
        .chunks(4)
        .zip(cut.chunks(4))
        .filter(|(w, c)| !near(w, background, 8) && near(c, background, 8))
        .count();
    let grown = whole
        .chunks(4)
        .zip(cut.chunks(4))
        .filter(|(w, c)| {
            near(w, background, 8) && !near(c, background, 8) && !near(c, OUTLINE_RED, 60)
        })
        .count();
    assert!(
        gone * 10 > mesh,
        "the cut half's pixels go: {gone} of {mesh}"
    );
    assert!(grown * 200 < mesh, "nothing beyond the cube: {grown}");
    // The cut face fills in the cap's colour, outlined around.
    assert!(
        cap * 6 > mesh,
        "the cap fills the cut square: {cap} of {mesh}"
    );
    assert!(outline > 200, "the cut outline is drawn: {outline}");
    let mesh_view = scene
        .app
        .world()
        .entity(scene.part)
        .get::<MeshMaterial3d<chamfer_bevy::SectionMaterial>>()
        .is_some();
    assert!(mesh_view, "the section material is swapped in");

    // Hatched: lines of the hatch colour over the fill.
    scene
        .app
        .world_mut()
        .entity_mut(scene.part)
        .insert(section_in(planes, true));
    let hatched = render(&mut scene.app, &scene.image);
    keep(&hatched, "section-hatched");
    let (_, fill, _, lines) = tally(&hatched);
    assert!(
        lines > 100 && fill > lines,
        "hatched: {lines} line pixels over {fill}"
    );

    // The section goes: the cube is whole again, with its own material.
    scene
        .app
        .world_mut()
        .entity_mut(scene.part)
        .remove::<chamfer_bevy::ChamferSection>();
    let again = render(&mut scene.app, &scene.image);
    assert!(differing(&again, &whole).iter().all(|&d| !d), "whole again");
    assert_eq!(edges_material(scene.app.world(), scene.part), own_material);

    // An open box cut the same way shows into it: no cap, the outline kept.
    let mut open = Scene::new(folder.path(), "open", view, Msaa::Off, false);
    open.app.insert_resource(clear);
    open.app
        .world_mut()
        .entity_mut(open.part)
        .insert(section_in(planes, false));
    let (open_mesh, open_cap, open_outline, _) = tally(&render(&mut open.app, &open.image));
    assert!(open_mesh > 3000, "the open box is drawn: {open_mesh}");
    assert_eq!(open_cap, 0, "an open mesh is not capped");
    assert!(open_outline > 100, "its outline is drawn: {open_outline}");
}

#[test]
fn every_section_and_cut_entry_reaches_the_section_component() {
    use chamfer_bevy::{ChamferSection, CutSettings, Section};
    use chamfer_runtime::schema::{Schema, Value};
    let mut section = Section::default();
    Section::entry("section")
        .expect("section")
        .set_example(&mut section);
    // Hatched (at a spacing other than the example's), so the hatch entries tell.
    let base_cut = CutSettings {
        cap_hatch_spacing: 3.0,
        ..CutSettings::default()
    };
    let base = ChamferSection::from_settings(&section, &base_cut).expect("valid");
    assert!(!base.cut.section.is_empty());
    for entry in Section::ENTRIES {
        let mut other = Section::default();
        entry.set_example(&mut other);
        let made = ChamferSection::from_settings(&other, &base_cut).expect(entry.name);
        assert!(!made.cut.section.is_empty(), "{}", entry.name);
    }
    for entry in CutSettings::ENTRIES {
        let mut cut = base_cut;
        entry.set_example(&mut cut);
        let made = ChamferSection::from_settings(&section, &cut).expect(entry.name);
        assert_ne!(made, base, "{}", entry.name);
    }
    let mut negative = CutSettings::default();
    CutSettings::entry("cut_outline_width")
        .expect("width")
        .set(&mut negative, Value::Number(-1.0))
        .expect("set");
    let refused = ChamferSection::from_settings(&section, &negative).expect_err("refused");
    assert!(
        refused.to_string().contains("cut_outline_width"),
        "{refused}"
    );
}
