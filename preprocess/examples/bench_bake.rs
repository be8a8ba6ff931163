//! Bake benchmark: per-stage times, throughput and peak memory, beside a naive baseline in the same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_bake -- [--runs 5] [MESH...]
//! cargo run --release -p chamfer-preprocess --example bench_bake -- --write-torus 10000000
//! ```
//! With no mesh it benches `fixtures/meshes/bunny-loop2.ply.gz` and a generated faceted torus of
//! 2,000,000 triangles (written once as binary PLY under `target/bench/`). Every measurement runs in a
//! fresh child process so peak RSS (Linux `VmHWM`) belongs to that one bake; the table reports medians.

use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use chamfer_preprocess::write::write_atomically;
use chamfer_preprocess::{BakeOptions, Limits, load};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [mode, path] = args.as_slice() {
        if mode == "--child-ours" {
            return child_ours(Path::new(path));
        }
        if mode == "--child-naive" {
            return child_naive(Path::new(path));
        }
    }
    let mut runs = 5;
    let mut meshes = Vec::new();
    let mut iter = args.iter();
    while let Some(arg) = iter.next() {
        if arg == "--runs" {
            runs = iter.next().ok_or("--runs needs a number")?.parse()?;
        } else if arg == "--write-torus" {
            // Only writes the generated torus of that many triangles and prints its path.
            let triangles = iter.next().ok_or("--write-torus needs a number")?.parse()?;
            let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/bench");
            println!("{}", generated_torus(&dir, triangles)?.display());
            return Ok(());
        } else {
            meshes.push(PathBuf::from(arg));
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    if meshes.is_empty() {
        meshes.push(root.join("fixtures/meshes/bunny-loop2.ply.gz"));
        meshes.push(generated_torus(&root.join("target/bench"), 2_000_000)?);
    }
    println!(
        "threads: {}, runs per row: {runs} (medians)\n",
        rayon::current_num_threads()
    );
    println!(
        "| mesh | triangles | parse | weld | adjacency | classify | caps | normals | assemble | write | non-parse | M tri/s | mesh MB | peak RSS MB | peak / mesh |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut baselines = Vec::new();
    for mesh in &meshes {
        let ours = median_of(runs, || run_child("--child-ours", mesh))?;
        let naive = median_of(runs, || run_child("--child-naive", mesh))?;
        let ms = |k: &str| ours[k] * 1e3;
        let non_parse = [
            "weld",
            "adjacency",
            "classify",
            "caps",
            "normals",
            "assemble",
            "write",
        ]
        .iter()
        .map(|k| ms(k))
        .sum::<f64>();
        println!(
            "| {} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} | {:.1} | {:.1} | {:.2}× |",
            name(mesh),
            ours["triangles"],
            ms("parse"),
            ms("weld"),
            ms("adjacency"),
            ms("classify"),
            ms("caps"),
            ms("normals"),
            ms("assemble"),
            ms("write"),
            non_parse,
            ours["triangles"] / non_parse / 1e3,
            ours["mesh_bytes"] / 1e6,
            ours["peak_rss"] / 1e6,
            ours["peak_rss"] / ours["mesh_bytes"],
        );
        baselines.push((name(mesh), ours, naive));
    }
    println!(
        "\nBaseline: `HashMap<[u32; 3], u32>` weld + `HashMap<(u32, u32), Vec<u32>>` adjacency, same runs.\n"
    );
    println!(
        "| mesh | ours weld + adjacency ms | naive weld + adjacency ms | speed-up | naive peak RSS MB |"
    );
    println!("|---|---:|---:|---:|---:|");
    for (mesh, ours, naive) in baselines {
        let ours_ms = (ours["weld"] + ours["adjacency"]) * 1e3;
        let naive_ms = (naive["weld"] + naive["adjacency"]) * 1e3;
        println!(
            "| {mesh} | {ours_ms:.0} | {naive_ms:.0} | {:.1}× | {:.1} |",
            naive_ms / ours_ms,
            naive["peak_rss"] / 1e6
        );
    }
    Ok(())
}

type Sample = HashMap<String, f64>;

fn name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Runs `sample` `runs` times and keeps the median of every key.
fn median_of(
    runs: usize,
    mut sample: impl FnMut() -> Result<Sample, Box<dyn std::error::Error>>,
) -> Result<Sample, Box<dyn std::error::Error>> {
    let samples: Vec<Sample> = (0..runs).map(|_| sample()).collect::<Result<_, _>>()?;
    let mut median = Sample::new();
    for key in samples[0].keys() {
        let mut values: Vec<f64> = samples.iter().map(|s| s[key]).collect();
        values.sort_by(f64::total_cmp);
        median.insert(key.clone(), values[values.len() / 2]);
    }
    Ok(median)
}

fn run_child(mode: &str, mesh: &Path) -> Result<Sample, Box<dyn std::error::Error>> {
    let output = Command::new(std::env::current_exe()?)
        .arg(mode)
        .arg(mesh)
        .output()?;
    if !output.status.success() {
        return Err(format!(
            "{mode} {}: {}",
            mesh.display(),
            String::from_utf8_lossy(&output.stderr)
        )
        .into());
    }
    Ok(serde_json::from_slice(&output.stdout)?)
}

fn peak_rss() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kib = status
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        .unwrap_or(f64::NAN);
    kib * 1024.0
}

fn child_ours(path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let baked = chamfer_preprocess::bake_file(path, &BakeOptions::DEFAULT)?;
    let dir = tempfile::tempdir()?;
    let start = Instant::now();
    write_atomically(&dir.path().join("out.chamfer"), |out| {
        baked.asset.encode(out)
    })?;
    let write = start.elapsed();
    let t = baked.timings;
    let s = |d: Duration| d.as_secs_f64();
    report(&[
        ("triangles", baked.asset.header.stats.input_triangles as f64),
        ("parse", s(t.parse)),
        ("weld", s(t.weld)),
        ("adjacency", s(t.adjacency)),
        ("classify", s(t.classify)),
        ("caps", s(t.caps)),
        ("normals", s(t.normals)),
        ("assemble", s(t.assemble)),
        ("write", s(write)),
        ("mesh_bytes", baked.mesh_bytes as f64),
        ("peak_rss", peak_rss()),
    ])
}

/// Prints a child's measurements as one JSON object for the parent.
fn report(values: &[(&str, f64)]) -> Result<(), Box<dyn std::error::Error>> {
    let sample: Sample = values.iter().map(|&(k, v)| (k.to_owned(), v)).collect();
    println!("{}", serde_json::to_string(&sample)?);
    Ok(())
}

/// The obvious implementation: hash every position, then hash every edge to its list of faces.
fn child_naive(path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let mesh = load::load(path, &Limits::DEFAULT)?.mesh;
    let start = Instant::now();
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let remap: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let next = ids.len() as u32;
            *ids.entry(p.to_array().map(|c| if c == 0.0 { 0 } else { c.to_bits() }))
                .or_insert(next)
        })
        .collect();
    let weld = start.elapsed();
    let start = Instant::now();
    let mut faces: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
    for (f, t) in mesh.triangles.iter().enumerate() {
        let w = t.map(|i| remap[i as usize]);
        if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (w[k], w[(k + 1) % 3]);
            faces
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push(f as u32);
        }
    }
    // v0 v1 v2 v3 per edge, as the bake emits them.
    let edges: Vec<[u32; 4]> = faces
        .iter()
        .map(|(&(a, b), fs)| {
            let opposite = |f: u32| {
                mesh.triangles[f as usize]
                    .map(|i| remap[i as usize])
                    .into_iter()
                    .find(|&v| v != a && v != b)
            };
            let v2 = opposite(fs[0]).unwrap_or(a);
            let v3 = fs.get(1).and_then(|&f| opposite(f)).unwrap_or(a);
            [a, b, v2, v3]
        })
        .collect();
    let adjacency = start.elapsed();
    std::hint::black_box(&edges);
    report(&[
        ("weld", weld.as_secs_f64()),
        ("adjacency", adjacency.as_secs_f64()),
        ("edges", edges.len() as f64),
        ("peak_rss", peak_rss()),
    ])
}

/// A torus whose cross-section is an octagon: flat strips (coplanar edges), 45° creases, smooth sweeps.
/// Written as binary little-endian PLY with about `triangles` triangles; reused if already there.
fn generated_torus(dir: &Path, triangles: usize) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let path = dir.join(format!("torus-{}k.ply", triangles / 1000));
    if path.exists() {
        return Ok(path);
    }
    std::fs::create_dir_all(dir)?;
    let per_side = 25; // segments along each flat side of the octagon
    let around_section = 8 * per_side;
    let around_ring = triangles / (2 * around_section);
    let (big, small) = (3.0f32, 1.0f32);
    let corner = |k: usize| {
        let a = std::f32::consts::TAU * k as f32 / 8.0;
        (a.cos() * small, a.sin() * small)
    };
    let mut positions = Vec::with_capacity(around_ring * around_section);
    for i in 0..around_ring {
        let phi = std::f32::consts::TAU * i as f32 / around_ring as f32;
        for j in 0..around_section {
            let (side, step) = (j / per_side, j % per_side);
            let (a, b) = (corner(side), corner(side + 1));
            let t = step as f32 / per_side as f32;
            let (r, z) = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
            positions.push([(big + r) * phi.cos(), (big + r) * phi.sin(), z]);
        }
    }
    let index =
        |i: usize, j: usize| ((i % around_ring) * around_section + j % around_section) as u32;
    let mut body = Vec::with_capacity(positions.len() * 12 + around_ring * around_section * 26);
    for p in &positions {
        for c in p {
            body.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in 0..around_ring {
        for j in 0..around_section {
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            for tri in [[a, b, c], [a, c, d]] {
                body.push(3);
                for v in tri {
                    body.extend_from_slice(&v.to_le_bytes());
                }
            }
        }
    }
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment chamfer bench: octagonal torus\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nelement face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        positions.len(),
        2 * around_ring * around_section
    );
    let mut file = std::io::BufWriter::new(std::fs::File::create(&path)?);
    file.write_all(header.as_bytes())?;
    file.write_all(&body)?;
    file.flush()?;
    Ok(path)
}
