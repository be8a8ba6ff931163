//! The `chamfer` command as a user runs it: exit codes, messages, files written and left alone.

use chamfer_tests::fixture;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn chamfer(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chamfer"))
        .args(args)
        .output()
        .expect("run chamfer")
}

/// Runs `chamfer args` and checks it succeeded (else fails the test with its stderr).
fn succeed(args: &[&str]) -> Output {
    let run = chamfer(args);
    assert!(
        run.status.success(),
        "chamfer {args:?} failed: {}",
        text(&run.stderr)
    );
    run
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
    succeed(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "-o",
        path_str(&out),
    ]);
    let run = succeed(&["inspect", path_str(&out), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
    for key in [
        "vertices",
        "welded_vertices",
        "triangles",
        "degenerate_triangles",
        "edges",
        "motion",
        "bytes",
    ] {
        assert!(json.get(key).is_some(), "missing {key}: {json}");
    }
    assert_eq!(
        json["motion"]["joints"], 0,
        "a still asset: {}",
        json["motion"]
    );
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
    // The 24 render vertices repeat the 8 corners' positions: the file holds a count per corner.
    assert_eq!(
        json["bytes"]["per_section"]["render_positions"], 0,
        "{json}"
    );
    assert_eq!(
        json["bytes"]["per_section"]["render_vertex_counts"], 8,
        "{json}"
    );
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
fn compact_bakes_state_their_precision_and_decode_to_the_same_edges() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fandisk = fixture("meshes/fandisk.obj");
    let (raw, compact, lossless) = (
        dir.path().join("raw.chamfer"),
        dir.path().join("compact.chamfer"),
        dir.path().join("lossless.chamfer"),
    );
    for (out, flags) in [
        (&raw, &[][..]),
        (&compact, &["--compact"][..]),
        (
            &lossless,
            &["--compact", "--position-bits", "32", "--normal-bits", "32"][..],
        ),
    ] {
        let mut args = vec!["bake", path_str(&fandisk), "-o", path_str(out)];
        args.extend(flags);
        let run = succeed(&args);
        // The report gives the file's own size.
        let size = std::fs::metadata(out).expect("written").len();
        assert!(
            text(&run.stdout).contains(&format!("{size} bytes")),
            "{}",
            text(&run.stdout)
        );
    }
    let json = |path: &Path| -> serde_json::Value {
        let run = succeed(&["inspect", path_str(path), "--json"]);
        serde_json::from_slice(&run.stdout).expect("JSON")
    };
    let (raw, compact_json, lossless) = (json(&raw), json(&compact), json(&lossless));
    assert_eq!(compact_json["edges"], raw["edges"]);
    assert_eq!(
        compact_json["bytes"]["decoded_total"],
        raw["bytes"]["decoded_total"]
    );
    assert!(compact_json["bytes"]["total"].as_u64() < raw["bytes"]["total"].as_u64());
    assert_eq!(compact_json["precision"]["position_bits"], 16);
    assert_eq!(compact_json["precision"]["normal_bits"], 12);
    assert!(
        compact_json["precision"]["position_error"]
            .as_f64()
            .is_some_and(|e| e > 0.0)
    );
    assert_eq!(raw["precision"]["position_error"], 0.0);
    assert_eq!(lossless["precision"]["position_bits"], 32);
    assert!(
        compact_json["bytes"]["per_section"]["edge_corners"]
            .as_u64()
            .is_some_and(|b| b > 0)
    );
    // The table says it too, and --timings adds what each section took.
    let table = succeed(&["inspect", path_str(&compact), "--timings"]);
    let table = text(&table.stdout);
    assert!(
        table.contains("16-bit grid") && table.contains("decode ms"),
        "{table}"
    );
    // Bits out of range, and bits without --compact, are refused before anything is baked.
    let out = dir.path().join("never.chamfer");
    for flags in [
        &["--compact", "--position-bits", "17"][..],
        &["--compact", "--normal-bits", "1"][..],
        &["--position-bits", "12"][..],
    ] {
        let mut args = vec!["bake", path_str(&fandisk), "-o", path_str(&out)];
        args.extend(flags);
        let run = chamfer(&args);
        assert!(!run.status.success(), "{flags:?} accepted");
        assert!(!out.exists());
    }
}

#[test]
fn radius_flags_mark_chamfer_edges() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cube.chamfer");
    succeed(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "--radius",
        "0.05",
        "-o",
        path_str(&out),
    ]);
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
    succeed(&args.iter().map(String::as_str).collect::<Vec<_>>());
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
    let run = succeed(&[
        "annotate",
        path_str(&input),
        "--radius",
        "0.2",
        "-o",
        path_str(&out),
    ]);
    assert!(
        text(&run.stdout).contains("13 marked or chamfer edges"),
        "{}",
        text(&run.stdout)
    );
    let asset = dir.path().join("marked.chamfer");
    succeed(&["bake", path_str(&out), "-o", path_str(&asset)]);
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
    // An OBJ cannot hold edges: the error names the output and what to call it instead.
    assert_eq!(run.status.code(), Some(1));
    let stderr = text(&run.stderr);
    assert!(
        stderr.contains("c.obj") && stderr.contains(".glb") && stderr.lines().count() == 1,
        "{stderr}"
    );
}

#[test]
fn annotate_writes_the_glb_edge_extensions_it_is_told_to() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cube.glb");
    let input = fixture("shapes/cube.obj");
    let run = succeed(&[
        "annotate",
        path_str(&input),
        "--gltf-edges",
        "extras,edge-visibility,CESIUM_primitive_outline",
        "-o",
        path_str(&out),
    ]);
    assert!(
        text(&run.stdout).contains("12 hard and 0 silhouette edges"),
        "{}",
        text(&run.stdout)
    );
    let bytes = std::fs::read(&out).expect("GLB");
    let length = u32::from_le_bytes(bytes[12..16].try_into().expect("4 bytes")) as usize;
    let document: serde_json::Value =
        serde_json::from_slice(&bytes[20..20 + length]).expect("JSON chunk");
    assert_eq!(
        document["extensionsUsed"],
        serde_json::json!([
            "EXT_mesh_primitive_edge_visibility",
            "CESIUM_primitive_outline"
        ])
    );
    // The extensions are glTF's: a PLY output with them is refused, in one line, before writing.
    let ply = dir.path().join("cube.ply");
    let run = chamfer(&[
        "annotate",
        path_str(&input),
        "--gltf-edges",
        "edge-visibility",
        "-o",
        path_str(&ply),
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert_eq!(
        text(&run.stderr).lines().count(),
        1,
        "{}",
        text(&run.stderr)
    );
    assert!(!ply.exists());
    let run = chamfer(&["annotate", "--help"]);
    assert!(text(&run.stdout).contains("--gltf-edges"));
}

/// Width and height of a PNG, from its IHDR chunk.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    let be = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    (be(16), be(20))
}

/// The RGBA pixels of a PNG.
fn png_pixels(bytes: &[u8]) -> Vec<[u8; 4]> {
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .expect("a PNG");
    let mut buffer = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buffer).expect("a frame");
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buffer[..info.buffer_size()]
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect()
}

#[test]
fn render_shades_chamfers_with_pbr_under_a_spot_and_an_environment() {
    let dir = tempfile::tempdir().expect("tempdir");
    let cube = fixture("shapes/cube.obj");
    let png = dir.path().join("cube.png");
    let sky = fixture("environments/sky.hdr");
    // An orange cube with PBR strips, no ambient, lit as `light` says; its pixels.
    let render = |light: &[&str]| {
        let mut args = vec![
            "render",
            path_str(&cube),
            "-o",
            path_str(&png),
            "--width",
            "96",
            "--height",
            "64",
            "--style",
            "chamfer",
            "--radius-rel",
            "0.02",
            "--shading",
            "pbr",
            "--roughness",
            "0.3",
            "--metallic",
            "0.2",
            "--base-color",
            "0.9,0.6,0.3",
            "--ambient",
            "0",
        ];
        args.extend(light);
        succeed(&args);
        let pixels = png_pixels(&std::fs::read(&png).expect("png"));
        assert_eq!(pixels.len(), 96 * 64);
        pixels
    };
    let orange = |pixels: &[[u8; 4]]| {
        pixels
            .iter()
            .filter(|p| p[0] > 40 && p[0] > p[2].saturating_add(20))
            .count()
    };
    let spot = |direction| {
        render(&[
            "--light-pos",
            "2,3,2",
            "--spot-dir",
            direction,
            "--spot-angles",
            "10,40",
            "--light-intensity",
            "40",
        ])
    };
    // The spot aimed at the cube lights its faces and strips; aimed away, the cube is black (the
    // background is white).
    let aimed = orange(&spot("-2,-3,-2"));
    assert!(aimed > 200, "{aimed} lit pixels");
    let away = spot("2,3,2");
    let black = away.iter().filter(|p| p[0].max(p[1]).max(p[2]) < 8).count();
    assert!(orange(&away) == 0 && black > 200, "{black} black pixels");
    // No light but the environment: lit again.
    let sky_lit = render(&["--light-intensity", "0", "--env", path_str(&sky)]);
    let lit = sky_lit
        .iter()
        .filter(|p| p[0].max(p[1]).max(p[2]) > 40 && p[0] < 250)
        .count();
    assert!(lit > 200, "{lit} pixels lit by the sky");
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
        succeed(&args);
        assert_eq!(png_size(&std::fs::read(&png).expect("png")), (96, 64));
    }
}

/// Issue 39: the highlight renders on every asset, chamfer edges or not (an empty corner buffer used
/// to fail the frame). Each mesh fixture (public meshes, a CAD part, a cylinder without corners) is
/// rendered with `--style chamfer` without a radius, with one, and baked first then rendered; the
/// strips must show where there are chamfer edges, and a bake with none draws the plain frame.
#[test]
fn the_highlight_renders_on_every_mesh_fixture_with_or_without_a_radius() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut meshes: Vec<PathBuf> = std::fs::read_dir(fixture("meshes"))
        .expect("meshes")
        .map(|entry| entry.expect("entry").path())
        .filter(|path| path.extension().is_some_and(|e| e != "md"))
        .collect();
    meshes.extend([
        fixture("shapes/cube.obj"),
        fixture("shapes/cube-cad-jittered.glb"),
    ]);
    meshes.sort();
    assert!(meshes.len() >= 12, "{meshes:?}");
    let render = |input: &Path, extra: &[&str]| {
        let png = dir.path().join("frame.png");
        let mut args = vec!["render", path_str(input), "-o", path_str(&png)];
        // 320 × 240: at 80 × 60 bunny-loop2's few strips (its base's 63 chamfer edges, about 7
        // pixels) drown in its lines' frame-to-frame flicker (8 to 15 pixels between two plain
        // frames there, 2 here, where the strips change 16).
        args.extend(["--style", "chamfer", "--width", "320", "--height", "240"]);
        args.extend(extra);
        let run = chamfer(&args);
        assert!(
            run.status.success(),
            "chamfer {args:?}: {}",
            text(&run.stderr)
        );
        png_pixels(&std::fs::read(&png).expect("png"))
    };
    // How many pixels the strips change in a view, beyond what two plain frames of it differ by
    // (a 1.1 M-triangle mesh differs by a few pixels from frame to frame).
    let strips = |mesh: &Path, view: &[&str]| {
        let plain = render(mesh, view);
        let noise = plain
            .iter()
            .zip(&render(mesh, view))
            .filter(|(a, b)| a != b)
            .count();
        let rounded = render(mesh, &[view, &["--radius-rel", "0.01"]].concat());
        let changed = plain.iter().zip(&rounded).filter(|(a, b)| a != b).count();
        (changed, noise)
    };
    for mesh in &meshes {
        let asset = dir.path().join("baked.chamfer");
        let run = chamfer(&[
            "bake",
            path_str(mesh),
            "-o",
            path_str(&asset),
            "--radius-rel",
            "0.01",
        ]);
        assert!(
            run.status.success(),
            "{}: {}",
            mesh.display(),
            text(&run.stderr)
        );
        // Baked first, then rendered: the asset path draws too (its framing is the asset's bounds).
        render(&asset, &[]);
        let run = chamfer(&["inspect", path_str(&asset), "--json"]);
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("JSON");
        let chamfer_edges = json["chamfer"]["edges"].as_u64().expect("chamfer edges");
        // The default view, then from below (bunny-loop2's chamfer edges are on its base).
        let mut shown = false;
        for view in [&[][..], &["--elevation", "-85"][..]] {
            let (changed, noise) = strips(mesh, view);
            eprintln!(
                "{} {view:?}: {chamfer_edges} chamfer edges, {changed} pixels changed, {noise} between plain frames",
                mesh.display()
            );
            if chamfer_edges == 0 {
                assert!(changed <= noise, "{}: nothing to highlight", mesh.display());
                break;
            }
            shown = changed > noise;
            if shown {
                break;
            }
        }
        assert!(
            chamfer_edges == 0 || shown,
            "{}: the strips show",
            mesh.display()
        );
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
    let chamfer_style = |extra: &[&'static str]| {
        let mut args = vec![path_str(&cube), "--style", "chamfer", "--shading", "pbr"];
        args.extend(extra);
        args
    };
    let truncated_hdr = fixture("broken/truncated.hdr");
    let sky = fixture("environments/sky.hdr");
    let cases: [(Vec<&str>, &str); 15] = [
        (
            {
                let mut args = chamfer_style(&[]);
                args.extend(["--env", path_str(&truncated_hdr)]);
                args
            },
            "truncated.hdr",
        ),
        (
            vec![
                path_str(&cube),
                "--style",
                "chamfer",
                "--env",
                path_str(&sky),
            ],
            "--env",
        ),
        (chamfer_style(&["--roughness", "1.5"]), "--roughness"),
        (chamfer_style(&["--metallic", "NaN"]), "--metallic"),
        (chamfer_style(&["--base-color", "0.5,0.5"]), "--base-color"),
        (
            chamfer_style(&["--light-intensity", "1e10"]),
            "--light-intensity",
        ),
        (
            chamfer_style(&["--light-pos", "1,2,3", "--spot-dir", "0,0,0"]),
            "--spot-dir",
        ),
        (
            chamfer_style(&[
                "--light-pos",
                "1,2,3",
                "--spot-dir",
                "0,-1,0",
                "--spot-angles",
                "30,10",
            ]),
            "--spot-angles",
        ),
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
    // An unknown technique is a usage error (exit 2), with the names that exist.
    let run = chamfer(&[
        "render",
        "-o",
        path_str(&png),
        path_str(&cube),
        "--technique",
        "no-such",
    ]);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--technique") && stderr.contains("mcguire-hughes"),
        "{stderr}"
    );
    assert_eq!(std::fs::read(&png).expect("png"), b"previous picture");
}

#[test]
fn render_draws_every_technique_its_help_lists() {
    let run = chamfer(&["render", "--help"]);
    let help = text(&run.stdout);
    let names: Vec<&str> = help
        .lines()
        .find_map(|l| l.trim().strip_prefix("[possible values: joined"))
        .map(|rest| rest.trim_end_matches(']').split(", ").skip(1).collect())
        .expect("the technique list in --help");
    assert!(names.len() >= 20, "{names:?}");
    let dir = tempfile::tempdir().expect("tempdir");
    for name in std::iter::once("joined").chain(names) {
        let png = dir.path().join(format!("{name}.png"));
        let run = chamfer(&[
            "render",
            path_str(&fixture("shapes/cube.obj")),
            "-o",
            path_str(&png),
            "--width",
            "64",
            "--height",
            "48",
            "--technique",
            name,
        ]);
        assert!(run.status.success(), "{name}: {}", text(&run.stderr));
        let bytes = std::fs::read(&png).expect("png");
        assert_eq!(&bytes[1..4], b"PNG", "{name}");
    }
}

#[test]
fn a_picture_the_device_cannot_hold_is_an_error_not_a_panic() {
    // 16384² with 4 samples needs a 4 GiB colour texture for MSAA alone: the software adapter
    // refuses it (and a device that accepts it renders it). Either way, no panic.
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("huge.png");
    let run = chamfer(&[
        "render",
        path_str(&fixture("shapes/cube.obj")),
        "-o",
        path_str(&png),
        "--width",
        "16384",
        "--height",
        "16384",
    ]);
    let stderr = text(&run.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    match run.status.code() {
        Some(0) => assert!(png.exists()),
        Some(1) => {
            assert!(
                stderr.contains("cube.obj") && stderr.contains("GPU"),
                "{stderr}"
            );
            assert!(!png.exists());
        }
        other => panic!("exit {other:?}: {stderr}"),
    }
}

/// Runs `command`, killing it and failing the test if it has not exited within 30 s.
fn finish(mut command: Command) -> Output {
    use std::process::Stdio;
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let start = std::time::Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > std::time::Duration::from_secs(30) {
            let _ = child.kill();
            panic!("{command:?} did not finish within 30 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    assert!(
        Command::new("mkfifo")
            .arg(path)
            .status()
            .expect("mkfifo")
            .success()
    );
}

#[cfg(unix)]
fn mode(path: &Path) -> u32 {
    use std::os::unix::fs::PermissionsExt;
    std::fs::metadata(path)
        .expect("metadata")
        .permissions()
        .mode()
        & 0o7777
}

#[cfg(unix)]
#[test]
fn outputs_get_the_umask_mode_and_replaced_files_keep_theirs() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cube.chamfer");
    let cube = fixture("shapes/cube.obj");
    let bake_under_umask_022 = || {
        let mut command = Command::new("sh");
        command.args([
            "-c",
            "umask 022 && exec \"$0\" \"$@\"",
            env!("CARGO_BIN_EXE_chamfer"),
            "bake",
            path_str(&cube),
            "-o",
            path_str(&out),
        ]);
        let run = finish(command);
        assert!(run.status.success(), "{}", text(&run.stderr));
    };
    bake_under_umask_022();
    assert_eq!(
        mode(&out),
        0o644,
        "a new asset is -rw-r--r-- under umask 022"
    );
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o640)).expect("chmod");
    bake_under_umask_022();
    assert_eq!(mode(&out), 0o640, "a replaced asset keeps its mode");
}

#[cfg(unix)]
#[test]
fn an_output_that_is_a_fifo_is_refused_and_left_a_fifo() {
    use std::os::unix::fs::FileTypeExt;
    let dir = tempfile::tempdir().expect("tempdir");
    let fifo = dir.path().join("some.fifo");
    mkfifo(&fifo);
    let mut command = Command::new(env!("CARGO_BIN_EXE_chamfer"));
    command.args([
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "-o",
        path_str(&fifo),
    ]);
    let run = finish(command);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("some.fifo") && stderr.contains("FIFO"),
        "{stderr}"
    );
    let file_type = std::fs::symlink_metadata(&fifo)
        .expect("still there")
        .file_type();
    assert!(file_type.is_fifo(), "the FIFO was replaced");
    // Reading one as an asset does not block either.
    let mut command = Command::new(env!("CARGO_BIN_EXE_chamfer"));
    command.args(["inspect", path_str(&fifo)]);
    let run = finish(command);
    assert_eq!(run.status.code(), Some(1));
    assert!(text(&run.stderr).contains("FIFO"), "{}", text(&run.stderr));
}

#[test]
fn write_errors_name_the_output_not_the_temporary_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("missing/cube.chamfer");
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "-o",
        path_str(&out),
    ]);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(path_str(&out)), "{stderr}");
    assert!(
        !stderr.contains(".chamfer-") && !stderr.contains("at path"),
        "{stderr}"
    );
    assert!(stderr.contains("No such file or directory"), "{stderr}");
}

#[cfg(target_os = "linux")]
#[test]
fn stdout_errors_are_errors_and_a_closed_pipe_is_quiet() {
    let dir = tempfile::tempdir().expect("tempdir");
    let asset = dir.path().join("cube.chamfer");
    let cube = fixture("shapes/cube.obj");
    assert!(
        chamfer(&["bake", path_str(&cube), "-o", path_str(&asset)])
            .status
            .success()
    );
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    let run = Command::new(env!("CARGO_BIN_EXE_chamfer"))
        .args(["inspect", path_str(&asset)])
        .stdout(full)
        .output()
        .expect("run");
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("standard output") && !stderr.contains("panicked"),
        "{stderr}"
    );
    for args in [
        vec!["bake", path_str(&cube), "-o", path_str(&asset)],
        vec!["inspect", path_str(&asset)],
    ] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_chamfer"))
            .args(&args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("spawn");
        drop(child.stdout.take()); // the reader is gone before anything is written
        let run = child.wait_with_output().expect("wait");
        assert_eq!(
            run.status.code(),
            Some(0),
            "{args:?}: {}",
            text(&run.stderr)
        );
        assert!(run.stderr.is_empty(), "{args:?}: {}", text(&run.stderr));
    }
}

#[test]
fn inputs_of_one_stem_fail_before_anything_is_created() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("baked");
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/two-materials.glb")),
        path_str(&fixture("shapes/two-materials.gltf")),
        "-o",
        path_str(&out),
    ]);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("two-materials.glb") && stderr.contains("two-materials.gltf"),
        "{stderr}"
    );
    assert!(!out.exists(), "the output folder was created");
}

#[test]
fn a_folder_input_is_baked_like_build_bake_dir() {
    let dir = tempfile::tempdir().expect("tempdir");
    let assets = dir.path().join("assets");
    std::fs::create_dir_all(assets.join("props")).expect("mkdir");
    std::fs::copy(fixture("shapes/cube.obj"), assets.join("cube.obj")).expect("copy");
    std::fs::copy(
        fixture("shapes/two-materials.glb"),
        assets.join("props/pair.glb"),
    )
    .expect("copy");
    std::fs::write(assets.join("notes.txt"), "not a mesh").expect("write");
    let out = dir.path().join("baked");
    succeed(&["bake", path_str(&assets), "-o", path_str(&out)]);
    assert!(out.join("cube.chamfer").is_file());
    assert!(out.join("props/pair.chamfer").is_file());
    assert_eq!(std::fs::read_dir(&out).expect("dir").count(), 2);
}

#[test]
fn warnings_go_to_stderr() {
    let dir = tempfile::tempdir().expect("tempdir");
    let obj = dir.path().join("lonely.obj");
    std::fs::write(
        &obj,
        "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .expect("write");
    let out = dir.path().join("lonely.chamfer");
    let run = succeed(&["bake", path_str(&obj), "-o", path_str(&out)]);
    assert!(
        !text(&run.stdout).contains("warning"),
        "{}",
        text(&run.stdout)
    );
    assert!(
        text(&run.stderr).contains("warning: ") && text(&run.stderr).contains("gone.mtl"),
        "{}",
        text(&run.stderr)
    );
}

#[test]
fn limits_are_flags_and_documented_in_help() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cube.chamfer");
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "--max-triangles",
        "11",
        "-o",
        path_str(&out),
    ]);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("cube.obj") && stderr.contains("--max-triangles"),
        "{stderr}"
    );
    assert!(!out.exists());
    let help = text(&chamfer(&["bake", "--help"]).stdout);
    for flag in [
        "--max-triangles",
        "--max-vertices",
        "--max-instances",
        "--max-input-bytes",
        "Limits:",
        "inside the mesh's folder",
    ] {
        assert!(help.contains(flag), "bake --help lacks {flag}");
    }
}

#[test]
fn bake_intersections_then_inspect_json_shows_them() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("cubes.chamfer");
    let input = fixture("shapes/two-cubes.obj");
    let run = succeed(&[
        "bake",
        path_str(&input),
        "-o",
        path_str(&out),
        "--intersections",
    ]);
    assert!(
        text(&run.stdout).contains("intersections: "),
        "{}",
        text(&run.stdout)
    );
    let run = succeed(&["inspect", path_str(&out), "--json"]);
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
                succeed(&["bake", path_str(&input), "-o", path_str(&plain)]);
                plain
            }
        };
        let run = succeed(&["inspect", path_str(&path), "--json"]);
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
        assert_eq!(json["intersections"]["segments"], 0, "{json}");
        assert_eq!(json["intersections"]["length"], 0.0);
    }
}

#[test]
fn bake_scene_keeps_a_gltf_scene_and_render_draws_it() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("baked");
    let gltf = fixture("shapes/two-cube-instances.gltf");
    succeed(&["bake", path_str(&gltf), "--scene", "-o", path_str(&out)]);
    let scene_path = out.join("two-cube-instances.scene.json");
    let scene = std::fs::read_to_string(&scene_path).expect("scene file");
    let parsed: serde_json::Value = serde_json::from_str(&scene).expect("JSON");
    assert_eq!(
        parsed["assets"].as_array().map(Vec::len),
        Some(1),
        "one mesh"
    );
    assert_eq!(
        parsed["instances"].as_array().map(Vec::len),
        Some(2),
        "two nodes"
    );
    assert!(out.join("two-cube-instances.mesh0.chamfer").is_file());
    let png = dir.path().join("scene.png");
    let run = succeed(&[
        "render",
        path_str(&scene_path),
        "-o",
        path_str(&png),
        "--width",
        "96",
        "--height",
        "64",
    ]);
    assert!(text(&run.stdout).contains("2 instances of 1 assets"));
    // A scene reaching outside its folder is refused, naming the file and the name.
    let sneaky = dir.path().join("sneaky.scene.json");
    std::fs::write(
        &sneaky,
        scene.replace("two-cube-instances.mesh0", "../etc/x"),
    )
    .expect("write");
    let run = chamfer(&["render", path_str(&sneaky), "-o", path_str(&png)]);
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("sneaky.scene.json") && stderr.contains("plain file name"),
        "{stderr}"
    );
    // So is a plain name that is a link leading out of the scene's folder.
    #[cfg(unix)]
    {
        let inside = dir.path().join("inside");
        std::fs::create_dir(&inside).expect("mkdir");
        std::os::unix::fs::symlink(
            out.join("two-cube-instances.mesh0.chamfer"),
            inside.join("two-cube-instances.mesh0.chamfer"),
        )
        .expect("symlink");
        let linked = inside.join("linked.scene.json");
        std::fs::write(&linked, &scene).expect("write");
        let run = chamfer(&["render", path_str(&linked), "-o", path_str(&png)]);
        let stderr = text(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains("linked.scene.json") && stderr.contains("outside the file's folder"),
            "{stderr}"
        );
    }
    // A scene needs a node graph.
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/cube.obj")),
        "--scene",
        "-o",
        path_str(&out),
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert!(text(&run.stderr).contains("cube.obj"));
}

#[test]
fn the_default_weld_is_relative_and_weld_epsilon_zero_keeps_it_exact() {
    let dir = tempfile::tempdir().expect("tempdir");
    let input = fixture("shapes/cube-cad-jittered.glb");
    let welded = |flags: &[&str]| {
        let asset = dir.path().join("cube.chamfer");
        let mut args = vec!["bake", path_str(&input), "-o", path_str(&asset)];
        args.extend_from_slice(flags);
        succeed(&args);
        let run = chamfer(&["inspect", path_str(&asset), "--json"]);
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("valid JSON");
        (
            json["welded_vertices"].clone(),
            json["edges"]["boundary"].clone(),
        )
    };
    assert_eq!(welded(&[]), (8.into(), 0.into()));
    assert_eq!(welded(&["--weld-rel", "1e-6"]), (8.into(), 0.into()));
    let (exact, boundary) = welded(&["--weld-epsilon", "0", "--no-stitch"]);
    assert!(
        exact.as_u64() > Some(8) && boundary == 24,
        "{exact} {boundary}"
    );
    // A stitch wider than the copies' 4 ULPs closes what the exact weld leaves; inspect says so.
    let stitched = welded(&["--weld-epsilon", "0", "--stitch-epsilon", "1e-3"]);
    assert_eq!(stitched.1, 0);
    let asset = dir.path().join("cube.chamfer");
    let run = chamfer(&["inspect", path_str(&asset)]);
    let summary = text(&run.stdout);
    assert!(
        summary.contains("stitch") && summary.contains("24 boundary edges"),
        "{summary}"
    );
    let run = chamfer(&[
        "bake",
        path_str(&input),
        "--weld-epsilon",
        "0",
        "--weld-rel",
        "1e-6",
        "-o",
        path_str(&dir.path().join("both.chamfer")),
    ]);
    assert_eq!(run.status.code(), Some(2), "the two are one choice");
    assert!(
        text(&run.stderr).contains("cannot be used with"),
        "{}",
        text(&run.stderr)
    );
    let run = chamfer(&["bake", "--help"]);
    assert!(text(&run.stdout).contains("--weld-rel"));
}

#[test]
fn stl_and_3mf_bake_from_the_command_line_and_inspect_reports_the_stitch() {
    let dir = tempfile::tempdir().expect("tempdir");
    let asset = dir.path().join("step.chamfer");
    let run = succeed(&[
        "bake",
        path_str(&fixture("shapes/step-binary.stl")),
        "-o",
        path_str(&asset),
    ]);
    assert!(
        text(&run.stdout).contains("0 boundary"),
        "{}",
        text(&run.stdout)
    );
    // The cracked cube: stitched, and both reports say how many boundary edges were closed.
    let cracked = dir.path().join("cracked.chamfer");
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/box-cracked.obj")),
        "-o",
        path_str(&cracked),
    ]);
    let report = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        report.contains("stitched: 46 boundary edges closed") && report.contains("0 remain"),
        "{report}"
    );
    let run = chamfer(&["inspect", path_str(&cracked), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).expect("JSON");
    assert_eq!(json["stitch"]["stitched"], 46, "{}", json["stitch"]);
    assert_eq!(json["stitch"]["remaining"], 0);
    let run = chamfer(&["inspect", path_str(&cracked)]);
    assert!(
        text(&run.stdout).contains("46 boundary edges stitched, 0 remain"),
        "{}",
        text(&run.stdout)
    );
    // A 3MF's build as a scene: one asset per object, an instance per placement.
    let out = dir.path().join("scene");
    succeed(&[
        "bake",
        path_str(&fixture("shapes/step-components.3mf")),
        "--scene",
        "-o",
        path_str(&out),
    ]);
    let scene = std::fs::read_to_string(out.join("step-components.scene.json")).expect("scene");
    let parsed: serde_json::Value = serde_json::from_str(&scene).expect("JSON");
    assert_eq!(parsed["instances"].as_array().map(Vec::len), Some(3));
    assert!(out.join("step-components.mesh1.chamfer").is_file());
    // --scene of an STL says why not.
    let run = chamfer(&[
        "bake",
        path_str(&fixture("shapes/step-binary.stl")),
        "--scene",
        "-o",
        path_str(&out),
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert!(
        text(&run.stderr).contains("glTF, GLB or 3MF"),
        "{}",
        text(&run.stderr)
    );
}

/// The frame benchmarks (`examples/bench_render.rs`, `bench_section.rs`, `bench_display.rs`,
/// `bench_scene.rs`, `bench_pose.rs`, built
/// by `cargo test`) run: one frame of each configuration at 64 × 64 on a cube (with chamfer radii
/// for bench_render, the highlight's row included; the scenes of 2³ instances).
#[test]
fn the_frame_benchmarks_run_at_a_tiny_size() {
    let cube = fixture("shapes/cube.obj");
    let cube = cube.to_str().expect("a UTF-8 path");
    for (name, extra, rows) in [
        (
            "bench_render",
            &["--radius-rel", "0.02", cube][..],
            &["| cube.obj"][..],
        ),
        (
            "bench_section",
            &["--grid", "2", cube][..],
            &["| cube.obj", "| 8 instances (scene)"][..],
        ),
        (
            "bench_display",
            &["--grid", "2", cube][..],
            &["| cube.obj", "| 8 instances (scene)"][..],
        ),
        (
            "bench_scene",
            &["--grid", "2", "--no-separate", "--large", cube][..],
            &["| + one SceneRenderer"][..],
        ),
        (
            "bench_pose",
            &["--vertices", "500", "--joints", "4"][..],
            &["| 450"][..],
        ),
    ] {
        run_frame_bench(name, extra, rows);
    }
}

fn run_frame_bench(name: &str, args: &[&str], rows: &[&str]) {
    let chamfer = Path::new(env!("CARGO_BIN_EXE_chamfer"));
    let bench = chamfer
        .parent()
        .expect("target folder")
        .join("examples")
        .join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    assert!(bench.exists(), "{} is built by cargo test", bench.display());
    let run = Command::new(&bench)
        .args(["--frames", "1", "--size", "64x64"])
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("run {name}: {e}"));
    let out = text(&run.stdout);
    assert!(run.status.success(), "{out}{}", text(&run.stderr));
    for start in rows {
        let row = out
            .lines()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("{name}: no row {start}: {out}"));
        assert!(!row.contains("NaN") && !row.contains("inf"), "{row}");
    }
}

/// Issue 40: every entry of the bake's schema is a flag of `chamfer bake`, and its example value
/// given as that flag bakes what the same settings bake through the library (Python, the page and
/// Bevy check theirs against the same settings).
#[test]
fn every_schema_option_is_a_flag_that_bakes_what_the_settings_bake() {
    use chamfer_preprocess::BakeSettings;
    use chamfer_runtime::schema::{Schema, Value};

    let dir = tempfile::tempdir().expect("tempdir");
    let mesh = fixture("meshes/fandisk.obj");
    let help = text(&chamfer(&["bake", "--help"]).stdout);
    for entry in BakeSettings::ENTRIES {
        let flag = chamfer_runtime::schema::flag(entry.name);
        assert!(help.contains(&flag), "{flag} is not in chamfer bake --help");
        let mut settings = BakeSettings::default();
        let mut args = vec![
            "bake".to_owned(),
            path_str(&mesh).to_owned(),
            "-o".to_owned(),
        ];
        let out = dir.path().join(format!("{}.chamfer", entry.name));
        args.push(path_str(&out).to_owned());
        for name in entry.requires.iter().copied().chain([entry.name]) {
            let entry = BakeSettings::entry(name).expect("known");
            entry.set_example(&mut settings);
            args.push(chamfer_runtime::schema::flag(name));
            match entry.example().expect("an example") {
                Value::Flag(_) => {}
                value => args.push(value.to_string()),
            }
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let run = chamfer(&args);
        assert!(run.status.success(), "{args:?}: {}", text(&run.stderr));
        let (options, compact) = settings.options().expect(entry.name);
        let baked = chamfer_preprocess::bake_file(&mesh, &options).expect("bake");
        let mut expected = Vec::new();
        chamfer_preprocess::compact::encode(&baked.asset, compact.as_ref(), &mut expected)
            .expect("encode");
        assert!(
            std::fs::read(&out).expect("baked") == expected,
            "{args:?} baked other bytes than the settings"
        );
    }
}

/// Issue 40: every entry of the view and style schemas is a flag of `chamfer render` (and the view's
/// of `chamfer draw`), its example accepted and changing the picture; a value out of range is
/// refused naming the flag.
#[test]
fn every_view_and_style_entry_is_a_render_flag_that_changes_the_picture() {
    use chamfer_runtime::camera::Orbit;
    use chamfer_runtime::render::StyleSettings;
    use chamfer_runtime::schema::{Entry, Schema, Value, flag};

    let dir = tempfile::tempdir().expect("tempdir");
    let mesh = fixture("shapes/cube.obj");
    let render_help = text(&succeed(&["render", "--help"]).stdout);
    let draw_help = text(&succeed(&["draw", "--help"]).stdout);
    // Plain edges for the camera and the edges' own numbers; the chamfer highlight (with radii)
    // for its numbers, under PBR for the two that are PBR's.
    let kind = |name: &str| match name {
        "roughness" | "metallic" => 2,
        "diffuse" | "specular" | "ambient" | "shininess" | "light_intensity" | "k"
        | "sharp_corners" => 1,
        _ => 0,
    };
    let base = |kind: usize| {
        let mut args = vec![
            "render",
            path_str(&mesh),
            "--width",
            "96",
            "--height",
            "72",
            "--radius",
            "0.15",
        ];
        args.extend(
            [
                &[][..],
                &["--style", "chamfer"],
                &["--style", "chamfer", "--shading", "pbr"],
            ][kind],
        );
        args.into_iter().map(str::to_owned).collect::<Vec<_>>()
    };
    let picture = |args: &[String], name: &str| {
        let out = dir.path().join(format!("{name}.png"));
        let mut args = args.to_vec();
        args.extend(["-o".to_owned(), path_str(&out).to_owned()]);
        succeed(&args.iter().map(String::as_str).collect::<Vec<_>>());
        std::fs::read(&out).expect("png")
    };
    let defaults = [0, 1, 2].map(|k| picture(&base(k), &format!("default-{k}")));
    fn flags<S: Schema>(entry: &Entry<S>) -> Vec<String> {
        match entry.example().expect("an example") {
            Value::Flag(_) => vec![flag(entry.name)],
            value => vec![flag(entry.name), value.to_string()],
        }
    }
    let check = |name: &'static str, given: Vec<String>, in_draw: bool| {
        assert!(
            render_help.contains(&given[0]),
            "{} is not in render --help",
            given[0]
        );
        assert!(
            !in_draw || draw_help.contains(&given[0]),
            "{} is not in draw --help",
            given[0]
        );
        let mut args = base(kind(name));
        args.extend(given.iter().cloned());
        assert_ne!(
            picture(&args, name),
            defaults[kind(name)],
            "{given:?} changed nothing"
        );
    };
    for entry in Orbit::ENTRIES {
        check(entry.name, flags(entry), true);
    }
    for entry in StyleSettings::ENTRIES {
        check(entry.name, flags(entry), false);
    }
    for (args, message) in [
        (
            &["--elevation", "95"][..],
            "--elevation must be -90 to 90, not 95",
        ),
        (&["--fov-y", "0.5"][..], "--fov-y must be 1 to 170, not 0.5"),
        (&["--samples", "2"][..], "--samples must be 1 or 4, not 2"),
        (
            &["--shininess", "500"][..],
            "--shininess must be 1 to 128, not 500",
        ),
        (&["--k", "-1"][..], "--k must be at least 0, not -1"),
    ] {
        let mut all = base(1);
        all.extend(args.iter().map(|a| (*a).to_owned()));
        all.extend([
            "-o".to_owned(),
            path_str(&dir.path().join("refused.png")).to_owned(),
        ]);
        let run = chamfer(&all.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(!run.status.success(), "{args:?} accepted");
        assert!(
            text(&run.stderr).contains(message),
            "{args:?}: {}",
            text(&run.stderr)
        );
    }
    assert!(!dir.path().join("refused.png").exists());
}

/// Issue 43: every section and cut-look entry is a flag of `chamfer render`, its example accepted
/// and changing the picture (the cut look's over a cube cut at x = 0.5 with a hatch); malformed
/// sections and colours are refused naming the flag, and nothing is written.
#[test]
fn every_section_entry_is_a_render_flag_that_changes_the_picture() {
    use chamfer_runtime::schema::{Entry, Schema, Value, flag};
    use chamfer_runtime::section::{CutSettings, Section};

    let dir = tempfile::tempdir().expect("tempdir");
    let mesh = fixture("shapes/cube.obj");
    let help = text(&succeed(&["render", "--help"]).stdout);
    let cut = ["--section", "1,0,0,0.5", "--cap-hatch-spacing", "4"];
    let picture = |extra: &[String], name: &str| {
        let out = dir.path().join(format!("{name}.png"));
        let mut args = vec!["render", path_str(&mesh), "--width", "96", "--height", "72"];
        args.extend(extra.iter().map(String::as_str));
        args.extend(["-o", path_str(&out)]);
        succeed(&args);
        std::fs::read(&out).expect("png")
    };
    fn flags<S: Schema>(entry: &Entry<S>) -> Vec<String> {
        match entry.example().expect("an example") {
            Value::Flag(_) => vec![flag(entry.name)],
            value => vec![flag(entry.name), value.to_string()],
        }
    }
    let whole = picture(&[], "whole");
    let cut_open: Vec<String> = cut.iter().map(|a| (*a).to_owned()).collect();
    let hatched = picture(&cut_open, "hatched");
    assert_ne!(whole, hatched, "the section changes the picture");
    for entry in Section::ENTRIES {
        let given = flags(entry);
        assert!(
            help.contains(&given[0]),
            "{} is not in render --help",
            given[0]
        );
        assert_ne!(
            picture(&given, entry.name),
            whole,
            "{given:?} changed nothing"
        );
    }
    for entry in CutSettings::ENTRIES {
        let given = flags(entry);
        assert!(
            help.contains(&given[0]),
            "{} is not in render --help",
            given[0]
        );
        // The hatch's own spacing replaces the base's.
        let base = if entry.name == "cap_hatch_spacing" {
            &cut_open[..2]
        } else {
            &cut_open[..]
        };
        let args = [base.to_vec(), given.clone()].concat();
        assert_ne!(
            picture(&args, entry.name),
            hatched,
            "{given:?} changed nothing"
        );
    }
    let refused = dir.path().join("refused.png");
    for (args, message) in [
        (
            &["--section", "1,0,0"][..],
            "--section must be 1 to 6 planes",
        ),
        (
            &["--section", "0,0,0,1"][..],
            "--section needs a finite plane with a non-zero normal",
        ),
        (
            &["--section-box", "1,0,0,0,1,1"][..],
            "--section-box must be six finite numbers",
        ),
        (
            &["--section", "1,0,0,0.5", "--cap-color", "1,1"][..],
            "--cap-color must be three numbers",
        ),
        (
            &["--section", "1,0,0,0.5", "--cut-outline-width", "-2"][..],
            "--cut-outline-width must be",
        ),
    ] {
        let mut all = vec!["render", path_str(&mesh), "-o", path_str(&refused)];
        all.extend(args);
        let run = chamfer(&all);
        let stderr = text(&run.stderr);
        assert!(!run.status.success(), "{args:?} accepted");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    assert!(!refused.exists());
}

/// Issue 42: every display schema entry is a flag of `chamfer render`, in its help, accepted with its
/// example and changing the picture (over hidden edges and a fade, which the hidden and fade entries
/// style); conflicting modes, a hidden line wider than the edges, a technique without hidden edges
/// and a fade without its end are refused naming the flag, and nothing is written.
#[test]
fn every_display_entry_is_a_render_flag_that_changes_the_picture() {
    use chamfer_runtime::render::DisplaySettings;
    use chamfer_runtime::schema::{Schema, Value, flag};

    let dir = tempfile::tempdir().expect("tempdir");
    let mesh = fixture("shapes/cube.obj");
    let help = text(&succeed(&["render", "--help"]).stdout);
    let picture = |extra: &[String], name: &str| {
        let out = dir.path().join(format!("{name}.png"));
        let mut args = vec!["render", path_str(&mesh), "--width", "96", "--height", "72"];
        args.extend(extra.iter().map(String::as_str));
        args.extend(["-o", path_str(&out)]);
        succeed(&args);
        std::fs::read(&out).expect("png")
    };
    let owned = |args: &[&str]| args.iter().map(|a| (*a).to_owned()).collect::<Vec<_>>();
    let styled = owned(&["--hidden-edges", "--fade-start", "0.5", "--fade-end", "8"]);
    assert_ne!(picture(&styled, "styled"), picture(&[], "shaded"));
    for entry in DisplaySettings::ENTRIES {
        let given = match entry.example().expect("an example") {
            Value::Flag(_) => vec![flag(entry.name)],
            value => vec![flag(entry.name), value.to_string()],
        };
        assert!(
            help.contains(&given[0]),
            "{} is not in render --help",
            given[0]
        );
        // Wireframe excludes hidden edges; hidden edges are the entry itself; the fade's own
        // ends replace the base's.
        let fade = &styled[1..];
        let (without, with) = match entry.name {
            "hidden_edges" | "wireframe" => (fade.to_vec(), fade.to_vec()),
            "fade_start" => (
                styled.clone(),
                owned(&["--hidden-edges", "--fade-end", "8"]),
            ),
            "fade_end" => (
                styled.clone(),
                owned(&["--hidden-edges", "--fade-start", "0.5"]),
            ),
            _ => (styled.clone(), styled.clone()),
        };
        assert_ne!(
            picture(&[with, given.clone()].concat(), entry.name),
            picture(&without, &format!("{}-without", entry.name)),
            "{given:?} changed nothing"
        );
    }
    let refused = dir.path().join("refused.png");
    for (args, message) in [
        (
            &["--hidden-line", "--wireframe"][..],
            "the argument '--hidden-line' cannot be used with '--wireframe'",
        ),
        (
            &["--hidden-edges", "--hidden-width", "3"][..],
            "--hidden-width must be at most the edge width 2, not 3",
        ),
        (
            &["--hidden-edges", "--technique", "plug"][..],
            "--hidden-edges needs a technique that draws hidden edges (joined), not plug",
        ),
        (&["--fade-start", "2"][..], "--fade-end"),
        (
            &["--hidden-edges", "--hidden-dash", "1,-1"][..],
            "--hidden-dash must be",
        ),
    ] {
        let mut all = vec!["render", path_str(&mesh), "-o", path_str(&refused)];
        all.extend(args);
        let run = chamfer(&all);
        let stderr = text(&run.stderr);
        assert!(!run.status.success(), "{args:?} accepted");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    assert!(!refused.exists());
}

/// Issue 40: every parameter of every technique that has some (its module's table) is a flag of
/// `chamfer render`, `--{prefix}-{name}`, in its help, accepted with its example over the first
/// preset of its table and changing the picture; a parameter given to another technique and a value out
/// of range are refused naming the flag.
#[test]
fn every_technique_parameter_is_a_render_flag() {
    use chamfer_runtime::render::Technique;

    let dir = tempfile::tempdir().expect("tempdir");
    let mesh = fixture("meshes/fandisk.obj");
    let help = text(&succeed(&["render", "--help"]).stdout);
    let picture = |extra: &[String], name: &str| {
        let out = dir.path().join(format!("{name}.png"));
        let mut args: Vec<String> = [
            "render",
            path_str(&mesh),
            "--width",
            "120",
            "--height",
            "90",
        ]
        .map(str::to_owned)
        .into();
        args.extend(extra.iter().cloned());
        args.extend(["-o".to_owned(), path_str(&out).to_owned()]);
        succeed(&args.iter().map(String::as_str).collect::<Vec<_>>());
        std::fs::read(&out).expect("png")
    };
    let mut set = 0;
    let mut tables = Vec::new();
    for preset in Technique::presets() {
        // Each table once, over its first preset.
        let Some(table) = preset.technique.parameters() else {
            continue;
        };
        if tables.contains(&table.prefix()) {
            continue;
        }
        tables.push(table.prefix());
        let technique = ["--technique".to_owned(), preset.name.to_owned()];
        let before = picture(&technique, preset.name);
        for entry in table.schema_json().as_array().expect("a table") {
            let name = entry["name"].as_str().expect("a name");
            let spelled = format!("--{}-{}", table.prefix(), name).replace('_', "-");
            assert!(help.contains(&spelled), "{spelled} is not in render --help");
            let mut args = technique.to_vec();
            args.push(spelled.clone());
            if entry["kind"] != "flag" {
                args.push(entry["example"].to_string());
            }
            let after = picture(&args, &format!("{}-{name}", preset.name));
            assert_ne!(after, before, "{args:?} changed nothing");
            set += 1;
        }
    }
    assert_eq!(tables.len(), Technique::parameter_tables().len());
    assert!(set >= 9, "{set} parameters");
    for (args, message) in [
        (
            &["--technique", "joined", "--hybrid-step", "3"][..],
            "--hybrid-step is a parameter of --technique hybrid-edges, hybrid-ambient, hybrid-both, not of joined",
        ),
        (
            &["--technique", "hybrid-both", "--hybrid-step", "900"][..],
            "--hybrid-step must be 1 to 64, not 900",
        ),
        (
            &["--technique", "fins", "--fin-thickness", "-1"][..],
            "--fin-thickness must be at least 0, not -1",
        ),
    ] {
        let mut all: Vec<&str> = vec!["render", path_str(&mesh)];
        all.extend(args);
        let out = dir.path().join("refused.png");
        all.extend(["-o", path_str(&out)]);
        let run = chamfer(&all);
        assert!(!run.status.success(), "{args:?} accepted");
        assert!(
            text(&run.stderr).contains(message),
            "{args:?}: {}",
            text(&run.stderr)
        );
        assert!(!out.exists());
    }
}

/// Issue 41: `chamfer render` poses an animated glTF by the animation flags (every entry of
/// `AnimationSettings` is a flag that changes the picture), and refuses what does not fit.
#[test]
fn render_poses_an_animated_gltf_by_the_animation_flags() {
    use chamfer_runtime::rig::AnimationSettings;
    use chamfer_runtime::schema::{Schema, flag};

    let dir = tempfile::tempdir().expect("tempdir");
    let help = text(&succeed(&["render", "--help"]).stdout);
    for entry in AnimationSettings::ENTRIES {
        assert!(
            help.contains(&flag(entry.name)),
            "{} not in render --help",
            entry.name
        );
    }
    let picture = |mesh: &str, extra: &[&str], name: &str| {
        let mesh = fixture(mesh);
        let out = dir.path().join(format!("{name}.png"));
        let mut args = vec!["render", path_str(&mesh), "--width", "96", "--height", "72"];
        args.extend(extra);
        args.extend(["-o", path_str(&out)]);
        succeed(&args);
        png_pixels(&std::fs::read(&out).expect("png"))
    };
    let cylinder = "shapes/cylinder-skinned.glb";
    let rest = picture(cylinder, &[], "rest");
    let bent = picture(cylinder, &["--animation", "0", "--time", "1"], "bent");
    let by_name = picture(
        cylinder,
        &["--animation-name", "bend", "--time", "1"],
        "by-name",
    );
    let start = picture(cylinder, &["--animation", "0", "--time", "0"], "start");
    assert_ne!(rest, bent, "--time 1 bends the cylinder");
    assert_eq!(bent, by_name, "the animation by name or number is the same");
    assert_ne!(start, bent, "--time moves the pose");
    let cube = "shapes/cube-morph.glb";
    assert_ne!(
        picture(cube, &["--pose", "1"], "risen"),
        picture(cube, &[], "flat")
    );
    // `inspect` names what `--animation` and `--animation-name` take.
    let baked = dir.path().join("cylinder.chamfer");
    succeed(&["bake", path_str(&fixture(cylinder)), "-o", path_str(&baked)]);
    let report = text(&succeed(&["inspect", path_str(&baked)]).stdout);
    assert!(
        report.contains("2 joints moving") && report.contains("animation 0    \"bend\" (1.000 s"),
        "{report}"
    );
    let json: serde_json::Value =
        serde_json::from_slice(&succeed(&["inspect", "--json", path_str(&baked)]).stdout)
            .expect("JSON");
    assert_eq!(json["motion"]["animations"][0]["name"], "bend");

    let refused = dir.path().join("refused.png");
    for (mesh, args, message) in [
        (
            cylinder,
            &["--animation", "4"][..],
            "--animation must be below 1, not 4 (0 \"bend\")",
        ),
        (
            cylinder,
            &["--animation-name", "run"][..],
            "no such animation (the asset's: 0 \"bend\")",
        ),
        (
            cylinder,
            &["--time", "1"][..],
            "--time needs --animation or --animation-name",
        ),
        (
            cube,
            &["--pose", "1,1"][..],
            "--pose must be 1 weights, one per morph target, not 2",
        ),
        (
            "shapes/cube.obj",
            &["--animation", "0"][..],
            "--animation needs an animated asset",
        ),
        (
            cylinder,
            &["--animation", "0", "--time", "nan"][..],
            "--time",
        ),
    ] {
        let mesh = fixture(mesh);
        let mut all = vec!["render", path_str(&mesh), "-o", path_str(&refused)];
        all.extend(args);
        let out = chamfer(&all);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{args:?} was accepted");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!refused.exists(), "{args:?} wrote a picture");
    }
}
