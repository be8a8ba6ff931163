//! Compact assets (format 5, issue 24): bytes per section stored and decoded, encode and decode
//! times, against the uncompressed file read from a warm page cache, in the same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_compact -- [--runs 9] [MESH...]
//! ```
//! With no mesh it measures `fixtures/meshes/bunny-loop2.ply.gz` and `fixtures/meshes/fandisk.obj`.
//! Each mesh is baked once; its uncompressed and compact files are written under `target/bench/`
//! (`NAME.chamfer`, `NAME.compact.chamfer`; scripts/bench-compact.sh hands them to gltfpack and gzip).
//! Every load is timed from the file on disk (read, decode, validate: what a viewer does before its
//! upload) and reported as the median of `--runs`, after one warm-up read.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use chamfer_preprocess::compact::Meshopt;
use chamfer_preprocess::{BakeOptions, bake_file};
use chamfer_runtime::asset::{Asset, CompactOptions, SectionKind};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut runs = 9;
    let mut meshes = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--runs" {
            runs = args.next().ok_or("--runs needs a number")?.parse()?;
        } else {
            meshes.push(PathBuf::from(arg));
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    if meshes.is_empty() {
        meshes.push(root.join("fixtures/meshes/bunny-loop2.ply.gz"));
        meshes.push(root.join("fixtures/meshes/fandisk.obj"));
    }
    let out = root.join("target/bench");
    std::fs::create_dir_all(&out)?;
    println!(
        "threads: {}, runs per timing: {runs} (medians)\n",
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    for mesh in &meshes {
        measure(mesh, &out, runs)?;
    }
    Ok(())
}

fn measure(mesh: &Path, out: &Path, runs: usize) -> Result<(), Box<dyn std::error::Error>> {
    let name = mesh
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stem = name.split('.').next().unwrap_or("mesh").to_owned();
    let started = Instant::now();
    let asset = bake_file(mesh, &BakeOptions::DEFAULT)?.asset;
    let bake = started.elapsed();
    let triangles = asset.triangle_count() as f64;

    let raw_path = out.join(format!("{stem}.chamfer"));
    let compact_path = out.join(format!("{stem}.compact.chamfer"));
    let lossless_path = out.join(format!("{stem}.lossless.chamfer"));
    let (raw, raw_encode) = timed(runs, || asset.encode_to_vec());
    let options = CompactOptions::default();
    let (compact, compact_encode) = timed(runs, || {
        asset
            .encode_compact_to_vec(&options, &Meshopt)
            .expect("encodes")
    });
    let (lossless, _) = timed(1, || {
        asset
            .encode_compact_to_vec(&CompactOptions::LOSSLESS, &Meshopt)
            .expect("encodes")
    });
    std::fs::write(&raw_path, &raw)?;
    std::fs::write(&compact_path, &compact)?;
    std::fs::write(&lossless_path, &lossless)?;

    // Warm the page cache, then time whole loads from disk.
    for path in [&raw_path, &compact_path, &lossless_path] {
        std::fs::read(path)?;
    }
    let (_, read_raw) = timed(runs, || std::fs::read(&raw_path).expect("read"));
    let (_, load_raw) = timed(runs, || {
        Asset::decode(&std::fs::read(&raw_path).expect("read")).expect("decodes")
    });
    let (decoded, load_compact) = timed(runs, || {
        Asset::decode(&std::fs::read(&compact_path).expect("read")).expect("decodes")
    });
    let (_, load_lossless) = timed(runs, || {
        Asset::decode(&std::fs::read(&lossless_path).expect("read")).expect("decodes")
    });
    // The GPU-ready bytes a load produces: every section the renderer uploads.
    let gpu_bytes: usize = SectionKind::ALL
        .iter()
        .filter(|k| k.is_gpu_ready())
        .map(|&k| decoded.section_bytes(k).len())
        .sum();

    println!(
        "### {name}: {} triangles, {} edges (bake {:.0} ms)\n",
        asset.triangle_count(),
        asset.edge_count(),
        ms(bake)
    );
    println!(
        "| file | bytes | B/triangle | encode ms | load ms (read + decode + validate) | load / read of the uncompressed file | decoded MB/s |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mb_s = |d: Duration| gpu_bytes as f64 / 1e6 / d.as_secs_f64();
    println!(
        "| uncompressed | {} | {:.2} | {:.1} | {:.1} (read alone {:.1}) | {:.2}× | {:.0} |",
        raw.len(),
        raw.len() as f64 / triangles,
        ms(raw_encode),
        ms(load_raw),
        ms(read_raw),
        ratio(load_raw, read_raw),
        mb_s(load_raw)
    );
    for (label, bytes, encode, load) in [
        (
            format!(
                "compact ({} position bits, {} normal bits)",
                options.position_bits, options.normal_bits
            ),
            compact.len(),
            Some(compact_encode),
            load_compact,
        ),
        (
            "compact lossless".to_owned(),
            lossless.len(),
            None,
            load_lossless,
        ),
    ] {
        println!(
            "| {label} | {bytes} | {:.2} | {} | {:.1} | {:.2}× | {:.0} |",
            bytes as f64 / triangles,
            encode.map_or("—".into(), |d| format!("{:.1}", ms(d))),
            ms(load),
            ratio(load, read_raw),
            mb_s(load)
        );
    }
    // The floor under any decoder on this machine: fresh memory of the decoded size, allocated
    // and touched once per page (the kernel zeroes each page on its first touch).
    let (_, floor) = timed(runs, || {
        let mut fresh = vec![0u8; gpu_bytes];
        for at in (0..gpu_bytes).step_by(4096) {
            fresh[at] = 1;
        }
        fresh
    });
    println!(
        "| floor: {gpu_bytes} bytes of fresh memory, each page touched | — | — | — | {:.1} | {:.2}× | — |",
        ms(floor),
        ratio(floor, read_raw)
    );
    println!("\nGPU-ready bytes after a load: {gpu_bytes}\n");

    // Each section: stored, decoded, and what its decode steps take (median of their sums).
    let mut steps: Vec<Vec<(SectionKind, Duration)>> = Vec::new();
    for _ in 0..runs {
        let times = std::sync::Mutex::new((Instant::now(), Vec::<(SectionKind, Duration)>::new()));
        Asset::decode_observed(&compact, &|kind| {
            if let Ok(mut times) = times.lock() {
                let now = Instant::now();
                let since = now - times.0;
                match times.1.iter_mut().find(|(k, _)| *k == kind) {
                    Some((_, total)) => *total += since,
                    None => times.1.push((kind, since)),
                }
                times.0 = now;
            }
        })?;
        steps.push(times.into_inner()?.1);
    }
    let stored = Asset::decode(&compact)?.header.sections;
    let raw_sections = asset.encoded_sections();
    let length = |table: &[chamfer_runtime::asset::SectionEntry], k: SectionKind| {
        table
            .iter()
            .find(|s| s.kind == k as u32)
            .map_or(0, |s| s.length)
    };
    println!("| section | stored bytes | replaces | raw bytes | saved | decode ms |");
    println!("|---|---:|---|---:|---:|---:|");
    for &(kind, _) in &steps[0] {
        let mut times: Vec<Duration> = steps
            .iter()
            .filter_map(|s| s.iter().find(|(k, _)| *k == kind).map(|(_, d)| *d))
            .collect();
        times.sort_unstable();
        let twin = kind.twin();
        let raw_bytes = twin.map_or(length(&raw_sections, kind), |t| {
            length(&raw_sections, t)
                + if t == SectionKind::NextEnds {
                    length(&raw_sections, SectionKind::CapHeads)
                } else {
                    0
                }
        });
        let stored_bytes = length(&stored, kind);
        println!(
            "| {} | {} | {} | {} | {} | {:.2} |",
            kind.name(),
            stored_bytes,
            twin.map_or("—", |t| t.name()),
            raw_bytes,
            raw_bytes as i64 - stored_bytes as i64,
            ms(times[times.len() / 2])
        );
    }
    println!();
    Ok(())
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn ratio(a: Duration, b: Duration) -> f64 {
    a.as_secs_f64() / b.as_secs_f64()
}

/// The last result of `runs` calls of `f`, and their median time.
fn timed<T>(runs: usize, mut f: impl FnMut() -> T) -> (T, Duration) {
    let mut times = Vec::with_capacity(runs);
    let mut result = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        let value = std::hint::black_box(f());
        times.push(start.elapsed());
        result = Some(value);
    }
    times.sort_unstable();
    (result.expect("ran once"), times[times.len() / 2])
}
