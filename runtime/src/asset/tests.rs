//! Format tests: exact round trips, and every kind of damage is a typed error, never a panic.

use super::*;

/// A tetrahedron with one next-index ring per vertex and a cap head per vertex.
fn tetrahedron() -> Asset {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let tris = [[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    // v0 v1 and the opposite vertices of the two faces.
    let edges: [[u32; 4]; 6] = [
        [0, 1, 2, 3],
        [0, 2, 3, 1],
        [0, 3, 1, 2],
        [1, 2, 0, 3],
        [1, 3, 2, 0],
        [2, 3, 0, 1],
    ];
    let mut next = vec![0u32; 12];
    let mut heads = Vec::new();
    for v in 0..4u32 {
        let ends: Vec<u32> = (0..12u32)
            .filter(|&end| edges[end as usize / 2][end as usize % 2] == v)
            .collect();
        for (k, &end) in ends.iter().enumerate() {
            next[end as usize] = ends[(k + 1) % ends.len()];
        }
        heads.push(ends[0]);
    }
    let attributes: Vec<u32> = (0..6)
        .map(|e| {
            pack_attributes(
                if e == 0 {
                    EdgeFlags::RIDGE | EdgeFlags::CHAMFER
                } else {
                    EdgeFlags::RIDGE
                },
                0.25,
                0.25,
            )
        })
        .collect();
    let mut asset = Asset {
        header: Header {
            source: "tetra.obj".into(),
            generator: "test".into(),
            settings: vec![("crease_deg".into(), "30".into())],
            bounds_min: [0.0; 3],
            bounds_max: [1.0; 3],
            radius_scale: 0.25,
            stats: Stats {
                input_vertices: 4,
                welded_vertices: 4,
                input_triangles: 4,
                ..Stats::default()
            },
            sections: Vec::new(),
        },
        render_positions: tris.iter().flatten().map(|&i| p[i as usize]).collect(),
        render_normals: vec![[0.0, 0.0, 1.0]; 12],
        mesh_indices: Indices::with_bound((0..12).collect(), 12),
        topology_positions: p.to_vec(),
        edge_vertices: Indices::with_bound(edges.iter().flatten().copied().collect(), 4),
        edge_attributes: attributes,
        next_ends: Indices::with_bound(next, 12),
        cap_heads: Indices::with_bound(heads, 12),
        intersection_segments: Vec::new(),
        intersection_starts: Vec::new(),
        edge_clusters: Vec::new(),
        motion: Default::default(),
    };
    asset.edge_clusters = super::clusters::edge_clusters(&asset);
    asset
}

/// The tetrahedron with two intersection polylines: an open one of two segments, a closed triangle.
fn with_intersections() -> Asset {
    let (a, b, c) = ([0.1, 0.1, 0.1], [0.2, 0.1, 0.1], [0.2, 0.3, 0.1]);
    Asset {
        intersection_segments: vec![
            [[0.0, 0.5, 0.5], [0.5, 0.5, 0.5]],
            [[0.5, 0.5, 0.5], [0.5, 0.0, 0.5]],
            [a, b],
            [b, c],
            [c, a],
        ],
        intersection_starts: vec![0, 2],
        ..tetrahedron()
    }
}

fn decoded(asset: &Asset) -> Asset {
    Asset::decode(&asset.encode_to_vec()).expect("a freshly encoded asset decodes")
}

#[test]
fn round_trip_is_exact() {
    let asset = tetrahedron();
    let bytes = asset.encode_to_vec();
    assert_eq!(bytes.len() as u64, asset.encoded_len());
    let back = Asset::decode(&bytes).expect("decodes");
    assert_eq!(
        back.encode_to_vec(),
        bytes,
        "re-encoding gives the same bytes"
    );
    assert_eq!(back.render_positions, asset.render_positions);
    assert_eq!(back.edge_vertices, asset.edge_vertices);
    assert_eq!(back.next_ends, asset.next_ends);
    assert_eq!(back.edge_radius(0), 0.25);
    assert!(back.edge_flags(0).contains(EdgeFlags::CHAMFER));
    assert!(!back.edge_flags(1).contains(EdgeFlags::CHAMFER));
    assert_eq!(back.header.source, "tetra.obj");
}

#[test]
fn sections_are_aligned_and_use_narrow_indices() {
    let asset = decoded(&tetrahedron());
    for entry in &asset.header.sections {
        assert_eq!(entry.offset % SECTION_ALIGN as u64, 0);
    }
    assert_eq!(asset.edge_vertices.width(), IndexWidth::U16);
    assert_eq!(
        asset.section_bytes(SectionKind::EdgeVertices).len(),
        6 * 4 * 2
    );
}

#[test]
fn u32_indices_past_65536() {
    let mut asset = tetrahedron();
    let n = 70_000;
    asset.topology_positions = (0..n).map(|i| [i as f32, 0.0, 0.0]).collect();
    let mut ev = asset.edge_vertices.to_u32_vec();
    ev[0] = n as u32 - 1;
    asset.edge_vertices = Indices::with_bound(ev, n);
    asset.next_ends = Indices::default();
    asset.cap_heads = Indices::default();
    let back = decoded(&asset);
    assert_eq!(back.edge_vertices.width(), IndexWidth::U32);
    assert_eq!(back.edge(0)[0], n as u32 - 1);
}

#[test]
fn every_truncation_is_an_error() {
    let bytes = tetrahedron().encode_to_vec();
    for len in 0..bytes.len() {
        assert!(
            Asset::decode(&bytes[..len]).is_err(),
            "truncated to {len} bytes was accepted"
        );
    }
}

#[test]
fn trailing_bytes_are_an_error() {
    let mut bytes = tetrahedron().encode_to_vec();
    bytes.push(0);
    assert_eq!(Asset::decode(&bytes), Err(DecodeError::TrailingBytes(1)));
}

#[test]
fn magic_and_version_are_checked() {
    let bytes = tetrahedron().encode_to_vec();
    let mut bad = bytes.clone();
    bad[0] = b'X';
    assert_eq!(Asset::decode(&bad), Err(DecodeError::BadMagic));
    let mut newer = bytes;
    newer[8..12].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
    assert_eq!(
        Asset::decode(&newer),
        Err(DecodeError::UnsupportedVersion {
            found: FORMAT_VERSION + 1,
            supported: FORMAT_VERSION
        })
    );
}

#[test]
fn a_huge_header_length_is_refused_before_allocating() {
    let mut bytes = tetrahedron().encode_to_vec();
    bytes[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(matches!(
        Asset::decode(&bytes),
        Err(DecodeError::BadHeader(_))
    ));
}

#[test]
fn every_single_byte_corruption_is_handled() {
    // Flipping any bit of any byte either still decodes (e.g. a float's low bits) or is a typed error.
    let bytes = tetrahedron().encode_to_vec();
    let mut rejected = 0;
    for at in 0..bytes.len() {
        for bit in [0x01u8, 0x80] {
            let mut bad = bytes.clone();
            bad[at] ^= bit;
            if Asset::decode(&bad).is_err() {
                rejected += 1;
            }
        }
    }
    assert!(
        rejected > bytes.len() / 4,
        "only {rejected} corruptions were noticed"
    );
}

#[test]
fn out_of_range_index_names_the_section() {
    let mut asset = tetrahedron();
    let mut ev = asset.edge_vertices.to_u32_vec();
    ev[5] = 4;
    asset.edge_vertices = Indices::U16(ev.iter().map(|&v| v as u16).collect());
    let err = Asset::decode(&asset.encode_to_vec()).expect_err("index 4 of 4 vertices");
    assert_eq!(
        err,
        DecodeError::IndexOutOfRange {
            kind: SectionKind::EdgeVertices,
            position: 5,
            value: 4,
            bound: 4
        }
    );
    assert!(err.to_string().contains("edge_vertices"));
}

#[test]
fn non_finite_positions_are_refused() {
    let mut asset = tetrahedron();
    asset.topology_positions[2][1] = f32::NAN;
    assert_eq!(
        Asset::decode(&asset.encode_to_vec()),
        Err(DecodeError::NonFinite {
            kind: SectionKind::TopologyPositions,
            position: 2
        })
    );
}

#[test]
fn unknown_flags_and_negative_radii_are_refused() {
    let mut asset = tetrahedron();
    asset.edge_attributes[3] |= 1 << 12;
    assert!(matches!(
        Asset::decode(&asset.encode_to_vec()),
        Err(DecodeError::Invalid { position: 3, .. })
    ));
    let mut asset = tetrahedron();
    asset.edge_attributes[1] = pack_attributes(EdgeFlags::RIDGE, -1.0, 1.0);
    assert!(matches!(
        Asset::decode(&asset.encode_to_vec()),
        Err(DecodeError::Invalid { position: 1, .. })
    ));
}

#[test]
fn broken_rings_are_refused() {
    // Pointing two ends at the same next end breaks the permutation.
    let mut asset = tetrahedron();
    let mut next = asset.next_ends.to_u32_vec();
    let end_at_v0 = next[0];
    let other = (0..12)
        .find(|&e| e != 0 && next[e] != end_at_v0 && asset.end_vertex(e as u32) == 0)
        .unwrap_or(0);
    next[other] = end_at_v0;
    asset.next_ends = Indices::with_bound(next.clone(), 12);
    assert!(matches!(
        Asset::decode(&asset.encode_to_vec()),
        Err(DecodeError::Invalid {
            kind: SectionKind::NextEnds,
            ..
        })
    ));
    // Pointing to an end at another vertex leaves the vertex.
    next = tetrahedron().next_ends.to_u32_vec();
    next[0] = 1; // end 1 is edge 0's v1 = vertex 1, while end 0 is vertex 0
    asset.next_ends = Indices::with_bound(next, 12);
    assert!(matches!(
        Asset::decode(&asset.encode_to_vec()),
        Err(DecodeError::Invalid {
            kind: SectionKind::NextEnds,
            ..
        })
    ));
}

#[test]
fn mismatched_lengths_are_refused() {
    let mut asset = tetrahedron();
    asset.render_normals.pop();
    assert!(matches!(
        Asset::decode(&asset.encode_to_vec()),
        Err(DecodeError::BadSectionLength {
            kind: SectionKind::RenderNormals,
            ..
        })
    ));
    let mut asset = tetrahedron();
    asset.edge_attributes.pop();
    asset.next_ends = Indices::default();
    asset.cap_heads = Indices::default();
    assert!(Asset::decode(&asset.encode_to_vec()).is_err());
}

#[test]
fn radius_packing_keeps_half_precision() {
    for r in [0.0f32, 1e-3, 0.1, 0.5, 1.0] {
        let word = pack_attributes(EdgeFlags::MARKED, r, 1.0);
        assert!((attribute_radius(word, 1.0) - r).abs() <= r * 1e-3, "{r}");
        assert_eq!(attribute_flags(word), EdgeFlags::MARKED);
    }
}

/// `spokes` boundary edges from vertex 0 to vertices 1..=spokes, one next-index ring at vertex 0.
fn star(spokes: u32) -> Asset {
    let mut asset = tetrahedron();
    asset.topology_positions = (0..=spokes).map(|i| [i as f32, 0.0, 0.0]).collect();
    let vertices = spokes as usize + 1;
    let edges: Vec<u32> = (1..=spokes)
        .flat_map(|i| [0, i, i % spokes + 1, 0])
        .collect();
    asset.edge_vertices = Indices::with_bound(edges, vertices);
    asset.edge_attributes = vec![pack_attributes(EdgeFlags::BOUNDARY, 0.0, 0.0); spokes as usize];
    let ends = 2 * spokes;
    let next: Vec<u32> = (0..ends)
        .map(|end| if end % 2 == 0 { (end + 2) % ends } else { end })
        .collect();
    asset.next_ends = Indices::with_bound(next, ends as usize);
    asset.cap_heads = Indices::with_bound(vec![0], ends as usize);
    asset
}

#[test]
fn a_vertex_with_more_ends_than_the_join_walk_follows_is_refused() {
    assert!(Asset::decode(&star(MAX_RING).encode_to_vec()).is_ok());
    let error = Asset::decode(&star(MAX_RING + 1).encode_to_vec()).expect_err("ring too long");
    assert_eq!(
        error,
        DecodeError::RingTooLong {
            vertex: 0,
            ends: u64::from(MAX_RING) + 1,
            limit: MAX_RING
        }
    );
    assert!(error.to_string().contains("4097 kept edge ends"), "{error}");
}

#[test]
fn errors_read_as_sentences_not_rust_debug_text() {
    // The header starts with the source name's length: make it absurd.
    let mut bytes = tetrahedron().encode_to_vec();
    bytes[16..24].copy_from_slice(&(1u64 << 40).to_le_bytes());
    let error = Asset::decode(&bytes).expect_err("bad header");
    let text = error.to_string();
    assert!(matches!(error, DecodeError::BadHeader(_)), "{error:?}");
    assert!(
        text.contains("header limit") && !text.contains("LimitExceeded"),
        "{text}"
    );
    // Section names are the report names, not enum variants.
    let mut asset = tetrahedron();
    asset.mesh_indices = Indices::with_bound(vec![0, 1, 99], 100);
    let text = Asset::decode(&asset.encode_to_vec())
        .expect_err("out of range")
        .to_string();
    assert!(text.contains("section mesh_indices"), "{text}");
}

#[test]
fn cap_heads_without_next_ends_are_refused() {
    // Found by the fuzz harness (tests/fuzz.rs, asset target): a section table that empties
    // NextEnds but keeps CapHeads decoded, leaving heads whose rings do not exist.
    let mut asset = tetrahedron();
    asset.next_ends = Indices::default();
    assert!(matches!(
        Asset::decode(&asset.encode_to_vec()),
        Err(DecodeError::BadSectionLength {
            kind: SectionKind::CapHeads,
            ..
        })
    ));
    asset.cap_heads = Indices::default();
    assert!(
        Asset::decode(&asset.encode_to_vec()).is_ok(),
        "neither is fine"
    );
}

#[test]
fn intersections_round_trip_and_read_as_polylines() {
    let asset = with_intersections();
    let back = decoded(&asset);
    assert_eq!(back.intersection_segments, asset.intersection_segments);
    assert_eq!(back.intersection_starts, asset.intersection_starts);
    assert_eq!(back.encode_to_vec(), asset.encode_to_vec());
    let polylines: Vec<&[[[f32; 3]; 2]]> = back.intersection_polylines().collect();
    assert_eq!(polylines.len(), 2);
    assert_eq!(polylines[0].len(), 2);
    assert_eq!(polylines[1].len(), 3);
    assert_eq!(
        polylines[1][2][1], polylines[1][0][0],
        "the second one is closed"
    );
    let expected = 0.5 + 0.5 + 0.1 + 0.2 + (0.1f64 * 0.1 + 0.2 * 0.2).sqrt();
    assert!((back.intersection_length() - expected).abs() < 1e-6);
    assert_eq!(
        back.section_bytes(SectionKind::IntersectionSegments).len(),
        5 * 24
    );
}

#[test]
fn version_1_files_are_read_without_intersections() {
    let asset = tetrahedron();
    let mut v1 = Vec::new();
    asset.encode_version(1, &mut v1).expect("a v1 layout");
    assert_eq!(v1[8..12], 1u32.to_le_bytes());
    let back = Asset::decode(&v1).expect("version 1 is still read");
    assert_eq!(back.intersection_segments, Vec::<[[f32; 3]; 2]>::new());
    assert_eq!(back.intersection_polylines().len(), 0);
    assert_eq!(
        back.encode_to_vec(),
        asset.encode_to_vec(),
        "re-encoded as version 3"
    );
    // A version-1 file cannot hold intersection sections: kind 9 is unknown there.
    assert!(
        with_intersections()
            .encode_version(1, &mut Vec::new())
            .is_err()
    );
    let mut lying = asset.encode_to_vec();
    lying[8..12].copy_from_slice(&1u32.to_le_bytes());
    assert!(matches!(
        Asset::decode(&lying),
        Err(DecodeError::BadSectionTable(reason)) if reason.contains("kind 9")
    ));
    // And a version-2 file must have them (empty is fine).
    let mut missing = v1;
    missing[8..12].copy_from_slice(&2u32.to_le_bytes());
    assert!(matches!(
        Asset::decode(&missing),
        Err(DecodeError::BadSectionTable(reason)) if reason.contains("missing")
    ));
}

#[test]
fn broken_intersection_polylines_are_refused() {
    let refused = |asset: Asset| Asset::decode(&asset.encode_to_vec()).expect_err("refused");
    let mut unchained = with_intersections();
    unchained.intersection_segments[1][0][0] += 0.25;
    assert!(matches!(
        refused(unchained),
        DecodeError::Invalid {
            kind: SectionKind::IntersectionSegments,
            position: 1,
            ..
        }
    ));
    // The same break is fine where a new polyline starts.
    let mut split = with_intersections();
    split.intersection_segments[1][0][0] += 0.25;
    split.intersection_starts = vec![0, 1, 2];
    assert!(Asset::decode(&split.encode_to_vec()).is_ok());
    for starts in [vec![1, 2], vec![0, 0], vec![0, 3, 2], vec![0, 5], vec![]] {
        let mut bad = with_intersections();
        bad.intersection_starts = starts.clone();
        let err = refused(bad);
        assert!(
            matches!(
                err,
                DecodeError::Invalid {
                    kind: SectionKind::IntersectionPolylines,
                    ..
                } | DecodeError::BadSectionLength {
                    kind: SectionKind::IntersectionPolylines,
                    ..
                }
            ),
            "{starts:?}: {err}"
        );
    }
    let mut point = with_intersections();
    point.intersection_segments[4][1] = point.intersection_segments[4][0];
    assert!(matches!(
        refused(point),
        DecodeError::Invalid { position: 4, .. }
    ));
    let mut nan = with_intersections();
    nan.intersection_segments[3][1][2] = f32::NAN;
    assert_eq!(
        refused(nan),
        DecodeError::NonFinite {
            kind: SectionKind::IntersectionSegments,
            position: 7
        }
    );
    let mut ragged = with_intersections().encode_to_vec();
    ragged.truncate(ragged.len() - 4); // the last polyline start, cut in half
    assert!(Asset::decode(&ragged).is_err());
}

#[test]
fn version_2_files_get_their_clusters_computed() {
    let asset = with_intersections();
    let mut v2 = Vec::new();
    asset.encode_version(2, &mut v2).expect("a v2 layout");
    let back = Asset::decode(&v2).expect("version 2 is still read");
    assert_eq!(back.edge_clusters, super::clusters::edge_clusters(&asset));
    assert_eq!(back.encode_to_vec(), asset.encode_to_vec());
    // A version-3 file must have them.
    let mut missing = v2;
    missing[8..12].copy_from_slice(&3u32.to_le_bytes());
    assert!(matches!(
        Asset::decode(&missing),
        Err(DecodeError::BadSectionTable(reason)) if reason.contains("edge_clusters is missing")
    ));
}

#[test]
fn an_asset_built_without_clusters_encodes_them() {
    let mut asset = tetrahedron();
    let clusters = std::mem::take(&mut asset.edge_clusters);
    assert_eq!(clusters.len(), 1);
    assert_eq!(asset.encode_to_vec(), tetrahedron().encode_to_vec());
    assert_eq!(decoded(&asset).edge_clusters, clusters);
}

#[test]
fn broken_clusters_are_refused() {
    let nan = {
        let mut asset = tetrahedron();
        asset.edge_clusters[0].radius = f32::NAN;
        Asset::decode(&asset.encode_to_vec())
    };
    assert_eq!(
        nan,
        Err(DecodeError::NonFinite {
            kind: SectionKind::EdgeClusters,
            position: 0
        })
    );
    let wide = {
        let mut asset = tetrahedron();
        asset.edge_clusters[0].cos_angle = 1.5;
        Asset::decode(&asset.encode_to_vec())
    };
    assert!(matches!(
        wide,
        Err(DecodeError::Invalid {
            kind: SectionKind::EdgeClusters,
            ..
        })
    ));
    // One cluster too many: the length disagrees with the edges (encode would recompute a wrong
    // count, so the bytes are edited: the table says 96 bytes where there are 48).
    let mut two = tetrahedron();
    two.edge_clusters.push(two.edge_clusters[0]);
    let bytes = {
        let mut out = Vec::new();
        two.encode_as_stored(&mut out).expect("encode");
        out
    };
    assert!(matches!(
        Asset::decode(&bytes),
        Err(DecodeError::BadSectionLength {
            kind: SectionKind::EdgeClusters,
            ..
        })
    ));
}

/// The tetrahedron with its render vertices numbered as the bake numbers them: topology vertex by
/// topology vertex (three each, one per face at it), so their positions need not be stored.
fn tetrahedron_split_by_vertex() -> Asset {
    let asset = tetrahedron();
    let tris = [[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    let mut seen = [0u32; 4];
    let mut indices = Vec::new();
    for v in tris.into_iter().flatten() {
        indices.push(3 * v + seen[v as usize]);
        seen[v as usize] += 1;
    }
    let render_positions = asset
        .topology_positions
        .iter()
        .flat_map(|&p| [p; 3])
        .collect();
    Asset {
        render_positions,
        mesh_indices: Indices::with_bound(indices, 12),
        ..asset
    }
}

fn section_length(asset: &Asset, kind: SectionKind) -> Option<u64> {
    asset
        .header
        .sections
        .iter()
        .find(|s| s.kind == kind as u32)
        .map(|s| s.length)
}

#[test]
fn render_positions_the_topology_repeats_are_not_stored() {
    let asset = tetrahedron_split_by_vertex();
    let bytes = asset.encode_to_vec();
    let back = Asset::decode(&bytes).expect("decodes");
    assert_eq!(back.render_positions, asset.render_positions);
    assert_eq!(
        back.encode_to_vec(),
        bytes,
        "re-encoding gives the same bytes"
    );
    assert_eq!(section_length(&back, SectionKind::RenderPositions), Some(0));
    assert_eq!(
        section_length(&back, SectionKind::RenderVertexCounts),
        Some(4)
    );
    assert_eq!(asset.encoded_sections(), back.header.sections);
    assert_eq!(asset.encoded_len(), bytes.len() as u64);

    // Positions the topology does not give in order are stored, and the counts are not.
    let explicit = decoded(&tetrahedron());
    assert_eq!(
        section_length(&explicit, SectionKind::RenderPositions),
        Some(12 * 12)
    );
    assert_eq!(
        section_length(&explicit, SectionKind::RenderVertexCounts),
        Some(0)
    );

    // A version-3 file stores every render position, and still reads.
    let mut v3 = Vec::new();
    asset.encode_version(3, &mut v3).expect("a v3 layout");
    let old = Asset::decode(&v3).expect("version 3 is still read");
    assert_eq!(old.render_positions, asset.render_positions);
    assert_eq!(
        section_length(&old, SectionKind::RenderPositions),
        Some(12 * 12)
    );
    assert_eq!(old.encode_to_vec(), bytes, "re-encoded as today's version");

    // A version-4 file (no coded sections) still reads, and re-encodes the same.
    let mut v4 = Vec::new();
    asset.encode_version(4, &mut v4).expect("a v4 layout");
    assert_eq!(v4[8..12], 4u32.to_le_bytes());
    let old = Asset::decode(&v4).expect("version 4 is still read");
    assert_eq!(old.encode_to_vec(), bytes, "re-encoded as today's version");

    // More than 255 render vertices at one topology vertex: stored, not counted.
    let mut crowded = tetrahedron_split_by_vertex();
    let extra = 300;
    crowded.render_positions.splice(0..0, vec![[0.0; 3]; extra]);
    crowded.render_normals.extend(vec![[0.0, 0.0, 1.0]; extra]);
    let back = decoded(&crowded);
    assert_eq!(back.render_positions, crowded.render_positions);
    assert_eq!(
        section_length(&back, SectionKind::RenderVertexCounts),
        Some(0)
    );
}

#[test]
fn broken_render_vertex_counts_are_refused() {
    let asset = tetrahedron_split_by_vertex();
    let bytes = asset.encode_to_vec();
    let entry = asset
        .encoded_sections()
        .into_iter()
        .find(|s| s.kind == SectionKind::RenderVertexCounts as u32)
        .expect("a counts section");
    let mut short = bytes.clone();
    short[entry.offset as usize] = 2; // 11 render vertices for 12 normals
    let error = Asset::decode(&short).expect_err("counts disagree with the normals");
    assert!(
        matches!(
            error,
            DecodeError::BadSectionLength {
                kind: SectionKind::RenderVertexCounts,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(
        error.to_string().contains("render_vertex_counts"),
        "{error}"
    );

    // A count beyond what the normals hold.
    let mut long = bytes.clone();
    long[entry.offset as usize + 3] = 255;
    assert!(matches!(
        Asset::decode(&long),
        Err(DecodeError::BadSectionLength {
            kind: SectionKind::RenderVertexCounts,
            ..
        })
    ));

    // Counts beside stored positions: a file holds one or the other.
    let mut both = Vec::new();
    asset
        .encode_with_positions_and_counts(&mut both)
        .expect("encodes");
    let error = Asset::decode(&both).expect_err("both are present");
    assert!(error.to_string().contains("one or the other"), "{error}");

    // Every truncation and every single-bit flip of a file with counts is handled.
    let bytes = asset.encode_to_vec();
    for len in 0..bytes.len() {
        assert!(Asset::decode(&bytes[..len]).is_err(), "truncated to {len}");
    }
    for at in 0..bytes.len() {
        let mut bad = bytes.clone();
        bad[at] ^= 0x80;
        let _ = Asset::decode(&bad);
    }
}

#[test]
fn a_coded_section_beside_its_raw_twin_is_refused() {
    let asset = tetrahedron();
    let raw = asset.section_bytes(SectionKind::EdgeAttributes).to_vec();
    let mut bytes = Vec::new();
    asset
        .encode_with_sections(
            vec![
                (SectionKind::EdgeAttributes, raw),
                (SectionKind::EdgeAttributesCoded, vec![0; 8]),
            ],
            &mut bytes,
        )
        .expect("encodes");
    let error = Asset::decode(&bytes).expect_err("both twins");
    assert!(
        matches!(
            error,
            DecodeError::BadSectionLength {
                kind: SectionKind::EdgeAttributesCoded,
                ..
            }
        ),
        "{error}"
    );
    assert!(
        error.to_string().contains("beside edge_attributes"),
        "{error}"
    );
}

#[test]
fn ring_orders_without_corner_coded_edges_are_refused() {
    let asset = tetrahedron();
    let mut bytes = Vec::new();
    asset
        .encode_with_sections(vec![(SectionKind::RingOrders, vec![0; 16])], &mut bytes)
        .expect("encodes");
    let error = Asset::decode(&bytes).expect_err("no corners");
    assert!(
        error.to_string().contains("without edge corners"),
        "{error}"
    );
}

/// The tetrahedron with a two-joint skin (vertex 3 on joint 1), a morph target moving vertices 1
/// and 3, and an animation of the second joint.
fn animated_tetrahedron() -> Asset {
    use crate::rig::{Animation, Channel, Interpolation, Joint, Node, Rig, Target, Transform};
    let rig = Rig {
        nodes: vec![
            Node::default(),
            Node {
                name: "tip".into(),
                parent: Some(0),
                rest: Transform::IDENTITY,
            },
        ],
        joints: (0..2)
            .map(|node| Joint {
                node,
                inverse_bind: glam::Mat4::IDENTITY.to_cols_array(),
            })
            .collect(),
        morph_weights: vec![0.0],
        morph_names: vec!["lift".into()],
        animations: vec![Animation {
            name: "nod".into(),
            channels: vec![Channel {
                target: Target::Translation(1),
                interpolation: Interpolation::Linear,
                times: vec![0.0, 1.0],
                values: vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            }],
        }],
    };
    Asset {
        motion: Motion {
            joints: vec![[0; 4], [0; 4], [0; 4], [1, 0, 0, 0]],
            weights: vec![[1.0, 0.0, 0.0, 0.0]; 4],
            morph_starts: vec![0],
            morph_vertices: vec![1, 3],
            morph_deltas: vec![[0.0, 0.5, 0.0], [0.0, 0.5, 0.0]],
            rig,
        },
        ..tetrahedron()
    }
}

#[test]
fn animated_assets_round_trip_and_pose() {
    let asset = animated_tetrahedron();
    let back = decoded(&asset);
    assert_eq!(back.motion, asset.motion);
    let rig = &back.motion.rig;
    let pose = crate::rig::Pose::sampled(rig, 0, 0.5).expect("animation 0");
    let mut weighted = pose.clone();
    weighted.weights = vec![1.0];
    let posed = back
        .motion
        .pose_positions(&back.topology_positions, &weighted);
    assert_eq!(
        posed[3],
        [0.0, 0.5, 1.5],
        "lifted by the target, moved by joint 1"
    );
    assert_eq!(posed[1], [1.0, 0.5, 0.0], "lifted only");
    assert_eq!(posed[0], back.topology_positions[0]);
}

#[test]
fn broken_motion_sections_are_refused() {
    let refuse = |change: &dyn Fn(&mut Motion), expected: &str| {
        let mut asset = animated_tetrahedron();
        change(&mut asset.motion);
        let error = Asset::decode(&asset.encode_to_vec()).expect_err(expected);
        let text = error.to_string();
        assert!(text.contains(expected), "{expected}: {text}");
    };
    refuse(
        &|m| m.joints[2][0] = 2,
        "skin_joints: element 2 is 2, out of range",
    );
    refuse(
        &|m| m.weights.truncate(3),
        "3 entries for 4 topology vertices",
    );
    refuse(
        &|m| m.weights[1] = [0.5, 0.0, 0.0, 0.0],
        "weights sum to 0.5",
    );
    refuse(&|m| m.weights[1] = [1.5, -0.5, 0.0, 0.0], "negative weight");
    refuse(
        &|m| m.weights[1][0] = f32::NAN,
        "skin_weights: element 1 is not a finite number",
    );
    refuse(
        &|m| m.morph_vertices = vec![3, 1],
        "target 0 lists vertex 1 after 3",
    );
    refuse(
        &|m| m.morph_vertices[1] = 4,
        "morph_vertices: element 1 is 4",
    );
    refuse(
        &|m| m.morph_deltas.pop().map_or((), drop),
        "1 deltas for 2 morph vertices",
    );
    refuse(
        &|m| m.morph_starts = vec![1],
        "the first target starts at 1",
    );
    refuse(
        &|m| m.morph_starts.clear(),
        "0 targets, the rig has 1 morph weights",
    );
    refuse(
        &|m| m.rig.nodes[0].parent = Some(1),
        "node 0 comes before its parent",
    );
    refuse(&|m| m.rig.joints[1].node = 7, "joint 1 refers to node 7");
    refuse(
        &|m| m.rig.animations[0].channels[0].times = vec![1.0, 1.0],
        "animation 0 channel 0: key times are not increasing",
    );
    refuse(
        &|m| m.rig.animations[0].channels[0].values.push(0.0),
        "7 values for 2 keys of 3 numbers",
    );
    // A rig section that is not a rig at all.
    let asset = animated_tetrahedron();
    let garbage = vec![0xff; 40];
    let mut bytes = Vec::new();
    asset
        .encode_with_sections(vec![(SectionKind::Rig, garbage)], &mut bytes)
        .expect("encodes");
    let text = Asset::decode(&bytes).expect_err("garbage rig").to_string();
    assert!(text.starts_with("section rig:"), "{text}");
}
