//! Headless pixel tests of the wgpu runtime on whatever adapter the machine has (Mesa's lavapipe on
//! CI). Each test bakes a fixture, renders it with a known camera and looks at the pixels where the
//! geometry says edges, faces, corners and silhouettes must land.

use chamfer_runtime::render::{Camera, CapMethod, EdgeClasses, EdgeStyle, Image, MeshStyle, Orbit};
use chamfer_tests::cube::*;
use chamfer_tests::{bake_fixture, draw_frame, render};
use glam::{Vec2, Vec3};

#[test]
fn cube_shows_its_nine_visible_edges_and_no_hidden_one() {
    let asset = bake_fixture("shapes/cube.obj");
    for orthographic in [false, true] {
        let camera = cube_camera(256, orthographic);
        let image = render(
            &asset,
            &camera,
            Some(&grey_mesh()),
            Some(&edges_in(RED, 3.0, CapMethod::NextIndex)),
            BLUE_BACKGROUND,
        );
        check_cube_edges(&image, &camera).unwrap_or_else(|e| panic!("ortho {orthographic}: {e}"));
    }
}

/// `camera` with a reverse-Z projection: depth `1 − d` of the standard one (near 1, far 0).
fn reversed(camera: &Camera) -> Camera {
    let flip = glam::Mat4::from_cols(
        glam::Vec4::X,
        glam::Vec4::Y,
        glam::Vec4::new(0.0, 0.0, -1.0, 0.0),
        glam::Vec4::new(0.0, 0.0, 1.0, 1.0),
    );
    Camera {
        projection: flip * camera.projection,
        ..*camera
    }
}

#[test]
fn a_reverse_z_target_draws_what_a_standard_one_does() {
    let gpu = chamfer_tests::gpu();
    let asset = bake_fixture("shapes/cube.obj");
    let style = edges_in(RED, 3.0, CapMethod::NextIndex);
    for orthographic in [false, true] {
        let camera = cube_camera(256, orthographic);
        let standard = render(
            &asset,
            &camera,
            Some(&grey_mesh()),
            Some(&style),
            BLUE_BACKGROUND,
        );
        let formats = gpu.formats(1).with_reverse_z(true);
        let target = gpu
            .target_with(256, 256, formats)
            .expect("reverse-Z target");
        let reverse = reversed(&camera);
        let image = chamfer_tests::render_on(
            &target,
            &asset,
            &reverse,
            Some(&grey_mesh()),
            Some(&style),
            BLUE_BACKGROUND,
        );
        check_cube_edges(&image, &camera).unwrap_or_else(|e| panic!("ortho {orthographic}: {e}"));
        let differing = standard
            .rgba
            .chunks(4)
            .zip(image.rgba.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        // Depth is stored the other way round, so a pixel may tip where two depths nearly tie.
        assert!(
            differing < 40,
            "{differing} pixels differ (ortho {orthographic})"
        );

        // The control: the same reverse projection in a target declared standard draws wrongly.
        let wrong = render(
            &asset,
            &reverse,
            Some(&grey_mesh()),
            Some(&style),
            BLUE_BACKGROUND,
        );
        assert!(
            check_cube_edges(&wrong, &camera).is_err(),
            "ortho {orthographic}"
        );
    }
}

#[test]
fn hidden_edges_are_hidden_by_the_depth_test_not_by_luck() {
    // The same frame with back-facing creases kept and a bias far larger than the cube: the hidden
    // edges now win the depth test, so the test above would see them.
    let asset = bake_fixture("shapes/cube.obj");
    let camera = cube_camera(256, false);
    let style = EdgeStyle {
        depth_bias_px: Some(1000.0),
        cull_back_facing: false,
        ..edges_in(RED, 3.0, CapMethod::NextIndex)
    };
    let image = render(
        &asset,
        &camera,
        Some(&grey_mesh()),
        Some(&style),
        BLUE_BACKGROUND,
    );
    let hidden_corner = (0..8)
        .find(|&c| {
            cube_edges()
                .iter()
                .filter(|e| e.0 == c || e.1 == c)
                .all(|e| !edge_seen(&camera, e))
        })
        .expect("a corner whose three edges are all hidden");
    let p = project(&camera, corner(hidden_corner));
    assert!(
        disk(&image, p, 2.0).into_iter().any(is_red),
        "hidden corner {hidden_corner} at {p}"
    );
}

/// Along rays from the centre of the picture of a smooth closed mesh: the outermost drawn pixel on
/// every ray is contour colour, and contour colour appears only near the silhouette.
fn assert_silhouette_outlined(image: &Image, center: Vec2, what: &str) {
    for ray in 0..64 {
        let angle = ray as f32 / 64.0 * std::f32::consts::TAU;
        let direction = Vec2::new(angle.cos(), angle.sin());
        let mut samples = Vec::new();
        let mut r = 0.0;
        loop {
            let p = center + direction * r;
            if p.x < 0.0 || p.y < 0.0 || p.x >= image.width as f32 || p.y >= image.height as f32 {
                break;
            }
            samples.push((r, pixel_at(image, p)));
            r += 0.5;
        }
        let (outer, last) = samples
            .iter()
            .rev()
            .find(|(_, p)| !is_background(*p))
            .copied()
            .unwrap_or_else(|| panic!("{what}: ray {ray} sees no mesh"));
        assert!(
            is_red(last),
            "{what}: ray {ray} ends on {last:?} at {outer} px, not the contour"
        );
        let first_red = samples
            .iter()
            .find(|(_, p)| is_red(*p))
            .map_or(f32::MAX, |s| s.0);
        assert!(
            first_red > 0.75 * outer,
            "{what}: ray {ray} has contour colour at {first_red} px, inside the silhouette at {outer} px"
        );
    }
}

#[test]
fn a_spheres_silhouette_is_drawn_as_a_contour_from_any_camera() {
    let asset = bake_fixture("shapes/sphere-16x32.obj");
    assert_eq!(
        asset.header.stats.edges.crease, 0,
        "the sphere must be smooth"
    );
    let bounds = [asset.header.bounds_min, asset.header.bounds_max];
    let center = (Vec3::from(bounds[0]) + Vec3::from(bounds[1])) * 0.5;
    let style = EdgeStyle {
        classes: EdgeClasses::CONTOUR,
        ..edges_in(RED, 3.0, CapMethod::NextIndex)
    };
    for (azimuth, elevation, orthographic) in [
        (0.0, 0.0, false),
        (60.0, 30.0, false),
        (200.0, -50.0, false),
        (30.0, 89.5, false),
        (30.0, 10.0, true),
    ] {
        let orbit = Orbit {
            azimuth,
            elevation,
            ortho: orthographic,
            distance: Some(3.0 * Vec3::from(bounds[1]).distance(center)),
            ..Orbit::default()
        };
        let camera = Camera::orbit(bounds, &orbit, [200, 160]);
        let image = render(
            &asset,
            &camera,
            Some(&grey_mesh()),
            Some(&style),
            BLUE_BACKGROUND,
        );
        let what = format!("azimuth {azimuth}, elevation {elevation}, ortho {orthographic}");
        assert_silhouette_outlined(&image, project(&camera, center), &what);
    }
}

#[test]
fn thick_edges_join_without_gaps_with_either_cap_method() {
    let asset = bake_fixture("shapes/cube.obj");
    let camera = cube_camera(256, false);
    let corners = visible_corners(&camera);
    assert_eq!(corners.len(), 7);
    let gaps = |caps| {
        let style = edges_in(RED, 12.0, caps);
        let image = render(
            &asset,
            &camera,
            Some(&grey_mesh()),
            Some(&style),
            BLUE_BACKGROUND,
        );
        corners
            .iter()
            .filter(|&&c| {
                disk(&image, project(&camera, corner(c)), 0.8 * 6.0)
                    .into_iter()
                    .any(is_background)
            })
            .count()
    };
    assert_eq!(gaps(CapMethod::NextIndex), 0, "next-index caps");
    assert_eq!(gaps(CapMethod::CapBuffer), 0, "cap-buffer caps");
    // Without caps the silhouette corners show the background: the check above can fail.
    assert!(gaps(CapMethod::None) >= 3);
}

#[test]
fn a_translucent_colour_blends_once_at_joins() {
    let asset = bake_fixture("shapes/cube.obj");
    let camera = cube_camera(256, false);
    let black_mesh = MeshStyle {
        color: [0.0, 0.0, 0.0, 1.0],
        ambient: 1.0,
        ..MeshStyle::default()
    };
    let half_white = [1.0, 1.0, 1.0, 0.5];
    let brightest = |caps| {
        let style = edges_in(half_white, 12.0, caps);
        let image = render(
            &asset,
            &camera,
            Some(&black_mesh),
            Some(&style),
            [0.0, 0.0, 0.0, 1.0],
        );
        let along_edge = pixel_at(&image, project(&camera, (corner(5) + corner(7)) * 0.5))[0];
        let at_joins: Vec<u8> = visible_corners(&camera)
            .iter()
            .map(|&c| pixel_at(&image, project(&camera, corner(c)))[0])
            .collect();
        (
            image.rgba.chunks(4).map(|p| p[0]).max(),
            along_edge,
            at_joins,
        )
    };
    for caps in [CapMethod::NextIndex, CapMethod::CapBuffer] {
        let (max, along_edge, at_joins) = brightest(caps);
        // One blend of half white over black is 127.5; two would be 191.
        assert!((126..=129).contains(&along_edge), "{caps:?}: {along_edge}");
        assert!(
            max <= Some(129),
            "{caps:?}: a pixel blended twice ({max:?})"
        );
        for value in at_joins {
            assert!(
                value.abs_diff(along_edge) <= 1,
                "{caps:?}: join {value} vs edge {along_edge}"
            );
        }
    }
    // Plain overlapping quads blend twice where they cross: the check above can fail.
    assert!(brightest(CapMethod::None).0 > Some(180));
}

#[test]
fn both_cap_methods_draw_the_same_pixels() {
    for fixture in [
        "shapes/cube.obj",
        "shapes/cylinder-16.obj",
        "meshes/fandisk.obj",
    ] {
        let asset = bake_fixture(fixture);
        let bounds = [asset.header.bounds_min, asset.header.bounds_max];
        let camera = Camera::orbit(bounds, &Orbit::default(), [240, 200]);
        // One colour: where unrelated edges overlap, the draw order (atomic, so free) cannot show.
        let style = |caps| edges_in(RED, 7.0, caps);
        let next = render(
            &asset,
            &camera,
            Some(&grey_mesh()),
            Some(&style(CapMethod::NextIndex)),
            BLUE_BACKGROUND,
        );
        let heads = render(
            &asset,
            &camera,
            Some(&grey_mesh()),
            Some(&style(CapMethod::CapBuffer)),
            BLUE_BACKGROUND,
        );
        let differing = next
            .rgba
            .chunks(4)
            .zip(heads.rgba.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(differing, 0, "{fixture}");
    }
}

#[test]
fn wide_and_narrow_index_sections_draw_the_same_pixels() {
    use chamfer_runtime::asset::Indices;
    let narrow = bake_fixture("shapes/cylinder-16.obj");
    let widen = |indices: &Indices| Indices::U32(indices.to_u32_vec());
    let wide = chamfer_runtime::asset::Asset {
        mesh_indices: widen(&narrow.mesh_indices),
        edge_vertices: widen(&narrow.edge_vertices),
        next_ends: widen(&narrow.next_ends),
        cap_heads: widen(&narrow.cap_heads),
        ..narrow.clone()
    };
    assert!(matches!(narrow.edge_vertices, Indices::U16(_)));
    let camera = Camera::orbit(
        [narrow.header.bounds_min, narrow.header.bounds_max],
        &Orbit::default(),
        [200, 200],
    );
    let style = EdgeStyle {
        width_px: 5.0,
        ..EdgeStyle::default()
    };
    let a = render(
        &narrow,
        &camera,
        Some(&grey_mesh()),
        Some(&style),
        BLUE_BACKGROUND,
    );
    let b = render(
        &wide,
        &camera,
        Some(&grey_mesh()),
        Some(&style),
        BLUE_BACKGROUND,
    );
    assert!(a == b);
    assert!(
        a.rgba
            .chunks(4)
            .any(|p| p[..3] != [128, 128, 128] && p[2] < 200),
        "edges were drawn"
    );
}

/// The contour edges of `asset` seen from `eye`, counted on the CPU in f64 (an independent reference).
fn cpu_contours(asset: &chamfer_runtime::asset::Asset, eye: glam::DVec4) -> u32 {
    use chamfer_runtime::asset::EdgeFlags;
    let p = |v: u32| glam::Vec3::from(asset.topology_positions[v as usize]).as_dvec3();
    (0..asset.edge_count())
        .filter(|&e| {
            let flags = asset.edge_flags(e);
            if flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD) {
                return false;
            }
            let [v0, v1, v2, v3] = asset.edge(e).map(p);
            let front = |n: glam::DVec3, at: glam::DVec3| n.dot(eye.truncate() - at * eye.w) > 0.0;
            let mut nb = (v0 - v1).cross(v3 - v1);
            if flags.contains(EdgeFlags::FLIPPED) {
                nb = -nb;
            }
            front((v1 - v0).cross(v2 - v0), v0) != front(nb, v1)
        })
        .count() as u32
}

#[test]
fn the_gpu_draws_the_edges_a_cpu_reference_counts() {
    use chamfer_runtime::render::{EdgeRenderer, GpuAsset};
    let gpu = chamfer_tests::gpu();
    let mut cases = Vec::new();
    for fixture in [
        "shapes/sphere-16x32.obj",
        "meshes/spot.obj",
        "meshes/fandisk.obj",
    ] {
        let asset = bake_fixture(fixture);
        for (azimuth, orthographic) in [(20.0, false), (130.0, true)] {
            let orbit = Orbit {
                azimuth,
                ortho: orthographic,
                ..Orbit::default()
            };
            let camera = Camera::orbit(
                [asset.header.bounds_min, asset.header.bounds_max],
                &orbit,
                [64, 64],
            );
            cases.push((fixture, asset.clone(), camera));
        }
    }
    for (fixture, asset, camera) in cases {
        let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
        let target = gpu.target(64, 64, 1).expect("target");
        let mut edges = EdgeRenderer::new(&chamfer_tests::pipelines(target.formats()), &uploaded);
        let style = EdgeStyle {
            classes: EdgeClasses::CONTOUR,
            ..EdgeStyle::default()
        };
        let mut encoder = gpu.encoder();
        edges
            .prepare(&gpu.queue, &mut encoder, &camera, &style)
            .expect("prepare");
        gpu.submit(encoder).expect("submit");
        let counts = edges.read_counts(&gpu.device, &gpu.queue).expect("counts");
        let expected = cpu_contours(&asset, camera.eye().as_dvec4());
        // f32 on the GPU against f64 here: a face seen exactly edge-on may tip either way.
        assert!(expected > 0, "{fixture}");
        assert!(
            counts.edges.abs_diff(expected) <= expected / 500 + 1,
            "{fixture}: GPU {} contours, CPU {expected}",
            counts.edges
        );
    }
}

#[test]
fn a_renderer_reused_across_frames_draws_what_a_fresh_one_does() {
    // Per-edge state left by an earlier frame must not leak into the next one.
    use chamfer_runtime::render::{EdgeRenderer, GpuAsset, MeshRenderer};
    let gpu = chamfer_tests::gpu();
    let asset = bake_fixture("meshes/fandisk.obj");
    let bounds = [asset.header.bounds_min, asset.header.bounds_max];
    let cameras = [20.0, 140.0, 260.0].map(|azimuth| {
        let orbit = Orbit {
            azimuth,
            ..Orbit::default()
        };
        Camera::orbit(bounds, &orbit, [200, 160])
    });
    let target = gpu.target(200, 160, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    let style = edges_in(RED, 6.0, CapMethod::NextIndex);
    let mut mesh = MeshRenderer::new(&pipelines, &uploaded).expect("mesh");
    let mut reused = EdgeRenderer::new(&pipelines, &uploaded);
    for camera in &cameras {
        let mut draw = |edges: &mut EdgeRenderer| {
            draw_frame(
                &target,
                camera,
                BLUE_BACKGROUND,
                Some((&mut mesh, &grey_mesh())),
                Some((edges, &style)),
            )
        };
        let again = draw(&mut reused);
        let mut fresh = EdgeRenderer::new(&pipelines, &uploaded);
        assert!(again == draw(&mut fresh), "camera {:?}", camera.eye());
    }
}

/// Red length, in pixels, along the line through `p` in direction `dir` (±20 px).
fn red_across(image: &Image, p: Vec2, dir: Vec2) -> f32 {
    (-80..=80)
        .map(|k| p + dir * (k as f32 * 0.25))
        .filter(|q| is_red(pixel_at(image, *q)))
        .count() as f32
        * 0.25
}

#[test]
fn depth_scaled_edges_are_wider_in_front_than_behind() {
    let asset = bake_fixture("shapes/cube.obj");
    let orbit = Orbit {
        distance: Some(2.2),
        fov_y: 60.0,
        ..Orbit::default()
    };
    let camera = Camera::orbit([[0.0; 3], [1.0; 3]], &orbit, [320, 320]);
    let view_depth = |p: Vec3| -(camera.model_view * p.extend(1.0)).z;
    let mut visible: Vec<(f32, Vec2, Vec2)> = cube_edges()
        .into_iter()
        .filter(|e| edge_seen(&camera, e))
        .map(|(a, b, _)| {
            let (pa, pb) = (project(&camera, corner(a)), project(&camera, corner(b)));
            let along = (pb - pa).normalize();
            (
                view_depth((corner(a) + corner(b)) * 0.5),
                (pa + pb) * 0.5,
                Vec2::new(-along.y, along.x),
            )
        })
        .collect();
    visible.sort_by(|x, y| x.0.total_cmp(&y.0));
    let (near, far) = (visible[0], visible[visible.len() - 1]);
    let widths = |depth_scaled| {
        let style = EdgeStyle {
            depth_scaled,
            min_width_px: 2.0,
            ..edges_in(RED, 10.0, CapMethod::NextIndex)
        };
        let image = render(
            &asset,
            &camera,
            Some(&grey_mesh()),
            Some(&style),
            BLUE_BACKGROUND,
        );
        (
            red_across(&image, near.1, near.2),
            red_across(&image, far.1, far.2),
        )
    };
    let (near_flat, far_flat) = widths(false);
    assert!(
        (near_flat - 10.0).abs() <= 1.5 && (far_flat - 10.0).abs() <= 1.5,
        "{near_flat} {far_flat}"
    );
    let (near_scaled, far_scaled) = widths(true);
    // The width follows 1 / depth (thesis §9.1): the ratio of the widths is the ratio of the depths.
    let expected = far.0 / near.0;
    assert!(expected > 1.3, "the camera must see depth: {expected}");
    let ratio = near_scaled / far_scaled;
    assert!(
        (ratio - expected).abs() < 0.25 * expected,
        "widths {near_scaled} / {far_scaled} = {ratio}, depths {expected}"
    );
}

#[test]
fn a_highlighted_chamfer_sums_to_the_integral_of_its_rounded_strip() {
    use chamfer_preprocess::{BakeOptions, Radius};
    use chamfer_runtime::highlight::strip::{self, ArcView, Material};
    use chamfer_runtime::highlight::table::CosPowerRow;
    use chamfer_runtime::render::{Highlight, Light, Shading};
    let radius = 0.06;
    let path = chamfer_tests::fixture("shapes/cube.obj");
    let options = BakeOptions::DEFAULT.with_radius(Radius::Absolute(radius));
    let asset = chamfer_preprocess::bake_file(&path, &options)
        .expect("bake")
        .asset;
    assert_eq!(asset.header.stats.chamfer.edges, 12);
    let camera = cube_camera(320, false);
    let black_mesh = MeshStyle {
        color: [0.0, 0.0, 0.0, 1.0],
        ambient: 1.0,
        ..MeshStyle::default()
    };
    let material = Material {
        diffuse: 0.6,
        specular: 0.5,
        shininess: 12.5,
    };
    let to_light = Vec3::new(0.3, 0.9, 0.6).normalize();
    // The edge between the two faces nearest the camera: x = 1 and z = 1, along y.
    let (a, b) = (corner(5), corner(7));
    let middle = (a + b) * 0.5;
    let eye = camera.eye().truncate();
    let highlight = Highlight {
        light: Light::Directional(to_light.to_array()),
        color: [0.5; 3],
        shading: Shading::Blinn(material),
        ambient: 0.0,
        k: Some(eye.distance(middle)),
        ..Highlight::default()
    };
    let style = EdgeStyle {
        highlight: Some(highlight),
        classes: EdgeClasses::RIDGE,
        ..EdgeStyle::default()
    };
    let image = render(
        &asset,
        &camera,
        Some(&black_mesh),
        Some(&style),
        [0.0, 0.0, 0.0, 1.0],
    );

    // On screen: light summed across the strip, in units of full white.
    let (pa, pb) = (project(&camera, a), project(&camera, b));
    let along = (pb - pa).normalize();
    let normal = Vec2::new(-along.y, along.x);
    let summed = |t: f32| -> f32 {
        let p = pa.lerp(pb, t);
        (-40..=40)
            .map(|k| f32::from(pixel_at(&image, p + normal * k as f32)[0]) / 255.0)
            .sum()
    };

    // The same from the CPU twin: mean intensity over the visible arc × its projected width.
    let to_viewer = (eye - middle).normalize();
    let view = ArcView {
        n1: Vec3::X,
        n2: Vec3::Z,
        to_light,
        to_viewer,
        across: to_viewer.cross(Vec3::Y).normalize(),
    };
    let visible = strip::visible_arc(&view).expect("the edge faces the camera");
    let row = CosPowerRow::new(material.shininess + 1.0);
    let (mean, projected) = strip::arc_intensity(&view, visible, &material, &row);
    let clip_w = (camera.view_projection() * middle.extend(1.0)).w;
    let radius_px = radius / (camera.pixel_scale() * clip_w);
    let expected = 0.5 * mean * projected * radius_px;
    assert!(
        radius_px > 4.0,
        "the strip must be several pixels wide: {radius_px}"
    );
    for t in [0.35, 0.5, 0.65] {
        let got = summed(t);
        assert!(
            (got - expected).abs() < 0.08 * expected,
            "at {t}: {got} on screen, {expected} expected"
        );
    }
}
