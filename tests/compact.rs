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

/// Issue 44: a position error picks the grid: the fewest bits whose stated bound is within it
/// (one bit fewer would not be), every decoded position within the bound; an error no 16-bit grid
/// meets keeps the positions exact; a coarser error makes a smaller file.
#[test]
fn a_position_error_picks_the_fewest_grid_bits_within_it() {
    for (name, asset) in assets() {
        let diagonal = {
            let points = asset
                .topology_positions
                .iter()
                .map(|&p| glam::Vec3::from(p));
            let lo = points.clone().fold(glam::Vec3::INFINITY, glam::Vec3::min);
            let hi = points.fold(glam::Vec3::NEG_INFINITY, glam::Vec3::max);
            (hi - lo).length()
        };
        let mut sizes = Vec::new();
        for share in [1e-2, 1e-4] {
            let error = diagonal * share;
            let options = CompactOptions {
                position_error: Some(error),
                ..CompactOptions::DEFAULT
            };
            let bytes = compact(&asset, &options);
            let precision = Asset::precision(&bytes).expect("precision");
            assert!(
                (1..=16).contains(&precision.position_bits),
                "{name}: {} bits",
                precision.position_bits
            );
            assert!(
                precision.position_error <= error,
                "{name}: {precision:?} over {error}"
            );
            let fewer = CompactOptions {
                position_bits: precision.position_bits - 1,
                ..CompactOptions::DEFAULT
            };
            if fewer.position_bits > 0 {
                let looser = Asset::precision(&compact(&asset, &fewer)).expect("precision");
                assert!(
                    looser.position_error > error,
                    "{name}: {looser:?} is within {error}"
                );
            }
            let decoded = Asset::decode(&bytes).expect("decodes");
            for (p, q) in asset
                .topology_positions
                .iter()
                .zip(&decoded.topology_positions)
            {
                assert!(
                    (0..3).all(|k| (p[k] - q[k]).abs() <= error),
                    "{name}: {p:?} -> {q:?}"
                );
            }
            sizes.push(bytes.len());
        }
        assert!(sizes[0] < sizes[1], "{name}: {sizes:?} bytes");
        let exact = CompactOptions {
            position_error: Some(diagonal * 1e-9),
            ..CompactOptions::DEFAULT
        };
        let bytes = compact(&asset, &exact);
        assert_eq!(
            Asset::precision(&bytes).expect("precision").position_bits,
            32,
            "{name}"
        );
        let decoded = Asset::decode(&bytes).expect("decodes");
        assert_eq!(
            decoded.topology_positions, asset.topology_positions,
            "{name}"
        );
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
            ..CompactOptions::DEFAULT
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

// Hostile compact files: each class of damage to a coded section is a typed error naming the
// section, found before anything the file declares is allocated.

/// The fandisk's compact file, and where each of its sections lies.
fn hostile_seed() -> (Vec<u8>, Vec<chamfer_runtime::asset::SectionEntry>) {
    let asset = bake_file(&fixture("meshes/fandisk.obj"), &BakeOptions::DEFAULT)
        .expect("bakes")
        .asset;
    let bytes = compact(&asset, &CompactOptions::default());
    let sections = Asset::decode(&bytes).expect("decodes").header.sections;
    (bytes, sections)
}

fn section_range(
    sections: &[chamfer_runtime::asset::SectionEntry],
    kind: SectionKind,
) -> std::ops::Range<usize> {
    let entry = sections
        .iter()
        .find(|s| s.kind == kind as u32)
        .expect("section listed");
    entry.offset as usize..(entry.offset + entry.length) as usize
}

/// `bytes` with `value` written at `at` bytes into section `kind` (`at` may count from its end
/// when negative).
fn patched(kind: SectionKind, at: isize, value: &[u8]) -> Vec<u8> {
    let (mut bytes, sections) = hostile_seed();
    let range = section_range(&sections, kind);
    let start = if at < 0 {
        range.end - at.unsigned_abs()
    } else {
        range.start + at as usize
    };
    bytes[start..start + value.len()].copy_from_slice(value);
    bytes
}

/// `bytes` with section `kind` cut to `length` bytes in the section table (the rest of its bytes
/// left as a gap, which the format allows, or cut off the file after the last section).
fn shortened(kind: SectionKind, length: u64) -> Vec<u8> {
    let (mut bytes, sections) = hostile_seed();
    let entry = sections
        .iter()
        .find(|s| s.kind == kind as u32)
        .expect("section listed");
    let mut pattern = entry.kind.to_le_bytes().to_vec();
    pattern.extend(entry.offset.to_le_bytes());
    pattern.extend(entry.length.to_le_bytes());
    let at = bytes
        .windows(pattern.len())
        .position(|w| w == pattern.as_slice())
        .expect("the entry is in the header");
    bytes[at + 12..at + 20].copy_from_slice(&length.to_le_bytes());
    // The last section's cut-off bytes would be trailing bytes: they go.
    if entry.offset + entry.length == bytes.len() as u64 {
        bytes.truncate((entry.offset + length) as usize);
    }
    bytes
}

fn refused(bytes: &[u8]) -> String {
    let error = Asset::decode(bytes).expect_err("refused");
    error.to_string()
}

#[test]
fn compact_files_that_were_not_damaged_decode() {
    let (bytes, _) = hostile_seed();
    Asset::decode(&bytes).expect("the seed decodes");
}

#[test]
fn a_declared_count_beyond_what_the_triangles_allow_is_refused_before_allocating() {
    for kind in [
        SectionKind::TopologyPositionsCoded,
        SectionKind::RenderNormalsCoded,
        SectionKind::EdgeAttributesCoded,
        SectionKind::EdgeCorners,
        SectionKind::RenderVertexCountsCoded,
        SectionKind::EdgeClustersCoded,
    ] {
        let error = refused(&patched(kind, 0, &u32::MAX.to_le_bytes()));
        assert!(
            error.contains(kind.name()) && error.contains("declares 4294967295 elements"),
            "{}: {error}",
            kind.name()
        );
    }
    // The triangle count is held to a code byte per triangle.
    let error = refused(&patched(
        SectionKind::MeshIndicesCoded,
        0,
        &u32::MAX.to_le_bytes(),
    ));
    assert!(
        error.contains("mesh_indices_coded") && error.contains("ends early"),
        "{error}"
    );
}

#[test]
fn a_stream_that_is_not_a_codec_stream_is_refused_by_name() {
    let error = refused(&patched(SectionKind::EdgeAttributesCoded, 4, &[0x00]));
    assert!(
        error.contains("edge_attributes_coded") && error.contains("not a meshopt stream"),
        "{error}"
    );
    let error = refused(&patched(SectionKind::MeshIndicesCoded, 4, &[0x00]));
    assert!(error.contains("not a meshopt stream"), "{error}");
}

#[test]
fn a_truncated_section_is_refused_by_name() {
    for kind in [
        SectionKind::MeshIndicesCoded,
        SectionKind::TopologyPositionsCoded,
        SectionKind::RenderNormalsCoded,
        SectionKind::EdgeCorners,
        SectionKind::EdgeAttributesCoded,
        SectionKind::RingOrders,
        SectionKind::RenderVertexCountsCoded,
        SectionKind::EdgeClustersCoded,
    ] {
        for length in [2, 7, 40] {
            let error = refused(&shortened(kind, length));
            assert!(
                error.contains(kind.name()),
                "{} cut to {length}: {error}",
                kind.name()
            );
        }
    }
    // Every truncation of the whole file is an error too, never a panic.
    let (bytes, _) = hostile_seed();
    for length in (0..bytes.len()).step_by(97) {
        assert!(Asset::decode(&bytes[..length]).is_err(), "cut at {length}");
    }
}

#[test]
fn grid_points_and_octahedral_codes_beyond_their_bits_are_refused() {
    // The grid's bits read as 4: fandisk's 16-bit grid points are past 15.
    let error = refused(&patched(
        SectionKind::TopologyPositionsCoded,
        4,
        &4u32.to_le_bytes(),
    ));
    assert!(error.contains("grid point beyond 4 bits"), "{error}");
    let error = refused(&patched(
        SectionKind::TopologyPositionsCoded,
        4,
        &20u32.to_le_bytes(),
    ));
    assert!(error.contains("20 bits per axis"), "{error}");
    let error = refused(&patched(
        SectionKind::RenderNormalsCoded,
        4,
        &3u32.to_le_bytes(),
    ));
    assert!(error.contains("octahedral code beyond 3 bits"), "{error}");
}

#[test]
fn a_grid_or_cluster_unit_that_is_not_finite_is_refused() {
    let nan = f32::NAN.to_le_bytes();
    let error = refused(&patched(SectionKind::TopologyPositionsCoded, 8, &nan));
    assert!(error.contains("grid origin or step not finite"), "{error}");
    let error = refused(&patched(
        SectionKind::TopologyPositionsCoded,
        20,
        &(-1.0f32).to_le_bytes(),
    ));
    assert!(error.contains("a step negative"), "{error}");
    // The clusters' radius unit (after count, origin and step).
    let error = refused(&patched(SectionKind::EdgeClustersCoded, 28, &nan));
    assert!(
        error.contains("edge_clusters_coded") && error.contains("not finite"),
        "{error}"
    );
}

#[test]
fn corner_bits_that_disagree_with_the_edges_are_refused() {
    // One corner more or less than the edges declared.
    let (bytes, sections) = hostile_seed();
    let range = section_range(&sections, SectionKind::EdgeCorners);
    let mut flipped = bytes.clone();
    flipped[range.start + 4] ^= 1;
    let error = refused(&flipped);
    assert!(error.contains("corners set for 9865 edges"), "{error}");
    // A bit past the last corner (fandisk has 3 × 12 946 = 38 838 corners: two spare bits).
    let mut spare = bytes;
    spare[range.end - 1] |= 0x80;
    let error = refused(&spare);
    assert!(error.contains("past the last corner"), "{error}");
}

#[test]
fn ring_codes_that_do_not_fit_their_rings_are_refused() {
    // The code's bit count one more than its rings use.
    let (bytes, sections) = hostile_seed();
    let range = section_range(&sections, SectionKind::RingOrders);
    let bits = u64::from_le_bytes(bytes[range.start..range.start + 8].try_into().expect("8"));
    let mut longer = bytes.clone();
    longer[range.start..range.start + 8].copy_from_slice(&(bits + 1).to_le_bytes());
    let error = refused(&longer);
    assert!(error.contains("ring_orders"), "{error}");
    // All ones: ranks past the ends left at a vertex.
    let mut ones = bytes;
    ones[range.start + 8..range.end].fill(0xff);
    let error = refused(&ones);
    assert!(error.contains("ring_orders"), "{error}");
    // Ring orders without the corner bits they are coded over.
    let error = refused(&shortened(SectionKind::EdgeCorners, 0));
    assert!(
        error.contains("ring_orders") || error.contains("edge"),
        "{error}"
    );
}

#[test]
fn cluster_bounds_for_another_number_of_edges_are_refused() {
    let error = refused(&patched(
        SectionKind::EdgeClustersCoded,
        0,
        &3u32.to_le_bytes(),
    ));
    assert!(error.contains("3 clusters for 9865 edges"), "{error}");
}

#[test]
fn every_byte_of_the_coded_sections_damaged_decodes_or_is_refused_never_panics() {
    let (bytes, sections) = hostile_seed();
    let coded: Vec<_> = sections
        .iter()
        .filter(|s| s.kind >= SectionKind::MeshIndicesCoded as u32 && s.length > 0)
        .collect();
    let mut checked = 0;
    for entry in coded {
        let step = (entry.length as usize / 300).max(1);
        for at in (entry.offset as usize..(entry.offset + entry.length) as usize).step_by(step) {
            for mask in [0x01u8, 0x80, 0xff] {
                let mut bad = bytes.clone();
                bad[at] ^= mask;
                // Either result is fine; what must not happen is a panic or a hang.
                let _ = Asset::decode(&bad);
                checked += 1;
            }
        }
    }
    assert!(checked > 1000, "{checked} damaged files");
}

#[test]
fn a_mesh_of_subnormal_size_keeps_exact_bounds() {
    // Found by the fuzz harness: a box so small that its radius unit is a subnormal f32, where
    // rounding the radius up one unit at a time never reached it. Such bounds stay raw, computed
    // from the positions the file decodes to.
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("tiny.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 4e-39 0 0\nv 0 4e-39 0\nv 0 0 4e-39\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n",
    )
    .expect("write");
    let asset = bake_file(&path, &BakeOptions::DEFAULT)
        .expect("bakes")
        .asset;
    let bytes = compact(&asset, &CompactOptions::default());
    let decoded = Asset::decode(&bytes).expect("decodes");
    assert_eq!(stored(&bytes, SectionKind::EdgeClustersCoded), 0);
    assert!(stored(&bytes, SectionKind::EdgeClusters) > 0);
    check_clusters_hold_their_edges("tiny", &decoded);
}
