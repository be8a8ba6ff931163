//! The `chamfer` command as a user runs it: exit codes, messages, files written and left alone.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fixture(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures")
        .join(relative)
}

fn chamfer(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chamfer"))
        .args(args)
        .output()
        .expect("run chamfer")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn path_str(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

#[test]
fn bake_then_inspect_json_has_the_documented_keys() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cube.chamfer");
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "-o",
        path_str(&out),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let run = chamfer(&["inspect", path_str(&out), "--json"]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
    for key in [
        "vertices",
        "welded_vertices",
        "triangles",
        "degenerate_triangles",
        "edges",
        "bytes",
    ] {
        assert!(json.get(key).is_some(), "missing {key}: {json}");
    }
    for key in [
        "total",
        "boundary",
        "crease",
        "ridge",
        "valley",
        "marked",
        "material",
        "non_manifold",
        "smooth",
        "coplanar_dropped",
    ] {
        assert!(
            json["edges"].get(key).is_some(),
            "missing edges.{key}: {json}"
        );
    }
    assert_eq!(json["edges"]["total"], 18);
    assert_eq!(json["caps"], 8, "every cube corner joins three kept edges");
    assert_eq!(json["chamfer"]["edges"], 0);
    for key in ["next_ends", "cap_heads"] {
        assert!(
            json["bytes"]["per_section"][key]
                .as_u64()
                .is_some_and(|b| b > 0),
            "{key}: {json}"
        );
    }
    assert_eq!(json["edges"]["crease"], 12);
    assert_eq!(json["edges"]["coplanar_dropped"], 6);
    assert_eq!(
        json["bytes"]["total"].as_u64(),
        Some(std::fs::metadata(&out).expect("asset").len())
    );
    assert!(json["bytes"]["per_section"].is_object());
    assert!(json["bytes"]["per_edge"].as_f64().is_some_and(|b| b > 0.0));

    let table = chamfer(&["inspect", path_str(&out)]);
    assert!(table.status.success());
    assert!(
        text(&table.stdout).contains("coplanar"),
        "{}",
        text(&table.stdout)
    );
}

#[test]
fn radius_flags_mark_chamfer_edges() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cube.chamfer");
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "--radius",
        "0.05",
        "-o",
        path_str(&out),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let run = chamfer(&["inspect", path_str(&out), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
    assert_eq!(json["chamfer"]["edges"], 12);
    assert_eq!(json["chamfer"]["clamped"], 0);
    assert!((json["chamfer"]["radius_max"].as_f64().unwrap_or(0.0) - 0.05).abs() < 1e-6);
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "--radius=-1",
        "-o",
        path_str(&out),
    ]);
    assert!(
        !run.status.success() && text(&run.stderr).contains("radius"),
        "{}",
        text(&run.stderr)
    );
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "--radius",
        "1",
        "--radius-rel",
        "0.1",
        "-o",
        path_str(&out),
    ]);
    assert!(
        !run.status.success(),
        "--radius and --radius-rel together must be refused"
    );
}

#[test]
fn many_inputs_bake_into_a_directory() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("baked");
    let inputs = [
        "shapes/cube.obj",
        "shapes/cone-16.obj",
        "shapes/two-materials.glb",
        "shapes/cube-marked-le.ply",
    ];
    let mut args = vec!["bake".to_owned()];
    args.extend(inputs.iter().map(|i| path_str(&fixture(i)).to_owned()));
    args.extend(["-o".to_owned(), path_str(&out).to_owned()]);
    let run = chamfer(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(run.status.success(), "{}", text(&run.stderr));
    for name in ["cube", "cone-16", "two-materials", "cube-marked-le"] {
        assert!(
            out.join(format!("{name}.chamfer")).is_file(),
            "{name}.chamfer missing"
        );
    }
}

#[test]
fn broken_input_fails_naming_the_file_and_leaves_the_old_output() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("model.chamfer");
    std::fs::write(&out, b"previous bake").expect("write");
    for broken in [
        "empty.obj",
        "truncated.ply",
        "nan-position.obj",
        "draco-required.gltf",
        "truncated.glb",
    ] {
        let input = fixture(&format!("broken/{broken}"));
        let run = chamfer(&["bake", path_str(&input), "-o", path_str(&out)]);
        let stderr = text(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{broken}: {stderr}");
        assert!(
            stderr.contains(broken),
            "{broken}: stderr does not name the file: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{broken}: {stderr}");
        assert_eq!(
            std::fs::read(&out).expect("output"),
            b"previous bake",
            "{broken}: old output replaced"
        );
    }
    let leftovers: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").collect();
    assert_eq!(
        leftovers.len(),
        1,
        "temporary files left behind: {leftovers:?}"
    );
}

#[test]
fn refuses_to_overwrite_an_input_and_bad_options() {
    let dir = tempfile::tempdir().expect("tempdir");
    let input = dir.path().join("cube.obj");
    std::fs::copy(fixture("shapes/cube.obj"), &input).expect("copy");
    let before = std::fs::read(&input).expect("read");
    let run = chamfer(&["bake", path_str(&input), "-o", path_str(&input)]);
    assert!(!run.status.success());
    assert!(
        text(&run.stderr).contains("overwrite"),
        "{}",
        text(&run.stderr)
    );
    assert_eq!(std::fs::read(&input).expect("read"), before);

    let out = dir.path().join("x.chamfer");
    let run = chamfer(&[
        "bake",
        path_str(&input),
        "--crease-deg=200",
        "-o",
        path_str(&out),
    ]);
    assert!(!run.status.success());
    assert!(
        text(&run.stderr).contains("crease"),
        "{}",
        text(&run.stderr)
    );
    let run = chamfer(&[
        "bake",
        path_str(&input),
        "--weld-epsilon=nan",
        "-o",
        path_str(&out),
    ]);
    assert!(!run.status.success());
    assert!(!out.exists());
}

#[test]
fn inspect_rejects_what_is_not_an_asset() {
    let run = chamfer(&["inspect", path_str(&fixture("shapes/cube.obj"))]);
    assert_eq!(run.status.code(), Some(1));
    let stderr = text(&run.stderr);
    assert!(
        stderr.contains("cube.obj") && stderr.contains("magic"),
        "{stderr}"
    );
    let run = chamfer(&["inspect", "/no/such/file.chamfer"]);
    assert_eq!(run.status.code(), Some(1));
    assert!(text(&run.stderr).contains("/no/such/file.chamfer"));
}

#[test]
fn help_shows_examples() {
    let run = chamfer(&["bake", "--help"]);
    assert!(run.status.success());
    assert!(
        text(&run.stdout).contains("chamfer bake"),
        "{}",
        text(&run.stdout)
    );
}

#[test]
fn annotate_writes_marks_that_bake_reads_back() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("marked.ply");
    let input = fixture("shapes/cube-marked-le.ply");
    let run = chamfer(&[
        "annotate",
        path_str(&input),
        "--radius",
        "0.2",
        "-o",
        path_str(&out),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains("13 marked or chamfer edges"),
        "{}",
        text(&run.stdout)
    );
    let asset = dir.path().join("marked.chamfer");
    let run = chamfer(&["bake", path_str(&out), "-o", path_str(&asset)]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let run = chamfer(&["inspect", path_str(&asset), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
    assert_eq!(json["edges"]["marked"], 13);
    assert_eq!(json["chamfer"]["edges"], 13);
    let run = chamfer(&[
        "annotate",
        path_str(&fixture("shapes/cube.obj")),
        "-o",
        path_str(&dir.path().join("c.obj")),
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert!(
        text(&run.stderr).contains("cube.obj"),
        "{}",
        text(&run.stderr)
    );
}

/// Width and height of a PNG, from its IHDR chunk.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    let be = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    (be(16), be(20))
}

#[test]
fn render_writes_a_png_of_a_mesh_or_an_asset() {
    let dir = tempfile::tempdir().expect("tempdir");
    let asset = dir.path().join("cube.chamfer");
    let cube = fixture("shapes/cube.obj");
    assert!(
        chamfer(&["bake", path_str(&cube), "-o", path_str(&asset)])
            .status
            .success()
    );
    for (input, extra) in [
        (&cube, vec!["--style", "mesh", "--ortho"]),
        (
            &asset,
            vec![
                "--caps",
                "cap-buffer",
                "--classes",
                "contour,ridge",
                "--azimuth",
                "-60",
            ],
        ),
    ] {
        let png = dir.path().join("cube.png");
        let mut args = vec![
            "render",
            path_str(input),
            "-o",
            path_str(&png),
            "--width",
            "96",
            "--height",
            "64",
        ];
        args.extend(extra);
        let run = chamfer(&args);
        assert!(run.status.success(), "{}", text(&run.stderr));
        assert_eq!(png_size(&std::fs::read(&png).expect("png")), (96, 64));
    }
}

#[test]
fn render_refuses_bad_input_and_options_and_keeps_the_old_picture() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("picture.png");
    std::fs::write(&png, b"previous picture").expect("write");
    let not_an_asset = dir.path().join("fake.chamfer");
    std::fs::write(&not_an_asset, b"CHAMFER\0 but nothing else").expect("write");
    let cube = fixture("shapes/cube.obj");
    let truncated = fixture("broken/truncated.glb");
    let cases: [(Vec<&str>, &str); 7] = [
        (vec![path_str(&not_an_asset)], "fake.chamfer"),
        (vec![path_str(&truncated)], "truncated.glb"),
        (vec![path_str(&cube), "--width", "0"], "--width"),
        (vec![path_str(&cube), "--edge-width", "NaN"], "--edge-width"),
        (vec![path_str(&cube), "--samples", "3"], "--samples"),
        (
            vec![path_str(&cube), "--style", "chamfer", "--shininess", "200"],
            "--shininess",
        ),
        (
            vec![
                path_str(&cube),
                "--style",
                "chamfer",
                "--light-dir",
                "0,0,0",
            ],
            "--light-dir",
        ),
    ];
    for (args, named) in cases {
        let mut all = vec!["render", "-o", path_str(&png)];
        all.extend(args);
        let run = chamfer(&all);
        let stderr = text(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{all:?}: {stderr}");
        assert!(stderr.contains(named), "{all:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert_eq!(std::fs::read(&png).expect("png"), b"previous picture");
    }
    assert_eq!(
        std::fs::read_dir(dir.path()).expect("dir").count(),
        2,
        "temporary files left"
    );
}

#[test]
fn bake_intersections_then_inspect_json_shows_them() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cubes.chamfer");
    let input = fixture("shapes/two-cubes.obj");
    let run = chamfer(&[
        "bake",
        path_str(&input),
        "-o",
        path_str(&out),
        "--intersections",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains("intersections: "),
        "{}",
        text(&run.stdout)
    );
    let run = chamfer(&["inspect", path_str(&out), "--json"]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
    let i = &json["intersections"];
    assert_eq!(i["polylines"], 1, "{json}");
    assert_eq!(i["closed"], 1);
    assert!(i["segments"].as_u64().is_some_and(|s| s >= 6));
    assert!((i["length"].as_f64().unwrap_or(0.0) - 3.9).abs() < 1e-5);
    assert_eq!(json["settings"]["intersections"], "true");
    // Without the flag the object is there, empty; a version-1 asset reads the same way.
    for asset in [None, Some(fixture("assets/cube-v1.chamfer"))] {
        let path = match asset {
            Some(p) => p,
            None => {
                let plain = dir.path().join("plain.chamfer");
                let run = chamfer(&["bake", path_str(&input), "-o", path_str(&plain)]);
                assert!(run.status.success(), "{}", text(&run.stderr));
                plain
            }
        };
        let run = chamfer(&["inspect", path_str(&path), "--json"]);
        assert!(run.status.success(), "{}", text(&run.stderr));
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
        assert_eq!(json["intersections"]["segments"], 0, "{json}");
        assert_eq!(json["intersections"]["length"], 0.0);
    }
}
