//! Compact assets (format 5, issue 24): lossless files decode to the baked asset itself, lossy ones
//! keep every index and flag and move positions and normals within the bounds the file states,
//! their cluster bounds still hold their edges, every technique draws the same picture from them,
//! and bunny-loop2 fits in 8 bytes per triangle.

use chamfer_preprocess::compact::Meshopt;
use chamfer_preprocess::{BakeOptions, Radius, bake_file};
use chamfer_runtime::asset::{Asset, CompactOptions, EdgeFlags, SectionKind, attribute_flags};
use chamfer_runtime::render::{
    Camera, EdgeRenderer, EdgeStyle, GpuAsset, Image, MeshRenderer, MeshStyle, Orbit, Technique,
};
use chamfer_tests::{draw_frame, fixture, gpu};
use glam::DVec3;

/// Assets of every kind the bake makes: seams, boundaries, marks and radii, materials, a
/// stitched CAD soup, intersection edges, and a mesh above 65 536 vertices (32-bit indices).
fn assets() -> Vec<(&'static str, Asset)> {
    let bake = |relative: &str, options: &BakeOptions| {
        bake_file(&fixture(relative), options)
            .unwrap_or_else(|e| panic!("{relative}: {e}"))
            .asset
    };
    let default = BakeOptions::DEFAULT;
    vec![
        ("cube", bake("shapes/cube.obj", &default)),
        ("fandisk", bake("meshes/fandisk.obj", &default)),
        (
            "marked PLY with radii",
            bake(
                "shapes/cube-marked-le.ply",
                &default.with_radius(Radius::Relative(0.01)),
            ),
        ),
        ("two materials", bake("shapes/two-materials.glb", &default)),
        ("suzanne (open)", bake("meshes/suzanne.obj", &default)),
        (
            "cracked box (stitched)",
            bake("shapes/box-cracked.obj", &default),
        ),
        (
            "intersections",
            bake("shapes/two-cubes.obj", &default.with_intersections(true)),
        ),
        (
            "non-manifold fan",
            bake("shapes/nonmanifold-fan.obj", &default),
        ),
        (
            "stanford bunny",
            bake("meshes/stanford-bunny.obj", &default),
        ),
    ]
}

fn compact(asset: &Asset, options: &CompactOptions) -> Vec<u8> {
    asset
        .encode_compact_to_vec(options, &Meshopt)
        .expect("encodes")
}

fn stored(bytes: &[u8], kind: SectionKind) -> u64 {
    Asset::decode(bytes)
        .expect("decodes")
        .header
        .sections
        .iter()
        .find(|s| s.kind == kind as u32)
        .map_or(0, |s| s.length)
}

#[test]
fn lossless_files_decode_to_the_baked_asset() {
    for (name, asset) in assets() {
        let bytes = compact(&asset, &CompactOptions::LOSSLESS);
        let mut decoded = Asset::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        // Every section the bake makes is coded: none fell back to raw.
        for kind in [
            SectionKind::MeshIndicesCoded,
            SectionKind::TopologyPositionsCoded,
            SectionKind::RenderNormalsCoded,
            SectionKind::EdgeCorners,
            SectionKind::EdgeAttributesCoded,
            SectionKind::RingOrders,
            SectionKind::RenderVertexCountsCoded,
        ] {
            assert!(
                stored(&bytes, kind) > 0,
                "{name}: {} not coded",
                kind.name()
            );
        }
        assert!(
            (bytes.len() as u64) < asset.encoded_len(),
            "{name}: {} bytes, uncompressed {}",
            bytes.len(),
            asset.encoded_len()
        );
        decoded.header.sections.clear();
        let mut expected = asset.clone();
        expected.header.sections.clear();
        assert!(
            decoded == expected,
            "{name}: the lossless file decodes to another asset"
        );
    }
}

#[test]
fn lossy_files_keep_every_index_and_stay_within_their_stated_bounds() {
    for (name, asset) in assets() {
        let options = CompactOptions::default();
        let bytes = compact(&asset, &options);
        let decoded = Asset::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        let precision = Asset::precision(&bytes).expect("precision");
        assert_eq!(precision.position_bits, options.position_bits);
        assert_eq!(precision.normal_bits, options.normal_bits);
        assert!(precision.position_error > 0.0 && precision.normal_error > 0.0);
        // What the runtime indexes and classifies by is exact.
        assert_eq!(decoded.mesh_indices, asset.mesh_indices, "{name}");
        assert_eq!(decoded.edge_vertices, asset.edge_vertices, "{name}");
        assert_eq!(decoded.edge_attributes, asset.edge_attributes, "{name}");
        assert_eq!(decoded.next_ends, asset.next_ends, "{name}");
        assert_eq!(decoded.cap_heads, asset.cap_heads, "{name}");
        assert_eq!(
            decoded.intersection_segments, asset.intersection_segments,
            "{name}"
        );
        for (p, q) in asset
            .topology_positions
            .iter()
            .zip(&decoded.topology_positions)
        {
            for k in 0..3 {
                assert!(
                    (p[k] - q[k]).abs() <= precision.position_error,
                    "{name}: {p:?} decoded as {q:?}, bound {}",
                    precision.position_error
                );
            }
        }
        // Render positions repeat the decoded topology positions, as the counts say.
        assert_eq!(decoded.render_positions.len(), asset.render_positions.len());
        for (n, m) in asset.render_normals.iter().zip(&decoded.render_normals) {
            let (n, m) = (DVec3::from(n.map(f64::from)), DVec3::from(m.map(f64::from)));
            let angle = n.cross(m).length().atan2(n.dot(m));
            assert!(
                angle <= f64::from(precision.normal_error),
                "{name}: a normal turned {angle} rad, bound {}",
                precision.normal_error
            );
        }
        check_clusters_hold_their_edges(name, &decoded);
    }
}

/// Every edge's end points lie in its cluster's sphere, and each of its faces' normals (exact,
/// from the decoded positions) lies in the cluster's cone; each cluster's flags are its edges'.
fn check_clusters_hold_their_edges(name: &str, asset: &Asset) {
    let position = |v: u32| DVec3::from(asset.topology_positions[v as usize].map(f64::from));
    for (c, cluster) in asset.edge_clusters.iter().enumerate() {
        let center = DVec3::from(cluster.center.map(f64::from));
        let axis = DVec3::from(cluster.axis.map(f64::from));
        let mut flags = EdgeFlags::default();
        for e in c * 64..((c + 1) * 64).min(asset.edge_count()) {
            let [v0, v1, v2, v3] = asset.edge(e).map(position);
            for p in [v0, v1] {
                assert!(
                    p.distance(center) <= f64::from(cluster.radius),
                    "{name}: edge {e} outside cluster {c}'s sphere"
                );
            }
            let edge_flags = attribute_flags(asset.edge_attributes[e]);
            flags |= edge_flags;
            if cluster.cos_angle <= -1.0 {
                continue;
            }
            let sign = if edge_flags.contains(EdgeFlags::FLIPPED) {
                -1.0
            } else {
                1.0
            };
            let one_face = edge_flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD);
            let faces = [
                ((v1 - v0).cross(v2 - v0), 1.0),
                ((v0 - v1).cross(v3 - v1), sign),
            ];
            for (normal, sign) in &faces[..if one_face { 1 } else { 2 }] {
                let n = normal.normalize() * *sign;
                assert!(
                    n.dot(axis) >= f64::from(cluster.cos_angle) - 1e-9,
                    "{name}: a face of edge {e} outside cluster {c}'s cone"
                );
            }
        }
        assert_eq!(
            cluster.flags,
            u32::from(flags.0),
            "{name}: cluster {c}'s flags"
        );
    }
}

#[test]
fn bunny_loop2_fits_in_8_bytes_per_triangle() {
    let asset = bake_file(&fixture("meshes/bunny-loop2.ply.gz"), &BakeOptions::DEFAULT)
        .expect("bakes")
        .asset;
    let bytes = compact(&asset, &CompactOptions::default());
    let per_triangle = bytes.len() as f64 / asset.triangle_count() as f64;
    assert!(
        per_triangle <= 8.0,
        "{} bytes for {} triangles: {per_triangle:.2} per triangle",
        bytes.len(),
        asset.triangle_count()
    );
    // Against the uncompressed file, measured in BENCHMARKS.md: about 9x smaller.
    assert!(bytes.len() as u64 * 8 < asset.encoded_len());
}

/// `asset` drawn with `technique` over the grey mesh, from a fixed camera.
fn picture(asset: &Asset, technique: Technique) -> Image {
    let gpu = gpu();
    let camera = Camera::orbit(
        [asset.header.bounds_min, asset.header.bounds_max],
        &Orbit::default(),
        [192, 160],
    );
    let target = gpu.target(192, 160, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let uploaded = GpuAsset::for_techniques(&gpu.device, asset, &[technique]).expect("upload");
    let mut mesh = MeshRenderer::new(&pipelines, &uploaded).expect("mesh");
    let mut edges = EdgeRenderer::new(&pipelines, &uploaded);
    let style = EdgeStyle {
        technique,
        width_px: 2.0,
        ..EdgeStyle::default()
    };
    draw_frame(
        &target,
        &camera,
        [1.0; 4],
        Some((&mut mesh, &MeshStyle::default())),
        Some((&mut edges, &style)),
    )
}

/// The share of pixels whose colours differ by more than `tolerance` in any channel.
fn differing(a: &Image, b: &Image, tolerance: u8) -> f64 {
    let count = a
        .rgba
        .chunks_exact(4)
        .zip(b.rgba.chunks_exact(4))
        .filter(|(p, q)| p.iter().zip(*q).any(|(x, y)| x.abs_diff(*y) > tolerance))
        .count();
    count as f64 / (a.rgba.len() / 4) as f64
}

#[test]
fn every_technique_draws_the_same_picture_from_a_compact_file() {
    let asset = bake_file(&fixture("meshes/fandisk.obj"), &BakeOptions::DEFAULT)
        .expect("bakes")
        .asset;
    let lossless = Asset::decode(&compact(&asset, &CompactOptions::LOSSLESS)).expect("decodes");
    let lossy = Asset::decode(&compact(&asset, &CompactOptions::default())).expect("decodes");
    // The control: 6 bits per axis moves fandisk's vertices by up to 1/126 of its box, pixels
    // at this size; 4-bit normals turn them by up to half a radian.
    let coarse = Asset::decode(&compact(
        &asset,
        &CompactOptions {
            position_bits: 6,
            normal_bits: 4,
        },
    ))
    .expect("decodes");
    // 16-bit positions move fandisk's vertices by below a thousandth of a pixel here and 12-bit
    // normals turn them by at most 2.4e-3 rad (a shade within one level of 255): what may differ
    // is a pixel on a rasterization boundary, or a level of shading.
    const SHADE: u8 = 2;
    const BOUNDARY_PIXELS: f64 = 0.001;
    const RUN_TO_RUN: f64 = 0.0005;
    for technique in Technique::all() {
        let name = technique.name();
        let reference = picture(&asset, technique);
        // (The decoded asset equals the baked one, tested above; lavapipe's compaction order
        // moves a pixel or two between runs of the same asset.)
        let share = differing(&reference, &picture(&lossless, technique), SHADE);
        assert!(
            share <= RUN_TO_RUN,
            "{name}: {:.3} % of pixels differ from the lossless file's",
            share * 100.0
        );
        let share = differing(&reference, &picture(&lossy, technique), SHADE);
        assert!(
            share <= BOUNDARY_PIXELS,
            "{name}: {:.3} % of pixels differ from a 16/12-bit file",
            share * 100.0
        );
        let coarse_share = differing(&reference, &picture(&coarse, technique), SHADE);
        assert!(
            coarse_share > BOUNDARY_PIXELS,
            "{name}: the control (6-bit positions, 4-bit normals) differs in only {:.3} % of pixels",
            coarse_share * 100.0
        );
    }
}
