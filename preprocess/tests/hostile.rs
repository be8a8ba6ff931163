//! Hostile inputs, each made by hand in a few hundred bytes (issue 16) or found by the fuzz
//! harness (`tests/fuzz.rs`): every one must be a one-line error naming the file, reached in
//! bounded time and memory, never a panic, a hang or a read outside the input's folder.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use base64::Engine;
use chamfer_preprocess::build::bake_dir_into;
use chamfer_preprocess::{BakeOptions, Baked, Error, bake_bytes, bake_file};
use chamfer_runtime::asset::{Asset, MAX_RING};

/// Runs `f` on another thread and fails the test if it has not finished in `seconds` (a hang is
/// the bug: the stuck thread is left behind and dies with the test process).
fn within<T: Send + 'static>(seconds: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(f());
    });
    receive
        .recv_timeout(Duration::from_secs(seconds))
        .unwrap_or_else(|_| panic!("did not finish within {seconds} s"))
}

/// Bakes `path` with the default options, off the test thread, within 30 s.
fn bake(path: &Path) -> Result<Baked, Error> {
    let path = path.to_owned();
    within(30, move || bake_file(&path, &BakeOptions::DEFAULT))
}

/// The error of baking `path`, checked to be one line naming the file.
fn refused(path: &Path) -> String {
    let error = bake(path)
        .err()
        .unwrap_or_else(|| panic!("{} was accepted", path.display()));
    let text = error.to_string();
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    assert!(
        name.is_some_and(|n| text.contains(&n)),
        "the error does not name the file: {text}"
    );
    assert_eq!(text.lines().count(), 1, "{text}");
    text
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo");
    assert!(status.success());
}

/// One triangle's three positions, as a base64 `data:` URI.
fn triangle_uri() -> String {
    let floats: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// A glTF with one buffer (`uri`), one view, the given accessor JSON and nodes JSON.
fn gltf(uri: &str, accessor: &str, nodes: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":36,"uri":"{uri}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],"accessors":[{accessor}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}]{nodes}}}"#
    )
}

const POSITIONS: &str = r#"{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}"#;

const CUBE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

#[test]
fn gltf_byte_offset_near_u64_max_is_an_error_not_a_wrapped_bounds_check() {
    let dir = tempfile::tempdir().expect("tempdir");
    let accessor = r#"{"bufferView":0,"byteOffset":18446744073709551612,"componentType":5126,"count":1,"type":"VEC3"}"#;
    let path = write(
        dir.path(),
        "offset.gltf",
        gltf(&triangle_uri(), accessor, ""),
    );
    let text = refused(&path);
    assert!(text.contains("runs past the end"), "{text}");
}

#[test]
fn gltf_nodes_listing_a_child_twice_are_counted_not_expanded() {
    let dir = tempfile::tempdir().expect("tempdir");
    // 40 nodes, each listing the next twice: 2^40 instances of the mesh in 1.5 KB.
    let mut nodes: Vec<String> = (1..=40)
        .map(|next| format!(r#"{{"children":[{next},{next}]}}"#))
        .collect();
    nodes.push(r#"{"mesh":0}"#.into());
    let graph = format!(
        r#","nodes":[{}],"scenes":[{{"nodes":[0]}}],"scene":0"#,
        nodes.join(",")
    );
    let path = write(
        dir.path(),
        "amplify.gltf",
        gltf(&triangle_uri(), POSITIONS, &graph),
    );
    let text = refused(&path);
    assert!(
        text.contains("instances") && text.contains("--max-instances"),
        "{text}"
    );
}

#[test]
fn gltf_node_cycles_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let graph = r#","nodes":[{"children":[1]},{"children":[0],"mesh":0}],"scenes":[{"nodes":[0]}]"#;
    let path = write(
        dir.path(),
        "cycle.gltf",
        gltf(&triangle_uri(), POSITIONS, graph),
    );
    assert!(refused(&path).contains("cycle"));
}

#[test]
fn gltf_accessors_without_data_reused_by_many_primitives_hit_the_vertex_limit() {
    let dir = tempfile::tempdir().expect("tempdir");
    // 2^24 zeros, used as the positions of 64 primitives: 2^30 vertices from 2 KB.
    let primitives = vec![r#"{"attributes":{"POSITION":0}}"#; 64].join(",");
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"accessors":[{{"componentType":5126,"count":16777216,"type":"VEC3"}}],
        "meshes":[{{"primitives":[{primitives}]}}]}}"#
    );
    let path = write(dir.path(), "implicit.gltf", json);
    let text = refused(&path);
    assert!(
        text.contains("vertices") && text.contains("--max-vertices"),
        "{text}"
    );
}

/// A GLB of one triangle; `length` is what its header claims.
fn glb(extra_buffers: usize, length_delta: i64, trailing: &[u8]) -> Vec<u8> {
    let buffers = std::iter::once(r#"{"byteLength":36}"#)
        .chain(std::iter::repeat_n(r#"{"byteLength":36}"#, extra_buffers))
        .collect::<Vec<_>>()
        .join(",");
    let mut json = format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{buffers}],"bufferViews":[{{"buffer":0,"byteLength":36}}],
        "accessors":[{POSITIONS}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}]}}"#
    )
    .into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let floats: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let mut body = Vec::new();
    body.extend((json.len() as u32).to_le_bytes());
    body.extend(b"JSON");
    body.extend(&json);
    body.extend(36u32.to_le_bytes());
    body.extend(b"BIN\0");
    body.extend(floats.iter().flat_map(|f| f.to_le_bytes()));
    let length = (12 + body.len()) as i64 + length_delta;
    let mut file = b"glTF".to_vec();
    file.extend(2u32.to_le_bytes());
    file.extend((length as u32).to_le_bytes());
    file.extend(body);
    file.extend(trailing);
    file
}

#[test]
fn glb_header_length_must_be_the_file_length() {
    let dir = tempfile::tempdir().expect("tempdir");
    let good = write(dir.path(), "good.glb", glb(0, 0, b""));
    assert!(bake(&good).is_ok(), "{:?}", bake(&good).err());
    let short = write(dir.path(), "short.glb", glb(0, 0, b"trailing bytes!!"));
    assert!(refused(&short).contains("GLB header says"));
    let tiny = write(dir.path(), "tiny.glb", glb(0, -100, b""));
    assert!(refused(&tiny).contains("GLB header says"));
}

#[test]
fn glb_only_buffer_0_may_be_the_binary_chunk() {
    let dir = tempfile::tempdir().expect("tempdir");
    // A thousand buffers without a uri must not each become a copy of the binary chunk.
    let path = write(dir.path(), "copies.glb", glb(1000, 0, b""));
    assert!(refused(&path).contains("only buffer 0"));
}

fn ply_triangle(extra_header: &str) -> Vec<u8> {
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n{extra_header}end_header\n"
    )
    .into_bytes();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        bytes.extend(v.to_le_bytes());
    }
    bytes.push(3);
    for i in [0i32, 1, 2] {
        bytes.extend(i.to_le_bytes());
    }
    bytes
}

#[test]
fn ply_element_without_properties_and_a_huge_count_is_nothing_to_read() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write(
        dir.path(),
        "empty-element.ply",
        ply_triangle("element nothing 18446744073709551615\n"),
    );
    let baked = bake(&path).expect("the empty element holds no data: the triangle bakes");
    assert_eq!(baked.asset.triangle_count(), 1);
}

#[test]
fn ply_vertex_element_without_coordinates_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write(
        dir.path(),
        "no-coordinates.ply",
        "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\nend_header\n",
    );
    assert!(refused(&path).contains("no x, y, z"));
}

#[test]
fn ply_counts_larger_than_the_file_are_refused_before_reading() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write(
        dir.path(),
        "many-faces.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 4294967296\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    );
    assert!(refused(&path).contains("claims 4294967296 elements"));
}

#[test]
fn ply_gz_that_inflates_past_the_input_limit_is_refused_while_inflating() {
    use std::io::Write;
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("bomb.ply.gz");
    let mut gz = flate2::write::GzEncoder::new(
        std::fs::File::create(&path).expect("create"),
        flate2::Compression::best(),
    );
    gz.write_all(&ply_triangle("")).expect("write");
    gz.write_all(&vec![0u8; 64 << 20]).expect("write"); // 64 MiB of zeros, ~64 KB on disk
    gz.finish().expect("finish");
    let limits = chamfer_preprocess::Limits::DEFAULT.with_max_input_bytes(16 << 20);
    let options = BakeOptions::DEFAULT.with_limits(limits);
    let text = bake_file(&path, &options).expect_err("bomb").to_string();
    assert!(
        text.contains("bomb.ply.gz") && text.contains("--max-input-bytes"),
        "{text}"
    );
    // Within the default limit the same file is read.
    assert!(
        !bake(&path)
            .err()
            .is_some_and(|e| e.to_string().contains("--max-input-bytes"))
    );
}

#[test]
fn obj_material_libraries_outside_the_folder_are_refused() {
    let outer = tempfile::tempdir().expect("tempdir");
    let dir = outer.path().join("model");
    std::fs::create_dir(&dir).expect("mkdir");
    write(outer.path(), "secret.mtl", "newmtl secret\nKd 1 0 0\n");
    for (name, mtllib) in [
        ("absolute.obj", "/etc/passwd"),
        ("parent.obj", "../secret.mtl"),
        ("zero.obj", "/dev/zero"),
    ] {
        let path = write(&dir, name, format!("mtllib {mtllib}\n{CUBE_OBJ}"));
        let text = refused(&path);
        assert!(
            text.contains("outside the file's folder") && text.contains("line 1"),
            "{text}"
        );
    }
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(outer.path().join("secret.mtl"), dir.join("link.mtl"))
            .expect("symlink");
        let path = write(&dir, "link.obj", format!("mtllib link.mtl\n{CUBE_OBJ}"));
        assert!(refused(&path).contains("outside the file's folder"));
    }
    // Beside the file is fine, and a missing one is only a warning.
    write(&dir, "ok.mtl", "newmtl red\nKd 1 0 0\n");
    let path = write(
        &dir,
        "ok.obj",
        format!("mtllib ok.mtl\nmtllib gone.mtl\n{CUBE_OBJ}"),
    );
    let baked = bake(&path).expect("bakes");
    assert!(
        baked.warnings.iter().any(|w| w.contains("gone.mtl")),
        "{:?}",
        baked.warnings
    );
}

#[cfg(unix)]
#[test]
fn a_fifo_named_by_an_input_or_as_one_is_refused_without_blocking() {
    let dir = tempfile::tempdir().expect("tempdir");
    mkfifo(&dir.path().join("pipe.mtl"));
    mkfifo(&dir.path().join("pipe.bin"));
    mkfifo(&dir.path().join("pipe.obj"));
    let obj = write(
        dir.path(),
        "fifo-mtl.obj",
        format!("mtllib pipe.mtl\n{CUBE_OBJ}"),
    );
    assert!(refused(&obj).contains("FIFO"));
    let json = gltf("pipe.bin", POSITIONS, "");
    let gltf = write(dir.path(), "fifo-buffer.gltf", json);
    assert!(refused(&gltf).contains("FIFO"));
    assert!(refused(&dir.path().join("pipe.obj")).contains("FIFO"));
}

#[cfg(unix)]
#[test]
fn gltf_buffer_links_that_leave_the_folder_are_refused() {
    let outer = tempfile::tempdir().expect("tempdir");
    let dir = outer.path().join("scene");
    std::fs::create_dir(&dir).expect("mkdir");
    std::os::unix::fs::symlink("/etc/passwd", dir.join("passwd.bin")).expect("symlink");
    let path = write(&dir, "link.gltf", gltf("passwd.bin", POSITIONS, ""));
    assert!(refused(&path).contains("outside the file's folder"));
    // A link that stays inside is followed.
    let floats: Vec<u8> = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    write(&dir, "real.bin", floats);
    std::os::unix::fs::symlink("real.bin", dir.join("alias.bin")).expect("symlink");
    let path = write(&dir, "alias.gltf", gltf("alias.bin", POSITIONS, ""));
    assert!(bake(&path).is_ok());
}

#[test]
fn obj_byte_order_mark_does_not_swallow_the_first_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write(dir.path(), "bom.obj", format!("\u{feff}{CUBE_OBJ}"));
    let baked = bake(&path).expect("a BOM is not part of the first vertex");
    assert_eq!(baked.asset.triangle_count(), 1);
}

#[test]
fn obj_errors_name_the_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write(
        dir.path(),
        "bad-face.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n# c\nf 1 2 x\n",
    );
    assert!(refused(&path).contains("line 5"), "{}", refused(&path));
    let path = write(
        dir.path(),
        "out-of-range.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3\nf 1 2 9\n",
    );
    let text = refused(&path);
    assert!(
        text.contains("line 6") && text.contains("f 1 2 9"),
        "{text}"
    );
}

/// `spokes` separate triangles around vertex 1: every spoke is a boundary edge, so vertex 1 has
/// `2 * spokes` kept edge ends.
fn star_obj(spokes: u32) -> String {
    let mut text = String::from("v 0 0 0\n");
    for i in 0..spokes {
        let a = std::f32::consts::TAU * i as f32 / spokes as f32;
        let b = a + 0.5 * std::f32::consts::TAU / spokes as f32;
        text += &format!(
            "v {} {} 0\nv {} {} 0.1\n",
            a.cos(),
            a.sin(),
            b.cos(),
            b.sin()
        );
    }
    for i in 0..spokes {
        text += &format!("f 1 {} {}\n", 2 + 2 * i, 3 + 2 * i);
    }
    text
}

#[test]
fn bake_refuses_a_vertex_with_more_ends_than_the_join_walk_follows() {
    let at_bound = star_obj(MAX_RING / 2);
    let baked = bake_bytes(
        "star.obj".as_ref(),
        at_bound.as_bytes(),
        &BakeOptions::DEFAULT,
    )
    .expect("4096 ends bake");
    Asset::decode(&baked.asset.encode_to_vec()).expect("and decode");
    let over = star_obj(MAX_RING / 2 + 1);
    let text = bake_bytes("star.obj".as_ref(), over.as_bytes(), &BakeOptions::DEFAULT)
        .expect_err("4098 ends")
        .to_string();
    assert!(
        text.contains("star.obj") && text.contains("welded vertex 0"),
        "{text}"
    );
}

#[test]
fn bake_dir_reads_nothing_outside_its_folder_and_refuses_clashes_before_writing() {
    let outer = tempfile::tempdir().expect("tempdir");
    let assets = outer.path().join("assets");
    let out = outer.path().join("out");
    std::fs::create_dir(&assets).expect("mkdir");
    std::fs::create_dir(&out).expect("mkdir");
    write(&assets, "part.obj", CUBE_OBJ);
    let bake_all = || bake_dir_into(&assets, &out, &BakeOptions::DEFAULT, &mut |_| ());
    assert_eq!(bake_all().expect("bakes").len(), 1);

    // Two inputs, one output: refused before anything is written.
    std::fs::remove_file(out.join("part.chamfer")).expect("rm");
    write(&assets, "part.ply", ply_triangle(""));
    let error = bake_all().expect_err("clash").to_string();
    assert!(
        error.contains("part.obj") && error.contains("part.ply"),
        "{error}"
    );
    assert!(
        !out.join("part.chamfer").exists(),
        "written before the clash was found"
    );
    std::fs::remove_file(assets.join("part.ply")).expect("rm");

    #[cfg(unix)]
    {
        // A mesh link leaving the folder, then a folder link leaving it.
        write(outer.path(), "elsewhere.obj", CUBE_OBJ);
        let link = assets.join("link.obj");
        std::os::unix::fs::symlink(outer.path().join("elsewhere.obj"), &link).expect("symlink");
        assert!(
            bake_all()
                .expect_err("outside")
                .to_string()
                .contains("resolves outside")
        );
        std::fs::remove_file(&link).expect("rm");
        std::os::unix::fs::symlink(outer.path(), assets.join("up")).expect("symlink");
        assert!(
            bake_all()
                .expect_err("outside")
                .to_string()
                .contains("resolves outside")
        );
        std::fs::remove_file(assets.join("up")).expect("rm");
        // A link loop inside the folder ends.
        std::os::unix::fs::symlink(".", assets.join("loop")).expect("symlink");
        assert_eq!(bake_all().expect("bakes").len(), 1);
        // A FIFO named like a mesh is refused, not opened.
        mkfifo(&assets.join("pipe.obj"));
        let error = within(30, bake_all_owned(&assets, &out)).expect_err("fifo");
        assert!(error.to_string().contains("FIFO"), "{error}");
        // Special files that are not meshes are never opened to key the cache.
        std::fs::remove_file(assets.join("pipe.obj")).expect("rm");
        mkfifo(&assets.join("notes.txt"));
        assert!(within(30, bake_all_owned(&assets, &out)).is_ok());
    }
}

fn bake_all_owned(
    assets: &Path,
    out: &Path,
) -> impl FnOnce() -> Result<Vec<chamfer_preprocess::build::BakedFile>, Error> + Send + 'static {
    let (assets, out) = (assets.to_owned(), out.to_owned());
    move || bake_dir_into(&assets, &out, &BakeOptions::DEFAULT, &mut |_| ())
}

/// Inputs the fuzz harness (`tests/fuzz.rs`) stopped on when run against the code before issue 16
/// was fixed: a memory abort (`mtllib /dev/zero`), a hang (a PLY element with no properties and
/// 2^64 - 1 elements) and a panic (a glTF `byteOffset` of `u64::MAX`). Each is now an error.
#[test]
fn fuzz_findings_on_the_unfixed_code_are_errors() {
    let hostile = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/hostile");
    for (name, expected) in [
        ("fuzz-obj-mtllib-dev-zero.obj", "outside the file's folder"),
        ("fuzz-ply-empty-element.ply", "no 'x' property"),
        ("fuzz-gltf-offset-overflow.gltf", "runs past the end"),
    ] {
        let text = refused(&hostile.join(name));
        assert!(text.contains(expected), "{name}: {text}");
    }
}
