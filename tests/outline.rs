//! Issue 39: the chamfer highlight over whole frames, silhouettes and corners included, against the
//! truly rounded solids (box, cylinder, turned part; `chamfer_tests::rounded`) from random views.
//!
//! Per view, over every pixel within 2 r of a chamfer edge that has a face towards the camera
//! (outline pixels included): the mean and 99th percentile of the per-pixel error as a share of the
//! truth's lit range there, under Blinn (seed 000), PBR and an environment alone; and the coverage:
//! pixels more than half covered by one picture and not by the other. A picture's coverage is read
//! from drawing it twice, over black and over white: a pixel's share of background is their
//! difference. The truth is supersampled 4 × 4. `cargo test --release -p chamfer-tests --test outline
//! -- --nocapture` prints the table.

use std::sync::Arc;

use chamfer_preprocess::mesh::Mesh;
use chamfer_runtime::asset::{Asset, EdgeFlags, attribute_flags};
use chamfer_runtime::highlight::ggx::PbrMaterial;
use chamfer_runtime::highlight::strip::Material;
use chamfer_runtime::render::{
    Camera, EdgeClasses, EdgeStyle, Highlight, Image, Light, MeshLight, MeshStyle, Orbit, Shading,
};
use chamfer_tests::rounded::{
    BLACK, render_lit_on, render_supersampled_on, rounded_and_sharp, rounded_box, rounded_cylinder,
    rounded_turned_part, sky_with_a_light, to_pixels,
};
use glam::{Vec2, Vec3};

/// Pixels a side of the pictures compared.
const SIZE: u32 = 300;
/// Samples a side of each truth pixel.
const FACTOR: u32 = 4;
/// Random views per shape.
const VIEWS: usize = 50;
const WHITE: [f64; 4] = [1.0; 4];
/// A truth pixel is covered when more than half its samples are, not covered when fewer than half; at
/// exactly half the rounded outline crosses the pixel's middle within the samples' spacing, a tie that
/// counts neither way.
const TRUTH_COVERED: f64 = (0.5 * (FACTOR * FACTOR) as f64 + 0.5) / (FACTOR * FACTOR) as f64;
const TRUTH_UNCOVERED: f64 = (0.5 * (FACTOR * FACTOR) as f64 - 0.5) / (FACTOR * FACTOR) as f64;

const BLINN: Material = Material {
    diffuse: 0.55,
    specular: 0.35,
    shininess: 20.0,
};
const DIELECTRIC: PbrMaterial = PbrMaterial {
    base_color: [0.6; 3],
    metallic: 0.0,
    roughness: 0.45,
};
const METAL: PbrMaterial = PbrMaterial {
    base_color: [0.8; 3],
    metallic: 1.0,
    roughness: 0.35,
};

/// The three ways a view is lit.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Lit {
    Blinn,
    Pbr,
    Environment,
}

impl Lit {
    const ALL: [Lit; 3] = [Lit::Blinn, Lit::Pbr, Lit::Environment];

    fn name(self) -> &'static str {
        match self {
            Lit::Blinn => "Blinn",
            Lit::Pbr => "PBR",
            Lit::Environment => "environment",
        }
    }

    /// The faces' style and the strips' under light `towards`.
    fn styles(self, towards: Vec3) -> (MeshStyle, EdgeStyle) {
        let light = Light::Directional(towards.to_array());
        let (mesh, shading, intensity) = match self {
            Lit::Blinn => (
                MeshStyle {
                    color: [BLINN.diffuse, BLINN.diffuse, BLINN.diffuse, 1.0],
                    light: MeshLight::Model(light),
                    ambient: 0.0,
                    specular: BLINN.specular,
                    shininess: BLINN.shininess,
                    ..MeshStyle::default()
                },
                Shading::Blinn(BLINN),
                1.0,
            ),
            Lit::Pbr | Lit::Environment => {
                let (material, intensity) = if self == Lit::Pbr {
                    (DIELECTRIC, 0.6 * std::f32::consts::PI)
                } else {
                    (METAL, 0.0)
                };
                (
                    MeshStyle {
                        light: MeshLight::Model(light),
                        light_color: [intensity; 3],
                        ambient: 0.0,
                        pbr: Some(material),
                        ..MeshStyle::default()
                    },
                    Shading::Pbr(material),
                    intensity,
                )
            }
        };
        let edges = EdgeStyle {
            classes: EdgeClasses::NONE,
            highlight: Some(Highlight {
                light,
                color: [intensity; 3],
                shading,
                ambient: 0.0,
                k: None,
                ..Highlight::default()
            }),
            ..EdgeStyle::default()
        };
        (mesh, edges)
    }
}

/// A small deterministic generator (the views must be the same on every run).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn between(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }

    /// A unit vector, uniformly over the sphere.
    fn direction(&mut self) -> Vec3 {
        let z = self.between(-1.0, 1.0);
        let phi = self.between(0.0, std::f32::consts::TAU);
        let s = (1.0 - z * z).sqrt();
        Vec3::new(s * phi.cos(), z, s * phi.sin())
    }
}

/// A random view of the solids: any azimuth, elevations up to 75° either way (uniform over the
/// sphere), 5 to 8 units from the centre, one in five orthographic; a light towards the camera's side.
fn random_view(random: &mut Random) -> (Orbit, Vec3) {
    let elevation = random.between(-75f32.to_radians().sin(), 75f32.to_radians().sin());
    let orbit = Orbit {
        azimuth: random.between(0.0, 360.0),
        elevation: elevation.asin().to_degrees(),
        distance: Some(random.between(5.0, 8.0)),
        ortho: random.next() < 0.2,
        ..Orbit::default()
    };
    let camera = Camera::orbit([[-1.0; 3], [1.0; 3]], &orbit, [SIZE; 2]);
    let eye = camera.eye();
    // Towards the camera from the centre (the eye's direction when orthographic).
    let towards_eye = eye.truncate().normalize();
    // Lights from anywhere on the viewer's half, so highlights land on strips, corners and outlines.
    let mut light = random.direction();
    if light.dot(towards_eye) < 0.0 {
        light -= 2.0 * light.dot(towards_eye) * towards_eye;
    }
    (orbit, light)
}

/// The chamfer edges of `sharp` with a face towards `camera`, on screen: end points in pixels and
/// the radius there in pixels.
fn seen_chamfer_edges(sharp: &Asset, camera: &Camera) -> Vec<(Vec2, Vec2, f32)> {
    let eye = camera.eye();
    let vp = camera.view_projection();
    let p = |v: u32| Vec3::from(sharp.topology_positions[v as usize]);
    let faces_eye = |n: Vec3, on: Vec3| n.dot(eye.truncate() - on * eye.w) > 0.0;
    let mut seen = Vec::new();
    for (e, &word) in sharp.edge_attributes.iter().enumerate() {
        let flags = attribute_flags(word);
        if !flags.contains(EdgeFlags::CHAMFER) {
            continue;
        }
        let [v0, v1, v2, v3] = std::array::from_fn(|k| p(sharp.edge_vertices.get(4 * e + k)));
        let a = (v1 - v0).cross(v2 - v0);
        let mut b = (v0 - v1).cross(v3 - v1);
        if flags.contains(EdgeFlags::FLIPPED) {
            b = -b;
        }
        if !faces_eye(a, v0) && !faces_eye(b, v1) {
            continue;
        }
        let middle = 0.5 * (v0 + v1);
        let w = (vp * middle.extend(1.0)).w;
        let radius_px = chamfer_runtime::asset::attribute_radius(word, sharp.header.radius_scale)
            / (camera.pixel_scale() * w);
        seen.push((to_pixels(camera, v0), to_pixels(camera, v1), radius_px));
    }
    seen
}

/// The pixels whose centres lie within 2 r of a seen chamfer edge.
fn pixels_near_edges(edges: &[(Vec2, Vec2, f32)]) -> Vec<(u32, u32)> {
    let mut near = vec![false; (SIZE * SIZE) as usize];
    for &(a, b, r) in edges {
        let reach = 2.0 * r;
        let lo = a.min(b) - Vec2::splat(reach + 1.0);
        let hi = a.max(b) + Vec2::splat(reach + 1.0);
        let clamp = |v: f32| v.clamp(0.0, SIZE as f32 - 1.0) as u32;
        for y in clamp(lo.y)..=clamp(hi.y) {
            for x in clamp(lo.x)..=clamp(hi.x) {
                let q = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                let t = ((q - a).dot(b - a) / (b - a).length_squared().max(1e-12)).clamp(0.0, 1.0);
                if q.distance(a + t * (b - a)) <= reach {
                    near[(y * SIZE + x) as usize] = true;
                }
            }
        }
    }
    (0..SIZE * SIZE)
        .filter(|&i| near[i as usize])
        .map(|i| (i % SIZE, i / SIZE))
        .collect()
}

fn value(image: &Image, (x, y): (u32, u32)) -> f64 {
    let p = image.pixel(x, y);
    (f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2])) / (3.0 * 255.0)
}

/// How much of each pixel a picture covers, from the same picture over black and over white.
fn coverage(black: &Image, white: &Image, pixel: (u32, u32)) -> f64 {
    1.0 - (value(white, pixel) - value(black, pixel))
}

/// Per-pixel errors of `ours` against `truth` as shares of the truth's lit range over `pixels`.
fn errors(ours: &Image, truth: &Image, pixels: &[(u32, u32)]) -> Vec<f64> {
    let (lo, hi) = pixels.iter().fold((f64::MAX, f64::MIN), |(lo, hi), &p| {
        (lo.min(value(truth, p)), hi.max(value(truth, p)))
    });
    let range = (hi - lo).max(1e-6);
    pixels
        .iter()
        .map(|&p| (value(ours, p) - value(truth, p)).abs() / range)
        .collect()
}

fn percentile(values: &mut [f64], share: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values
        .get(((values.len() as f64 * share) as usize).min(values.len().saturating_sub(1)))
        .copied()
        .unwrap_or(0.0)
}

/// What a shape's views add up to.
#[derive(Default)]
struct Tally {
    pixels: usize,
    overhang: usize,
    missing: usize,
    /// Per lighting: every per-pixel error, and the worst view's mean.
    errors: [Vec<f64>; 3],
    worst_view: [f64; 3],
    /// The view with the most pixels covered by ours and not the truth: (pixels, view).
    worst_overhang: (usize, usize),
    /// Time in the truth's renders and in ours (for BENCHMARKS: what the validation costs).
    truth_time: std::time::Duration,
    ours_time: std::time::Duration,
}

/// The box of radius `r` from `chamfer render`'s default camera direction, rounded and sharp with the
/// highlight, whole and around its upper left silhouette corner (4× larger), for docs/highlight.md:
/// written to the temporary folder as `chamfer-outline-{truth,ours}{,-corner}.png`.
fn save_pictures(r: f32) {
    let orbit = Orbit {
        distance: Some(6.0),
        ..Orbit::default()
    };
    let camera = Camera::orbit([[-1.0; 3], [1.0; 3]], &orbit, [SIZE; 2]);
    let (rounded, sharp) = rounded_and_sharp(rounded_box, r);
    let (mesh, edges) = Lit::Pbr.styles(Vec3::new(0.3, 0.9, 0.5).normalize());
    let truth = render_supersampled_on(&rounded, &orbit, SIZE, &mesh, FACTOR, None, WHITE);
    let ours = render_lit_on(&sharp, &camera, &mesh, Some(&edges), None, WHITE);
    let corner = to_pixels(&camera, Vec3::new(-1.0, 1.0, 1.0));
    for (what, image) in [("truth", &truth), ("ours", &ours)] {
        let folder = std::env::temp_dir();
        chamfer_tests::save_png(image, &folder.join(format!("chamfer-outline-{what}.png")));
        chamfer_tests::save_png(
            &crop(image, corner, 64),
            &folder.join(format!("chamfer-outline-{what}-corner.png")),
        );
    }
}

/// The `size` × `size` pixels of `image` around `centre`, each drawn as 4 × 4.
fn crop(image: &Image, centre: Vec2, size: u32) -> Image {
    let zoom = 4;
    let x0 = (centre.x as u32).saturating_sub(size / 2);
    let y0 = (centre.y as u32).saturating_sub(size / 2);
    let mut rgba = Vec::with_capacity((size * size * zoom * zoom * 4) as usize);
    for y in 0..size * zoom {
        for x in 0..size * zoom {
            let (px, py) = (
                (x0 + x / zoom).min(image.width - 1),
                (y0 + y / zoom).min(image.height - 1),
            );
            rgba.extend_from_slice(&image.pixel(px, py));
        }
    }
    Image {
        width: size * zoom,
        height: size * zoom,
        rgba,
    }
}

#[test]
fn whole_frames_of_the_highlight_match_the_rounded_solids() {
    let shapes: [(&str, fn(f32) -> Mesh); 3] = [
        ("box", rounded_box),
        ("cylinder", rounded_cylinder),
        ("turned part", rounded_turned_part),
    ];
    // Radii of about 3 and 6 px at 6 units (the views' distances spread them from 2 to 7 px).
    let reference = Camera::orbit(
        [[-1.0; 3], [1.0; 3]],
        &Orbit {
            distance: Some(6.0),
            ..Orbit::default()
        },
        [SIZE; 2],
    );
    let unit_px = 1.0 / (reference.pixel_scale() * 6.0);
    let radii = [3.0 / unit_px, 6.0 / unit_px];
    let environment = Arc::new(sky_with_a_light(Vec3::new(0.3, 0.8, 0.5)));
    save_pictures(radii[1]);
    let mut random = Random(39);
    let views: Vec<(Orbit, Vec3)> = (0..VIEWS).map(|_| random_view(&mut random)).collect();
    println!(
        "| shape | views | pixels near chamfer edges | covered by ours, not the truth | by the truth, not ours | lighting | mean error / lit range | worst view | 99th percentile |"
    );
    println!("|---|---:|---:|---:|---:|---|---:|---:|---:|");
    let (mut all_pixels, mut all_overhang) = (0usize, 0usize);
    let mut worst_mean = [0.0f64; 3];
    for (name, shape) in shapes {
        let solids = radii.map(|r| rounded_and_sharp(shape, r));
        let mut tally = Tally::default();
        for (k, (orbit, towards)) in views.iter().enumerate() {
            let (rounded, sharp) = &solids[k % 2];
            let camera = Camera::orbit([[-1.0; 3], [1.0; 3]], orbit, [SIZE; 2]);
            let pixels = pixels_near_edges(&seen_chamfer_edges(sharp, &camera));
            if pixels.is_empty() {
                continue;
            }
            for (l, lit) in Lit::ALL.into_iter().enumerate() {
                let (mesh, edges) = lit.styles(*towards);
                let env = (lit == Lit::Environment).then_some(&environment);
                let started = std::time::Instant::now();
                let truth = render_supersampled_on(rounded, orbit, SIZE, &mesh, FACTOR, env, BLACK);
                tally.truth_time += started.elapsed();
                let started = std::time::Instant::now();
                let ours = render_lit_on(sharp, &camera, &mesh, Some(&edges), env, BLACK);
                tally.ours_time += started.elapsed();
                if lit == Lit::Blinn {
                    let truth_white =
                        render_supersampled_on(rounded, orbit, SIZE, &mesh, FACTOR, env, WHITE);
                    let ours_white = render_lit_on(sharp, &camera, &mesh, Some(&edges), env, WHITE);
                    let mut overhang = 0;
                    for &p in &pixels {
                        let (o, t) = (
                            coverage(&ours, &ours_white, p),
                            coverage(&truth, &truth_white, p),
                        );
                        overhang += usize::from(o >= 0.5 && t < TRUTH_UNCOVERED);
                        tally.missing += usize::from(t > TRUTH_COVERED && o < 0.5);
                    }
                    tally.overhang += overhang;
                    tally.worst_overhang = tally.worst_overhang.max((overhang, k));
                    tally.pixels += pixels.len();
                }
                let e = errors(&ours, &truth, &pixels);
                let mean = e.iter().sum::<f64>() / e.len() as f64;
                tally.worst_view[l] = tally.worst_view[l].max(mean);
                tally.errors[l].extend(e);
            }
        }
        all_pixels += tally.pixels;
        all_overhang += tally.overhang;
        println!(
            "{name}: the truth's renders took {:.1} s, ours {:.1} s (Blinn's white-background pair not counted)",
            tally.truth_time.as_secs_f64(),
            tally.ours_time.as_secs_f64()
        );
        let (over, view) = tally.worst_overhang;
        println!(
            "{name}: the most pixels covered by ours and not the truth, {over}, in view {view}: {:?}",
            views[view].0
        );
        for (l, lit) in Lit::ALL.into_iter().enumerate() {
            let e = &mut tally.errors[l];
            let mean = e.iter().sum::<f64>() / e.len().max(1) as f64;
            worst_mean[l] = worst_mean[l].max(mean);
            let p99 = percentile(e, 0.99);
            println!(
                "| {name} | {VIEWS} | {} | {} ({:.3} %) | {} ({:.3} %) | {} | {:.2} % | {:.2} % | {:.1} % |",
                tally.pixels,
                tally.overhang,
                100.0 * tally.overhang as f64 / tally.pixels.max(1) as f64,
                tally.missing,
                100.0 * tally.missing as f64 / tally.pixels.max(1) as f64,
                lit.name(),
                mean * 100.0,
                tally.worst_view[l] * 100.0,
                p99 * 100.0,
            );
        }
    }
    let overhang = all_overhang as f64 / all_pixels.max(1) as f64;
    println!(
        "covered by ours and not the truth: {:.3} % of {all_pixels} pixels; worst mean error: Blinn {:.2} %, PBR {:.2} %, environment {:.2} %",
        overhang * 100.0,
        worst_mean[0] * 100.0,
        worst_mean[1] * 100.0,
        worst_mean[2] * 100.0
    );
    assert!(
        overhang <= 0.001,
        "{:.3} % of the pixels near chamfer edges are covered by ours and not the rounded truth (at most 0.1 %)",
        overhang * 100.0
    );
    for (l, lit) in Lit::ALL.into_iter().enumerate() {
        assert!(
            worst_mean[l] <= 0.01,
            "{}: a shape's mean error is {:.2} % of the lit range (at most 1 %)",
            lit.name(),
            worst_mean[l] * 100.0
        );
    }
}

/// Issue 39: every asset renders with the highlight on (an empty corner buffer used to fail the
/// frame): a box baked without a radius (no chamfer edges: the frame is the one without the
/// highlight), the cylinder (chamfer edges, no corner where three rounded edges meet) and the box
/// with a radius (rounded corners).
#[test]
fn the_highlight_renders_with_and_without_chamfer_edges_and_corners() {
    let r = 0.1;
    let plain = chamfer_preprocess::bake(
        rounded_box(0.0),
        "plain",
        &chamfer_preprocess::BakeOptions::DEFAULT,
    )
    .expect("bake")
    .asset;
    let (_, cylinder) = rounded_and_sharp(rounded_cylinder, r);
    let (_, rounded) = rounded_and_sharp(rounded_box, r);
    let orbit = Orbit::default();
    let camera = Camera::orbit([[-1.0; 3], [1.0; 3]], &orbit, [120, 90]);
    let (mesh, edges) = Lit::Pbr.styles(Vec3::new(0.3, 0.9, 0.5).normalize());
    let without = EdgeStyle {
        highlight: None,
        ..edges
    };
    for (name, asset, strips) in [
        ("no chamfer edges", &plain, false),
        ("chamfer edges, no corners", &cylinder, true),
        ("corners", &rounded, true),
    ] {
        let lit = render_lit_on(asset, &camera, &mesh, Some(&edges), None, BLACK);
        let unlit = render_lit_on(asset, &camera, &mesh, Some(&without), None, BLACK);
        let changed = lit
            .rgba
            .chunks(4)
            .zip(unlit.rgba.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        eprintln!("{name}: {changed} pixels changed by the highlight");
        if strips {
            assert!(changed > 100, "{name}: {changed} pixels");
        } else {
            assert_eq!(changed, 0, "{name}");
        }
    }
}
