//! Small fixtures with answers known by construction (fixtures/make_fixtures.py), and broken files.

use chamfer_preprocess::{BakeOptions, Error, Radius, Stitch, bake_file};
use chamfer_runtime::asset::{Asset, EdgeFlags, EdgeStats};
use chamfer_tests::fixture;

fn bake(relative: &str) -> Asset {
    let asset = bake_file(&fixture(relative), &BakeOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"))
        .asset;
    Asset::decode(&asset.encode_to_vec()).unwrap_or_else(|e| panic!("{relative}: {e}"))
}

fn edges(relative: &str) -> EdgeStats {
    bake(relative).header.stats.edges
}

#[test]
fn cube_keeps_twelve_creases_and_drops_six_diagonals() {
    let e = edges("shapes/cube.obj");
    assert_eq!(
        (e.total, e.kept, e.crease, e.ridge, e.coplanar_dropped),
        (18, 12, 12, 12, 6)
    );
    assert_eq!(
        (e.boundary, e.non_manifold, e.smooth, e.valley),
        (0, 0, 0, 0)
    );
}

#[test]
fn cylinder_drops_half_its_edges_and_keeps_its_sides_as_contour_candidates() {
    // 16 sides: 96 edges; 16 side diagonals and 32 cap spokes are coplanar; 32 rim edges are 90° creases;
    // the 16 side edges bend by 22.5°, below the 30° crease angle: smooth, kept for contours.
    let e = edges("shapes/cylinder-16.obj");
    assert_eq!(
        (e.total, e.coplanar_dropped, e.crease, e.smooth, e.kept),
        (96, 48, 32, 16, 48)
    );
}

#[test]
fn cone_keeps_its_rim_as_crease_and_its_sides_as_smooth() {
    let e = edges("shapes/cone-16.obj");
    assert_eq!(
        (e.total, e.coplanar_dropped, e.crease, e.ridge, e.smooth),
        (48, 16, 16, 16, 16)
    );
}

#[test]
fn open_plane_keeps_only_its_boundary() {
    let asset = bake("shapes/plane-4x4.obj");
    let e = asset.header.stats.edges;
    assert_eq!(
        (e.total, e.boundary, e.coplanar_dropped, e.kept),
        (56, 16, 40, 16)
    );
    for k in 0..asset.edge_count() {
        let [v0, _, _, v3] = asset.edge(k);
        assert_eq!(v3, v0, "boundary edges carry v3 = v0");
    }
}

#[test]
fn non_manifold_fan_keeps_and_flags_the_shared_edge() {
    let asset = bake("shapes/nonmanifold-fan.obj");
    let e = asset.header.stats.edges;
    assert_eq!((e.total, e.non_manifold, e.boundary), (7, 1, 6));
    let shared: Vec<usize> = (0..asset.edge_count())
        .filter(|&k| asset.edge_flags(k).contains(EdgeFlags::NON_MANIFOLD))
        .collect();
    assert_eq!(shared.len(), 1);
    let [v0, v1, ..] = asset.edge(shared[0]);
    let ends = [v0, v1].map(|v| asset.topology_positions[v as usize]);
    assert!(
        ends.contains(&[0.0, 0.0, 0.0]) && ends.contains(&[1.0, 0.0, 0.0]),
        "{ends:?}"
    );
}

#[test]
fn ply_edge_elements_become_marks_with_radii_in_every_encoding() {
    let mut answers = Vec::new();
    for name in ["ascii", "le", "be"] {
        let asset = bake(&format!("shapes/cube-marked-{name}.ply"));
        let e = asset.header.stats.edges;
        // The marked diagonal (0, 3) survives coplanar dropping.
        assert_eq!(
            (e.marked, e.kept, e.coplanar_dropped, e.marks_unmatched),
            (4, 13, 5, 0),
            "{name}"
        );
        let mut marks: Vec<([f32; 3], [f32; 3], f32)> = (0..asset.edge_count())
            .filter(|&k| asset.edge_flags(k).contains(EdgeFlags::MARKED))
            .map(|k| {
                let [v0, v1, ..] = asset.edge(k);
                let (a, b) = (
                    asset.topology_positions[v0 as usize],
                    asset.topology_positions[v1 as usize],
                );
                (
                    if a < b { a } else { b },
                    if a < b { b } else { a },
                    asset.edge_radius(k),
                )
            })
            .collect();
        marks.sort_by(|x, y| x.partial_cmp(y).expect("finite"));
        answers.push(marks);
    }
    let close = |a: f32, b: f32| (a - b).abs() <= b * 1e-3;
    let m = &answers[0];
    assert_eq!(m.len(), 4);
    let radius_of = |a: [f32; 3], b: [f32; 3]| m.iter().find(|x| x.0 == a && x.1 == b).map(|x| x.2);
    assert!(close(
        radius_of([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]).expect("edge 0-1"),
        0.05
    ));
    assert!(close(
        radius_of([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]).expect("edge 0-4"),
        0.1
    ));
    assert!(close(
        radius_of([0.0, 0.0, 0.0], [0.0, 1.0, 1.0]).expect("diagonal 0-3"),
        0.02
    ));
    assert_eq!(radius_of([1.0, 1.0, 0.0], [1.0, 1.0, 1.0]), Some(0.0));
    assert_eq!(answers[0], answers[1], "ascii and little-endian agree");
    assert_eq!(answers[0], answers[2], "ascii and big-endian agree");
}

#[test]
fn gltf_primitives_with_different_materials_leave_a_seam() {
    for file in [
        "two-materials.gltf",
        "two-materials.glb",
        "two-materials-external.gltf",
    ] {
        let baked = bake_file(&fixture(&format!("shapes/{file}")), &BakeOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("{e}"));
        let asset = &baked.asset;
        let e = asset.header.stats.edges;
        // Two coplanar quads: the seam between them is kept as a material edge, the diagonals dropped.
        assert_eq!(
            (e.total, e.material, e.boundary, e.coplanar_dropped, e.kept),
            (9, 1, 6, 2, 7),
            "{file}"
        );
        assert_eq!(
            asset.header.stats.welded_vertices, 6,
            "{file}: the seam's duplicated vertices weld"
        );
        assert_eq!(
            asset.triangle_count(),
            4,
            "{file}: list + strip; the points primitive is skipped"
        );
        assert!(
            baked.warnings.iter().any(|w| w.contains("Points")),
            "{file}: {:?}",
            baked.warnings
        );
        // The node's translation is applied.
        assert_eq!(asset.header.bounds_min, [10.0, 0.0, 0.0], "{file}");
        assert_eq!(asset.header.bounds_max, [12.0, 1.0, 0.0], "{file}");
    }
}

#[test]
fn quantized_sparse_gltf_under_nested_transforms() {
    // Normalized u8 positions (KHR_mesh_quantization), a sparse accessor, a matrix node inside a scaled node.
    let asset = bake("shapes/cube-quantized.gltf");
    let e = asset.header.stats.edges;
    assert_eq!(
        (e.total, e.kept, e.crease, e.coplanar_dropped),
        (18, 12, 12, 6)
    );
    assert_eq!(asset.header.bounds_min, [2.0, 4.0, 6.0]);
    assert_eq!(asset.header.bounds_max, [3.0, 5.0, 7.0]);
}

/// Each broken file gives an error that names it and says what is wrong.
#[test]
fn broken_files_are_typed_errors_naming_the_file() {
    let cases = [
        ("empty.obj", "no triangles"),
        ("nan-position.obj", "non-finite"),
        ("index-out-of-range.obj", "out of bounds"),
        ("all-degenerate.obj", "degenerate"),
        ("truncated.ply", "element 'edge'"),
        ("wrong-header.ply", "invalid PLY"),
        ("truncated.glb", "invalid glTF"),
        ("bad-index.gltf", "runs past the end"),
        ("draco-required.gltf", "KHR_draco_mesh_compression"),
    ];
    for (file, what) in cases {
        let path = fixture(&format!("broken/{file}"));
        let before = std::fs::read(&path).expect("fixture");
        let error = match bake_file(&path, &BakeOptions::DEFAULT) {
            Ok(_) => panic!("{file}: broken input was baked"),
            Err(e) => e,
        };
        let message = error.to_string();
        assert!(
            message.contains(file),
            "{file}: message does not name the file: {message}"
        );
        assert!(
            message.contains(what),
            "{file}: expected '{what}' in: {message}"
        );
        assert!(!matches!(error, Error::Read { .. }), "{file}: {message}");
        assert_eq!(
            std::fs::read(&path).expect("fixture"),
            before,
            "{file}: input was modified"
        );
    }
}

#[test]
fn a_cube_marked_by_rule_gets_twelve_chamfer_edges() {
    let options = BakeOptions::DEFAULT.with_radius(Radius::Absolute(0.05));
    let asset = bake_file(&fixture("shapes/cube.obj"), &options)
        .unwrap_or_else(|e| panic!("{e}"))
        .asset;
    let chamfer = asset.header.stats.chamfer;
    assert_eq!((chamfer.edges, chamfer.clamped), (12, 0));
    for e in 0..asset.edge_count() {
        assert!(asset.edge_flags(e).contains(EdgeFlags::CHAMFER));
        assert!(
            (asset.edge_radius(e) - 0.05).abs() < 1e-5,
            "{}",
            asset.edge_radius(e)
        );
    }
    // Too large for the faces: clamped to the triangles' height over the edge (1 on the unit cube).
    let options = BakeOptions::DEFAULT.with_radius(Radius::Absolute(3.0));
    let chamfer = bake_file(&fixture("shapes/cube.obj"), &options)
        .unwrap_or_else(|e| panic!("{e}"))
        .asset
        .header
        .stats
        .chamfer;
    assert_eq!((chamfer.edges, chamfer.clamped), (12, 12));
    assert!((chamfer.radius_max - 1.0).abs() < 1e-5);
}

#[test]
fn file_radii_win_over_the_rule_and_valleys_are_opt_in() {
    // The marked PLY cube: three marks carry radii, one does not; the rule fills that one and the other ridges.
    let options = BakeOptions::DEFAULT.with_radius(Radius::Absolute(0.2));
    let asset = bake_file(&fixture("shapes/cube-marked-ascii.ply"), &options)
        .unwrap_or_else(|e| panic!("{e}"))
        .asset;
    let mut radii: Vec<f32> = (0..asset.edge_count())
        .map(|e| asset.edge_radius(e))
        .collect();
    radii.sort_by(f32::total_cmp);
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-3 * b;
    assert!(
        close(radii[0], 0.02) && close(radii[1], 0.05) && close(radii[2], 0.1),
        "{radii:?}"
    );
    assert!(radii[3..].iter().all(|&r| close(r, 0.2)), "{radii:?}");
    // A cone's base rim is a ridge; nothing in it is a valley, so valleys change nothing there.
    let ridges = BakeOptions::DEFAULT.with_radius(Radius::Relative(0.01));
    let both = ridges.with_radius_valleys(true);
    let count = |o: &BakeOptions| {
        bake_file(&fixture("shapes/cone-16.obj"), o)
            .map(|b| b.asset.header.stats.chamfer.edges)
            .ok()
    };
    assert_eq!(count(&ridges), Some(16));
    assert_eq!(count(&both), Some(16));
}

#[test]
fn gltf_marks_in_extras_cesium_outline_and_edge_visibility() {
    // extras.chamfer carries the same four marks as the PLY fixtures (three with radii).
    for file in ["cube-marked-extras.gltf", "cube-marked-extras.glb"] {
        let asset = bake(&format!("shapes/{file}"));
        let e = asset.header.stats.edges;
        assert_eq!((e.marked, e.kept, e.marks_unmatched), (4, 13, 0), "{file}");
        assert_eq!(asset.header.stats.chamfer.edges, 3, "{file}");
        assert!(
            (asset.header.stats.chamfer.radius_max - 0.1).abs() < 1e-4,
            "{file}"
        );
    }
    // Both extensions list the cube's 12 edges (the visibility bits mark each as hard once, then "repeated").
    for file in ["cube-outline.gltf", "cube-edge-visibility.gltf"] {
        let e = bake(&format!("shapes/{file}")).header.stats.edges;
        assert_eq!(
            (e.marked, e.kept, e.coplanar_dropped, e.marks_unmatched),
            (12, 12, 6, 0),
            "{file}"
        );
    }
}

/// A mesh's triangles as corner positions (bits), each rotated to start at its smallest corner
/// (winding kept), sorted: equal for two files that hold the same faces however they number them.
fn canonical_triangles(relative: &str) -> Vec<[[u32; 3]; 3]> {
    let mesh =
        chamfer_preprocess::load::load(&fixture(relative), &chamfer_preprocess::Limits::DEFAULT)
            .unwrap_or_else(|e| panic!("{e}"))
            .mesh;
    let mut triangles: Vec<[[u32; 3]; 3]> = mesh
        .triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| mesh.positions[v as usize].to_array().map(f32::to_bits));
            let k = (0..3).min_by_key(|&k| p[k]).expect("three corners");
            [p[k], p[(k + 1) % 3], p[(k + 2) % 3]]
        })
        .collect();
    triangles.sort_unstable();
    triangles
}

#[test]
fn ply_header_lines_that_are_not_keywords_are_read_with_a_warning() {
    // Blender 2.4x's "Created by Blender ..." line, unprefixed, among the header keywords.
    let path = fixture("shapes/cube-blender24.ply");
    let loaded = chamfer_preprocess::load::load(&path, &chamfer_preprocess::Limits::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.warnings.len(), 1, "{:?}", loaded.warnings);
    assert!(
        loaded.warnings[0].contains("Created by Blender 2.49"),
        "{:?}",
        loaded.warnings
    );
    // The quads fan into the cube's own triangles (same vertex numbering and winding).
    assert_eq!(
        canonical_triangles("shapes/cube-blender24.ply"),
        canonical_triangles("shapes/cube.obj")
    );
    assert_eq!(edges("shapes/cube-blender24.ply"), edges("shapes/cube.obj"));
}

#[test]
fn ply_tristrips_with_restarts_are_the_cube_with_its_winding() {
    // Six strips (two stitched by repeated vertices, the rest split by -1) make the cube's 12
    // triangles, each wound as the OBJ winds it: every odd strip triangle has its last two swapped.
    assert_eq!(
        canonical_triangles("shapes/cube-tristrips.ply"),
        canonical_triangles("shapes/cube.obj")
    );
    let stats = bake("shapes/cube-tristrips.ply").header.stats;
    assert_eq!(stats.edges, edges("shapes/cube.obj"));
    assert_eq!(
        (
            stats.input_triangles,
            stats.degenerate_triangles,
            stats.edges.ridge
        ),
        (12, 0, 12)
    );
}

#[test]
fn ply_tristrips_count_against_the_triangle_limit_before_they_are_added() {
    let path = fixture("shapes/cube-tristrips.ply");
    // The first strip list holds at most 13 - 2 = 11 triangles: over a limit of 10 before any is added.
    let limits = chamfer_preprocess::Limits::DEFAULT.with_max_triangles(10);
    let error = chamfer_preprocess::load::load(&path, &limits).expect_err("over the limit");
    assert!(matches!(error, Error::LimitExceeded { .. }), "{error}");
    assert!(error.to_string().contains("cube-tristrips.ply"), "{error}");
    let bytes = std::fs::read(&path).expect("fixture");
    // A negative index other than -1 is an error naming it.
    let at = bytes
        .windows(4)
        .position(|w| w == (-1i32).to_be_bytes())
        .expect("a restart");
    let mut bad = bytes.clone();
    bad[at..at + 4].copy_from_slice(&(-2i32).to_be_bytes());
    let error = chamfer_preprocess::load::load_bytes(
        std::path::Path::new("bad-strip.ply"),
        &bad,
        &chamfer_preprocess::Limits::DEFAULT,
    )
    .expect_err("-2 is no restart");
    assert!(
        error.to_string().contains("negative vertex index -2"),
        "{error}"
    );
}

#[test]
fn the_default_weld_closes_a_cad_export_whose_copies_are_ulps_apart() {
    // Each face has its own corners, 1 to 4 ULPs from the other faces' copies, 2,000 units from the
    // origin: a tolerance relative to the model's extent (1.7e-6 here) would not join them.
    let path = fixture("shapes/cube-cad-jittered.glb");
    let default = bake_file(&path, &BakeOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"))
        .asset
        .header
        .stats;
    assert_eq!((default.input_vertices, default.welded_vertices), (24, 8));
    // The cube's 18 edges and 12 ridges, no crack. (The welded corners keep the first copy's
    // jitter, so a face diagonal may be more than the 0.01° coplanar threshold from flat: smooth.)
    let e = default.edges;
    assert_eq!((e.total, e.boundary, e.crease, e.ridge), (18, 0, 12, 12));
    assert_eq!(e.smooth + e.coplanar_dropped, 6);
    // --weld-epsilon 0 with --no-stitch keeps the exact weld: every face is its own open square.
    let exact = BakeOptions::DEFAULT.with_weld_epsilon(0.0);
    let open = bake_file(&path, &exact.with_stitch(Stitch::Off))
        .unwrap_or_else(|e| panic!("{e}"))
        .asset
        .header
        .stats;
    assert!(open.welded_vertices > 8, "{}", open.welded_vertices);
    assert_eq!((open.edges.boundary, open.edges.crease), (24, 0));
    // Stitching within 1e-3 (the copies are up to 4 ULPs, 4.9e-4, apart; the default stitch, 1e-4
    // of the 1.7 diagonal, is less) closes what the exact weld left: the corner copies joined into
    // 8, the 24 squares' sides paired into the cube's 12 ridges.
    let stitched = bake_file(&path, &exact.with_stitch(Stitch::Absolute(1e-3)))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(stitched.stitched.boundary_before, 24);
    assert_eq!(
        stitched.stitched.boundary_after, 0,
        "{:?}",
        stitched.stitched
    );
    assert_eq!(stitched.stitched.joined_vertices, open.welded_vertices - 8);
    let e = stitched.asset.header.stats.edges;
    assert_eq!((e.total, e.boundary, e.crease, e.ridge), (18, 0, 12, 12));
}

#[test]
fn the_relative_weld_distance_follows_the_farthest_corner() {
    use chamfer_preprocess::WeldTolerance;
    use glam::Vec3;
    let far = [
        Vec3::new(1000.0, 2000.0, -2.0),
        Vec3::new(1001.0, 2001.0, 2.0),
    ];
    let expected = 1e-6 * Vec3::new(1001.0, 2001.0, 2.0).length();
    assert!((WeldTolerance::DEFAULT.distance(&far) - expected).abs() < 1e-9);
    assert_eq!(WeldTolerance::EXACT.distance(&far), 0.0);
    // Distinct vertices a thousandth of the model apart never weld by default.
    let near_origin = [Vec3::ZERO, Vec3::new(1e-3, 0.0, 0.0), Vec3::ONE];
    let weld =
        chamfer_preprocess::weld::weld(&near_origin, WeldTolerance::DEFAULT.distance(&near_origin));
    assert_eq!(weld.remap, [0, 1, 2]);
}
