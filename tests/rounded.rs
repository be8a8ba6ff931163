//! Solids with truly rounded edges, and the same solids sharp, for validating the chamfer highlight
//! against real fillets (seed 000, Fig. 5): a box, a cylinder and a turned part (a flat top, a 45° cone,
//! a cylinder), tessellated finely, with the renders the validations compare (supersampled truth).

use std::sync::Arc;

use chamfer_preprocess::mesh::Mesh;
use chamfer_preprocess::{BakeOptions, Radius, bake};
use chamfer_runtime::highlight::environment::Environment;
use chamfer_runtime::render::{
    Camera, EdgeRenderer, EdgeStyle, GpuAsset, Image, MeshRenderer, MeshStyle, Orbit,
};
use glam::{Vec2, Vec3};

/// The box [-1, 1]³, its edges rounded with radius `r` (0: sharp). Each face is a grid whose lines
/// crowd into the rounded bands so every fillet gets `BAND` segments per quarter turn; grid points are
/// pushed onto the rounded box (the inner box grown by a sphere of radius r).
pub fn rounded_box(r: f32) -> Mesh {
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
        // A line just inside each band, so the normals interpolated across the last flat cell turn
        // only within a twentieth of r of the band (as the real surface does), not across the cell.
        let near = inner - 0.05 * r;
        coords.insert(BAND + 1, -near);
        coords.insert(coords.len() - 1, near);
    }
    if r > 0.0 {
        coords.extend(
            (1..=BAND)
                .map(|k| inner + r * (k as f32 / BAND as f32 * std::f32::consts::FRAC_PI_4).tan()),
        );
    } else {
        coords.push(1.0);
    }
    assert!(
        coords.windows(2).all(|w| w[0] <= w[1]),
        "grid lines in order"
    );
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

/// A shape baked twice: truly rounded with radius `r` (smooth normals across its fillets), and sharp
/// with `r` as every crease's chamfer radius.
pub fn rounded_and_sharp(
    shape: fn(f32) -> Mesh,
    r: f32,
) -> (chamfer_runtime::asset::Asset, chamfer_runtime::asset::Asset) {
    let smooth = BakeOptions::DEFAULT.with_crease_deg(60.0);
    let rounded = bake(shape(r), "rounded", &smooth).expect("rounded").asset;
    let chamfered = BakeOptions::DEFAULT.with_radius(Radius::Absolute(r));
    let sharp = bake(shape(0.0), "sharp", &chamfered).expect("sharp").asset;
    (rounded, sharp)
}

/// Where `p` lands in `camera`'s picture, in pixels from the top left.
pub fn to_pixels(camera: &Camera, p: Vec3) -> Vec2 {
    let c = camera.view_projection() * p.extend(1.0);
    let [w, h] = camera.viewport.map(|v| v as f32);
    Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h)
}

/// A cylinder of radius 1 along y from −1 to 1, both rims rounded with radius `r` (0: sharp), turned
/// by `lathe`.
pub fn rounded_cylinder(r: f32) -> Mesh {
    const BAND: usize = 16;
    let inner = 1.0 - r;
    // The profile (ρ, y) from the top's centre to the bottom's.
    // Each flat part gets a ring a twentieth of r before its fillet, so interpolated normals turn
    // only there (see rounded_box).
    let near = inner - 0.05 * r;
    let quarter = |k: usize| k as f32 / BAND as f32 * std::f32::consts::FRAC_PI_2;
    let mut profile: Vec<(f32, f32)> = (0..=8).map(|k| (near * k as f32 / 8.0, 1.0)).collect();
    if r > 0.0 {
        profile.push((inner, 1.0));
        profile.extend(
            (1..=BAND).map(|k| (inner + r * quarter(k).sin(), inner + r * quarter(k).cos())),
        );
        profile.push((1.0, near));
    }
    profile.extend((1..24).map(|k| (1.0, near - 2.0 * near * k as f32 / 24.0)));
    profile.push((1.0, -near));
    if r > 0.0 {
        profile.push((1.0, -inner));
        profile.extend(
            (1..=BAND).map(|k| (inner + r * quarter(k).cos(), -inner - r * quarter(k).sin())),
        );
        profile.push((near, -1.0));
    }
    profile.extend((1..=8).map(|k| (near * (1.0 - k as f32 / 8.0), -1.0)));

    lathe(&profile)
}

/// The sharp profile (ρ, y) of the turned part, from the top's centre to the bottom's: a flat top, a
/// 45° cone, a cylinder and a flat bottom. Its rims turn by 45°, 45° and 90°: oblique creases between
/// flat and curved faces, the kind the fandisk has, where the box's and the cylinder's are square.
pub const TURNED_PROFILE: [(f32, f32); 5] =
    [(0.0, 0.6), (0.4, 0.6), (1.0, 0.0), (1.0, -1.0), (0.0, -1.0)];

/// The turned part, its rims rounded with radius `r` (0: sharp). Every corner of the profile is
/// replaced by its circular arc (16 segments per quarter turn), each straight part is cut into pieces
/// with a point a twentieth of r before each arc (see rounded_box), and the profile is turned.
pub fn rounded_turned_part(r: f32) -> Mesh {
    let p: Vec<Vec2> = TURNED_PROFILE
        .iter()
        .map(|&(x, y)| Vec2::new(x, y))
        .collect();
    // Per corner: where its arc starts and ends (the sharp corner twice when r = 0), and its points.
    let mut arcs: Vec<(Vec2, Vec2, Vec<Vec2>)> = vec![(p[0], p[0], Vec::new())];
    for k in 1..p.len() - 1 {
        let (a, b) = ((p[k] - p[k - 1]).normalize(), (p[k + 1] - p[k]).normalize());
        if r == 0.0 {
            arcs.push((p[k], p[k], Vec::new()));
            continue;
        }
        let turn = a.angle_to(b);
        let tangent = r * (0.5 * turn.abs()).tan();
        let (start, end) = (p[k] - a * tangent, p[k] + b * tangent);
        // Inwards of the profile (it runs with the solid on its right).
        let centre = start + Vec2::new(a.y, -a.x) * r;
        let steps = ((turn.abs() / std::f32::consts::FRAC_PI_2 * 16.0).ceil() as usize).max(2);
        let from = start - centre;
        let points = (1..steps)
            .map(|j| centre + Vec2::from_angle(turn * j as f32 / steps as f32).rotate(from))
            .collect();
        arcs.push((start, end, points));
    }
    let last = p[p.len() - 1];
    arcs.push((last, last, Vec::new()));
    let mut profile = Vec::new();
    for k in 0..arcs.len() - 1 {
        let (_, from, _) = &arcs[k];
        let (to, _, _) = &arcs[k + 1];
        let (from, to) = (*from, *to);
        let dir = (to - from).normalize_or_zero();
        let near = 0.05 * r;
        let (inner_from, inner_to) = (
            if k > 0 { from + dir * near } else { from },
            if k + 1 < arcs.len() - 1 {
                to - dir * near
            } else {
                to
            },
        );
        profile.push(from);
        // The rounded solid's flat runs in pieces (its normals stay the faces' up to the arcs); the
        // sharp solid's whole, or the bake would clamp its radii to the narrow pieces.
        let pieces = if r == 0.0 { 1 } else { 24 };
        profile.extend((0..=pieces).map(|j| inner_from.lerp(inner_to, j as f32 / pieces as f32)));
        profile.push(to);
        profile.extend(arcs[k + 1].2.iter().copied());
    }
    profile.push(last);
    profile.dedup_by(|a, b| a.distance(*b) < 1e-7);
    let mut points: Vec<(f32, f32)> = profile.iter().map(|q| (q.x, q.y)).collect();
    // Exactly on the axis at the two ends (the lathe closes them with fans).
    if let Some(first) = points.first_mut() {
        first.0 = 0.0;
    }
    if let Some(last) = points.last_mut() {
        last.0 = 0.0;
    }
    lathe(&points)
}

/// The solid turned from `profile` (ρ, y) about y, `AROUND` facets around; a point with ρ = 0 is one
/// vertex (the ends' fans).
pub fn lathe(profile: &[(f32, f32)]) -> Mesh {
    const AROUND: usize = 192;
    let mut mesh = Mesh::default();
    let mut rings = Vec::new();
    for &(rho, y) in profile {
        let first = mesh.positions.len() as u32;
        let count = if rho == 0.0 { 1 } else { AROUND };
        for j in 0..count {
            let phi = j as f32 / AROUND as f32 * std::f32::consts::TAU;
            mesh.positions
                .push(Vec3::new(rho * phi.cos(), y, rho * phi.sin()));
        }
        rings.push((first, count));
    }
    for pair in rings.windows(2) {
        let (ring, next) = (pair[0], pair[1]);
        let at = |(first, count): (u32, usize), j: usize| first + (j % count) as u32;
        for j in 0..AROUND {
            let (a, b, c, d) = (at(ring, j), at(ring, j + 1), at(next, j), at(next, j + 1));
            if ring.1 > 1 {
                mesh.triangles.push([a, b, c]);
            }
            if next.1 > 1 {
                mesh.triangles.push([b, d, c]);
            }
        }
    }
    mesh.materials = vec![0; mesh.triangles.len()];
    mesh
}

/// Twice the signed volume's sign check: the triangles face outwards.
pub fn faces_outwards(mesh: &Mesh) -> bool {
    let volume: f32 = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            a.dot(b.cross(c))
        })
        .sum();
    volume > 0.0
}

/// `asset` drawn `factor` times larger each way and averaged back, `factor²` samples per pixel: the
/// truth, integrated over each pixel as the highlight integrates its slice of the arc (a single sample
/// per pixel would catch or miss a narrow specular lobe on a fillet a few pixels wide).
pub fn render_supersampled(
    asset: &chamfer_runtime::asset::Asset,
    orbit: &Orbit,
    size: u32,
    mesh: &MeshStyle,
    factor: u32,
    environment: Option<&Arc<Environment>>,
) -> Image {
    render_supersampled_on(asset, orbit, size, mesh, factor, environment, BLACK)
}

/// [`render_supersampled`] over `background`.
pub fn render_supersampled_on(
    asset: &chamfer_runtime::asset::Asset,
    orbit: &Orbit,
    size: u32,
    mesh: &MeshStyle,
    factor: u32,
    environment: Option<&Arc<Environment>>,
    background: [f64; 4],
) -> Image {
    let camera = Camera::orbit([[-1.0; 3], [1.0; 3]], orbit, [size * factor; 2]);
    let large = render_lit_on(asset, &camera, mesh, None, environment, background);
    let mut rgba = Vec::with_capacity((size * size * 4) as usize);
    for y in 0..size {
        for x in 0..size {
            for channel in 0..4 {
                let mut sum = 0u32;
                for dy in 0..factor {
                    for dx in 0..factor {
                        sum += u32::from(large.pixel(x * factor + dx, y * factor + dy)[channel]);
                    }
                }
                rgba.push(((sum + factor * factor / 2) / (factor * factor)) as u8);
            }
        }
    }
    Image {
        width: size,
        height: size,
        rgba,
    }
}

/// Opaque black, the validations' background.
pub const BLACK: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// `asset` drawn on black with `mesh` and, if given, `edges`, both lit by `environment` too.
pub fn render_lit(
    asset: &chamfer_runtime::asset::Asset,
    camera: &Camera,
    mesh: &MeshStyle,
    edges: Option<&EdgeStyle>,
    environment: Option<&Arc<Environment>>,
) -> Image {
    render_lit_on(asset, camera, mesh, edges, environment, BLACK)
}

/// [`render_lit`] over `background`.
pub fn render_lit_on(
    asset: &chamfer_runtime::asset::Asset,
    camera: &Camera,
    mesh: &MeshStyle,
    edges: Option<&EdgeStyle>,
    environment: Option<&Arc<Environment>>,
    background: [f64; 4],
) -> Image {
    let gpu = crate::gpu();
    let [width, height] = camera.viewport;
    let target = gpu.target(width, height, 1).expect("target");
    let pipelines = crate::pipelines(target.formats());
    let uploaded = GpuAsset::new(&gpu.device, asset).expect("upload");
    let mut mesh_renderer = MeshRenderer::new(&pipelines, &uploaded).expect("mesh renderer");
    mesh_renderer.set_environment(environment.cloned());
    let mut edge_renderer = EdgeRenderer::new(&pipelines, &uploaded);
    edge_renderer.set_environment(environment.cloned());
    crate::draw_frame(
        &target,
        camera,
        background,
        Some((&mut mesh_renderer, mesh)),
        edges.map(|style| (&mut edge_renderer, style)),
    )
}

/// An environment of a dim sky over a dark ground and a bright round light (radius 12°) whose centre
/// is `towards`: what a rounded edge should catch.
pub fn sky_with_a_light(towards: Vec3) -> Environment {
    let (width, height) = (256u32, 128u32);
    let towards = towards.normalize();
    let texels = (0..width * height)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            let d = chamfer_runtime::highlight::environment::direction(
                (x as f32 + 0.5) / width as f32,
                (y as f32 + 0.5) / height as f32,
            );
            let sky = if d.y > 0.0 { 0.05 + 0.1 * d.y } else { 0.02 };
            let light = if d.dot(towards) > 12f32.to_radians().cos() {
                0.9
            } else {
                0.0
            };
            [sky + light, sky + light * 0.95, sky + light * 0.85]
        })
        .collect();
    Environment::new(width, height, texels).expect("environment")
}
