//! Section planes on the GPU (issue 43): the mesh and every edge technique drop what a plane cuts
//! away, on the unit cube cut at x = 0.5, checked against where the kept and the cut-away parts
//! land on screen; the cut faces of closed meshes are filled (solid, hatched on screen or on the
//! model), a torus cut through its hole shows two discs, and an open mesh gets no cap.

use chamfer_runtime::asset::Asset;
use chamfer_runtime::render::{
    Camera, CapHatch, CapMethod, CapStyle, CutOutline, CutRenderer, CutStyle, EdgeRenderer,
    EdgeStyle, FinSettings, GpuAsset, Image, Instance, MeshRenderer, MeshStyle, Orbit, Technique,
};
use chamfer_runtime::section::{ClipPlanes, Plane};
use chamfer_tests::cube::*;
use chamfer_tests::{bake_fixture, draw_frame, gpu};
use glam::{Vec2, Vec3};

/// Keeps x < 0.5 of the unit cube.
fn half_cube() -> ClipPlanes {
    ClipPlanes::new(&[Plane {
        normal: [1.0, 0.0, 0.0],
        offset: 0.5,
    }])
}

fn picture(camera: &Camera, mesh: &MeshStyle, style: &EdgeStyle) -> Image {
    let gpu = gpu();
    let asset = bake_fixture("shapes/cube.obj");
    let [width, height] = camera.viewport;
    let target = gpu.target(width, height, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let uploaded =
        GpuAsset::for_techniques(&gpu.device, &asset, &[style.technique]).expect("upload");
    let mut mesh_renderer = MeshRenderer::new(&pipelines, &uploaded).expect("mesh");
    let mut edges = EdgeRenderer::new(&pipelines, &uploaded);
    draw_frame(
        &target,
        camera,
        BLUE_BACKGROUND,
        Some((&mut mesh_renderer, mesh)),
        Some((&mut edges, style)),
    )
}

const GREEN: [f32; 4] = [0.0, 1.0, 0.0, 1.0];
const BLACK: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
const YELLOW: [f32; 4] = [1.0, 1.0, 0.0, 1.0];

fn is_yellow(p: [u8; 4]) -> bool {
    p[0] > 200 && p[1] > 200 && p[2] < 60
}

/// True if a pixel within 2 px of where `q` projects is the outline's colour.
fn outlined_at(image: &Image, camera: &Camera, q: Vec3) -> bool {
    disk(image, project(camera, q), 2.0)
        .into_iter()
        .any(is_yellow)
}

fn is_green(p: [u8; 4]) -> bool {
    p[1] > 200 && p[0] < 60 && p[2] < 60
}

fn is_black(p: [u8; 4]) -> bool {
    p[0] < 40 && p[1] < 40 && p[2] < 40
}

/// `asset` with the mesh pass, the cut faces of `cut` (if any) and the edges, all cut by `cut`'s
/// section (or none).
fn cut_picture(asset: &Asset, camera: &Camera, cut: Option<&CutStyle>, edges: &EdgeStyle) -> Image {
    let gpu = gpu();
    let [width, height] = camera.viewport;
    let target = gpu.target(width, height, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let uploaded = GpuAsset::new(&gpu.device, asset).expect("upload");
    let section = cut.map_or(ClipPlanes::NONE, |c| c.section);
    let mut mesh = MeshRenderer::new(&pipelines, &uploaded).expect("mesh");
    let mut faces = CutRenderer::new(&pipelines).expect("a stencil target");
    let mut edge_renderer = EdgeRenderer::new(&pipelines, &uploaded);
    let mut encoder = gpu.encoder();
    mesh.prepare(
        &gpu.queue,
        camera,
        &MeshStyle {
            section,
            ..grey_mesh()
        },
    );
    let instances = [Instance::new(&uploaded)];
    if let Some(cut) = cut {
        faces.prepare(&gpu.queue, camera, &instances, cut);
    }
    let prepared = edge_renderer
        .prepare(
            &gpu.queue,
            &mut encoder,
            camera,
            &EdgeStyle { section, ..*edges },
        )
        .expect("prepare");
    {
        let mut pass = target.begin_pass(&mut encoder, BLUE_BACKGROUND);
        mesh.render(&mut pass);
        if cut.is_some() {
            faces.render(&mut pass);
        }
        prepared.render(&mut pass);
    }
    prepared
        .finish(&mut encoder, &target.views())
        .expect("finish");
    gpu.submit(encoder).expect("submit");
    let image = target.read(gpu).expect("read back");
    if let Ok(dir) = std::env::var("CHAMFER_TEST_IMAGES") {
        let name = format!(
            "sections-{}.png",
            std::thread::current().name().unwrap_or("x")
        );
        chamfer_tests::save_png(&image, &std::path::Path::new(&dir).join(name));
    }
    image
}

/// The pixels on the cut square of the cube cut at x = 0.5 (its middle, away from its outline).
fn cut_square(image: &Image, camera: &Camera) -> Vec<[u8; 4]> {
    let mut pixels = Vec::new();
    for i in 0..=12 {
        for j in 0..=12 {
            let q = Vec3::new(
                0.5,
                0.15 + 0.7 * i as f32 / 12.0,
                0.15 + 0.7 * j as f32 / 12.0,
            );
            pixels.push(pixel_at(image, project(camera, q)));
        }
    }
    pixels
}

/// True if `p` (pixels) lies on the projection of the box `lo..hi`.
fn on_projected_box(camera: &Camera, lo: Vec3, hi: Vec3, p: Vec2) -> bool {
    let corner = |i: usize| {
        project(
            camera,
            Vec3::select(glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), hi, lo),
        )
    };
    let inside = |a: Vec2, b: Vec2, c: Vec2| {
        let side = |u: Vec2, v: Vec2| (v - u).perp_dot(p - u);
        let (x, y, z) = (side(a, b), side(b, c), side(c, a));
        (x >= 0.0 && y >= 0.0 && z >= 0.0) || (x <= 0.0 && y <= 0.0 && z <= 0.0)
    };
    // The projection of a box is the union of its faces' projections: two triangles per face.
    let faces = [
        [0, 1, 3, 2],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 3, 7, 5],
    ];
    faces.iter().any(|f| {
        let [a, b, c, d] = f.map(corner);
        inside(a, b, c) || inside(a, c, d)
    })
}

/// Checks a picture of the cube cut at x = 0.5: the kept parts of the visible edges are red, the
/// cut-away parts of all edges are not (where no kept edge lies near them on screen), and the
/// cut-away part's faces show the background where the kept half is not behind them.
fn check_half_cube(image: &Image, camera: &Camera) -> Result<(), String> {
    let (lo, hi) = (Vec3::ZERO, Vec3::new(0.5, 1.0, 1.0));
    let kept_edges: Vec<(Vec2, Vec2)> = cube_edges()
        .iter()
        .map(|&(a, b, _)| {
            let clip = |p: Vec3| p.min(Vec3::new(0.5, 1.0, 1.0));
            (
                project(camera, clip(corner(a))),
                project(camera, clip(corner(b))),
            )
        })
        .collect();
    let (mut kept_checked, mut cut_checked, mut faces_checked) = (0, 0, 0);
    for edge in cube_edges() {
        let (a, b) = (corner(edge.0), corner(edge.1));
        for t in [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9] {
            let q = a.lerp(b, t);
            let p = project(camera, q);
            let red = disk(image, p, 2.0).into_iter().any(is_red);
            if q.x < 0.4 && edge_seen(camera, &edge) {
                kept_checked += 1;
                if !red {
                    return Err(format!("kept edge {edge:?} at {q}: not drawn"));
                }
            }
            let near_kept = kept_edges.iter().any(|&s| distance_to_segment(p, s) < 6.0);
            if q.x > 0.6 && !near_kept {
                cut_checked += 1;
                if red {
                    return Err(format!("cut-away edge {edge:?} at {q}: drawn"));
                }
            }
        }
    }
    // Points on the cut-away half's faces, off the kept half's projection: background.
    for i in 0..=8 {
        for j in 0..=8 {
            let (u, v) = (i as f32 / 8.0, j as f32 / 8.0);
            for q in [
                Vec3::new(0.55 + 0.45 * u, v, 0.0),
                Vec3::new(0.55 + 0.45 * u, v, 1.0),
                Vec3::new(0.55 + 0.45 * u, 0.0, v),
                Vec3::new(0.55 + 0.45 * u, 1.0, v),
                Vec3::new(1.0, u, v),
            ] {
                let p = project(camera, q);
                let clear = !on_projected_box(camera, lo, hi, p)
                    && kept_edges.iter().all(|&s| distance_to_segment(p, s) > 6.0);
                if clear {
                    faces_checked += 1;
                    let pixel = pixel_at(image, p);
                    if !is_background(pixel) {
                        return Err(format!("cut-away face at {q} ({p}): {pixel:?}"));
                    }
                }
            }
        }
    }
    if kept_checked < 10 || cut_checked < 10 || faces_checked < 20 {
        return Err(format!(
            "too few samples: {kept_checked} kept, {cut_checked} cut, {faces_checked} faces"
        ));
    }
    Ok(())
}

#[test]
fn the_mesh_and_every_edge_technique_drop_what_the_plane_cuts_away() {
    for orthographic in [false, true] {
        let camera = cube_camera(256, orthographic);
        let mesh = MeshStyle {
            section: half_cube(),
            ..grey_mesh()
        };
        for technique in [
            Technique::Joined,
            Technique::McGuireHughes,
            Technique::Plug,
            Technique::House,
            Technique::Fins(FinSettings::default()),
        ] {
            let style = EdgeStyle {
                technique,
                section: half_cube(),
                ..edges_in(RED, 3.0, CapMethod::NextIndex)
            };
            let image = picture(&camera, &mesh, &style);
            check_half_cube(&image, &camera)
                .unwrap_or_else(|e| panic!("{} (ortho {orthographic}): {e}", technique.name()));
            // The control: the whole cube fails the same check.
            let whole = picture(
                &camera,
                &grey_mesh(),
                &EdgeStyle {
                    section: ClipPlanes::NONE,
                    ..style
                },
            );
            assert!(
                check_half_cube(&whole, &camera).is_err(),
                "{}",
                technique.name()
            );
        }
    }
}

#[test]
fn a_cube_cut_through_its_middle_has_its_cut_square_filled_solid_or_hatched() {
    let camera = cube_camera(256, false);
    let cube = bake_fixture("shapes/cube.obj");
    let edges = edges_in(RED, 3.0, CapMethod::NextIndex);
    let solid = CutStyle {
        section: half_cube(),
        cap: CapStyle {
            color: GREEN,
            hatch: None,
        },
        outline: Some(CutOutline {
            color: YELLOW,
            width_px: 3.0,
        }),
        caps: true,
    };
    let image = cut_picture(&cube, &camera, Some(&solid), &edges);
    check_half_cube(&image, &camera).expect("the cut still drops the half");
    let square = cut_square(&image, &camera);
    assert!(
        square.iter().all(|&p| is_green(p)),
        "{:?}",
        square.iter().find(|&&p| !is_green(p))
    );
    // The control: without the cut faces the square shows the cube's inside, not the cap colour.
    let open = cut_picture(
        &cube,
        &camera,
        None,
        &EdgeStyle {
            section: half_cube(),
            ..edges
        },
    );
    assert!(cut_square(&open, &camera).iter().all(|&p| !is_green(p)));

    // Hatched, on screen and on the model: lines of the hatch colour over the fill, about as
    // much of the square as width / spacing.
    for in_model in [false, true] {
        let hatched = CutStyle {
            cap: CapStyle {
                color: GREEN,
                hatch: Some(CapHatch {
                    color: BLACK,
                    spacing: if in_model { 0.08 } else { 10.0 },
                    angle_deg: 45.0,
                    width_px: 3.0,
                    in_model,
                }),
            },
            ..solid
        };
        let image = cut_picture(&cube, &camera, Some(&hatched), &edges);
        let square = cut_square(&image, &camera);
        let black = square.iter().filter(|&&p| is_black(p)).count() as f32 / square.len() as f32;
        let green = square.iter().filter(|&&p| is_green(p)).count() as f32 / square.len() as f32;
        assert!(
            black > 0.12 && green > 0.5 && black + green > 0.9,
            "in model {in_model}: {black} black, {green} green"
        );
    }
}

/// A torus around +Y through the origin: `major` the radius of its centre circle, `minor` its tube's.
fn torus(major: f32, minor: f32, around: u32, tube: u32) -> Asset {
    let mut positions = Vec::new();
    for i in 0..around {
        let a = i as f32 / around as f32 * std::f32::consts::TAU;
        for j in 0..tube {
            let b = j as f32 / tube as f32 * std::f32::consts::TAU;
            let r = major + minor * b.cos();
            positions.push(Vec3::new(r * a.cos(), minor * b.sin(), r * a.sin()));
        }
    }
    let index = |i: u32, j: u32| (i % around) * tube + j % tube;
    let mut triangles = Vec::new();
    for i in 0..around {
        for j in 0..tube {
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            triangles.push([a, c, b]);
            triangles.push([a, d, c]);
        }
    }
    let mesh = chamfer_preprocess::mesh::Mesh {
        positions,
        triangles,
        ..Default::default()
    };
    chamfer_preprocess::bake(mesh, "torus", &chamfer_preprocess::BakeOptions::DEFAULT)
        .expect("bake")
        .asset
}

#[test]
fn a_torus_cut_through_its_hole_shows_two_discs() {
    let (major, minor) = (1.0, 0.35);
    let asset = torus(major, minor, 48, 24);
    let orbit = Orbit {
        azimuth: 30.0,
        elevation: 12.0,
        ..Orbit::default()
    };
    let camera = Camera::orbit([[-1.4, -0.4, -1.4], [1.4, 0.4, 1.4]], &orbit, [256, 256]);
    // The plane through the axis that faces the camera: the discs at ±major along `across`.
    let eye = camera.eye().truncate();
    let normal = Vec3::new(eye.x, 0.0, eye.z).normalize();
    let across = Vec3::Y.cross(normal);
    let cut = CutStyle {
        section: ClipPlanes::new(&[Plane {
            normal: normal.as_dvec3().to_array(),
            offset: 0.0,
        }]),
        cap: CapStyle {
            color: GREEN,
            hatch: None,
        },
        outline: Some(CutOutline {
            color: YELLOW,
            width_px: 3.0,
        }),
        caps: true,
    };
    let image = cut_picture(
        &asset,
        &camera,
        Some(&cut),
        &edges_in(RED, 2.0, CapMethod::NextIndex),
    );
    for side in [-1.0, 1.0] {
        let centre = across * major * side;
        for (du, dv) in [(0.0, 0.0), (0.6, 0.0), (-0.6, 0.0), (0.0, 0.6), (0.0, -0.6)] {
            let q = centre + (across * du + Vec3::Y * dv) * minor;
            let pixel = pixel_at(&image, project(&camera, q));
            assert!(is_green(pixel), "disc at {side}: {q} is {pixel:?}");
        }
    }
    // Each disc's rim is outlined.
    for side in [-1.0, 1.0] {
        let centre = across * major * side;
        for q in [
            centre + across * minor,
            centre - across * minor,
            centre + Vec3::Y * minor,
        ] {
            assert!(outlined_at(&image, &camera, q), "rim of disc {side} at {q}");
        }
    }
    // The hole between them is not capped.
    for t in [-0.4, 0.0, 0.4] {
        let pixel = pixel_at(&image, project(&camera, across * t));
        assert!(!is_green(pixel), "the hole at {t}: {pixel:?}");
    }
}

#[test]
fn an_open_mesh_gets_no_cap() {
    let camera = cube_camera(256, false);
    let open_box = bake_fixture("shapes/open-box.obj");
    let uploaded = GpuAsset::new(&gpu().device, &open_box).expect("upload");
    assert!(!uploaded.is_closed());
    assert!(
        GpuAsset::new(&gpu().device, &bake_fixture("shapes/cube.obj"))
            .expect("cube")
            .is_closed()
    );
    let cut = CutStyle {
        section: half_cube(),
        cap: CapStyle {
            color: GREEN,
            hatch: None,
        },
        outline: Some(CutOutline {
            color: YELLOW,
            width_px: 3.0,
        }),
        caps: true,
    };
    let image = cut_picture(
        &open_box,
        &camera,
        Some(&cut),
        &edges_in(RED, 2.0, CapMethod::NextIndex),
    );
    let green = image
        .rgba
        .chunks(4)
        .filter(|p| is_green([p[0], p[1], p[2], p[3]]))
        .count();
    let mesh = image
        .rgba
        .chunks(4)
        .filter(|p| !is_background([p[0], p[1], p[2], p[3]]))
        .count();
    assert_eq!(green, 0, "an open mesh is not capped");
    assert!(mesh > 1000, "the open box is drawn: {mesh} pixels");
}
