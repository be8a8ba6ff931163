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

/// A GLB's JSON and binary chunk.
fn read_glb(path: &Path) -> (serde_json::Value, Vec<u8>) {
    let bytes = std::fs::read(path).expect("GLB");
    let word =
        |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes")) as usize;
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(word(8), bytes.len(), "GLB length");
    let json_end = 20 + word(12);
    let document = serde_json::from_slice(&bytes[20..json_end]).expect("JSON chunk");
    assert_eq!(word(json_end + 4), 0x004E_4942, "a BIN chunk follows");
    let bin = bytes[json_end + 8..json_end + 8 + word(json_end)].to_vec();
    (document, bin)
}

/// An accessor's components (tightly packed, buffer 0), with its component type.
fn accessor(document: &serde_json::Value, bin: &[u8], index: u64) -> (Vec<f64>, u64) {
    let a = &document["accessors"][index as usize];
    let view = &document["bufferViews"][a["bufferView"].as_u64().expect("bufferView") as usize];
    assert_eq!(view["buffer"], 0);
    assert!(view.get("byteStride").is_none());
    let component = a["componentType"].as_u64().expect("componentType");
    let width = match a["type"].as_str().expect("type") {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        other => panic!("type {other}"),
    };
    let start = view["byteOffset"].as_u64().unwrap_or(0) as usize
        + a["byteOffset"].as_u64().unwrap_or(0) as usize;
    let count = a["count"].as_u64().expect("count") as usize * width;
    let size = match component {
        5120 | 5121 => 1,
        5122 | 5123 => 2,
        5125 | 5126 => 4,
        other => panic!("componentType {other}"),
    };
    assert!(
        start + count * size <= bin.len()
            && count * size <= view["byteLength"].as_u64().expect("byteLength") as usize
    );
    let values = (0..count)
        .map(|i| {
            let b = &bin[start + i * size..start + (i + 1) * size];
            match component {
                5120 => f64::from(b[0] as i8),
                5121 => f64::from(b[0]),
                5122 => f64::from(i16::from_le_bytes([b[0], b[1]])),
                5123 => f64::from(u16::from_le_bytes([b[0], b[1]])),
                5125 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                _ => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            }
        })
        .collect();
    (values, component)
}

/// The asset's kept edges by end positions: (hard, silhouettes with their faces' unit normals).
fn hard_and_silhouettes(asset: &Asset) -> (Vec<Edge>, Vec<(Edge, [glam::Vec3; 2])>) {
    let p = |v: u32| glam::Vec3::from(asset.topology_positions[v as usize]);
    let (mut hard, mut silhouettes) = (Vec::new(), Vec::new());
    for e in 0..asset.edge_count() {
        let v = asset.edge(e);
        let (a, b) = (
            p(v[0]).to_array().map(f32::to_bits),
            p(v[1]).to_array().map(f32::to_bits),
        );
        let key = if a < b { (a, b) } else { (b, a) };
        let flags = asset.edge_flags(e);
        if flags.intersects(EdgeFlags(EdgeFlags::STATIC.0 | EdgeFlags::CHAMFER.0)) {
            hard.push(key);
        } else {
            let na = (p(v[1]) - p(v[0])).cross(p(v[2]) - p(v[0])).normalize();
            let nb = (p(v[3]) - p(v[0])).cross(p(v[1]) - p(v[0])).normalize();
            silhouettes.push((key, [na, nb]));
        }
    }
    hard.sort();
    (hard, silhouettes)
}

/// Checks an annotated GLB's two extensions against their specifications and the bake of `input`
/// (independently of the loader: triangles are assembled here from the spec's formulas, edges are
/// told apart by world position). Returns the hard edges the file lists.
fn check_edge_extensions(input: &Path, output: &Path, options: &BakeOptions) -> Vec<Edge> {
    let (hard, silhouettes) = hard_and_silhouettes(&bake(input, options));
    let silhouette_normals: std::collections::HashMap<Edge, [glam::Vec3; 2]> =
        silhouettes.iter().copied().collect();
    let (document, bin) = read_glb(output);
    let used: Vec<&str> = document["extensionsUsed"]
        .as_array()
        .expect("extensionsUsed")
        .iter()
        .filter_map(|n| n.as_str())
        .collect();
    // Every extension a primitive carries is declared.
    for name in [
        "EXT_mesh_primitive_edge_visibility",
        "CESIUM_primitive_outline",
    ] {
        let carried = document["meshes"]
            .as_array()
            .expect("meshes")
            .iter()
            .flat_map(|m| m["primitives"].as_array().expect("primitives"))
            .any(|p| p["extensions"].get(name).is_some());
        assert_eq!(used.contains(&name), carried, "{name} in {used:?}");
    }
    // Where each mesh is drawn: translation and scale only, in these fixtures.
    let node = document["nodes"]
        .as_array()
        .expect("nodes")
        .iter()
        .find(|n| n.get("mesh").is_some())
        .expect("a mesh node");
    assert!(node.get("matrix").is_none() && node.get("rotation").is_none());
    let vec3 = |key: &str, default: f32| {
        node.get(key).map_or([default; 3], |v| {
            std::array::from_fn(|k| v[k].as_f64().expect("number") as f32)
        })
    };
    let (scale, translation) = (vec3("scale", 1.0), vec3("translation", 0.0));
    let mut listed = Vec::new();
    let mut primitives_with_extensions = 0;
    for primitive in document["meshes"][0]["primitives"]
        .as_array()
        .expect("primitives")
    {
        let mode = primitive["mode"].as_u64().unwrap_or(4);
        if !(4..=6).contains(&mode) {
            continue;
        }
        let (positions, _) = accessor(
            &document,
            &bin,
            primitive["attributes"]["POSITION"]
                .as_u64()
                .expect("POSITION"),
        );
        let world = |v: usize| -> [u32; 3] {
            std::array::from_fn(|k| {
                (positions[3 * v + k] as f32 * scale[k] + translation[k]).to_bits()
            })
        };
        let indices: Vec<usize> = match primitive.get("indices").and_then(|i| i.as_u64()) {
            Some(i) => accessor(&document, &bin, i)
                .0
                .iter()
                .map(|&v| v as usize)
                .collect(),
            None => (0..positions.len() / 3).collect(),
        };
        // glTF 2.0 §3.7.2.1.
        let n = indices.len();
        let triangles: Vec<[usize; 3]> = match mode {
            4 => indices
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect(),
            5 => (0..n - 2)
                .map(|i| [indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2]])
                .collect(),
            _ => (0..n - 2)
                .map(|i| [indices[i + 1], indices[i + 2], indices[0]])
                .collect(),
        };
        let key = |a: usize, b: usize| {
            let (a, b) = (world(a), world(b));
            if a < b { (a, b) } else { (b, a) }
        };
        let Some(extensions) = primitive.get("extensions") else {
            continue;
        };
        primitives_with_extensions += 1;
        let visibility = &extensions["EXT_mesh_primitive_edge_visibility"];
        let (bits, component) = accessor(
            &document,
            &bin,
            visibility["visibility"].as_u64().expect("visibility"),
        );
        assert_eq!(
            (component, bits.len()),
            (5121, (6 * triangles.len()).div_ceil(8))
        );
        let value = |slot: usize| (bits[slot / 4] as u8 >> (2 * (slot % 4))) & 3;
        for slot in 3 * triangles.len()..4 * bits.len() {
            assert_eq!(value(slot), 0, "unused bits are zero");
        }
        let mut occurrences: std::collections::BTreeMap<Edge, Vec<u8>> = Default::default();
        let mut silhouette_order = Vec::new();
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                let edge = key(tri[k], tri[(k + 1) % 3]);
                if edge.0 == edge.1 {
                    continue;
                }
                let v = value(3 * t + k);
                if v == 1 {
                    silhouette_order.push(edge);
                }
                occurrences.entry(edge).or_default().push(v);
            }
        }
        assert!(
            occurrences.values().flatten().any(|&v| v != 0),
            "at least one non-zero value"
        );
        for (edge, values) in &occurrences {
            let count = |x: u8| values.iter().filter(|&&v| v == x).count();
            if hard.binary_search(edge).is_ok() {
                assert_eq!(
                    (count(2), count(3)),
                    (1, values.len() - 1),
                    "hard edge {edge:?}: {values:?}"
                );
                listed.push(*edge);
            } else if silhouette_normals.contains_key(edge) {
                assert_eq!(
                    (count(1), count(0)),
                    (1, values.len() - 1),
                    "silhouette {edge:?}: {values:?}"
                );
            } else {
                assert!(
                    values.iter().all(|&v| v == 0),
                    "hidden edge {edge:?}: {values:?}"
                );
            }
        }
        match visibility.get("silhouetteNormals") {
            None => assert!(silhouette_order.is_empty()),
            Some(index) => {
                let a = &document["accessors"][index.as_u64().expect("index") as usize];
                assert_eq!(
                    (a["type"].as_str(), a["normalized"].as_bool()),
                    (Some("VEC3"), Some(true))
                );
                let (normals, component) =
                    accessor(&document, &bin, index.as_u64().expect("index"));
                assert_eq!(
                    (component, normals.len()),
                    (5120, 6 * silhouette_order.len())
                );
                for (s, edge) in silhouette_order.iter().enumerate() {
                    for (k, expected) in silhouette_normals[edge].iter().enumerate() {
                        let n = glam::Vec3::from_slice(
                            &normals[6 * s + 3 * k..6 * s + 3 * k + 3]
                                .iter()
                                .map(|&c| c as f32 / 127.0)
                                .collect::<Vec<_>>(),
                        );
                        assert!((n.length() - 1.0).abs() < 0.02, "normal {n} is unit");
                        assert!(
                            n.dot(*expected) > 0.99,
                            "normal {n} of {edge:?} is its face's {expected}"
                        );
                    }
                }
            }
        }
        // CESIUM_primitive_outline: on TRIANGLES primitives, each hard edge once, as a triangle edge.
        let outline = extensions.get("CESIUM_primitive_outline");
        assert_eq!(outline.is_some(), mode == 4, "outline only on TRIANGLES");
        if let Some(outline) = outline {
            let (pairs, component) = accessor(
                &document,
                &bin,
                outline["indices"].as_u64().expect("indices"),
            );
            assert!(component == 5123 || component == 5125);
            assert_eq!(pairs.len() % 2, 0);
            let triangle_edges: std::collections::HashSet<(usize, usize)> = triangles
                .iter()
                .flat_map(|t| {
                    (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])))
                })
                .collect();
            let mut outlined: Vec<Edge> = pairs
                .chunks_exact(2)
                .map(|p| {
                    let (a, b) = (p[0] as usize, p[1] as usize);
                    assert!(
                        triangle_edges.contains(&(a.min(b), a.max(b))),
                        "{a}-{b} is a triangle edge"
                    );
                    key(a, b)
                })
                .collect();
            let mut expected: Vec<Edge> = occurrences
                .keys()
                .filter(|e| hard.binary_search(e).is_ok())
                .copied()
                .collect();
            outlined.sort();
            expected.sort();
            assert_eq!(outlined, expected, "the primitive's hard edges, once each");
        }
    }
    assert!(primitives_with_extensions > 0);
    listed.sort();
    listed.dedup();
    listed
}

/// The marked edges of a bake, by end positions.
fn marks_of(path: &Path, options: &BakeOptions) -> Vec<Edge> {
    chamfer_and_marks(&bake(path, options)).1
}

#[test]
fn edge_extensions_follow_their_specifications_and_read_back_as_the_hard_edges() {
    use chamfer_preprocess::annotate::{GltfEdges, annotate_with};
    let dir = tempfile::tempdir().expect("tempdir");
    let exact = BakeOptions::DEFAULT.with_weld_epsilon(0.0);
    let rule = exact.with_radius(Radius::Relative(0.005));
    let all = GltfEdges::DEFAULT
        .with_edge_visibility(true)
        .with_primitive_outline(true);
    // A CAD part from an OBJ (silhouettes and creases), a strip beside a list with a material seam,
    // and mirrored fans with byte indices.
    for input in [
        "meshes/fandisk.obj",
        "shapes/two-materials.glb",
        "shapes/pyramid-fans-mirrored.glb",
    ] {
        let input = fixture(input);
        let name = input
            .file_stem()
            .expect("name")
            .to_string_lossy()
            .into_owned();
        let output = dir.path().join(format!("{name}.glb"));
        let written = annotate_with(&input, &output, &rule, &all).unwrap_or_else(|e| panic!("{e}"));
        let listed = check_edge_extensions(&input, &output, &rule);
        let (hard, _) = hard_and_silhouettes(&bake(&input, &rule));
        assert_eq!(listed, hard, "{name}: every hard edge is in the file");
        assert!(written.hard_edges >= hard.len(), "{name}");
        // extras.chamfer wins: the marks read back are the bake's own.
        assert_eq!(
            chamfer_and_marks(&bake(&output, &exact)).0,
            chamfer_and_marks(&bake(&input, &rule)).0,
            "{name}: chamfer edges and radii from extras"
        );
        let (chamfer, marked) = chamfer_and_marks(&bake(&input, &rule));
        let mut extras_marks: Vec<Edge> = chamfer.iter().map(|c| c.0).chain(marked).collect();
        extras_marks.sort();
        extras_marks.dedup();
        assert_eq!(
            marks_of(&output, &exact),
            extras_marks,
            "{name}: the extensions beside extras.chamfer add no marks"
        );
        // Each extension alone reads back as marks on exactly the hard edges.
        for (dialect, dialects) in [
            (
                "visibility",
                GltfEdges::DEFAULT
                    .with_extras(false)
                    .with_edge_visibility(true),
            ),
            (
                "outline",
                GltfEdges::DEFAULT
                    .with_extras(false)
                    .with_primitive_outline(true),
            ),
        ] {
            let only = dir.path().join(format!("{name}-{dialect}.glb"));
            annotate_with(&input, &only, &exact, &dialects).unwrap_or_else(|e| panic!("{e}"));
            let marks = marks_of(&only, &exact);
            if dialect == "outline" && name == "pyramid-fans-mirrored" {
                assert!(marks.is_empty(), "no outline on fans");
                continue;
            }
            let outline_hard: Vec<Edge> = if dialect == "outline" && name == "two-materials" {
                // The strip primitive gets no outline: only the list's hard edges are marks.
                marks.clone()
            } else {
                hard.clone()
            };
            assert!(!marks.is_empty(), "{name} {dialect}");
            assert_eq!(
                marks, outline_hard,
                "{name} {dialect}: marks are the hard edges"
            );
            assert!(marks.iter().all(|m| hard.binary_search(m).is_ok()));
        }
    }
}

#[test]
fn obj_stl_and_3mf_annotate_into_ply_glb_and_gltf_with_marks_and_radii() {
    let dir = tempfile::tempdir().expect("tempdir");
    let rule = BakeOptions::DEFAULT.with_radius(Radius::Relative(0.005));
    for input in [
        "meshes/fandisk.obj",
        "shapes/step.obj",
        "shapes/two-objects.obj",
        "shapes/step-binary.stl",
        "shapes/two-cubes-ascii.stl",
        "shapes/step-components.3mf",
    ] {
        let input = fixture(input);
        let original = bake(&input, &rule);
        let (chamfer, _) = chamfer_and_marks(&original);
        assert!(!chamfer.is_empty());
        for extension in ["ply", "glb", "gltf"] {
            let name = input
                .file_stem()
                .expect("name")
                .to_string_lossy()
                .into_owned();
            let output = dir.path().join(format!("{name}.{extension}"));
            let written = annotate(&input, &output, &rule).unwrap_or_else(|e| panic!("{e}"));
            let back = bake(&output, &BakeOptions::DEFAULT);
            let (chamfer_back, marks_back) = chamfer_and_marks(&back);
            assert_eq!(
                chamfer_back, chamfer,
                "{name}.{extension}: chamfer edges and radii"
            );
            assert_eq!(written.edges, marks_back.len(), "{name}.{extension}");
            // Same geometry and classes (PLY has no materials, so no seams there).
            let (a, b) = (original.header.stats, back.header.stats);
            assert_eq!(
                (
                    a.welded_vertices,
                    a.input_triangles,
                    a.edges.total,
                    a.edges.crease
                ),
                (
                    b.welded_vertices,
                    b.input_triangles,
                    b.edges.total,
                    b.edges.crease
                ),
                "{name}.{extension}"
            );
            if extension != "ply" {
                assert_eq!(
                    a.edges.material, b.edges.material,
                    "{name}.{extension}: seams"
                );
            }
        }
    }
}
