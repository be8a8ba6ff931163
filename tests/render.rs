//! Headless pixel tests of the wgpu runtime on whatever adapter the machine has (Mesa's lavapipe on
//! CI). Each test bakes a fixture, renders it with a known camera and looks at the pixels where the
//! geometry says edges, faces, corners and silhouettes must land.

use chamfer_runtime::render::{
    Camera, CapMethod, EdgeClasses, EdgeColors, EdgeStyle, Image, MeshStyle, Orbit,
};
use chamfer_tests::{bake_fixture, render};
use glam::{Vec2, Vec3};

const RED: [f32; 4] = [1.0, 0.0, 0.0, 1.0];
const BLUE_BACKGROUND: [f64; 4] = [0.0, 0.0, 1.0, 1.0];

fn grey_mesh() -> MeshStyle {
    MeshStyle {
        color: [0.5, 0.5, 0.5, 1.0],
        ambient: 1.0,
        ..MeshStyle::default()
    }
}

fn edges_in(color: [f32; 4], width_px: f32, caps: CapMethod) -> EdgeStyle {
    EdgeStyle {
        colors: EdgeColors {
            contour: color,
            boundary: color,
            marked: color,
            ridge: color,
            valley: color,
        },
        width_px,
        caps,
        ..EdgeStyle::default()
    }
}

fn is_red(p: [u8; 4]) -> bool {
    p[0] > 200 && p[1] < 60 && p[2] < 60
}

fn is_background(p: [u8; 4]) -> bool {
    p[2] > 200 && p[0] < 60
}

/// Where `p` lands, in pixels from the top left (the shaders' convention).
fn project(camera: &Camera, p: Vec3) -> Vec2 {
    let c = camera.view_projection() * p.extend(1.0);
    let [w, h] = camera.viewport.map(|v| v as f32);
    Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h)
}

fn pixel_at(image: &Image, p: Vec2) -> [u8; 4] {
    image.pixel(p.x as u32, p.y as u32)
}

/// Pixels within `radius` of `center`.
fn disk(image: &Image, center: Vec2, radius: f32) -> Vec<[u8; 4]> {
    let mut pixels = Vec::new();
    for y in (center.y - radius).floor() as i32..=(center.y + radius).ceil() as i32 {
        for x in (center.x - radius).floor() as i32..=(center.x + radius).ceil() as i32 {
            let inside = Vec2::new(x as f32 + 0.5, y as f32 + 0.5).distance(center) <= radius;
            if inside && x >= 0 && y >= 0 && (x as u32) < image.width && (y as u32) < image.height {
                pixels.push(image.pixel(x as u32, y as u32));
            }
        }
    }
    pixels
}

/// The unit cube of `fixtures/shapes/cube.obj`: corner `i` is at the bits of `i` (x, y, z).
fn corner(i: usize) -> Vec3 {
    Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32)
}

/// The cube's 12 edges as corner pairs, each with the outward normals of its two faces.
fn cube_edges() -> Vec<(usize, usize, [Vec3; 2])> {
    let mut edges = Vec::new();
    for axis in 0..3 {
        for c in 0..8usize {
            if c & (1 << axis) != 0 {
                continue;
            }
            let normals: Vec<Vec3> = (0..3)
                .filter(|&b| b != axis)
                .map(|b| {
                    let sign = if c & (1 << b) != 0 { 1.0 } else { -1.0 };
                    Vec3::from_array(std::array::from_fn(|k| if k == b { sign } else { 0.0 }))
                })
                .collect();
            edges.push((c, c | (1 << axis), [normals[0], normals[1]]));
        }
    }
    edges
}

fn distance_to_segment(p: Vec2, (a, b): (Vec2, Vec2)) -> f32 {
    let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
    p.distance(a.lerp(b, t))
}

fn faces_eye(camera: &Camera, normal: Vec3, on_face: Vec3) -> bool {
    let eye = camera.eye();
    normal.dot(eye.truncate() - on_face * eye.w) > 0.0
}

fn cube_camera(size: u32, orthographic: bool) -> Camera {
    let orbit = Orbit {
        azimuth_deg: 35.0,
        elevation_deg: 28.0,
        orthographic,
        ..Orbit::default()
    };
    Camera::orbit([[0.0; 3], [1.0; 3]], &orbit, [size, size])
}

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
        let edges: Vec<(usize, usize, bool)> = cube_edges()
            .into_iter()
            .map(|(a, b, normals)| {
                let middle = (corner(a) + corner(b)) * 0.5;
                (a, b, normals.iter().any(|&n| faces_eye(&camera, n, middle)))
            })
            .collect();
        let on_screen = |a: usize, b: usize| (project(&camera, corner(a)), project(&camera, corner(b)));
        let near_visible_edge = |p: Vec2| {
            edges
                .iter()
                .filter(|e| e.2)
                .any(|&(a, b, _)| distance_to_segment(p, on_screen(a, b)) < 5.0)
        };
        let visible = edges.iter().filter(|e| e.2).count();
        let mut hidden_checked = 0;
        for &(a, b, seen) in &edges {
            for t in [0.3, 0.4, 0.5, 0.6, 0.7] {
                // Within 2 px: a silhouette edge lies outside its line (a half quad), a crease on it.
                let p = project(&camera, corner(a).lerp(corner(b), t));
                if !seen && near_visible_edge(p) {
                    continue; // a hidden edge crossing behind a visible one in the picture
                }
                hidden_checked += usize::from(!seen);
                let red = disk(&image, p, 2.0).into_iter().any(is_red);
                assert_eq!(
                    red, seen,
                    "edge {a}-{b} at t = {t} ({p}), visible: {seen}, ortho: {orthographic}"
                );
            }
        }
        assert_eq!(visible, 9, "the camera must see three faces");
        assert!(hidden_checked >= 8, "only {hidden_checked} hidden samples");
        // Inside the visible faces: the mesh, not edge colour.
        for axis in 0..3 {
            for side in [0.0, 1.0] {
                let normal = Vec3::from_array(std::array::from_fn(|k| {
                    if k == axis { side * 2.0 - 1.0 } else { 0.0 }
                }));
                let center = Vec3::splat(0.5) + normal * 0.5;
                if faces_eye(&camera, normal, center) {
                    let pixel = pixel_at(&image, project(&camera, center));
                    assert!(!is_red(pixel) && !is_background(pixel), "face {normal}: {pixel:?}");
                }
            }
        }
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
    let image = render(&asset, &camera, Some(&grey_mesh()), Some(&style), BLUE_BACKGROUND);
    let hidden_corner = (0..8)
        .find(|&c| {
            cube_edges()
                .iter()
                .filter(|e| e.0 == c || e.1 == c)
                .all(|(a, b, normals)| {
                    let middle = (corner(*a) + corner(*b)) * 0.5;
                    !normals.iter().any(|&n| faces_eye(&camera, n, middle))
                })
        })
        .expect("a corner whose three edges are all hidden");
    let p = project(&camera, corner(hidden_corner));
    assert!(disk(&image, p, 2.0).into_iter().any(is_red), "hidden corner {hidden_corner} at {p}");
}
