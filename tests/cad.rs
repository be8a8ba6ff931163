//! CAD meshes in (issue 30): STL, binary and ASCII, welded from triangle soup; the cracks between
//! separately tessellated faces stitched; the same part drawn the same whichever way it came.

use std::collections::BTreeSet;
use std::path::Path;

use chamfer_preprocess::{BakeOptions, Limits, Stitch, bake_file, load};
use chamfer_runtime::asset::Asset;
use chamfer_runtime::render::{CapMethod, EdgeColors, EdgeStyle, Image};
use chamfer_tests::cube::*;
use chamfer_tests::{bake_fixture, fixture, render};

fn bake(path: &Path, options: &BakeOptions) -> chamfer_preprocess::Baked {
    bake_file(path, options).unwrap_or_else(|e| panic!("{e}"))
}

/// The kept edges as pairs of endpoint positions (bit patterns, each pair sorted), so parts whose
/// vertices are numbered differently compare.
fn kept_segments(asset: &Asset) -> BTreeSet<[[u32; 3]; 2]> {
    let at = |v: u32| asset.topology_positions[v as usize].map(f32::to_bits);
    (0..asset.edge_vertices.len() / 4)
        .map(|e| {
            let mut pair = [
                at(asset.edge_vertices.get(4 * e)),
                at(asset.edge_vertices.get(4 * e + 1)),
            ];
            pair.sort();
            pair
        })
        .collect()
}

/// A mesh as a binary STL: every triangle with its own three vertices, as CAD tools write it.
fn soup_stl(mesh: &chamfer_preprocess::mesh::Mesh) -> Vec<u8> {
    let corner = |v: u32| mesh.positions[v as usize].to_array();
    chamfer_tests::files::binary_stl(
        b"solid exported by a CAD tool",
        mesh.triangles.len() as u32,
        mesh.triangles.iter().map(|t| t.map(corner)),
    )
}

#[test]
fn binary_and_ascii_stl_of_one_part_bake_to_the_same_asset() {
    let binary = fixture("shapes/step-binary.stl");
    let bytes = std::fs::read(&binary).expect("fixture");
    assert!(
        bytes.starts_with(b"solid"),
        "the classic trap: a binary file that begins with `solid`"
    );
    let mut from_binary = bake(&binary, &BakeOptions::DEFAULT).asset;
    let from_ascii = bake(&fixture("shapes/step-ascii.stl"), &BakeOptions::DEFAULT).asset;
    from_binary
        .header
        .source
        .clone_from(&from_ascii.header.source);
    assert_eq!(from_binary.encode_to_vec(), from_ascii.encode_to_vec());
    // And the step as an OBJ with shared vertices keeps the same edges.
    let obj = bake_fixture("shapes/step.obj");
    assert_eq!(kept_segments(&from_ascii), kept_segments(&obj));
    assert_eq!(from_ascii.header.stats.edges, obj.header.stats.edges);
}

#[test]
fn an_ascii_stl_with_two_solids_holds_both() {
    let loaded = load::load(&fixture("shapes/two-cubes-ascii.stl"), &Limits::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded.mesh.triangles.len(), 24);
    assert_eq!(
        loaded.mesh.positions.len(),
        72,
        "soup: three vertices a triangle"
    );
    let stats = bake(
        &fixture("shapes/two-cubes-ascii.stl"),
        &BakeOptions::DEFAULT,
    )
    .asset
    .header
    .stats;
    assert_eq!((stats.welded_vertices, stats.edges.boundary), (16, 0));
    assert_eq!(stats.edges.crease, 24, "two cubes' 12 ridges");
}

#[test]
fn a_cad_stl_export_welds_to_the_same_edges_as_the_obj_part() {
    let dir = tempfile::tempdir().expect("tempdir");
    for part in [
        "meshes/fandisk.obj",
        "shapes/step.obj",
        "shapes/cylinder-16.obj",
    ] {
        let obj = fixture(part);
        let mesh = load::load(&obj, &Limits::DEFAULT)
            .unwrap_or_else(|e| panic!("{e}"))
            .mesh;
        let stl = dir.path().join("part.stl");
        std::fs::write(&stl, soup_stl(&mesh)).expect("write");
        let from_stl = bake(&stl, &BakeOptions::DEFAULT);
        let from_obj = bake(&obj, &BakeOptions::DEFAULT).asset;
        let stats = from_stl.asset.header.stats;
        assert_eq!(stats.input_vertices, 3 * stats.input_triangles, "{part}");
        assert_eq!(stats.edges.boundary, 0, "{part}");
        assert_eq!(
            from_stl.stitched.boundary_before, 0,
            "{part}: the weld alone closes it"
        );
        assert_eq!(stats.edges, from_obj.header.stats.edges, "{part}");
        assert_eq!(
            kept_segments(&from_stl.asset),
            kept_segments(&from_obj),
            "{part}"
        );
        // Gzipped, the same.
        let gz = dir.path().join("part.stl.gz");
        let mut encoder = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        std::io::Write::write_all(&mut encoder, &soup_stl(&mesh)).expect("gzip");
        std::fs::write(&gz, encoder.finish().expect("gzip")).expect("write");
        assert_eq!(bake(&gz, &BakeOptions::DEFAULT).asset.header.stats, stats);
    }
}

/// Red edges except boundaries, which are green: a crack shows as green.
fn boundaries_in_green() -> EdgeStyle {
    EdgeStyle {
        colors: EdgeColors {
            boundary: [0.0, 1.0, 0.0, 1.0],
            ..EdgeColors::all(RED)
        },
        ..edges_in(RED, 3.0, CapMethod::NextIndex)
    }
}

fn green_pixels(image: &Image) -> usize {
    image
        .rgba
        .chunks_exact(4)
        .filter(|p| p[1] > 200 && p[0] < 60 && p[2] < 60)
        .count()
}

fn picture(asset: &Asset) -> Image {
    let camera = cube_camera(256, false);
    render(
        asset,
        &camera,
        Some(&grey_mesh()),
        Some(&boundaries_in_green()),
        BLUE_BACKGROUND,
    )
}

#[test]
fn a_cube_tessellated_face_by_face_is_stitched_and_drawn_as_the_watertight_cube() {
    let path = fixture("shapes/box-cracked.obj");
    let open = bake(&path, &BakeOptions::DEFAULT.with_stitch(Stitch::Off)).asset;
    assert!(
        open.header.stats.edges.boundary > 24,
        "the T-junctions leave the faces apart: {:?}",
        open.header.stats.edges
    );
    let stitched = bake(&path, &BakeOptions::DEFAULT);
    assert_eq!(
        stitched.stitched.joined_vertices, 0,
        "the weld joins the corners"
    );
    assert!(stitched.stitched.split_edges > 0);
    let edges = stitched.asset.header.stats.edges;
    assert_eq!((edges.boundary, edges.non_manifold), (0, 0), "{edges:?}");
    // The 12 ridges, in pieces where the faces' grids met, and nothing else.
    assert_eq!(edges.ridge, edges.kept, "{edges:?}");
    let length: f32 = kept_segments(&stitched.asset)
        .iter()
        .map(|[a, b]| {
            let p = |q: &[u32; 3]| glam::Vec3::from_array(q.map(f32::from_bits));
            p(a).distance(p(b))
        })
        .sum();
    assert!((length - 12.0).abs() < 1e-4, "ridge length {length}");

    let watertight = picture(&bake_fixture("shapes/cube.obj"));
    let image = picture(&stitched.asset);
    check_cube_edges(&image, &cube_camera(256, false)).unwrap_or_else(|e| panic!("{e}"));
    let differing = image
        .rgba
        .chunks_exact(4)
        .zip(watertight.rgba.chunks_exact(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 8))
        .count();
    assert!(
        differing < image.rgba.len() / 4 / 500,
        "{differing} pixels differ from the watertight cube's picture"
    );
    assert_eq!(green_pixels(&image), 0);
    // Unstitched, the cracks are drawn as boundaries.
    assert!(green_pixels(&picture(&open)) > 500);
}

#[test]
fn a_real_open_boundary_stays_open() {
    for (part, rim) in [("shapes/open-box.obj", 4), ("shapes/plane-4x4.obj", 16)] {
        let baked = bake(&fixture(part), &BakeOptions::DEFAULT);
        assert_eq!(baked.stitched.boundary_before, rim, "{part}");
        assert_eq!(baked.stitched.boundary_after, rim, "{part}");
        assert_eq!(baked.asset.header.stats.edges.boundary, rim, "{part}");
    }
    let picture = picture(&bake_fixture("shapes/open-box.obj"));
    assert!(
        green_pixels(&picture) > 100,
        "the open box's rim is drawn as a boundary"
    );
}

/// fixtures/make_fixtures.py's STEP_COMPONENTS and STEP_BUILD: 3MF's 4 x 3 row-vector matrices.
const STEP_COMPONENTS: [[f32; 12]; 3] = [
    [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 5.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 4.0, 0.0],
];
const STEP_BUILD: [f32; 12] = [
    2.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 2.0, 10.0, 20.0, 30.0,
];

/// `p · M` for a 3MF matrix, written out (no glam), so the test does not share the loader's math.
fn place(m: &[f32; 12], p: [f32; 3]) -> [f32; 3] {
    std::array::from_fn(|j| p[0] * m[j] + p[1] * m[3 + j] + p[2] * m[6 + j] + m[9 + j])
}

fn mirrors(m: &[f32; 12]) -> bool {
    let det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6])
        + m[2] * (m[3] * m[7] - m[4] * m[6]);
    det < 0.0
}

/// A mesh's triangles as positions (bit patterns), each rotated to start at its least corner so the
/// winding is kept, sorted.
fn triangles(mesh: &chamfer_preprocess::mesh::Mesh) -> Vec<[[u32; 3]; 3]> {
    let mut all: Vec<[[u32; 3]; 3]> = mesh
        .triangles
        .iter()
        .map(|t| {
            let corners = t.map(|v| mesh.positions[v as usize].to_array().map(f32::to_bits));
            let first = (0..3).min_by_key(|&k| corners[k]).unwrap_or(0);
            std::array::from_fn(|k| corners[(first + k) % 3])
        })
        .collect();
    all.sort();
    all
}

#[test]
fn a_3mf_with_components_and_build_transforms_equals_the_geometry_placed_by_hand() {
    let step = load::load(&fixture("shapes/step.obj"), &Limits::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"))
        .mesh;
    let mut by_hand = chamfer_preprocess::mesh::Mesh::default();
    for component in &STEP_COMPONENTS {
        let base = by_hand.positions.len() as u32;
        by_hand.positions.extend(
            step.positions.iter().map(|p| {
                glam::Vec3::from_array(place(&STEP_BUILD, place(component, p.to_array())))
            }),
        );
        let flip = mirrors(component) != mirrors(&STEP_BUILD);
        by_hand.triangles.extend(step.triangles.iter().map(|t| {
            let [a, b, c] = t.map(|v| v + base);
            if flip { [a, c, b] } else { [a, b, c] }
        }));
    }
    let path = fixture("shapes/step-components.3mf");
    let loaded = load::load(&path, &Limits::DEFAULT).unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    // The OBJ reader numbers the step's vertices its own way: compare triangles by position.
    assert_eq!(triangles(&loaded.mesh), triangles(&by_hand));
    // Baked, the same: three steps, each closed and with outward faces (no flipped edge).
    let from_3mf = bake(&path, &BakeOptions::DEFAULT).asset;
    let placed = chamfer_preprocess::bake(by_hand, "by hand", &BakeOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"))
        .asset;
    assert_eq!(kept_segments(&from_3mf), kept_segments(&placed));
    let edges = from_3mf.header.stats.edges;
    assert_eq!((edges.boundary, edges.flipped), (0, 0), "{edges:?}");
    assert_eq!(
        edges.crease,
        3 * bake_fixture("shapes/step.obj").header.stats.edges.crease
    );
}

#[test]
fn a_3mf_in_inches_is_read_in_millimetres() {
    let inch = load::load(&fixture("shapes/cube-inch.3mf"), &Limits::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"))
        .mesh;
    let millimetre = load::load(&fixture("shapes/cube.3mf"), &Limits::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"))
        .mesh;
    let scaled: Vec<glam::Vec3> = millimetre.positions.iter().map(|p| *p * 25.4).collect();
    assert_eq!(inch.positions, scaled);
    assert_eq!(inch.triangles, millimetre.triangles);
}

#[test]
fn bake_scene_keeps_a_3mf_object_apart_from_its_instances() {
    let baked = chamfer_preprocess::scene::bake_scene(
        &fixture("shapes/step-components.3mf"),
        "step",
        &BakeOptions::DEFAULT,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(baked.assets.len(), 1, "one mesh object, placed three times");
    assert_eq!(
        baked.assets[0].0, "step.mesh1.chamfer",
        "named by its object id"
    );
    assert_eq!(baked.scene.instances.len(), 3);
    for (instance, component) in baked.scene.instances.iter().zip(&STEP_COMPONENTS) {
        let transform = glam::Mat4::from_cols_array(&instance.transform);
        for p in [[0.0, 0.0, 0.0], [2.0, 1.0, 1.0], [1.0, 2.0, 0.0]] {
            let expected = place(&STEP_BUILD, place(component, p));
            let got = transform
                .transform_point3(glam::Vec3::from_array(p))
                .to_array();
            assert_eq!(got, expected);
        }
    }
}

/// fixtures/cad/SOURCES.md: the 3MF Consortium's conformance and example files.
#[test]
fn the_3mf_consortiums_passing_files_load_with_trimeshs_triangle_counts() {
    for (file, triangles) in [
        ("cube_gears.3mf", 25_692),
        ("cylinder.3mf", 88),
        ("MUSTPASS_Chapter4.2_Components.3mf", 60),
        ("MUSTPASS_Chapter3.2c_MultipleItemsTransform.3mf", 60),
        ("MUSTPASS_Chapter2.3a_IgnorableMarkup.3mf", 12),
        ("MUSTPASS_Chapter3.2b_UnitsMeasurementMM.3mf", 12),
    ] {
        let loaded = load::load(&fixture(&format!("cad/{file}")), &Limits::DEFAULT)
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(loaded.mesh.triangles.len(), triangles, "{file}");
        assert!(loaded.warnings.is_empty(), "{file}: {:?}", loaded.warnings);
    }
}

#[test]
fn the_3mf_consortiums_failing_files_are_refused_naming_the_problem() {
    for (file, expected) in [
        (
            "MUSTFAIL_Chapter2.1.1a_PartsRelationships_NonExist3DModelPart.3mf",
            "no relationship of the 3D model type",
        ),
        ("MUSTFAIL_Chapter2.3.2a_NonUTF_Encoding.3mf", "UTF-8"),
        (
            "MUSTFAIL_Chapter2.3.2b_DataTypeDefinitionInXMLMarkup.3mf",
            "DOCTYPE",
        ),
        (
            "MUSTFAIL_Chapter3.4.3.1a_NotMatchingObjectIdInBuildItem.3mf",
            "object 14 is placed but not defined",
        ),
        (
            "MUSTFAIL_Chapter3.4a_MoreThanOneModel.3mf",
            "two objects have id 13",
        ),
        (
            "MUSTFAIL_Chapter3.4b_MissingBuildElement.3mf",
            "the build places no object",
        ),
    ] {
        let error = load::load(&fixture(&format!("cad/{file}")), &Limits::DEFAULT)
            .err()
            .unwrap_or_else(|| panic!("{file} was accepted"))
            .to_string();
        assert!(error.contains(file) && error.contains(expected), "{error}");
    }
}

/// A CAD tool's export with cracks in every gear: the weld leaves 170 boundary edges, the default
/// stitch closes them all, object by object as in the flattened part.
#[test]
fn the_cracks_of_a_public_cad_export_are_stitched() {
    let path = fixture("cad/cube_gears.3mf");
    let open = bake(&path, &BakeOptions::DEFAULT.with_stitch(Stitch::Off)).asset;
    assert_eq!(open.header.stats.edges.boundary, 170);
    let stitched = bake(&path, &BakeOptions::DEFAULT);
    assert_eq!(
        (
            stitched.stitched.boundary_before,
            stitched.stitched.boundary_after
        ),
        (170, 0)
    );
    assert_eq!(stitched.asset.header.stats.edges.boundary, 0);
    let scene = chamfer_preprocess::scene::bake_scene(&path, "gears", &BakeOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.assets.len(), 17);
    let before: u64 = scene
        .assets
        .iter()
        .map(|(_, b)| b.stitched.boundary_before)
        .sum();
    assert!(before > 0);
    for (name, baked) in &scene.assets {
        assert_eq!(baked.asset.header.stats.edges.boundary, 0, "{name}");
    }
}
