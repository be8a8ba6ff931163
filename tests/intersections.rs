//! Intersection edges against known answers: two interpenetrating cubes (the loop's length exact),
//! a sphere through a plane (a circle, within the tessellation's bound), a torus through a box
//! (two loops of a length computed from the generator), none on closed meshes that have none, the
//! same result for any thread count, and old (version 1) assets still read.

use std::f64::consts::PI;

use chamfer_preprocess::intersections::{Intersections, find_intersections};
use chamfer_preprocess::mesh::Mesh;
use chamfer_preprocess::{BakeOptions, bake, bake_file};
use chamfer_runtime::asset::{Asset, FORMAT_VERSION};
use chamfer_tests::{check_rings, content, fixture};
use glam::{DVec3, Vec3};

fn baked(relative: &str) -> Asset {
    bake_file(
        &fixture(relative),
        &BakeOptions::DEFAULT.with_intersections(true),
    )
    .unwrap_or_else(|e| panic!("{relative}: {e}"))
    .asset
}

fn polyline_lengths(asset: &Asset) -> Vec<(f64, bool)> {
    asset
        .intersection_polylines()
        .map(|p| {
            let length = p
                .iter()
                .map(|[a, b]| (Vec3::from(*b).as_dvec3() - Vec3::from(*a).as_dvec3()).length())
                .sum();
            let closed = p.first().map(|s| s[0]) == p.last().map(|s| s[1]);
            (length, closed)
        })
        .collect()
}

#[test]
fn two_cubes_meet_in_one_loop_3_9_long_from_obj_objects_and_gltf_instances() {
    // The loop runs along the edges of the boxes' overlap [0.5, 1] x [0.25, 1] x [0.3, 1] that lie on
    // one face of each cube: 2 x (0.7 + 0.75 + 0.5).
    for file in ["shapes/two-cubes.obj", "shapes/two-cube-instances.gltf"] {
        let asset = baked(file);
        let loops = polyline_lengths(&asset);
        assert_eq!(loops.len(), 1, "{file}: {loops:?}");
        let (length, closed) = loops[0];
        assert!(closed, "{file}");
        assert!((length - 3.9).abs() < 1e-5, "{file}: {length}");
        assert!((asset.intersection_length() - 3.9).abs() < 1e-5);
        // It survives the file format.
        let back = Asset::decode(&asset.encode_to_vec()).expect("decodes");
        assert_eq!(back.intersection_segments, asset.intersection_segments);
    }
    // Without the option nothing is looked for.
    let plain = bake_file(&fixture("shapes/two-cubes.obj"), &BakeOptions::DEFAULT).expect("bakes");
    assert!(plain.asset.intersection_segments.is_empty() && plain.intersections.is_none());
}

/// A UV sphere (vertices on the sphere of radius `r`) and its triangles.
fn uv_sphere(r: f64, rings: u32, segments: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = vec![DVec3::new(0.0, 0.0, r)];
    for i in 1..rings {
        let theta = PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let phi = 2.0 * PI * f64::from(j) / f64::from(segments);
            p.push(
                r * DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ),
            );
        }
    }
    p.push(DVec3::new(0.0, 0.0, -r));
    let south = p.len() as u32 - 1;
    let at = |i: u32, j: u32| 1 + (i - 1) * segments + j % segments;
    let mut t = Vec::new();
    for j in 0..segments {
        t.push([0, at(1, j), at(1, j + 1)]);
        t.push([south, at(rings - 1, j + 1), at(rings - 1, j)]);
        for i in 1..rings - 1 {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    (p, t)
}

fn mesh_of(parts: &[(Vec<DVec3>, Vec<[u32; 3]>)]) -> Mesh {
    let mut mesh = Mesh::default();
    for (p, t) in parts {
        mesh.append(Mesh {
            positions: p.iter().map(|q| q.as_vec3()).collect(),
            triangles: t.clone(),
            ..Mesh::default()
        });
    }
    mesh
}

fn square_at_z(half: f64, z: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| DVec3::new(x * half, y * half, z));
    (p.to_vec(), vec![[0, 1, 2], [0, 2, 3]])
}

#[test]
fn a_sphere_through_a_plane_is_a_circle_within_the_tessellations_bound() {
    let (r, h) = (1.0, 0.3);
    let sphere = uv_sphere(r, 24, 48);
    // The bound: the sphere mesh is a convex polyhedron between the balls of radius r_in (its
    // nearest face plane) and r (its vertices), so its cut by the plane z = h is a convex polygon
    // between the circles of radius sqrt(r_in² - h²) and sqrt(r² - h²), and a convex curve inside
    // another is shorter: 2π sqrt(r_in² - h²) <= L <= 2π sqrt(r² - h²).
    let r_in = sphere
        .1
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| sphere.0[i as usize].as_vec3().as_dvec3());
            (b - a).cross(c - a).normalize().dot(a).abs()
        })
        .fold(f64::INFINITY, f64::min);
    let (lo, hi) = (
        2.0 * PI * (r_in * r_in - h * h).sqrt(),
        2.0 * PI * (r * r - h * h).sqrt(),
    );
    let mesh = mesh_of(&[sphere, square_at_z(2.0, h)]);
    let asset = bake(
        mesh,
        "sphere-plane",
        &BakeOptions::DEFAULT.with_intersections(true),
    )
    .expect("bakes")
    .asset;
    let loops = polyline_lengths(&asset);
    assert_eq!(loops.len(), 1, "{loops:?}");
    let (length, closed) = loops[0];
    assert!(closed);
    println!("sphere through a plane: {length} in [{lo}, {hi}] (2πρ = {hi})");
    assert!(
        length >= lo * (1.0 - 1e-6) && length <= hi * (1.0 + 1e-6),
        "{length} not in [{lo}, {hi}]"
    );
    assert!(hi - lo < 0.01 * hi, "the bound is tight: {lo} {hi}");
}

/// A torus around z (major radius `big`, minor `small`) whose meridians sit half a segment off the
/// planes x = 0, mirrored exactly across x = 0.
fn torus(big: f64, small: f64, major: u32, minor: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    assert_eq!(major % 4, 0);
    let mut p = Vec::new();
    for k in 0..major {
        let u = 2.0 * PI * (f64::from(k) + 0.5) / f64::from(major);
        for j in 0..minor {
            let v = 2.0 * PI * f64::from(j) / f64::from(minor);
            let radial = big + small * v.cos();
            p.push(DVec3::new(
                radial * u.cos(),
                radial * u.sin(),
                small * v.sin(),
            ));
        }
    }
    // Exact mirror pairs across x = 0: meridian k and major/2 - 1 - k (mod major).
    for k in 0..major / 4 {
        for (a, b) in [(k, major / 2 - 1 - k), (major / 2 + k, major - 1 - k)] {
            for j in 0..minor {
                let (ia, ib) = ((a * minor + j) as usize, (b * minor + j) as usize);
                p[ib] = DVec3::new(-p[ia].x, p[ia].y, p[ia].z);
            }
        }
    }
    let at = |k: u32, j: u32| (k % major) * minor + j % minor;
    let mut t = Vec::new();
    for k in 0..major {
        for j in 0..minor {
            let (a, b, c, d) = (at(k, j), at(k + 1, j), at(k + 1, j + 1), at(k, j + 1));
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    (p, t)
}

fn box_mesh(lo: DVec3, hi: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let p: Vec<DVec3> = (0..8)
        .map(|c| {
            DVec3::new(
                if c & 4 != 0 { hi.x } else { lo.x },
                if c & 2 != 0 { hi.y } else { lo.y },
                if c & 1 != 0 { hi.z } else { lo.z },
            )
        })
        .collect();
    let t = vec![
        [0, 1, 3],
        [0, 3, 2],
        [4, 6, 7],
        [4, 7, 5],
        [0, 4, 5],
        [0, 5, 1],
        [2, 3, 7],
        [2, 7, 6],
        [0, 2, 6],
        [0, 6, 4],
        [1, 5, 7],
        [1, 7, 3],
    ];
    (p, t)
}

#[test]
fn a_torus_through_a_box_is_two_loops_of_the_generators_length() {
    let (big, small, major, minor) = (1.0, 0.35, 48, 24);
    let torus = torus(big, small, major, minor);
    // The box's face x = 0 cuts the torus midway between two mirrored meridians. Each of its
    // quads there is an isosceles trapezoid (planar), cut through the midpoints of its two
    // horizontal edges, so each loop is the polygon of those midpoints:
    // (radial, z) = (cos δ (R + r cos v_j), r sin v_j), δ = half a segment.
    let delta = PI / f64::from(major);
    let expected: f64 = (0..minor)
        .map(|j| {
            let v = |j: u32| 2.0 * PI * f64::from(j) / f64::from(minor);
            let (v0, v1) = (v(j), v(j + 1));
            (small * delta.cos() * (v1.cos() - v0.cos())).hypot(small * (v1.sin() - v0.sin()))
        })
        .sum();
    let extent = big + small;
    let cut = box_mesh(
        DVec3::new(0.0, -2.0 * extent, -2.0 * small),
        DVec3::new(2.0 * extent, 2.0 * extent, 2.0 * small),
    );
    let mesh = mesh_of(&[torus, cut]);
    let asset = bake(
        mesh,
        "torus-box",
        &BakeOptions::DEFAULT.with_intersections(true),
    )
    .expect("bakes")
    .asset;
    let loops = polyline_lengths(&asset);
    println!("torus through a box: {loops:?}, expected 2 x {expected}");
    assert_eq!(loops.len(), 2, "{loops:?}");
    for (length, closed) in loops {
        assert!(closed);
        assert!(
            (length - expected).abs() < 1e-5 * expected,
            "{length} vs {expected}"
        );
    }
}

#[test]
fn closed_meshes_without_intersections_have_none() {
    for file in [
        "shapes/sphere-16x32.obj",
        "shapes/cube.obj",
        "meshes/fandisk.obj",
    ] {
        let baked = bake_file(
            &fixture(file),
            &BakeOptions::DEFAULT.with_intersections(true),
        )
        .unwrap_or_else(|e| panic!("{file}: {e}"));
        let stats = baked.intersections.expect("looked for");
        assert_eq!(stats.segments, 0, "{file}: {stats:?}");
        assert!(
            stats.candidate_pairs > 0,
            "{file}: neighbours are candidates"
        );
        assert!(baked.asset.intersection_segments.is_empty());
    }
}

fn welded(parts: &[(Vec<DVec3>, Vec<[u32; 3]>)]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mesh = mesh_of(parts);
    let w = chamfer_preprocess::weld::weld(&mesh.positions, 0.0);
    let t = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| w.remap[i as usize]))
        .collect();
    (w.positions, t)
}

#[test]
fn the_result_is_the_same_for_any_thread_count() {
    let (p, t) = welded(&[
        torus(1.0, 0.35, 48, 24),
        box_mesh(DVec3::new(0.0, -3.0, -0.7), DVec3::new(3.0, 3.0, 0.7)),
        uv_sphere(0.8, 12, 24),
    ]);
    let run = |threads: usize| -> Intersections {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| find_intersections(&p, &t))
    };
    let one = run(1);
    assert!(one.stats.segments > 100, "{:?}", one.stats);
    for threads in [2, 3, 8] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}

#[test]
fn degenerate_and_nan_triangles_are_skipped_and_counted() {
    let (mut p, mut t) = welded(&[
        box_mesh(DVec3::ZERO, DVec3::ONE),
        box_mesh(DVec3::new(0.5, 0.25, 0.3), DVec3::new(1.5, 1.25, 1.3)),
    ]);
    let clean = find_intersections(&p, &t);
    let nan = p.len() as u32;
    p.push(Vec3::new(f32::NAN, 0.5, 0.5));
    t.extend([
        [0, 0, 1],
        [0, 1, 0],
        [nan, 1, 2],
        [0, nan, 5],
        [0, 1, u32::MAX],
    ]);
    // A zero-area sliver right through the overlap.
    let (a, b) = (p.len() as u32, p.len() as u32 + 1);
    p.extend([Vec3::new(0.7, 0.6, -1.0), Vec3::new(0.7, 0.6, 2.0)]);
    t.push([a, b, a]);
    let c = p.len() as u32;
    p.push(Vec3::new(0.7, 0.6, 0.5)); // collinear with a and b
    t.push([a, c, b]);
    let dirty = find_intersections(&p, &t);
    assert_eq!(dirty.stats.skipped_triangles, 7);
    assert_eq!(dirty.segments, clean.segments);
    assert!((clean.stats.length - 3.9).abs() < 1e-5);
}

#[test]
fn version_1_assets_are_still_read_without_intersections() {
    let bytes = std::fs::read(fixture("assets/cube-v1.chamfer")).expect("fixture");
    assert_eq!(bytes[8..12], 1u32.to_le_bytes(), "a version-1 file");
    let old = Asset::decode(&bytes).expect("version 1 is read");
    assert!(old.intersection_segments.is_empty() && old.intersection_starts.is_empty());
    let new = bake_file(&fixture("shapes/cube.obj"), &BakeOptions::DEFAULT)
        .expect("bakes")
        .asset;
    assert_eq!(old.header.stats, new.header.stats);
    // Bakes have since reordered triangles, vertices (issue 24) and edges (issue 14): the same
    // triangles, edges, attributes and rings, named by their positions.
    assert_eq!(content(&old), content(&new));
    check_rings(&old).expect("the old rings are rings");
}

#[test]
fn version_3_assets_are_still_read_and_re_encode_as_a_fresh_bake() {
    let bytes = std::fs::read(fixture("assets/cube-v3.chamfer")).expect("fixture");
    assert_eq!(bytes[8..12], 3u32.to_le_bytes(), "a version-3 file");
    let old = Asset::decode(&bytes).expect("version 3 is read");
    let new = bake_file(&fixture("shapes/cube.obj"), &BakeOptions::DEFAULT)
        .expect("bakes")
        .asset;
    // The settings record the options of the bake that wrote the file, and options were added
    // since (stitch): everything else must be the same.
    assert!(
        old.header
            .settings
            .iter()
            .all(|s| new.header.settings.contains(s))
    );
    assert_eq!(old.header.stats, new.header.stats);
    assert_eq!(content(&old), content(&new));
    // Re-encoded, the old asset is a file of today's format that reads back as itself.
    let again = old.encode_to_vec();
    assert_eq!(again[8..12], FORMAT_VERSION.to_le_bytes());
    let mut reread = Asset::decode(&again).expect("re-encoded asset decodes");
    reread.header.sections.clone_from(&old.header.sections);
    assert_eq!(reread, old);
    // A fresh file stores the render positions as counts (format 4 on); its section table has
    // grown since (format 6's motion sections, 20 bytes an entry), so compare the section itself.
    let stored = |sections: &[chamfer_runtime::asset::SectionEntry]| {
        sections
            .iter()
            .find(|s| s.kind == chamfer_runtime::asset::SectionKind::RenderPositions as u32)
            .map(|s| s.length)
    };
    assert_eq!(stored(&old.header.sections), Some(24 * 12));
    assert_eq!(
        stored(&new.encoded_sections()),
        Some(0),
        "the cube's 24 render positions are not stored"
    );
}
