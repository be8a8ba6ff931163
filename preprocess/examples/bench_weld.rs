//! Weld tolerance benchmark: what a tolerance relative to the model's size changes (welded vertices,
//! boundary and non-manifold edges, degenerate triangles, bake time) against the exact weld, on the
//! shared meshes and on CAD-like glTF exports whose duplicated vertices are a few ULPs apart.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_weld -- [--runs 3]
//! ```
//! The CAD-like files are written once under `target/bench/`: a mesh exported the way CAD
//! tessellators do (every triangle with its own three vertices, each copy of a position moved by
//! 0 to 4 ULPs per coordinate, deterministic), at the origin and 100 diagonals away from it (world
//! coordinates). Each tolerance is tried relative to the bounding box's diagonal and relative to the
//! coordinates' magnitude (the length of the largest absolute coordinate per axis), since f32
//! spacing grows with the magnitude, not with the extent.

use std::path::{Path, PathBuf};
use std::time::Instant;

use chamfer_preprocess::mesh::Mesh;
use chamfer_preprocess::{BakeOptions, Limits, WeldTolerance, bake, load};
use glam::Vec3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs = match args.as_slice() {
        [flag, n] if flag == "--runs" => n.parse()?,
        _ => 3,
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("fixtures/meshes"))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| load::format_of(p).is_some())
        .collect();
    files.sort();
    let bench = root.join("target/bench");
    std::fs::create_dir_all(&bench)?;
    for source in ["fandisk.obj", "cylinder.obj", "cube.obj"] {
        let mesh = load::load(&root.join("fixtures/meshes").join(source), &Limits::DEFAULT)?.mesh;
        let stem = source.trim_end_matches(".obj");
        for (suffix, offset) in [("", 0.0), ("-far", 100.0)] {
            let path = bench.join(format!("cad-{stem}{suffix}.glb"));
            std::fs::write(&path, cad_export(&mesh, offset))?;
            files.push(path);
        }
    }
    let tolerances: [(&str, f32, Reference); 7] = [
        ("exact", 0.0, Reference::Diagonal),
        ("1e-7 diag", 1e-7, Reference::Diagonal),
        ("1e-6 diag", 1e-6, Reference::Diagonal),
        ("1e-5 diag", 1e-5, Reference::Diagonal),
        ("1e-7 mag", 1e-7, Reference::Magnitude),
        ("1e-6 mag", 1e-6, Reference::Magnitude),
        ("1e-5 mag", 1e-5, Reference::Magnitude),
    ];
    println!(
        "threads: {}, runs per row: {runs} (medians; load excluded)\n",
        rayon::current_num_threads()
    );
    println!(
        "| mesh | triangles | tolerance | distance | welded vertices | boundary | non-manifold | degenerate | kept edges | weld ms | bake ms | bake / exact |"
    );
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for file in &files {
        let mesh = load::load(file, &Limits::DEFAULT)?.mesh;
        let name = file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mut exact_ms = 0.0;
        for (label, fraction, reference) in tolerances {
            // The magnitude rows go through the option the bake offers (the default's form).
            let tolerance = match reference {
                Reference::Diagonal => {
                    WeldTolerance::Absolute(fraction * reference.length(&mesh.positions))
                }
                Reference::Magnitude => WeldTolerance::Relative(fraction),
            };
            let distance = tolerance.distance(&mesh.positions);
            let options = BakeOptions::DEFAULT.with_weld(tolerance);
            let mut times = Vec::new();
            let mut weld_times = Vec::new();
            let mut stats = None;
            for _ in 0..runs {
                let start = Instant::now();
                let baked = bake(mesh.clone(), &name, &options)?;
                times.push(start.elapsed());
                weld_times.push(baked.timings.weld);
                stats = Some(baked.asset.header.stats);
            }
            times.sort();
            weld_times.sort();
            let ms = times[times.len() / 2].as_secs_f64() * 1e3;
            let weld_ms = weld_times[weld_times.len() / 2].as_secs_f64() * 1e3;
            if fraction == 0.0 {
                exact_ms = ms;
            }
            let s = stats.ok_or("no run")?;
            println!(
                "| {name} | {} | {label} | {distance:.2e} | {} | {} | {} | {} | {} | {weld_ms:.1} | {ms:.1} | {:.2} |",
                mesh.triangles.len(),
                s.welded_vertices,
                s.edges.boundary,
                s.edges.non_manifold,
                s.degenerate_triangles,
                s.edges.kept,
                ms / exact_ms.max(f64::MIN_POSITIVE),
            );
        }
    }
    Ok(())
}

#[derive(Clone, Copy)]
enum Reference {
    /// The bounding box's diagonal.
    Diagonal,
    /// The length of (max |x|, max |y|, max |z|).
    Magnitude,
}

impl Reference {
    fn length(self, positions: &[Vec3]) -> f32 {
        let (lo, hi) = positions
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        match self {
            Reference::Diagonal => (hi - lo).length(),
            Reference::Magnitude => lo.abs().max(hi.abs()).length(),
        }
    }
}

/// `mesh` as a CAD tessellator exports it: a GLB whose triangles each have their own three vertices,
/// every copy moved by 0 to 4 ULPs per coordinate, the whole moved `offset` diagonals along (1, 1, 1).
fn cad_export(mesh: &Mesh, offset: f32) -> Vec<u8> {
    let diagonal = Reference::Diagonal.length(&mesh.positions);
    let shift = Vec3::splat(offset * diagonal / 3f32.sqrt());
    let mut state = 0x2545_f491_u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    };
    let mut positions = Vec::with_capacity(9 * mesh.triangles.len());
    for t in &mesh.triangles {
        for &v in t {
            let p = (mesh.positions[v as usize] + shift).to_array();
            for c in p {
                let ulps = (next() % 5) as i32 * if next() % 2 == 0 { 1 } else { -1 };
                let moved = if c == 0.0 {
                    c
                } else {
                    f32::from_bits((c.to_bits() as i32 + ulps) as u32)
                };
                positions.push(moved);
            }
        }
    }
    let (lo, hi) = positions.chunks_exact(3).fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|k| lo[k].min(p[k])),
                std::array::from_fn(|k| hi[k].max(p[k])),
            )
        },
    );
    let buffer: Vec<u8> = positions.iter().flat_map(|f| f.to_le_bytes()).collect();
    let json = serde_json::json!({
        "asset": {"version": "2.0", "generator": "chamfer bench_weld"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 4}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": positions.len() / 3,
                       "type": "VEC3", "min": lo, "max": hi}],
        "bufferViews": [{"buffer": 0, "byteLength": buffer.len(), "target": 34962}],
        "buffers": [{"byteLength": buffer.len()}],
    });
    let mut json = serde_json::to_vec(&json).unwrap_or_default();
    json.resize(json.len().next_multiple_of(4), b' ');
    let total = (12 + 8 + json.len() + 8 + buffer.len()) as u32;
    let mut out = Vec::new();
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend(total.to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&json);
    out.extend((buffer.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(&buffer);
    out
}
