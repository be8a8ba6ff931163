//! The stable-Rust fuzz harness CI runs: structured mutations of the real fixture files fed to
//! every loader and to the asset decoder, a fixed number of executions from a fixed seed (so a
//! run is reproducible and takes bounded time). Coverage-guided fuzzing with libFuzzer lives in
//! `fuzz/` (nightly); this harness needs nothing but `cargo test`.
//!
//! What must hold for every mutated input: no panic; a mesh that loads either bakes or is refused
//! with an error; every asset the bake produces decodes; every asset that decodes re-encodes to an
//! asset that decodes. `annotate`, `draw` and `render` read the same mutated meshes through their
//! own entry points: an annotated file must read back with the input's triangles, a drawing must
//! not panic. Every target must accept at least [`MIN_ACCEPTED`] of its inputs (a mutator that
//! breaks everything tests nothing), and the `chamfer` commands' peak memory on inputs that
//! declare huge counts is bounded against the same commands on a small file
//! ([`declared_counts_stay_within_a_memory_bound`]). A finding prints the seed file, the execution
//! number and where the input was saved; freeze it as a named test in `tests/hostile.rs`.
//!
//! `CHAMFER_FUZZ_EXECUTIONS` (per in-memory target, the file targets run an eighth; default
//! [`DEFAULT_EXECUTIONS`]) and `CHAMFER_FUZZ_SEED` change the run; `cargo test --release --test fuzz -- --nocapture` prints executions per second.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::Instant;

use chamfer_preprocess::annotate::{GltfEdges, annotate_with};
use chamfer_preprocess::compact::Meshopt;
use chamfer_preprocess::draw::paper::PaperOptions;
use chamfer_preprocess::draw::style::DrawingStyle;
use chamfer_preprocess::draw::{Camera, DrawOptions, dxf, hidden_lines, pdf, svg};
use chamfer_preprocess::{
    BakeOptions, Companions, Limits, bake, bake_bytes, bake_with_companions, input, load,
};
use chamfer_runtime::asset::{Asset, CompactOptions, SectionKind};
use chamfer_tests::fixture;
use glam::camera::rh::{proj::directx, view::look_at_mat4};
use serde_json::Value;

/// Executions per in-memory target in CI: five of them, 0.1 to 5 s each in release on two cores,
/// and three file targets (annotate, draw, render) at an eighth of it (BENCHMARKS.md). At this count the harness finds the hostile classes of issue 16 in the code
/// before it was fixed (the OBJ, PLY and glTF targets each stop with a finding).
const DEFAULT_EXECUTIONS: u64 = 40_000;

/// Small limits: a mutation that asks for a lot is refused quickly instead of baked slowly.
fn limits() -> Limits {
    Limits::DEFAULT
        .with_max_input_bytes(1 << 24)
        .with_max_vertices(1 << 18)
        .with_max_triangles(1 << 18)
        .with_max_instances(1 << 12)
}

fn executions() -> u64 {
    std::env::var("CHAMFER_FUZZ_EXECUTIONS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_EXECUTIONS)
}

/// xorshift64*: deterministic, no dependency.
struct Rng(u64);

impl Rng {
    fn new(salt: u64) -> Self {
        let seed = std::env::var("CHAMFER_FUZZ_SEED")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(0x5eed_c4a3_f3e0_0016u64);
        Self((seed ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15)) | 1)
    }
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

const NUMBERS: &[&str] = &[
    "0",
    "-1",
    "1",
    "2",
    "3",
    "-3",
    "255",
    "256",
    "65535",
    "65536",
    "4096",
    "4097",
    "16777216",
    "2147483647",
    "-2147483648",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "18446744073709551615",
    "18446744073709551612",
    "1e39",
    "-1e39",
    "1e-45",
    "nan",
    "inf",
    "0.5",
    "-0",
];
const WORDS: &[u32] = &[
    0,
    1,
    2,
    3,
    0x7f,
    0x80,
    0xff,
    0x100,
    0xffff,
    0x1_0000,
    4096,
    4097,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_fffe,
    0xffff_ffff,
];

/// Byte-level damage: bit flips, interesting values, insertions, deletions, duplication, truncation.
fn mutate_bytes(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let len = bytes.len();
    match rng.below(7) {
        0 if len > 0 => {
            let at = rng.below(len);
            bytes[at] ^= 1 << rng.below(8);
        }
        1 if len > 0 => {
            let at = rng.below(len);
            bytes[at] = *rng.pick(&[0, 1, 0x7f, 0x80, 0xff, b'\n', b' ', b'-']);
        }
        2 if len >= 4 => {
            let at = rng.below(len - 3);
            let word = rng.pick(WORDS).to_le_bytes();
            bytes[at..at + 4].copy_from_slice(&word);
        }
        3 => {
            let at = rng.below(len + 1);
            let count = 1 + rng.below(16);
            let noise: Vec<u8> = (0..count).map(|_| rng.next() as u8).collect();
            bytes.splice(at..at, noise);
        }
        4 if len > 0 => {
            let at = rng.below(len);
            let end = (at + 1 + rng.below(64)).min(len);
            bytes.drain(at..end);
        }
        5 if len > 0 => {
            let at = rng.below(len);
            let end = (at + 1 + rng.below(256)).min(len);
            let copy = bytes[at..end].to_vec();
            let to = rng.below(len + 1);
            bytes.splice(to..to, copy);
        }
        _ => bytes.truncate(rng.below(len + 1)),
    }
}

/// Spans of number tokens (runs of digits, signs, dots and exponents holding a digit).
fn number_spans(text: &[u8]) -> Vec<(usize, usize)> {
    let is_part = |b: u8| b.is_ascii_digit() || matches!(b, b'-' | b'+' | b'.' | b'e' | b'E');
    let mut spans = Vec::new();
    let mut i = 0;
    while i < text.len() {
        if is_part(text[i]) && (i == 0 || !text[i - 1].is_ascii_alphanumeric()) {
            let start = i;
            while i < text.len() && is_part(text[i]) {
                i += 1;
            }
            if text[start..i].iter().any(u8::is_ascii_digit) {
                spans.push((start, i));
            }
        } else {
            i += 1;
        }
    }
    spans
}

/// Line- and token-level damage for text formats, with lines the format knows.
fn mutate_text(text: &mut Vec<u8>, rng: &mut Rng, dictionary: &[&str]) {
    let mut lines: Vec<Vec<u8>> = text.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    match rng.below(6) {
        0 | 1 => {
            let spans = number_spans(text);
            if let Some(&(start, end)) = (!spans.is_empty()).then(|| rng.pick(&spans)) {
                let number = if rng.below(3) == 0 {
                    (rng.next() % 100_000).to_string()
                } else {
                    rng.pick(NUMBERS).to_string()
                };
                text.splice(start..end, number.into_bytes());
            }
            return;
        }
        2 if !lines.is_empty() => {
            let at = rng.below(lines.len());
            let line = lines[at].clone();
            lines.insert(rng.below(lines.len() + 1), line);
        }
        3 if !lines.is_empty() => {
            lines.remove(rng.below(lines.len()));
        }
        4 if lines.len() > 1 => {
            let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
            lines.swap(a, b);
        }
        _ => {
            let line = rng.pick(dictionary).as_bytes().to_vec();
            lines.insert(rng.below(lines.len() + 1), line);
        }
    }
    *text = lines.join(&b'\n');
}

const OBJ_LINES: &[&str] = &[
    "mtllib ../secret.mtl",
    "mtllib /dev/zero",
    "mtllib materials.mtl",
    "usemtl red",
    "usemtl blue",
    "o part",
    "g group",
    "f 1 2 3",
    "f -1 -2 -3",
    "f 1/1/1 2/2/2 3/3/3",
    "f 1//1 2//1 3//1",
    "f 1 2 3 4 5 6 7 8",
    "f 1 1 1",
    "f 0 1 2",
    "v 1e30 0 0",
    "v 0 0 0 1 0 0",
    "vt 0 0",
    "vn 0 0 1",
    "l 1 2",
    "p 1",
    "s 1",
    "\u{feff}v 0 0 0",
];

const PLY_HEADER_LINES: &[&str] = &[
    "element junk 18446744073709551615",
    "element edge 3",
    "property int vertex1",
    "property int vertex2",
    "property float radius",
    "property float nx",
    "property list uint int vertex_indices",
    "property list uchar uint vertex_index",
    "property double z",
    "comment fuzz",
    "format binary_big_endian 1.0",
];

const STL_LINES: &[&str] = &[
    "solid part",
    "endsolid part",
    "facet normal 0 0 1",
    "facet normal nan 0 0",
    "outer loop",
    "vertex 0 0 0",
    "vertex 1e39 0 0",
    "vertex 1 2",
    "endloop",
    "endfacet",
    "solid",
];

/// Mutates an STL: an ASCII one by lines and numbers, a binary one in its count (often to what the
/// file's size allows, give or take one) or its records.
fn mutate_stl(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let binary = bytes.len() >= 84
        && (bytes.len() - 84).is_multiple_of(50)
        && u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize
            == (bytes.len() - 84) / 50;
    if !binary {
        return if rng.below(4) == 0 {
            mutate_bytes(bytes, rng)
        } else {
            mutate_text(bytes, rng, STL_LINES)
        };
    }
    match rng.below(4) {
        0 => {
            let fits = ((bytes.len() - 84) / 50) as u32;
            let count = match rng.below(3) {
                0 => *rng.pick(WORDS),
                1 => fits.wrapping_add(1),
                _ => fits.wrapping_sub(1),
            };
            bytes[80..84].copy_from_slice(&count.to_le_bytes());
        }
        1 => {
            // A whole record added or dropped, the count kept: the size rule must catch it.
            if rng.below(2) == 0 {
                bytes.extend_from_within(84..134.min(bytes.len()));
            } else {
                bytes.truncate(bytes.len().saturating_sub(50).max(84));
            }
        }
        _ => mutate_bytes(bytes, rng),
    }
}

const THREEMF_LINES: &[&str] = &[
    r#"<object id="1"><mesh><vertices><vertex x="0" y="0" z="0"/></vertices></mesh></object>"#,
    r#"<object id="9"><components><component objectid="9"/></components></object>"#,
    r#"<object id="8" type="other"><components><component objectid="1" transform="-1 0 0 0 1 0 0 0 1 0 0 0"/></components></object>"#,
    r#"<component objectid="1" transform="0 1 0 -1 0 0 0 0 1 5 0 0"/>"#,
    r#"<item objectid="2" transform="2 0 0 0 2 0 0 0 2 1e30 0 0"/>"#,
    r#"<item objectid="1"/>"#,
    r#"<triangle v1="0" v2="1" v3="4294967295"/>"#,
    r#"<vertex x="1e39" y="nan" z="0"/>"#,
    "<!DOCTYPE model>",
    "</mesh>",
    "</object>",
    "<build>",
];

/// The parts of a zip package, or `None` if it does not open.
fn unzip(bytes: &[u8]) -> Option<Vec<(String, Vec<u8>)>> {
    use std::io::Read;
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).ok()?;
    (0..archive.len())
        .map(|i| {
            let mut entry = archive.by_index(i).ok()?;
            let mut data = Vec::new();
            entry.read_to_end(&mut data).ok()?;
            Some((entry.name().to_owned(), data))
        })
        .collect()
}

/// Mutates a 3MF: its model part as text (re-zipped, stored, so the package stays valid), or the
/// package's bytes.
fn mutate_threemf(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let Some(mut parts) = unzip(bytes).filter(|p| !p.is_empty() && rng.below(5) != 0) else {
        return mutate_bytes(bytes, rng);
    };
    let k = parts
        .iter()
        .position(|(name, _)| name.ends_with(".model") && rng.below(8) != 0)
        .unwrap_or_else(|| rng.below(parts.len()));
    mutate_text(&mut parts[k].1, rng, THREEMF_LINES);
    let parts: Vec<(&str, &[u8])> = parts.iter().map(|(n, d)| (n.as_str(), &d[..])).collect();
    if let Some(out) = chamfer_tests::files::try_zip(&parts, zip::CompressionMethod::Stored) {
        *bytes = out;
    }
}

/// Mutates a PLY: header lines and counts, or the body's bytes.
fn mutate_ply(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let marker = b"end_header\n";
    let split = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .map(|p| p + marker.len());
    match split {
        Some(at) if rng.below(2) == 0 => {
            let mut header = bytes[..at - marker.len()].to_vec();
            mutate_text(&mut header, rng, PLY_HEADER_LINES);
            let mut out = header;
            if !out.ends_with(b"\n") {
                out.push(b'\n');
            }
            out.extend_from_slice(&bytes[at - marker.len()..]);
            *bytes = out;
        }
        Some(at) => {
            let mut body = bytes[at..].to_vec();
            if bytes.starts_with(b"ply\nformat ascii") {
                mutate_text(&mut body, rng, &["3 0 1 2", "4 0 1 2 3", "0 0 0", "-1 2 3"]);
            } else {
                mutate_bytes(&mut body, rng);
            }
            bytes.truncate(at);
            bytes.extend(body);
        }
        None => mutate_bytes(bytes, rng),
    }
}

const JSON_KEYS: &[&str] = &[
    "byteOffset",
    "byteStride",
    "byteLength",
    "count",
    "bufferView",
    "buffer",
    "indices",
    "children",
    "mesh",
    "mode",
    "uri",
    "sparse",
    "componentType",
    "normalized",
    "matrix",
    "scale",
];
const JSON_STRINGS: &[&str] = &[
    "../secret.bin",
    "/etc/passwd",
    "/dev/zero",
    "two-materials.bin",
    "data:application/octet-stream;base64,AAAAAAAAAAAAAAAA",
    "data:application/octet-stream;base64,@@",
    "VEC3",
    "VEC2",
    "SCALAR",
    "MAT4",
    "KHR_draco_mesh_compression",
];

/// Every JSON pointer in `value`.
fn pointers(value: &Value, at: String, out: &mut Vec<String>) {
    match value {
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                pointers(item, format!("{at}/{i}"), out);
            }
        }
        Value::Object(map) => {
            for (key, item) in map {
                pointers(
                    item,
                    format!("{at}/{}", key.replace('~', "~0").replace('/', "~1")),
                    out,
                );
            }
        }
        _ => {}
    }
    out.push(at);
}

/// A structural change to a glTF document: numbers, strings, array elements and keys.
fn mutate_json(document: &mut Value, rng: &mut Rng) {
    let mut all = Vec::new();
    pointers(document, String::new(), &mut all);
    let target = rng.pick(&all).clone();
    let Some(slot) = document.pointer_mut(&target) else {
        return;
    };
    let number = |rng: &mut Rng| -> Value {
        let text = rng.pick(NUMBERS);
        serde_json::from_str(text).unwrap_or_else(|_| Value::from(rng.next() % 70_000))
    };
    match slot {
        Value::Number(_) | Value::Bool(_) | Value::Null => *slot = number(rng),
        Value::String(_) => *slot = Value::from(*rng.pick(JSON_STRINGS)),
        Value::Array(items) => match rng.below(4) {
            0 if !items.is_empty() => {
                let i = rng.below(items.len());
                let copy = items[i].clone();
                items.insert(i, copy);
            }
            1 if !items.is_empty() => {
                items.remove(rng.below(items.len()));
            }
            2 => items.push(number(rng)),
            _ => *slot = number(rng),
        },
        Value::Object(map) => match rng.below(3) {
            0 if !map.is_empty() => {
                let key = map
                    .keys()
                    .nth(rng.below(map.len()))
                    .cloned()
                    .unwrap_or_default();
                map.remove(&key);
            }
            _ => {
                let value = if rng.below(2) == 0 {
                    number(rng)
                } else {
                    Value::Array(vec![number(rng), number(rng)])
                };
                map.insert(rng.pick(JSON_KEYS).to_string(), value);
            }
        },
    }
}

fn mutate_gltf(bytes: &mut Vec<u8>, rng: &mut Rng) {
    match serde_json::from_slice::<Value>(bytes) {
        Ok(mut document) if rng.below(4) != 0 => {
            mutate_json(&mut document, rng);
            *bytes = serde_json::to_vec(&document).unwrap_or_default();
        }
        _ => mutate_text(bytes, rng, &["{", "}", "[]", "\"uri\": \"../x.bin\","]),
    }
}

/// Mutates a GLB's JSON chunk or binary chunk and rebuilds the container with true lengths, or
/// (a quarter of the time) damages the container itself.
fn mutate_glb(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let word = |b: &[u8], at: usize| {
        b.get(at..at + 4)
            .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]) as usize)
    };
    let chunks = (|| {
        let json_len = word(bytes, 12)?;
        let json = bytes.get(20..20 + json_len)?.to_vec();
        let bin_at = 20 + json_len;
        let bin = match word(bytes, bin_at) {
            Some(n) => bytes.get(bin_at + 8..bin_at + 8 + n)?.to_vec(),
            None => Vec::new(),
        };
        Some((json, bin))
    })();
    let Some((mut json, mut bin)) = chunks.filter(|_| rng.below(4) != 0) else {
        mutate_bytes(bytes, rng);
        return;
    };
    if rng.below(3) == 0 {
        mutate_bytes(&mut bin, rng);
    } else {
        mutate_gltf(&mut json, rng);
    }
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((28 + json.len() + bin.len()) as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    *bytes = out;
}

/// Damages an asset's bytes, often in its header and section table.
fn mutate_asset(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let header_end = bytes
        .get(12..16)
        .map_or(0, |w| {
            16 + u32::from_le_bytes([w[0], w[1], w[2], w[3]]) as usize
        })
        .min(bytes.len());
    if header_end > 24 && rng.below(2) == 0 {
        // A u64 of the header (lengths, counts, section offsets and lengths are all u64).
        let at = 16 + 8 * rng.below((header_end - 24) / 8);
        let value: u64 = match rng.below(4) {
            0 => u64::from(*rng.pick(WORDS)),
            1 => u64::MAX - rng.below(16) as u64,
            2 => rng.next() % (bytes.len() as u64 + 64),
            _ => 1 << rng.below(64),
        };
        bytes[at..at + 8].copy_from_slice(&value.to_le_bytes());
    } else {
        mutate_bytes(bytes, rng);
    }
}

/// A mesh file the harness starts from, copied (with its companions) into a scratch folder so
/// mutated references can only reach what is there.
struct Seed {
    name: String,
    bytes: Vec<u8>,
}

fn seeds(names: &[&str]) -> Vec<Seed> {
    names
        .iter()
        .map(|name| Seed {
            name: Path::new(name)
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            bytes: std::fs::read(fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}")),
        })
        .collect()
}

/// A scratch folder with the companion files the seeds refer to.
fn scratch() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::copy(
        fixture("shapes/two-materials.bin"),
        dir.path().join("two-materials.bin"),
    )
    .expect("copy");
    std::fs::write(
        dir.path().join("materials.mtl"),
        "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n",
    )
    .expect("write");
    dir
}

/// What one execution checks: loading never panics, a loaded mesh bakes or is refused, and every
/// baked asset decodes.
/// True if the input was accepted (loaded and baked).
fn load_and_bake(path: &Path, bytes: &[u8]) -> bool {
    let limits = limits();
    let Ok(loaded) = load::load_bytes(path, bytes, &limits) else {
        return false;
    };
    let options = BakeOptions::DEFAULT.with_limits(limits);
    let Ok(baked) = bake(loaded.mesh, "fuzz", &options) else {
        return false;
    };
    let encoded = baked.asset.encode_to_vec();
    if let Err(e) = Asset::decode(&encoded) {
        panic!("a baked asset does not decode: {e}");
    }
    // The compact file of every baked asset decodes too, to the same indices.
    let compact = baked
        .asset
        .encode_compact_to_vec(&CompactOptions::default(), &Meshopt)
        .expect("compact encoding into memory");
    match Asset::decode(&compact) {
        Ok(decoded) => assert!(
            decoded.edge_vertices == baked.asset.edge_vertices
                && decoded.mesh_indices == baked.asset.mesh_indices,
            "a compact asset decodes to other indices"
        ),
        Err(e) => panic!("a baked asset's compact file does not decode: {e}"),
    }
    true
}

/// Every decoded asset re-encodes to one that decodes to the same asset. True if it decoded.
fn decode_round_trip(_: &Path, bytes: &[u8]) -> bool {
    let decoded = Asset::decode(bytes);
    let accepted = decoded.is_ok();
    if let Ok(mut asset) = decoded {
        let mut again = Asset::decode(&asset.encode_to_vec()).expect("a re-encoded asset decodes");
        // The section table is the file's layout (padding may differ); the content must not.
        asset.header.sections.clear();
        again.header.sections.clear();
        assert_eq!(again, asset, "re-encoding changed the asset");
    }
    accepted
}

/// The input being checked, for the watchdog to save if it never returns.
type Current = std::sync::Mutex<(u64, String, Vec<u8>)>;

/// Runs `executions()` mutated inputs through `check`, reports speed, and on a panic (or an
/// execution still running after [`WATCHDOG_SECONDS`]) saves the input and names it.
fn run(
    target: &'static str,
    salt: u64,
    seeds: Vec<Seed>,
    mutate: fn(&mut Vec<u8>, &mut Rng),
    check: fn(&Path, &[u8]) -> bool,
) {
    run_n(target, salt, seeds, mutate, check, executions());
}

/// [`run`] for `total` executions.
fn run_n(
    target: &'static str,
    salt: u64,
    seeds: Vec<Seed>,
    mutate: fn(&mut Vec<u8>, &mut Rng),
    check: fn(&Path, &[u8]) -> bool,
    total: u64,
) {
    let current: std::sync::Arc<Current> = Default::default();
    let (done, finished) = std::sync::mpsc::channel();
    let worker = {
        let current = current.clone();
        std::thread::spawn(move || {
            execute(target, salt, &seeds, mutate, check, &current, total);
            let _ = done.send(());
        })
    };
    match finished.recv_timeout(std::time::Duration::from_secs(WATCHDOG_SECONDS)) {
        Ok(()) => {}
        Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
            let _ = worker.join(); // the worker panicked: its message names the input
            panic!("fuzz {target}: a finding (see above)");
        }
        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
            let (execution, name, bytes) = current.lock().map(|c| c.clone()).unwrap_or_default();
            let saved = save(target, execution, &name, &bytes);
            panic!(
                "fuzz {target}: execution {execution} (seed file {name}) still running after {WATCHDOG_SECONDS} s; input saved to {}",
                saved.display()
            );
        }
    }
}

/// Far above any execution's time: only a hang reaches it.
const WATCHDOG_SECONDS: u64 = 300;

fn save(target: &str, execution: u64, name: &str, bytes: &[u8]) -> PathBuf {
    let saved = std::env::temp_dir().join(format!("chamfer-fuzz-{target}-{execution}-{name}"));
    let _ = std::fs::write(&saved, bytes);
    saved
}

fn execute(
    target: &str,
    salt: u64,
    seeds: &[Seed],
    mutate: fn(&mut Vec<u8>, &mut Rng),
    check: fn(&Path, &[u8]) -> bool,
    current: &Current,
    total: u64,
) {
    let dir = scratch();
    let mut rng = Rng::new(salt);
    let start = Instant::now();
    let mut accepted = 0u64;
    for execution in 0..total {
        let seed = &seeds[execution as usize % seeds.len()];
        let mut bytes = seed.bytes.clone();
        for _ in 0..1 + rng.below(4) {
            mutate(&mut bytes, &mut rng);
        }
        if let Ok(mut c) = current.lock() {
            *c = (execution, seed.name.clone(), bytes.clone());
        }
        let path = dir.path().join(&seed.name);
        let outcome = catch_unwind(AssertUnwindSafe(|| check(&path, &bytes)));
        accepted += u64::from(outcome.as_ref().is_ok_and(|&a| a));
        if outcome.is_err() {
            let saved = save(target, execution, &seed.name, &bytes);
            panic!(
                "fuzz {target}: execution {execution} (seed file {}) panicked; input saved to {}",
                seed.name,
                saved.display()
            );
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    eprintln!(
        "fuzz {target}: {total} executions ({accepted} accepted) in {seconds:.2} s = {:.0} executions/s, no findings",
        total as f64 / seconds
    );
    assert!(
        accepted as f64 >= MIN_ACCEPTED * total as f64,
        "fuzz {target}: only {accepted} of {total} inputs were accepted, fewer than {}%: the \
         mutations break the inputs before they reach the code under test",
        MIN_ACCEPTED * 100.0
    );
}

/// The least share of its mutated inputs each target must accept: the lowest, `ply`, accepts about
/// 5 % at the default seed (BENCHMARKS.md), a mutator that breaks everything 0 %.
const MIN_ACCEPTED: f64 = 0.02;

#[test]
fn fuzz_obj() {
    let seeds = seeds(&[
        "shapes/cube.obj",
        "shapes/cone-16.obj",
        "shapes/nonmanifold-fan.obj",
        "shapes/plane-4x4.obj",
        "broken/index-out-of-range.obj",
        "broken/all-degenerate.obj",
    ]);
    run(
        "obj",
        1,
        seeds,
        |b, r| {
            if r.below(4) == 0 {
                mutate_bytes(b, r)
            } else {
                mutate_text(b, r, OBJ_LINES)
            }
        },
        load_and_bake,
    );
}

#[test]
fn fuzz_ply() {
    let seeds = seeds(&[
        "shapes/cube-marked-ascii.ply",
        "shapes/cube-marked-le.ply",
        "shapes/cube-marked-be.ply",
        "broken/truncated.ply",
    ]);
    run("ply", 2, seeds, mutate_ply, load_and_bake);
}

#[test]
fn fuzz_gltf() {
    let seeds = seeds(&[
        "shapes/cube-edge-visibility.gltf",
        "shapes/cube-marked-extras.gltf",
        "shapes/cube-outline.gltf",
        "shapes/cube-quantized.gltf",
        "shapes/two-materials.gltf",
        "shapes/two-materials-external.gltf",
        "broken/bad-index.gltf",
    ]);
    run("gltf", 3, seeds, mutate_gltf, load_and_bake);
}

#[test]
fn fuzz_glb() {
    let seeds = seeds(&[
        "shapes/cube-marked-extras.glb",
        "shapes/two-materials.glb",
        "shapes/cylinder-skinned.glb",
        "shapes/cube-morph.glb",
        "broken/truncated.glb",
    ]);
    run("glb", 4, seeds, mutate_glb, load_and_bake);
}

#[test]
fn fuzz_stl() {
    let seeds = seeds(&[
        "shapes/step-binary.stl",
        "shapes/step-ascii.stl",
        "shapes/two-cubes-ascii.stl",
    ]);
    run("stl", 9, seeds, mutate_stl, load_and_bake);
}

#[test]
fn fuzz_threemf() {
    let seeds = seeds(&[
        "shapes/cube.3mf",
        "shapes/cube-inch.3mf",
        "shapes/step-components.3mf",
    ]);
    run("3mf", 10, seeds, mutate_threemf, load_and_bake);
}

#[test]
fn fuzz_asset_decode() {
    let seeds: Vec<Seed> = [
        "shapes/cube.obj",
        "shapes/cube-marked-le.ply",
        "shapes/two-materials.glb",
    ]
    .iter()
    .map(|name| {
        let options = BakeOptions::DEFAULT.with_radius(chamfer_preprocess::Radius::Relative(0.01));
        let path = fixture(name);
        let bytes = std::fs::read(&path).expect("read");
        let baked = bake_bytes(&path, &bytes, &options).expect("seed bakes");
        Seed {
            name: format!("{name}.chamfer").replace('/', "-"),
            bytes: baked.asset.encode_to_vec(),
        }
    })
    .collect();
    run("asset", 5, seeds, mutate_asset, decode_round_trip);
}

/// Damages an animated asset inside its motion sections (skin joints and weights, morph targets,
/// the rig), found through its own section table: byte-level damage to the whole file rarely
/// reaches them intact enough to test their checks.
fn mutate_motion(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let motion: Vec<(usize, usize)> = Asset::decode(bytes)
        .map(|a| {
            a.header
                .sections
                .iter()
                .filter(|s| s.kind >= SectionKind::SkinJoints as u32 && s.length >= 4)
                .map(|s| (s.offset as usize, s.length as usize))
                .collect()
        })
        .unwrap_or_default();
    if motion.is_empty() || rng.below(8) == 0 {
        return mutate_asset(bytes, rng);
    }
    let (start, length) = *rng.pick(&motion);
    let at = start + rng.below(length.saturating_sub(3).max(1));
    match rng.below(3) {
        0 => bytes[at] ^= 1 << rng.below(8),
        1 => bytes[at] = rng.next() as u8,
        _ => {
            let end = (at + 4).min(start + length);
            let word = rng.pick(WORDS).to_le_bytes();
            bytes[at..end].copy_from_slice(&word[..end - at]);
        }
    }
}

#[test]
fn fuzz_motion_decode() {
    let seeds: Vec<Seed> = ["shapes/cylinder-skinned.glb", "shapes/cube-morph.glb"]
        .iter()
        .map(|name| {
            let path = fixture(name);
            let bytes = std::fs::read(&path).expect("read");
            let baked = bake_bytes(&path, &bytes, &BakeOptions::DEFAULT).expect("seed bakes");
            assert!(!baked.asset.motion.is_empty(), "{name} moves");
            Seed {
                name: format!("{name}.chamfer").replace('/', "-"),
                bytes: baked.asset.encode_to_vec(),
            }
        })
        .collect();
    run("motion", 12, seeds, mutate_motion, decode_round_trip);
}

/// Damages a compact asset inside one of its coded sections (found through its own section table
/// while it still decodes): their counts, bit fields and codec streams, where byte-level damage
/// to the whole file mostly breaks the header first.
fn mutate_compact(bytes: &mut Vec<u8>, rng: &mut Rng) {
    let coded: Vec<(usize, usize)> = Asset::decode(bytes)
        .map(|a| {
            a.header
                .sections
                .iter()
                .filter(|s| s.kind >= SectionKind::MeshIndicesCoded as u32 && s.length >= 4)
                .map(|s| (s.offset as usize, s.length as usize))
                .collect()
        })
        .unwrap_or_default();
    if coded.is_empty() || rng.below(8) == 0 {
        return mutate_asset(bytes, rng);
    }
    let (start, length) = *rng.pick(&coded);
    match rng.below(4) {
        // The declared count or bit field at the section's start.
        0 => {
            let at = start + 4 * rng.below(2.min(length / 4));
            let word = rng.pick(WORDS).to_le_bytes();
            bytes[at..at + 4].copy_from_slice(&word);
        }
        1 => {
            let at = start + rng.below(length);
            bytes[at] ^= 1 << rng.below(8);
        }
        2 => {
            let at = start + rng.below(length);
            bytes[at] = rng.next() as u8;
        }
        _ => {
            let at = start + rng.below(length.saturating_sub(3).max(1));
            let end = (at + 4).min(start + length);
            let word = rng.pick(WORDS).to_le_bytes();
            bytes[at..end].copy_from_slice(&word[..end - at]);
        }
    }
}

#[test]
fn fuzz_compact_decode() {
    let seeds: Vec<Seed> = [
        "shapes/cube-marked-le.ply",
        "shapes/two-materials.glb",
        "meshes/suzanne.obj",
        "shapes/nonmanifold-fan.obj",
    ]
    .iter()
    .flat_map(|name| {
        let options = BakeOptions::DEFAULT.with_radius(chamfer_preprocess::Radius::Relative(0.01));
        let path = fixture(name);
        let bytes = std::fs::read(&path).expect("read");
        let asset = bake_bytes(&path, &bytes, &options)
            .expect("seed bakes")
            .asset;
        [CompactOptions::default(), CompactOptions::LOSSLESS].map(|compact| Seed {
            name: format!("{name}-{}.chamfer", compact.position_bits).replace('/', "-"),
            bytes: asset
                .encode_compact_to_vec(&compact, &Meshopt)
                .expect("encodes"),
        })
    })
    .collect();
    run("compact", 11, seeds, mutate_compact, decode_round_trip);
}

/// Mutates a mesh of any format, told apart by its first bytes as its own target would be.
fn mutate_any(bytes: &mut Vec<u8>, rng: &mut Rng) {
    if bytes.starts_with(b"ply") {
        mutate_ply(bytes, rng)
    } else if bytes.starts_with(b"glTF") {
        mutate_glb(bytes, rng)
    } else if bytes.starts_with(b"{") {
        mutate_gltf(bytes, rng)
    } else if bytes.starts_with(b"solid") {
        mutate_stl(bytes, rng)
    } else if bytes.starts_with(b"PK") {
        mutate_threemf(bytes, rng)
    } else if rng.below(4) == 0 {
        mutate_bytes(bytes, rng)
    } else {
        mutate_text(bytes, rng, OBJ_LINES)
    }
}

/// The seeds of the loader targets, all formats: what `annotate`, `draw` and `render` read.
fn mesh_seeds() -> Vec<Seed> {
    seeds(&[
        "shapes/cube.obj",
        "shapes/cone-16.obj",
        "shapes/nonmanifold-fan.obj",
        "shapes/cube-marked-ascii.ply",
        "shapes/cube-marked-le.ply",
        "shapes/cube-marked-be.ply",
        "shapes/cube-edge-visibility.gltf",
        "shapes/cube-marked-extras.gltf",
        "shapes/two-materials-external.gltf",
        "shapes/cube-marked-extras.glb",
        "shapes/two-materials.glb",
        "shapes/pyramid-fans-mirrored.glb",
        "shapes/step-binary.stl",
        "shapes/two-cubes-ascii.stl",
        "shapes/step-components.3mf",
    ])
}

/// Executions of the targets that read files, as the commands do: an eighth of the in-memory
/// targets' (each execution writes its input to disk: ~0.3 ms on ext4 here, 3.5 ms when a file is
/// replaced in place, so every file is removed first).
fn file_executions() -> u64 {
    executions().div_ceil(8)
}

/// Writes `bytes` to `path` as a new file.
fn put(path: &Path, bytes: &[u8]) -> bool {
    let _ = std::fs::remove_file(path);
    std::fs::write(path, bytes).is_ok()
}

/// Annotates the mutated file (an OBJ into a GLB) into a sub-folder with every glTF dialect; what
/// is written must read back with the input's triangles.
fn annotate_and_read_back(path: &Path, bytes: &[u8]) -> bool {
    let limits = limits();
    let Some(folder) = path.parent() else {
        return false;
    };
    if !put(path, bytes) {
        return false;
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy())
        .unwrap_or_default();
    let name = name
        .strip_suffix(".obj")
        .map_or(name.to_string(), |stem| format!("{stem}.glb"));
    let output = folder.join("annotated").join(name);
    let _ = std::fs::create_dir_all(folder.join("annotated"));
    let _ = std::fs::remove_file(&output);
    let options = BakeOptions::DEFAULT.with_limits(limits);
    let dialects = GltfEdges::DEFAULT
        .with_edge_visibility(true)
        .with_primitive_outline(true);
    if annotate_with(path, &output, &options, &dialects).is_err() {
        return false;
    }
    let input = load::load_bytes(path, bytes, &limits)
        .unwrap_or_else(|e| panic!("annotated, but the input does not load: {e}"));
    let written = load::load(&output, &limits)
        .unwrap_or_else(|e| panic!("an annotated file does not read back: {e}"));
    assert_eq!(
        written.mesh.triangles.len(),
        input.mesh.triangles.len(),
        "the annotated file has other triangles"
    );
    true
}

/// What `chamfer draw` does with the mutated file: read it as `draw` reads (baked with
/// intersections) and draw its hidden lines from a camera framing it.
fn read_and_draw(path: &Path, bytes: &[u8]) -> bool {
    if !put(path, bytes) {
        return false;
    }
    let options = BakeOptions::DEFAULT
        .with_limits(limits())
        .with_intersections(true);
    let Ok(read) = input::read_asset(path, &options) else {
        return false;
    };
    let [lo, hi] =
        [read.asset.header.bounds_min, read.asset.header.bounds_max].map(glam::Vec3::from);
    let (center, radius) = ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1e-3));
    let eye = center + glam::Vec3::new(0.6, 0.5, 0.7).normalize() * radius * 3.0;
    let view = Camera {
        model_view: look_at_mat4(eye, center, glam::Vec3::Y),
        projection: directx::perspective(0.6, 4.0 / 3.0, radius * 0.5, radius * 6.0),
        viewport: [256, 192],
    };
    hidden_lines(&read.asset, &view, &DrawOptions::DEFAULT.with_hidden(true));
    // A section drawing through the middle (issue 43), written in every format.
    let plane = chamfer_runtime::section::Plane {
        normal: glam::DVec3::new(0.8, 0.5, 0.33).normalize().to_array(),
        offset: glam::DVec3::new(0.8, 0.5, 0.33)
            .normalize()
            .dot(center.as_dvec3()),
    };
    let options = DrawOptions::DEFAULT
        .with_hidden(true)
        .with_section(Some(plane));
    let drawing = hidden_lines(&read.asset, &view, &options);
    write_every_format(&drawing, &DrawingStyle::default());
    true
}

/// The drawing as SVG, PDF and DXF, into memory (which cannot fail).
fn write_every_format(drawing: &chamfer_preprocess::draw::Drawing, style: &DrawingStyle) {
    let paper = PaperOptions::DEFAULT;
    let mut out = Vec::new();
    svg::write_svg(drawing, style, &paper, &mut out).expect("svg into memory");
    pdf::write_pdf(drawing, style, &paper, &mut out).expect("pdf into memory");
    dxf::write_dxf(drawing, style, &paper, &mut out).expect("dxf into memory");
}

/// What `chamfer draw --style FILE` does with a mutated style file: parse it, check it, and write
/// a small section drawing with it in every format. True if the style was accepted.
fn style_file(_: &Path, bytes: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return false;
    };
    let Ok(style) = serde_json::from_str::<DrawingStyle>(text) else {
        return false;
    };
    if style.check().is_err() {
        return false;
    }
    let drawing = style_drawing();
    write_every_format(drawing, &style);
    true
}

/// A section drawing of the unit cube with a line of every role but intersections, drawn once.
fn style_drawing() -> &'static chamfer_preprocess::draw::Drawing {
    static DRAWING: std::sync::OnceLock<chamfer_preprocess::draw::Drawing> =
        std::sync::OnceLock::new();
    DRAWING.get_or_init(|| {
        let read = input::read_asset(&fixture("shapes/cube.obj"), &BakeOptions::DEFAULT)
            .expect("the cube");
        let view = Camera::orbit(
            [read.asset.header.bounds_min, read.asset.header.bounds_max],
            &chamfer_runtime::camera::Orbit::default(),
            [128, 96],
        );
        let plane = chamfer_runtime::section::Plane {
            normal: [1.0, 0.0, 0.0],
            offset: 0.5,
        };
        hidden_lines(
            &read.asset,
            &view,
            &DrawOptions::DEFAULT
                .with_hidden(true)
                .with_section(Some(plane)),
        )
    })
}

/// Style-file mutations: JSON values changed, keys and lines shuffled, and the style names.
fn mutate_style(bytes: &mut Vec<u8>, rng: &mut Rng) {
    if rng.below(2) == 0 {
        if let Ok(mut document) = serde_json::from_slice::<Value>(bytes) {
            mutate_json(&mut document, rng);
            *bytes = document.to_string().into_bytes();
            return;
        }
    }
    mutate_text(
        bytes,
        rng,
        &[
            "cut_weight",
            "hidden_dash",
            "hatch_color",
            "[]",
            "[1e38, -1]",
            "NaN",
            "1e400",
            "\"x\"",
        ],
    );
}

#[test]
fn fuzz_style_file() {
    let seeds = [
        r#"{"cut_weight": 0.7, "hidden_dash": [3, 0.75], "hatch_spacing": 2}"#,
        "{\n  \"cut_color\": [1, 0, 0],\n  \"hatch_angle\": 135,\n  \"visible_dash\": [1, 1, 2, 1]\n}",
        r#"{"silhouette_weight": 0.5, "boundary_dash": [], "hidden_color": [0.5, 0.5, 0.5]}"#,
    ]
    .iter()
    .enumerate()
    .map(|(i, text)| Seed {
        name: format!("style-{i}.json"),
        bytes: text.as_bytes().to_vec(),
    })
    .collect();
    run("style_file", 23, seeds, mutate_style, style_file);
}

/// What `chamfer render` reads before it draws: the mutated file as `render` reads it (baked
/// without intersections); the asset it hands the GPU must survive an encode and decode.
fn read_for_render(path: &Path, bytes: &[u8]) -> bool {
    if !put(path, bytes) {
        return false;
    }
    let options = BakeOptions::DEFAULT.with_limits(limits());
    let Ok(read) = input::read_asset(path, &options) else {
        return false;
    };
    if let Err(e) = Asset::decode(&read.asset.encode_to_vec()) {
        panic!("an asset render would draw does not decode: {e}");
    }
    true
}

#[test]
fn fuzz_annotate() {
    run_n(
        "annotate",
        6,
        mesh_seeds(),
        mutate_any,
        annotate_and_read_back,
        file_executions(),
    );
}

#[test]
fn fuzz_draw() {
    run_n(
        "draw",
        7,
        mesh_seeds(),
        mutate_any,
        read_and_draw,
        file_executions(),
    );
}

#[test]
fn fuzz_render() {
    run_n(
        "render",
        8,
        mesh_seeds(),
        mutate_any,
        read_for_render,
        file_executions(),
    );
}

/// The floor on accepted inputs catches a mutator that breaks every input.
#[test]
fn a_mutator_that_breaks_every_input_fails_the_harness() {
    let current = Current::default();
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        execute(
            "broken",
            9,
            &mesh_seeds(),
            |b, _| b.clear(),
            load_and_bake,
            &current,
            64,
        )
    }));
    let message = outcome.expect_err("nothing was accepted, yet the harness passed");
    let text = message
        .downcast_ref::<String>()
        .cloned()
        .unwrap_or_default();
    assert!(text.contains("only 0 of 64 inputs were accepted"), "{text}");
}

/// Files whose headers or JSON declare counts that would take gigabytes, in a few hundred bytes
/// (issue 23): each `chamfer` command must refuse or read them within [`MEMORY_MARGIN`] of its
/// own peak on a small good file, measured in the same run. Before issue 23, `annotate` of the
/// PLYs tried to allocate 4.5 GB and every command inflated the `.ply.gz` in full.
#[cfg(unix)]
#[test]
fn declared_counts_stay_within_a_memory_bound() {
    let dir = tempfile::tempdir().expect("tempdir");
    let put = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).expect("write");
        path
    };
    let triangle = |extra: &str| {
        let mut bytes = format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n{extra}end_header\n"
        )
        .into_bytes();
        for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
            bytes.extend(v.to_le_bytes());
        }
        bytes.push(3);
        bytes.extend([0i32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
        bytes
    };
    let good = put("good.ply", &triangle(""));
    let gz_bomb = {
        let path = dir.path().join("vertices.ply.gz");
        let head = b"ply\nformat binary_little_endian 1.0\nelement vertex 170000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        chamfer_tests::files::gzip_bomb(&path, head, 256, 1);
        path
    };
    let stl_gz_bomb = {
        let path = dir.path().join("facets.stl.gz");
        let mut header = vec![b' '; 80];
        header.extend(170_000_000u32.to_le_bytes());
        chamfer_tests::files::gzip_bomb(&path, &header, 256, 1);
        path
    };
    let mut stl_count = vec![b' '; 80];
    stl_count.extend(u32::MAX.to_le_bytes());
    stl_count.extend([0u8; 50]);
    let implicit = format!(
        r#"{{"asset":{{"version":"2.0"}},"accessors":[{{"componentType":5126,"count":16777216,"type":"VEC3"}}],
        "meshes":[{{"primitives":[{}]}}]}}"#,
        vec![r#"{"attributes":{"POSITION":0}}"#; 64].join(",")
    );
    let instancing = r#"{"asset":{"version":"2.0"},"extensionsUsed":["EXT_mesh_gpu_instancing"],
        "accessors":[{"componentType":5126,"count":3,"type":"VEC3"},{"componentType":5126,"count":1000000000,"type":"VEC3"}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "nodes":[{"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1}}}}],
        "scenes":[{"nodes":[0]}]}"#;
    let cases = [
        put("junk-u32.ply", &triangle("element junk 4294967295\n")),
        put(
            "junk-u64.ply",
            &triangle("element junk 18446744073709551615\n"),
        ),
        gz_bomb,
        stl_gz_bomb,
        put("count.stl", &stl_count),
        put("implicit.gltf", implicit.as_bytes()),
        put("instancing.gltf", instancing.as_bytes()),
    ];
    let commands: [(&str, &str, &[&str]); 4] = [
        ("bake", "chamfer", &[]),
        ("annotate", "same", &[]),
        ("draw", "svg", &[]),
        ("render", "png", &["--width", "64", "--height", "48"]),
    ];
    for (command, extension, flags) in commands {
        let run = |input: &Path| {
            let name = input
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let extension = match extension {
                "same" => name.split_once('.').map_or("ply", |(_, e)| e).to_owned(),
                other => other.to_owned(),
            };
            let output = dir.path().join(format!("out-{command}-{name}.{extension}"));
            peak_of(
                std::process::Command::new(env!("CARGO_BIN_EXE_chamfer"))
                    .arg(command)
                    .arg(input)
                    .arg("-o")
                    .arg(&output)
                    .args(flags),
            )
        };
        let (baseline, _) = run(&good);
        eprintln!("chamfer {command}: {} MiB on good.ply", baseline >> 20);
        for case in &cases {
            let start = Instant::now();
            let (peak, status) = run(case);
            eprintln!(
                "chamfer {command}: {} MiB, {:.2} s, exit {:?} on {}",
                peak >> 20,
                start.elapsed().as_secs_f64(),
                status.code(),
                case.file_name()
                    .map(|n| n.to_string_lossy())
                    .unwrap_or_default()
            );
            assert!(
                status.code().is_some(),
                "chamfer {command} {}: killed by a signal ({status:?})",
                case.display()
            );
            assert!(
                peak <= baseline + MEMORY_MARGIN,
                "chamfer {command} {}: peak RSS {} MiB, more than {} MiB over the {} MiB of a one-triangle file",
                case.display(),
                peak >> 20,
                MEMORY_MARGIN >> 20,
                baseline >> 20
            );
        }
    }
}

/// Compact assets whose coded sections declare more than they hold: `chamfer inspect` refuses
/// them within the same memory as it reads the good file in.
#[cfg(unix)]
#[test]
fn compact_declared_counts_stay_within_a_memory_bound() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = fixture("meshes/stanford-bunny.obj");
    let bytes = std::fs::read(&path).expect("read");
    let asset = bake_bytes(&path, &bytes, &BakeOptions::DEFAULT)
        .expect("bakes")
        .asset;
    let good = asset
        .encode_compact_to_vec(&CompactOptions::default(), &Meshopt)
        .expect("encodes");
    let sections = Asset::decode(&good).expect("decodes").header.sections;
    let start = |kind: SectionKind| {
        sections
            .iter()
            .find(|s| s.kind == kind as u32)
            .map(|s| s.offset as usize)
            .expect("listed")
    };
    let put = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).expect("write");
        path
    };
    let inspect = |path: &Path| {
        peak_of(
            std::process::Command::new(env!("CARGO_BIN_EXE_chamfer"))
                .arg("inspect")
                .arg(path),
        )
    };
    let (baseline, status) = inspect(&put("good.chamfer", &good));
    assert!(status.success());
    // Each count as large as the limit allows (three per triangle the index stream can hold), or
    // as large as a u32 goes.
    let limit = 3 * (start(SectionKind::MeshIndicesCoded) as u32);
    for (kind, value) in [
        (SectionKind::MeshIndicesCoded, u32::MAX),
        (SectionKind::TopologyPositionsCoded, limit),
        (SectionKind::RenderNormalsCoded, u32::MAX),
        (SectionKind::EdgeAttributesCoded, limit),
        (SectionKind::EdgeCorners, limit),
        (SectionKind::EdgeClustersCoded, u32::MAX),
    ] {
        let mut bad = good.clone();
        let at = start(kind);
        bad[at..at + 4].copy_from_slice(&value.to_le_bytes());
        let (peak, status) = inspect(&put(&format!("{}.chamfer", kind.name()), &bad));
        assert_eq!(status.code(), Some(1), "{}: {status:?}", kind.name());
        assert!(
            peak <= baseline + MEMORY_MARGIN,
            "{} declaring {value}: peak RSS {} MiB against {} MiB for the good file",
            kind.name(),
            peak >> 20,
            baseline >> 20
        );
    }
}

/// How far over the small file's peak a declared-count case may go: 64 MiB, against the
/// gigabytes the counts declare (the `.ply.gz` holds 256 MiB of zeros after its header).
#[cfg(unix)]
const MEMORY_MARGIN: u64 = 64 << 20;

/// Runs `command` to its end with its output discarded; returns its peak resident set (bytes,
/// from `wait4`) and exit status.
#[cfg(unix)]
fn peak_of(command: &mut std::process::Command) -> (u64, std::process::ExitStatus) {
    use std::os::unix::process::ExitStatusExt;
    let child = command
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("spawn chamfer");
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value of this plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: waits for our own child (std never reaps it: the `Child` is only dropped), with
    // pointers to live locals.
    let waited = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    assert_eq!(waited, pid, "wait4: {}", std::io::Error::last_os_error());
    drop(child);
    // Linux reports ru_maxrss in KiB.
    (
        u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024,
        std::process::ExitStatus::from_raw(status),
    )
}

#[test]
fn fuzz_environment() {
    let seeds = seeds(&["environments/sky.hdr", "broken/truncated.hdr"]);
    run("environment", 21, seeds, mutate_bytes, decode_environment);
}

/// A Radiance HDR environment decodes to finite, non-negative texels or is refused by name.
/// True if it decoded.
fn decode_environment(path: &Path, bytes: &[u8]) -> bool {
    match chamfer_preprocess::environment::environment_from_bytes(path, bytes) {
        Ok(environment) => {
            let [width, height] = environment.size();
            assert!(width >= 1 && height >= 1);
            assert!(
                u64::from(width) * u64::from(height) <= chamfer_preprocess::environment::MAX_TEXELS
            );
            true
        }
        Err(e) => {
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            assert!(name.is_some_and(|n| e.to_string().contains(&n)), "{e}");
            false
        }
    }
}

/// The web page's bake (issue 26): a dropped file with its companions in memory
/// ([`Companions::Memory`]), `.ply.gz` inflated in memory. Mutations reach the main file (a
/// `.gltf` whose buffer is given beside it, an OBJ whose material library is, a gzip-compressed
/// PLY mutated before compressing, or its compressed bytes).
#[test]
fn fuzz_dropped_files() {
    let mut seeds = seeds(&["shapes/two-materials-external.gltf"]);
    seeds.push(Seed {
        name: "materials.obj".into(),
        bytes: b"mtllib materials.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n\
                 usemtl red\nf 1 2 3\nf 1 3 4\nusemtl blue\nf 1 2 5\nf 2 3 5\n"
            .to_vec(),
    });
    let ply = std::fs::read(fixture("shapes/cube-marked-le.ply")).expect("ply");
    seeds.push(Seed {
        name: "cube.ply.gz".into(),
        bytes: gzip(&ply),
    });
    run(
        "dropped-files",
        22,
        seeds,
        |bytes, rng| match bytes.first() {
            Some(0x1f) if rng.below(4) != 0 => {
                let mut ply = inflate(bytes);
                mutate_ply(&mut ply, rng);
                *bytes = gzip(&ply);
            }
            Some(b'{') => mutate_gltf(bytes, rng),
            Some(b'm') => mutate_text(bytes, rng, OBJ_LINES),
            _ => mutate_bytes(bytes, rng),
        },
        bake_dropped,
    );
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    chamfer_tests::files::gzip(bytes, 1)
}

fn inflate(bytes: &[u8]) -> Vec<u8> {
    use std::io::Read;
    let mut out = Vec::new();
    let _ = flate2::read::GzDecoder::new(bytes).read_to_end(&mut out);
    out
}

/// Bakes `bytes` as the page does (its companions in memory, never from disk): a baked asset
/// decodes; a refusal names the file. True if it baked.
fn bake_dropped(path: &Path, bytes: &[u8]) -> bool {
    let companions = [
        (
            "two-materials.bin".to_owned(),
            std::fs::read(fixture("shapes/two-materials.bin")).expect("bin"),
        ),
        (
            "materials.mtl".to_owned(),
            b"newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n".to_vec(),
        ),
    ];
    let name = path.file_name().expect("a file name");
    let options = BakeOptions::DEFAULT.with_limits(limits());
    match bake_with_companions(
        Path::new(name),
        bytes,
        Companions::Memory(&companions),
        &options,
    ) {
        Ok(baked) => {
            if let Err(e) = Asset::decode(&baked.asset.encode_to_vec()) {
                panic!("a baked asset does not decode: {e}");
            }
            true
        }
        Err(e) => {
            let name = name.to_string_lossy();
            assert!(e.to_string().contains(&*name), "{e}");
            false
        }
    }
}
