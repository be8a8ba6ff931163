//! `annotate` round trips: the marks and radii written into a PLY or glTF read back unchanged, and
//! everything else in the file survives.

use std::path::Path;

use chamfer_preprocess::annotate::annotate;
use chamfer_preprocess::{BakeOptions, Limits, Radius, bake_file, load};
use chamfer_runtime::asset::{Asset, EdgeFlags};
use chamfer_tests::fixture;

type Edge = ([u32; 3], [u32; 3]);

/// Chamfer edges by end positions (bits), with their radii, and the marked edges.
fn chamfer_and_marks(asset: &Asset) -> (Vec<(Edge, u16)>, Vec<Edge>) {
    let key = |e: usize| {
        let [v0, v1, ..] = asset.edge(e);
        let (a, b) = (
            asset.topology_positions[v0 as usize],
            asset.topology_positions[v1 as usize],
        );
        let (a, b) = (a.map(f32::to_bits), b.map(f32::to_bits));
        if a < b { (a, b) } else { (b, a) }
    };
    let mut chamfer: Vec<(Edge, u16)> = (0..asset.edge_count())
        .filter(|&e| asset.edge_flags(e).contains(EdgeFlags::CHAMFER))
        .map(|e| (key(e), half_bits(asset.edge_radius(e))))
        .collect();
    let mut marks: Vec<Edge> = (0..asset.edge_count())
        .filter(|&e| asset.edge_flags(e).contains(EdgeFlags::MARKED))
        .map(key)
        .collect();
    chamfer.sort();
    marks.sort();
    (chamfer, marks)
}

/// Radii compared at the asset's own f16 precision relative to 1.
fn half_bits(r: f32) -> u16 {
    (r * 1e4).round() as u16
}

fn bake(path: &Path, options: &BakeOptions) -> Asset {
    bake_file(path, options)
        .unwrap_or_else(|e| panic!("{e}"))
        .asset
}

fn round_trip(input: &str, output_name: &str) {
    let dir = tempfile::tempdir().expect("tempdir");
    let input = fixture(input);
    let output = dir.path().join(output_name);
    let rule = BakeOptions::DEFAULT.with_radius(Radius::Absolute(0.2));
    let before = std::fs::read(&input).expect("input");
    let written = annotate(&input, &output, &rule).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        std::fs::read(&input).expect("input"),
        before,
        "input modified"
    );

    let original = bake(&input, &rule);
    let annotated = bake(&output, &BakeOptions::DEFAULT);
    let (chamfer, marks) = chamfer_and_marks(&original);
    let (chamfer_back, marks_back) = chamfer_and_marks(&annotated);
    assert!(!chamfer.is_empty());
    assert_eq!(
        chamfer_back, chamfer,
        "{output_name}: chamfer edges and radii"
    );
    assert_eq!(
        written.edges,
        marks_back.len(),
        "{output_name}: every written edge reads back as a mark"
    );
    assert!(
        marks.iter().all(|m| marks_back.contains(m)),
        "{output_name}: the file's marks survive"
    );
    assert_eq!(
        annotated.edge_vertices, original.edge_vertices,
        "{output_name}: same topology"
    );
    assert_eq!(annotated.mesh_indices, original.mesh_indices);

    // Annotating the annotated file again writes the same marks.
    let again = dir.path().join(format!("again-{output_name}"));
    annotate(&output, &again, &BakeOptions::DEFAULT).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        chamfer_and_marks(&bake(&again, &BakeOptions::DEFAULT)),
        (chamfer_back, marks_back)
    );

    // The geometry is what it was.
    let (a, b) = (
        load::load(&input, &Limits::DEFAULT).expect("load").mesh,
        load::load(&output, &Limits::DEFAULT).expect("load").mesh,
    );
    assert_eq!(
        (a.positions, a.triangles, a.materials),
        (b.positions, b.triangles, b.materials)
    );
}

#[test]
fn ply_marks_round_trip_in_every_encoding() {
    for (name, format) in [
        ("ascii", "ascii"),
        ("le", "binary_little_endian"),
        ("be", "binary_big_endian"),
    ] {
        round_trip(
            &format!("shapes/cube-marked-{name}.ply"),
            &format!("out-{name}.ply"),
        );
        let dir = tempfile::tempdir().expect("tempdir");
        let out = dir.path().join("x.ply");
        annotate(
            &fixture(&format!("shapes/cube-marked-{name}.ply")),
            &out,
            &BakeOptions::DEFAULT,
        )
        .expect("annotate");
        let text = String::from_utf8_lossy(&std::fs::read(&out).expect("output")).into_owned();
        assert!(
            text.contains(&format!("format {format} 1.0")),
            "{name}: encoding kept"
        );
        assert!(
            text.contains("comment chamfer fixture"),
            "{name}: comments kept"
        );
        assert!(text.contains("property ushort class"), "{name}");
    }
}

#[test]
fn gltf_marks_round_trip_as_extras() {
    round_trip("shapes/cube-marked-extras.gltf", "cube.gltf");
    round_trip("shapes/cube-outline.gltf", "outline.gltf");
    round_trip("shapes/cube-edge-visibility.gltf", "visibility.gltf");
}

#[test]
fn glb_keeps_its_binary_chunk_and_the_rest_of_its_json() {
    let dir = tempfile::tempdir().expect("tempdir");
    let input = fixture("shapes/two-materials.glb");
    let output = dir.path().join("pair.glb");
    // A flat pair has no ridge for the rule: nothing to write, so the JSON must come back equal.
    annotate(
        &input,
        &output,
        &BakeOptions::DEFAULT.with_radius(Radius::Absolute(0.1)),
    )
    .expect("annotate");
    let (a, b) = (
        std::fs::read(&input).expect("in"),
        std::fs::read(&output).expect("out"),
    );
    let chunks = |bytes: &[u8]| {
        let json_len = u32::from_le_bytes([bytes[12], bytes[13], bytes[14], bytes[15]]) as usize;
        let json: serde_json::Value =
            serde_json::from_slice(&bytes[20..20 + json_len]).expect("json");
        (json, bytes[20 + json_len..].to_vec())
    };
    let ((json_a, bin_a), (json_b, bin_b)) = (chunks(&a), chunks(&b));
    assert_eq!(bin_a, bin_b, "binary chunk copied byte for byte");
    assert_eq!(
        json_a, json_b,
        "no marks on this flat pair: the JSON is unchanged"
    );
    round_trip("shapes/cube-marked-extras.glb", "cube.glb");
    // Other keys of a primitive's extras stay.
    let out = dir.path().join("cube.glb");
    annotate(
        &fixture("shapes/cube-marked-extras.glb"),
        &out,
        &BakeOptions::DEFAULT,
    )
    .expect("annotate");
    let (json, _) = chunks(&std::fs::read(&out).expect("out"));
    assert_eq!(
        json["meshes"][0]["primitives"][0]["extras"]["author"],
        "chamfer fixtures"
    );
    assert_eq!(
        json["meshes"][0]["primitives"][0]["extras"]["chamfer"]["edges"]
            .as_array()
            .map(Vec::len),
        Some(4)
    );
}

#[test]
fn annotate_refuses_what_it_cannot_write() {
    let dir = tempfile::tempdir().expect("tempdir");
    let obj = fixture("shapes/cube.obj");
    assert!(
        annotate(&obj, &dir.path().join("cube.obj"), &BakeOptions::DEFAULT).is_err(),
        "OBJ has no edge data"
    );
    let ply = fixture("shapes/cube-marked-ascii.ply");
    let err = annotate(&ply, &dir.path().join("cube.glb"), &BakeOptions::DEFAULT)
        .expect_err("format change");
    assert!(err.to_string().contains("cube.glb"), "{err}");
    let err = annotate(&ply, &ply, &BakeOptions::DEFAULT).expect_err("overwrite");
    assert!(err.to_string().contains("overwrite"), "{err}");
}
