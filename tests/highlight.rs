//! The chamfer highlight against real rounded geometry (seed 000, Fig. 5): the same box (1) with its
//! edges truly rounded — fillets of radius r, finely tessellated, shaded per pixel with Blinn–Phong — and
//! (2) sharp, with the highlight, under the same camera, light and material. The light summed over each
//! edge's region must agree; `cargo test -p chamfer-tests --test highlight -- --nocapture` prints the sweep.

use chamfer_preprocess::mesh::Mesh;
use chamfer_preprocess::{BakeOptions, Radius, bake};
use chamfer_runtime::highlight::strip::Material;
use chamfer_runtime::render::{
    Camera, EdgeClasses, EdgeStyle, Highlight, Image, Light, MeshLight, MeshStyle, Orbit,
};
use chamfer_tests::render;
use glam::{Vec2, Vec3};

/// The box [-1, 1]³, its edges rounded with radius `r` (0: sharp). Each face is a grid whose lines
/// crowd into the rounded bands so every fillet gets `BAND` segments per quarter turn; grid points are
/// pushed onto the rounded box (the inner box grown by a sphere of radius r).
fn rounded_box(r: f32) -> Mesh {
    const BAND: usize = 16;
    const INTERIOR: usize = 24;
    let inner = 1.0 - r;
    let mut coords: Vec<f32> = Vec::new();
    if r > 0.0 {
        coords.extend(
            (1..=BAND).rev().map(|k| {
                -(inner + r * (k as f32 / BAND as f32 * std::f32::consts::FRAC_PI_4).tan())
            }),
        );
    } else {
        coords.push(-1.0);
    }
    coords.extend((0..=INTERIOR).map(|k| -inner + 2.0 * inner * k as f32 / INTERIOR as f32));
    if r > 0.0 {
        coords.extend(
            (1..=BAND)
                .map(|k| inner + r * (k as f32 / BAND as f32 * std::f32::consts::FRAC_PI_4).tan()),
        );
    } else {
        coords.push(1.0);
    }
    let n = coords.len();
    let mut mesh = Mesh::default();
    for axis in 0..3 {
        for side in [-1.0f32, 1.0] {
            // (u, v) axes with u × v along the outward normal.
            let (u_axis, v_axis) = if side > 0.0 {
                ((axis + 1) % 3, (axis + 2) % 3)
            } else {
                ((axis + 2) % 3, (axis + 1) % 3)
            };
            let base = mesh.positions.len() as u32;
            for &u in &coords {
                for &v in &coords {
                    let mut p = [0.0f32; 3];
                    p[axis] = side;
                    p[u_axis] = u;
                    p[v_axis] = v;
                    let p = Vec3::from(p);
                    let q = p.clamp(Vec3::splat(-inner), Vec3::splat(inner));
                    mesh.positions.push(if r > 0.0 {
                        q + (p - q).normalize() * r
                    } else {
                        p
                    });
                }
            }
            for i in 0..n - 1 {
                for j in 0..n - 1 {
                    let at = |a: usize, b: usize| base + (a * n + b) as u32;
                    mesh.triangles
                        .push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                    mesh.triangles
                        .push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
    }
    mesh.materials = vec![0; mesh.triangles.len()];
    mesh
}

const MATERIAL: Material = Material {
    diffuse: 0.55,
    specular: 0.35,
    shininess: 20.0,
};

/// Light summed over the middle 60 % of each edge whose faces both face the camera, within
/// `reach` pixels across it, for the rounded and the highlighted box.
fn edge_light(r: f32, light: Light, camera: &Camera) -> Vec<(f64, f64, f64)> {
    let mesh_style = MeshStyle {
        color: [MATERIAL.diffuse, MATERIAL.diffuse, MATERIAL.diffuse, 1.0],
        light: MeshLight::Model(light),
        ambient: 0.0,
        specular: MATERIAL.specular,
        shininess: MATERIAL.shininess,
    };
    let smooth = BakeOptions::DEFAULT.with_crease_deg(60.0);
    let rounded = bake(rounded_box(r), "rounded", &smooth)
        .expect("rounded box")
        .asset;
    let sharp = bake(
        rounded_box(0.0),
        "box",
        &BakeOptions::DEFAULT.with_radius(Radius::Absolute(r)),
    )
    .expect("box")
    .asset;
    let eye = camera.eye().truncate();
    let center_distance = eye.length();
    let highlight = EdgeStyle {
        classes: EdgeClasses::NONE,
        highlight: Some(Highlight {
            light,
            color: [1.0; 3],
            material: MATERIAL,
            ambient: 0.0,
            k: Some(center_distance),
        }),
        ..EdgeStyle::default()
    };
    let black = [0.0, 0.0, 0.0, 1.0];
    let truth = render(&rounded, camera, Some(&mesh_style), None, black);
    let ours = render(&sharp, camera, Some(&mesh_style), Some(&highlight), black);
    let plain = render(&sharp, camera, Some(&mesh_style), None, black);

    let project = |p: Vec3| {
        let c = camera.view_projection() * p.extend(1.0);
        let [w, h] = camera.viewport.map(|v| v as f32);
        Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h)
    };
    let radius_px = r / (camera.pixel_scale() * center_distance);
    let reach = (2.0 * radius_px).max(0.0) + 3.0;
    let mut sums = Vec::new();
    for axis in 0..3 {
        for corner in 0..4 {
            let signs = [
                if corner & 1 == 0 { -1.0 } else { 1.0 },
                if corner & 2 == 0 { -1.0 } else { 1.0 },
            ];
            let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
            let normals = [b, c]
                .map(|k| Vec3::from_array(std::array::from_fn(|i| if i == k { 1.0 } else { 0.0 })));
            let (nb, nc) = (normals[0] * signs[0], normals[1] * signs[1]);
            let mut a = [0.0f32; 3];
            a[b] = signs[0];
            a[c] = signs[1];
            let (mut start, mut end) = (Vec3::from(a), Vec3::from(a));
            start[axis] = -1.0;
            end[axis] = 1.0;
            let middle = (start + end) * 0.5;
            if nb.dot(eye - middle) <= 0.0 || nc.dot(eye - middle) <= 0.0 {
                continue;
            }
            let (ps, pe) = (project(start), project(end));
            let along = (pe - ps).normalize();
            let across = Vec2::new(-along.y, along.x);
            let mut pixels = std::collections::HashSet::new();
            let length = ps.distance(pe);
            for k in 0..(length * 0.6 * 4.0) as i32 {
                let p = ps + along * (0.2 * length + k as f32 * 0.25);
                for j in 0..=(8.0 * reach) as i32 {
                    let q = p + across * (j as f32 * 0.25 - reach);
                    pixels.insert((q.x as u32, q.y as u32));
                }
            }
            let sum = |image: &Image| -> f64 {
                pixels
                    .iter()
                    .map(|&(x, y)| f64::from(image.pixel(x, y)[0]) / 255.0)
                    .sum()
            };
            sums.push((sum(&ours), sum(&truth), sum(&plain)));
        }
    }
    sums
}

#[test]
fn the_highlight_carries_the_light_of_real_fillets() {
    let orbit = Orbit {
        azimuth_deg: 30.0,
        elevation_deg: 24.0,
        distance: Some(6.0),
        ..Orbit::default()
    };
    let camera = Camera::orbit([[-1.0; 3], [1.0; 3]], &orbit, [360, 360]);
    let pixels_per_unit = 1.0 / (camera.pixel_scale() * 6.0);
    let lights = [
        Light::Directional([0.3, 0.9, 0.5]),
        Light::Directional([0.9, 0.3, 0.6]),
        Light::Directional([-0.2, 0.6, 0.9]),
        Light::Directional([0.6, 0.6, 0.2]),
        // A point light 5 units from the box's centre: its direction changes along each edge.
        Light::Point([2.0, 4.0, 2.5]),
    ];
    let (mut worst, mut plain_worst) = (0.0f64, 0.0f64);
    println!(
        "| r (px) | light | edge light, highlight / rounded, 3 edges | error | sharp box without highlight: error |"
    );
    println!("|---:|---|---|---:|---:|");
    for radius_px in [0.6f32, 1.5, 3.0, 6.0] {
        let r = radius_px / pixels_per_unit;
        for light in lights {
            let sums = edge_light(r, light, &camera);
            assert_eq!(sums.len(), 3, "three edges face the camera");
            let worst_of = |pick: fn(&(f64, f64, f64)) -> f64| {
                sums.iter()
                    .map(|s| (pick(s) - s.1).abs() / s.1)
                    .fold(0.0, f64::max)
            };
            let (row, row_plain) = (worst_of(|s| s.0), worst_of(|s| s.2));
            worst = worst.max(row);
            if radius_px >= 3.0 {
                plain_worst = plain_worst.max(row_plain);
            }
            let pairs: Vec<String> = sums
                .iter()
                .map(|(o, t, _)| format!("{o:.1} / {t:.1}"))
                .collect();
            let light = match light {
                Light::Directional([x, y, z]) => format!("towards {x}, {y}, {z}"),
                Light::Point([x, y, z]) => format!("point at {x}, {y}, {z}"),
            };
            println!(
                "| {radius_px} | {light} | {} | {:.2} % | {:.1} % |",
                pairs.join(", "),
                row * 100.0,
                row_plain * 100.0
            );
        }
    }
    println!("worst: {:.2} %", worst * 100.0);
    // Measured: at most 0.94 % over this sweep, point light included (lavapipe, 1 sample). What is
    // left comes from the paper's own approximations (light and viewer directions taken at each edge's middle, the
    // corners ignored), from rasterizing the tessellated fillets and from 8-bit output. The bound
    // leaves room for other rasterizers while staying far below what the highlight contributes:
    // the same box drawn without it is off by the `plain` column (asserted above 3 % at r >= 3 px).
    assert!(plain_worst > 0.03, "the control must differ: {plain_worst}");
    assert!(worst < 0.025, "worst relative error {:.2} %", worst * 100.0);
}
