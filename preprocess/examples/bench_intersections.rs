//! Intersection-edge and `draw` benchmark, each beside a baseline measured in the same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_intersections -- [--runs 3]
//! ```
//! Meshes: `fixtures/meshes/stanford-bunny.obj` (69 k triangles), `fixtures/meshes/bunny-loop2.ply.gz`
//! (1.1 M), fandisk (13 k) and generated scenes of 10 and 100 overlapping UV spheres (10 k and 1 M
//! triangles, many intersecting pairs). Intersections: `find_intersections` on the welded mesh (the bake's step) against
//! all pairs with a box test and the same exact pair test (`intersect_triangles`), on the small scenes
//! where all pairs is feasible. Draw: `hidden_lines` plus the SVG (the `chamfer draw` default camera,
//! 1024 x 768) of the baked asset. Section drawings (issue 43): the same camera with hidden lines and a
//! plane through the middle of the box along x, against the whole model's drawing with hidden lines
//! (the baseline of the same run), and the section drawing written as SVG, PDF and DXF. Times are
//! medians.

use std::path::Path;
use std::time::{Duration, Instant};

use chamfer_preprocess::draw::paper::PaperOptions;
use chamfer_preprocess::draw::style::DrawingStyle;
use chamfer_preprocess::draw::svg::write_svg;
use chamfer_preprocess::draw::{DrawOptions, hidden_lines};
use chamfer_preprocess::intersections::{find_intersections, intersect_triangles};
use chamfer_preprocess::mesh::Mesh;
use chamfer_preprocess::{BakeOptions, bake, load, weld};
use chamfer_runtime::render::{Camera, Orbit};
use glam::Vec3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs: usize = match args.iter().position(|a| a == "--runs") {
        Some(i) => args.get(i + 1).ok_or("--runs needs a number")?.parse()?,
        None => 3,
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let meshes: Vec<(String, Mesh)> = vec![
        ("spheres-10 (generated)".into(), spheres(10, 16, 32)),
        (
            "fandisk.obj".into(),
            load_mesh(&root.join("fixtures/meshes/fandisk.obj"))?,
        ),
        (
            "stanford-bunny.obj".into(),
            load_mesh(&root.join("fixtures/meshes/stanford-bunny.obj"))?,
        ),
        (
            "bunny-loop2.ply.gz".into(),
            load_mesh(&root.join("fixtures/meshes/bunny-loop2.ply.gz"))?,
        ),
        ("spheres-100 (generated)".into(), spheres(100, 50, 100)),
    ];
    println!(
        "threads: {}, runs per row: {runs} (medians)\n",
        rayon::current_num_threads()
    );
    println!(
        "| mesh | triangles | intersections | segments | polylines | candidate pairs | all pairs (baseline) | ratio |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (name, mesh) in &meshes {
        let w = weld::weld(&mesh.positions, 0.0);
        let t: Vec<[u32; 3]> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|i| w.remap[i as usize]))
            .collect();
        let mut found = None;
        let ours = median(runs, || {
            let start = Instant::now();
            found = Some(find_intersections(&w.positions, &t));
            start.elapsed()
        });
        let stats = found.map(|f| f.stats).unwrap_or_default();
        let baseline = if t.len() <= 20_000 {
            let start = Instant::now();
            let crossing = all_pairs(&w.positions, &t);
            let elapsed = start.elapsed();
            assert_eq!(
                crossing as u64, stats.crossing_pairs,
                "{name}: the baseline disagrees"
            );
            Some(elapsed)
        } else {
            None
        };
        println!(
            "| {name} | {} | {:.1} ms | {} | {} | {} | {} | {} |",
            t.len(),
            ms(ours),
            stats.segments,
            stats.polylines,
            stats.candidate_pairs,
            baseline.map_or("n/a".into(), |b| format!("{:.0} ms", ms(b))),
            baseline.map_or("n/a".into(), |b| format!(
                "{:.0}x",
                b.as_secs_f64() / ours.as_secs_f64()
            )),
        );
    }
    println!(
        "\n| mesh | triangles | bake (with intersections) | draw: hidden lines | draw: SVG | lines | occlusion tests | polylines |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    let mut sections = Vec::new();
    for (name, mesh) in &meshes {
        let start = Instant::now();
        let asset = bake(
            mesh.clone(),
            name,
            &BakeOptions::DEFAULT.with_intersections(true),
        )?
        .asset;
        let baked = start.elapsed();
        let camera = Camera::orbit(
            [asset.header.bounds_min, asset.header.bounds_max],
            &Orbit::default(),
            [1024, 768],
        );
        let mut drawing = None;
        let lines = median(runs, || {
            let start = Instant::now();
            drawing = Some(hidden_lines(&asset, &camera, &DrawOptions::DEFAULT));
            start.elapsed()
        });
        let drawing = drawing.ok_or("no run")?;
        let mut svg = Vec::new();
        let start = Instant::now();
        write_svg(
            &drawing,
            &DrawingStyle::default(),
            &PaperOptions::DEFAULT,
            &mut svg,
        )?;
        let written = start.elapsed();
        let polylines: usize = drawing.lines.iter().map(|s| s.polylines.len()).sum();
        println!(
            "| {name} | {} | {:.0} ms | {:.1} ms | {:.1} ms | {} | {} | {polylines} |",
            asset.triangle_count(),
            ms(baked),
            ms(lines),
            ms(written),
            drawing.stats.lines,
            drawing.stats.occlusion_tests,
        );
        sections.push((name.clone(), section_row(&asset, &camera, runs)?));
    }
    println!(
        "\n| mesh | whole, hidden lines (baseline) | section, hidden lines | ratio | cut outlines | SVG | PDF | DXF |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (name, row) in sections {
        println!("| {name} | {row} |");
    }
    Ok(())
}

/// The section drawing's times against the whole model's, and its writes.
fn section_row(
    asset: &chamfer_runtime::asset::Asset,
    camera: &Camera,
    runs: usize,
) -> Result<String, Box<dyn std::error::Error>> {
    let lo = Vec3::from(asset.header.bounds_min);
    let hi = Vec3::from(asset.header.bounds_max);
    let plane = chamfer_runtime::section::Plane {
        normal: [1.0, 0.0, 0.0],
        offset: f64::from((lo.x + hi.x) * 0.5),
    };
    let whole_options = DrawOptions::DEFAULT.with_hidden(true);
    let section_options = whole_options.with_section(Some(plane));
    let whole = median(runs, || {
        let start = Instant::now();
        let _ = hidden_lines(asset, camera, &whole_options);
        start.elapsed()
    });
    let mut drawing = None;
    let section = median(runs, || {
        let start = Instant::now();
        drawing = Some(hidden_lines(asset, camera, &section_options));
        start.elapsed()
    });
    let drawing = drawing.ok_or("no run")?;
    let outlines = drawing
        .lines
        .iter()
        .filter(|s| s.class == chamfer_preprocess::draw::LineClass::Cut)
        .map(|s| s.polylines.len())
        .sum::<usize>();
    let style = DrawingStyle::default();
    let paper = PaperOptions::DEFAULT;
    let mut writes = Vec::new();
    type Writer = fn(
        &chamfer_preprocess::draw::Drawing,
        &DrawingStyle,
        &PaperOptions,
        &mut Vec<u8>,
    ) -> std::io::Result<()>;
    let writers: [Writer; 3] = [
        |d, s, p, o| write_svg(d, s, p, o),
        |d, s, p, o| chamfer_preprocess::draw::pdf::write_pdf(d, s, p, o),
        |d, s, p, o| chamfer_preprocess::draw::dxf::write_dxf(d, s, p, o),
    ];
    for write in writers {
        let mut bytes = Vec::new();
        let time = median(runs, || {
            bytes.clear();
            let start = Instant::now();
            let _ = write(&drawing, &style, &paper, &mut bytes);
            start.elapsed()
        });
        writes.push(format!("{:.1} ms ({} kB)", ms(time), bytes.len() / 1000));
    }
    Ok(format!(
        "{:.1} ms | {:.1} ms | {:.2}x | {outlines} | {}",
        ms(whole),
        ms(section),
        section.as_secs_f64() / whole.as_secs_f64().max(1e-12),
        writes.join(" | ")
    ))
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn median(runs: usize, mut f: impl FnMut() -> Duration) -> Duration {
    let mut times: Vec<Duration> = (0..runs.max(1)).map(|_| f()).collect();
    times.sort();
    times[times.len() / 2]
}

fn load_mesh(path: &Path) -> Result<Mesh, Box<dyn std::error::Error>> {
    Ok(load::load(path, &chamfer_preprocess::Limits::DEFAULT)?.mesh)
}

/// `count` UV spheres of `2 * rings * segments` triangles, radius 1, centres on a fixed
/// pseudo-random walk in a box small enough that most of them overlap others.
fn spheres(count: u32, rings: u32, segments: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let mut seed = 0x2545_f491_u32;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        f64::from(seed) / f64::from(u32::MAX)
    };
    let side = 1.6 * f64::from(count).cbrt();
    for _ in 0..count {
        let c = Vec3::new(
            (next() * side) as f32,
            (next() * side) as f32,
            (next() * side) as f32,
        );
        let mut positions = Vec::new();
        for i in 0..=rings {
            let theta = std::f32::consts::PI * i as f32 / rings as f32;
            for j in 0..segments {
                let phi = 2.0 * std::f32::consts::PI * j as f32 / segments as f32;
                positions.push(
                    c + Vec3::new(
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    ),
                );
            }
        }
        let at = |i: u32, j: u32| i * segments + j % segments;
        let mut triangles = Vec::new();
        for i in 0..rings {
            for j in 0..segments {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        mesh.append(Mesh {
            positions,
            triangles,
            ..Mesh::default()
        });
    }
    mesh
}

/// The baseline: every pair of triangles, a box test, then the same exact pair test.
fn all_pairs(positions: &[Vec3], triangles: &[[u32; 3]]) -> usize {
    let boxes: Vec<(Vec3, Vec3)> = triangles
        .iter()
        .map(|t| {
            let p = t.map(|i| positions[i as usize]);
            (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]))
        })
        .collect();
    let mut crossing = 0;
    for a in 0..triangles.len() {
        for b in a + 1..triangles.len() {
            let ((alo, ahi), (blo, bhi)) = (boxes[a], boxes[b]);
            if alo.cmple(bhi).all()
                && blo.cmple(ahi).all()
                && intersect_triangles(positions, triangles[a], triangles[b]).is_some()
            {
                crossing += 1;
            }
        }
    }
    crossing
}
