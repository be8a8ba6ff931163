//! Scenes: many instances of assets in one frame (SceneRenderer), checked against assets baked
//! already transformed, and the instance and list bookkeeping checked with counters.

use chamfer_preprocess::mesh::Mesh;
use chamfer_runtime::render::{
    Camera, FinSettings, GpuAsset, Image, Instance, MeshRenderer, Orbit, SceneRenderer, Technique,
};
use chamfer_tests::cube::*;
use chamfer_tests::{bake_fixture, gpu};
use glam::{Mat4, Vec3};

/// The fandisk (an asset with contours, ridges and valleys) as a mesh.
fn fandisk() -> Mesh {
    chamfer_preprocess::load::load(
        &chamfer_tests::fixture("meshes/fandisk.obj"),
        &chamfer_preprocess::Limits::DEFAULT,
    )
    .expect("fandisk")
    .mesh
}

/// `mesh` moved by `transform`, its winding flipped if the transform mirrors (as a glTF viewer
/// does), so its faces still face out.
fn transformed(mesh: &Mesh, transform: Mat4) -> Mesh {
    let mirrored = transform.determinant() < 0.0;
    Mesh {
        positions: mesh
            .positions
            .iter()
            .map(|&p| transform.transform_point3(p))
            .collect(),
        triangles: mesh
            .triangles
            .iter()
            .map(|&[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect(),
        ..Mesh::default()
    }
}

fn baked(mesh: Mesh) -> chamfer_runtime::asset::Asset {
    chamfer_preprocess::bake(mesh, "scene", &chamfer_preprocess::BakeOptions::DEFAULT)
        .expect("bake")
        .asset
}

/// One frame of `instances` (mesh and red edges) on blue.
fn scene_picture(camera: &Camera, instances: &[Instance<'_>], scene: &mut SceneRenderer) -> Image {
    let style = edges_in(RED, 2.0, chamfer_runtime::render::CapMethod::NextIndex);
    scene_picture_in(camera, instances, scene, &style)
}

/// One frame of `instances` in `style` over the grey mesh, on blue.
fn scene_picture_in(
    camera: &Camera,
    instances: &[Instance<'_>],
    scene: &mut SceneRenderer,
    style: &chamfer_runtime::render::EdgeStyle,
) -> Image {
    let gpu = gpu();
    let [w, h] = camera.viewport;
    let target = gpu.target(w, h, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let mut mesh = MeshRenderer::for_scenes(&pipelines).expect("mesh");
    mesh.prepare_scene(&gpu.queue, camera, instances, &grey_mesh());
    let mut encoder = gpu.encoder();
    let prepared = scene
        .prepare(&gpu.queue, &mut encoder, camera, instances, style)
        .expect("prepare");
    {
        let mut pass = target.begin_pass(&mut encoder, BLUE_BACKGROUND);
        mesh.render(&mut pass);
        prepared.render(&mut pass);
    }
    gpu.submit(encoder).expect("submit");
    target.read(gpu).expect("read")
}

fn differing(a: &Image, b: &Image) -> usize {
    a.rgba
        .chunks(4)
        .zip(b.rgba.chunks(4))
        .filter(|(p, q)| p != q)
        .count()
}

#[test]
fn instances_mirrored_and_scaled_draw_what_pretransformed_copies_do() {
    let gpu = gpu();
    let mesh = fandisk();
    let asset = baked(mesh.clone());
    // One copy moved, one mirrored in x and stretched unevenly.
    let first = Mat4::from_translation(Vec3::new(-2.0, 0.0, 0.0));
    let second = Mat4::from_translation(Vec3::new(2.5, 0.3, 0.0))
        * Mat4::from_scale(Vec3::new(-1.0, 1.2, 0.8));
    let mut both = transformed(&mesh, first);
    let mirrored = transformed(&mesh, second);
    let offset = both.positions.len() as u32;
    both.positions.extend(mirrored.positions);
    both.triangles
        .extend(mirrored.triangles.iter().map(|t| t.map(|i| i + offset)));
    let together = baked(both);
    let camera = Camera::orbit(
        [together.header.bounds_min, together.header.bounds_max],
        &Orbit {
            azimuth: 25.0,
            elevation: 20.0,
            ..Orbit::default()
        },
        [320, 200],
    );
    let pipelines = chamfer_tests::pipelines(gpu.formats(1));
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    let copies = GpuAsset::new(&gpu.device, &together).expect("upload");
    let scene = [
        Instance::new(&uploaded).with_transform(first),
        Instance::new(&uploaded).with_transform(second),
    ];
    let instanced = scene_picture(&camera, &scene, &mut SceneRenderer::new(&pipelines));
    let reference = scene_picture(
        &camera,
        &[Instance::new(&copies)],
        &mut SceneRenderer::new(&pipelines),
    );
    let one = scene_picture(&camera, &scene[..1], &mut SceneRenderer::new(&pipelines));
    let red = |image: &Image| {
        image
            .rgba
            .chunks(4)
            .filter(|p| is_red([p[0], p[1], p[2], p[3]]))
            .count()
    };
    let (diff, control) = (
        differing(&instanced, &reference),
        differing(&one, &reference),
    );
    eprintln!(
        "{diff} pixels differ from the pre-transformed copies ({} red); one instance alone: {control}",
        red(&reference)
    );
    // The same picture but for rounding where the copies' positions were transformed on the CPU.
    assert!(diff * 100 < red(&reference), "{diff}");
    // The check can fail: leaving out the mirrored instance changes thousands of pixels.
    assert!(control > 20 * diff.max(50), "{control}");
}

#[test]
fn an_instance_outside_the_view_costs_no_edge_work() {
    let gpu = gpu();
    let asset = bake_fixture("meshes/fandisk.obj");
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    let pipelines = chamfer_tests::pipelines(gpu.formats(1));
    let camera = Camera::orbit(
        [asset.header.bounds_min, asset.header.bounds_max],
        &Orbit::default(),
        [200, 160],
    );
    let far_away = Mat4::from_translation(Vec3::new(1e4, 0.0, 0.0));
    let counts = |instances: &[Instance<'_>]| {
        let mut scene = SceneRenderer::new(&pipelines);
        scene_picture(&camera, instances, &mut scene);
        (
            scene.read_counts(&gpu.device, &gpu.queue).expect("counts"),
            scene.stats(),
        )
    };
    let (alone, alone_stats) = counts(&[Instance::new(&uploaded)]);
    let (with_far, far_stats) = counts(&[
        Instance::new(&uploaded),
        Instance::new(&uploaded).with_transform(far_away),
    ]);
    // The joined technique culls whole instances on the GPU: the host hands it both.
    assert_eq!((alone_stats.instances, alone_stats.culled), (1, 0));
    assert_eq!((far_stats.instances, far_stats.culled), (2, 0));
    assert_eq!(
        (alone.instances_in_view, with_far.instances_in_view),
        (1, 1)
    );
    // Not one cluster kept, edge classified or drawn for the instance out of view.
    assert_eq!(with_far.clusters_kept, alone.clusters_kept);
    assert_eq!(with_far.wanted, alone.wanted);
    assert_eq!(with_far.edges, alone.edges);
    // And the counter counts: a second instance in view doubles the edges.
    let beside = Mat4::from_translation(Vec3::new(0.0, 0.0, -0.5));
    let (two, two_stats) = counts(&[
        Instance::new(&uploaded),
        Instance::new(&uploaded).with_transform(beside),
    ]);
    assert_eq!((two_stats.culled, two.instances_in_view), (0, 2));
    assert!(two.wanted > alone.wanted, "{two:?} vs {alone:?}");
    assert!(two.clusters_kept > alone.clusters_kept);
}

#[test]
fn lists_that_overflow_grow_for_the_next_frames() {
    let gpu = gpu();
    let asset = bake_fixture("meshes/fandisk.obj");
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    let pipelines = chamfer_tests::pipelines(gpu.formats(1));
    let camera = Camera::orbit(
        [asset.header.bounds_min, asset.header.bounds_max],
        &Orbit::default(),
        [200, 160],
    );
    let instances = [Instance::new(&uploaded)];
    // Lists far too small for the fandisk's drawn edges.
    let mut scene = SceneRenderer::with_first_slots(&pipelines, 64);
    let mut seen = Vec::new();
    for _ in 0..4 {
        scene_picture(&camera, &instances, &mut scene);
        seen.push(scene.read_counts(&gpu.device, &gpu.queue).expect("counts"));
    }
    eprintln!("{seen:?}");
    let first = seen[0];
    assert_eq!(first.edges, 64, "the first frame draws what fits");
    assert!(first.wanted > 64);
    let last = seen[3];
    assert_eq!(last.edges, last.wanted, "later frames draw every edge");
    assert_eq!(last.wanted, first.wanted);
}

/// One frame of `instances` drawn by one renderer per instance: each prepared, then all drawn in
/// one pass (what a scene did before batches), and the renderers' summed counts.
fn picture_instance_by_instance(
    camera: &Camera,
    instances: &[Instance<'_>],
    style: &chamfer_runtime::render::EdgeStyle,
) -> (Image, u32, u32) {
    let gpu = gpu();
    let [w, h] = camera.viewport;
    let target = gpu.target(w, h, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let mut mesh = MeshRenderer::for_scenes(&pipelines).expect("mesh");
    mesh.prepare_scene(&gpu.queue, camera, instances, &grey_mesh());
    let mut renderers: Vec<SceneRenderer> = instances
        .iter()
        .map(|_| SceneRenderer::new(&pipelines))
        .collect();
    let mut encoder = gpu.encoder();
    {
        let prepared: Vec<_> = renderers
            .iter_mut()
            .zip(instances)
            .map(|(renderer, instance)| {
                renderer
                    .prepare(
                        &gpu.queue,
                        &mut encoder,
                        camera,
                        std::slice::from_ref(instance),
                        style,
                    )
                    .expect("prepare")
            })
            .collect();
        let mut pass = target.begin_pass(&mut encoder, BLUE_BACKGROUND);
        mesh.render(&mut pass);
        for frame in &prepared {
            frame.render(&mut pass);
        }
    }
    gpu.submit(encoder).expect("submit");
    let image = target.read(gpu).expect("read");
    let (mut edges, mut caps) = (0, 0);
    for renderer in &renderers {
        // (Only the techniques that count what they draw have counts.)
        if let Ok(counts) = renderer.read_counts(&gpu.device, &gpu.queue) {
            edges += counts.edges;
            caps += counts.caps;
        }
    }
    (image, edges, caps)
}

#[test]
fn a_scene_drawn_in_batches_equals_it_drawn_instance_by_instance() {
    let gpu = gpu();
    // The techniques that draw in batches: the joined one (compute, counted) and the pulled
    // McGuire–Hughes and fins.
    let techniques = [
        Technique::Joined,
        Technique::McGuireHughes,
        Technique::Fins(FinSettings::default()),
    ];
    let assets: Vec<GpuAsset> = [
        "shapes/cube.obj",
        "meshes/fandisk.obj",
        "shapes/cone-16.obj",
    ]
    .iter()
    .map(|name| {
        GpuAsset::for_techniques(&gpu.device, &bake_fixture(name), &techniques).expect("upload")
    })
    .collect();
    // 27 instances on a lattice, turned, some mirrored and stretched, a few outside every view.
    let mut instances = Vec::new();
    for i in 0..27u32 {
        let (x, y, z) = (i % 3, (i / 3) % 3, i / 9);
        let asset = &assets[(i % 3) as usize];
        let [lo, hi] = asset.bounds().map(Vec3::from);
        let fit = Mat4::from_scale(Vec3::splat(0.7 / (hi - lo).max_element()))
            * Mat4::from_translation(-(lo + hi) * 0.5);
        let shape = match i % 4 {
            0 => Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)),
            1 => Mat4::from_scale(Vec3::new(1.0, 1.6, 0.8)),
            _ => Mat4::IDENTITY,
        };
        let turn = Mat4::from_rotation_y(i as f32 * 0.9) * Mat4::from_rotation_x(i as f32 * 0.4);
        let place = Mat4::from_translation(Vec3::new(x as f32, y as f32, z as f32));
        instances.push(Instance::new(asset).with_transform(place * turn * shape * fit));
    }
    for far in [-40.0, 60.0] {
        instances.push(
            Instance::new(&assets[1])
                .with_transform(Mat4::from_translation(Vec3::new(far, 0.0, 0.0))),
        );
    }
    let bounds = [[-0.5; 3], [2.5; 3]];
    let mut compared = 0;
    for technique in techniques {
        let style = chamfer_runtime::render::EdgeStyle {
            technique,
            ..edges_in(RED, 2.0, chamfer_runtime::render::CapMethod::NextIndex)
        };
        let counted = technique == Technique::Joined;
        for (k, azimuth) in [20.0f32, 110.0, 200.0, 290.0].into_iter().enumerate() {
            let camera = Camera::orbit(
                bounds,
                &Orbit {
                    azimuth,
                    elevation: 15.0 + 10.0 * k as f32,
                    ..Orbit::default()
                },
                [240, 180],
            );
            let name = technique.name();
            let mut scene = SceneRenderer::new(&chamfer_tests::pipelines(gpu.formats(1)));
            let batched = scene_picture_in(&camera, &instances, &mut scene, &style);
            let (separate, edges, caps) = picture_instance_by_instance(&camera, &instances, &style);
            if counted {
                let counts = scene.read_counts(&gpu.device, &gpu.queue).expect("counts");
                assert_eq!(counts.instances_in_view, 27, "azimuth {azimuth}");
                assert_eq!(
                    (counts.edges, counts.caps),
                    (edges, caps),
                    "azimuth {azimuth}"
                );
                assert!(counts.edges > 500, "azimuth {azimuth}: {counts:?}");
            }
            let red_pixels = batched
                .rgba
                .chunks_exact(4)
                .filter(|p| is_red([p[0], p[1], p[2], p[3]]))
                .count();
            assert!(
                red_pixels > 500,
                "{name}, azimuth {azimuth}: {red_pixels} edge pixels"
            );
            assert_eq!(
                differing(&batched, &separate),
                0,
                "{name}, azimuth {azimuth}: batched and instance by instance differ"
            );
            // The control: leave the lattice's first layer out of the separate drawing and the
            // pictures differ.
            let (fewer, _, _) = picture_instance_by_instance(&camera, &instances[9..], &style);
            let control = differing(&batched, &fewer);
            assert!(
                control > 100,
                "{name}, azimuth {azimuth}: control {control}"
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 12);
}

/// A highlight light given per instance (in each instance's model space) is what lets one draw
/// light differently turned instances from one scene light: the cube turned a quarter turn about
/// its vertical axis, lit by that turn's inverse of the light, looks as the unturned cube lit by the
/// light (the cube is symmetric under the turn); lit by the style's light it does not.
#[test]
fn an_instance_lit_by_its_own_light_is_lit_from_the_scene() {
    let gpu = gpu();
    let options = chamfer_preprocess::BakeOptions::DEFAULT
        .with_radius(chamfer_preprocess::Radius::Relative(0.02));
    let asset = chamfer_preprocess::bake_file(&chamfer_tests::fixture("shapes/cube.obj"), &options)
        .expect("bake")
        .asset;
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    let camera = cube_camera(240, false);
    let towards = Vec3::new(0.9, 0.6, 0.2).normalize();
    let center = (Vec3::from(asset.header.bounds_min) + Vec3::from(asset.header.bounds_max)) * 0.5;
    // K fixed (by default it is the first instance's distance, which the scene of two changes).
    let k = camera.eye().truncate().distance(center);
    let style = |light: Vec3| chamfer_runtime::render::EdgeStyle {
        highlight: Some(chamfer_runtime::render::Highlight {
            light: chamfer_runtime::render::Light::Directional(light.to_array()),
            k: Some(k),
            ..Default::default()
        }),
        ..edges_in(RED, 2.0, chamfer_runtime::render::CapMethod::NextIndex)
    };
    // A quarter turn about the cube's own vertical axis.
    let turn = Mat4::from_translation(center)
        * Mat4::from_rotation_y(std::f32::consts::FRAC_PI_2)
        * Mat4::from_translation(-center);
    let picture = |instance: Instance<'_>, light: Vec3| {
        scene_picture_in(
            &camera,
            &[instance],
            &mut SceneRenderer::new(&chamfer_tests::pipelines(
                gpu.target(240, 240, 1).expect("target").formats(),
            )),
            &style(light),
        )
    };
    let unturned = picture(Instance::new(&uploaded), towards);
    let seen_from_the_scene = picture(
        Instance::new(&uploaded).with_transform(turn).with_light(
            chamfer_runtime::render::Light::Directional(
                turn.inverse().transform_vector3(towards).to_array(),
            ),
        ),
        // The style's light, which the instance's own replaces.
        -towards,
    );
    let turned_with_it = picture(Instance::new(&uploaded).with_transform(turn), towards);
    let style_turned = picture(
        Instance::new(&uploaded).with_transform(turn),
        turn.inverse().transform_vector3(towards),
    );
    // One draw lights every instance's strips with that instance's own light: an instance first in
    // the scene (out of view, lit from the other side) must not lend the turned one its light.
    let away = Mat4::from_translation(Vec3::new(1000.0, 0.0, 0.0));
    let out_of_view = Instance::new(&uploaded).with_transform(away).with_light(
        chamfer_runtime::render::Light::Directional((-towards).to_array()),
    );
    let two = scene_picture_in(
        &camera,
        &[
            out_of_view,
            Instance::new(&uploaded).with_transform(turn).with_light(
                chamfer_runtime::render::Light::Directional(
                    turn.inverse().transform_vector3(towards).to_array(),
                ),
            ),
        ],
        &mut SceneRenderer::new(&chamfer_tests::pipelines(
            gpu.target(240, 240, 1).expect("target").formats(),
        )),
        &style(-towards),
    );
    assert_eq!(differing(&two, &seen_from_the_scene), 0);
    let same = differing(&unturned, &seen_from_the_scene);
    let control = differing(&unturned, &turned_with_it);
    eprintln!("lit by its own light: {same} pixels differ; by the style's: {control}");
    assert_eq!(differing(&seen_from_the_scene, &style_turned), 0);
    // The turned copy rasterizes a few pixels differently (62 measured).
    assert!(same <= 150, "{same}");
    assert!(control > 1000, "{control}");
}

/// The mesh pass lights an instance with its own light too, where its style's light is fixed to
/// the model (the highlight's matching shading): the turned cube of
/// [`an_instance_lit_by_its_own_light_is_lit_from_the_scene`], mesh alone.
#[test]
fn the_mesh_pass_lights_an_instance_with_its_own_light() {
    let gpu = gpu();
    let asset = chamfer_tests::bake_fixture("shapes/cube.obj");
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    let camera = cube_camera(240, false);
    let towards = Vec3::new(0.9, 0.6, 0.2).normalize();
    let center = (Vec3::from(asset.header.bounds_min) + Vec3::from(asset.header.bounds_max)) * 0.5;
    let turn = Mat4::from_translation(center)
        * Mat4::from_rotation_y(std::f32::consts::FRAC_PI_2)
        * Mat4::from_translation(-center);
    let picture = |instance: Instance<'_>| {
        let target = gpu.target(240, 240, 1).expect("target");
        let pipelines = chamfer_tests::pipelines(target.formats());
        let mut mesh = MeshRenderer::for_scenes(&pipelines).expect("mesh");
        let style = chamfer_runtime::render::MeshStyle {
            light: chamfer_runtime::render::MeshLight::Model(
                chamfer_runtime::render::Light::Directional(towards.to_array()),
            ),
            ambient: 0.0,
            ..grey_mesh()
        };
        mesh.prepare_scene(&gpu.queue, &camera, &[instance], &style);
        let mut encoder = gpu.encoder();
        {
            let mut pass = target.begin_pass(&mut encoder, BLUE_BACKGROUND);
            mesh.render(&mut pass);
        }
        gpu.submit(encoder).expect("submit");
        target.read(gpu).expect("read")
    };
    let unturned = picture(Instance::new(&uploaded));
    let own = picture(Instance::new(&uploaded).with_transform(turn).with_light(
        chamfer_runtime::render::Light::Directional(
            turn.inverse().transform_vector3(towards).to_array(),
        ),
    ));
    let styles = picture(Instance::new(&uploaded).with_transform(turn));
    let (same, control) = (differing(&unturned, &own), differing(&unturned, &styles));
    eprintln!("mesh lit by its own light: {same} pixels differ; by the style's: {control}");
    // 0 measured (22,055 for the control).
    assert!(same <= 20, "{same}");
    assert!(control > 1000, "{control}");
}
