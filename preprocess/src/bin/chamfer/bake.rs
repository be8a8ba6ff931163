//! `chamfer bake`: one or many meshes to `.chamfer` assets, in parallel, written atomically.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use chamfer_preprocess::write::{ensure_not_an_input, write_atomically};
use chamfer_preprocess::{BakeOptions, Baked, Radius, bake_file};
use clap::Args;
use rayon::prelude::*;

use crate::memory::peak_rss_bytes;

/// Bake meshes into .chamfer edge assets.
#[derive(Args)]
#[command(after_help = "Examples:
  chamfer bake model.obj -o model.chamfer
  chamfer bake assets/*.glb -o baked/            (many inputs: OUT is a directory)
  chamfer bake scan.ply.gz -o scan.chamfer --weld-epsilon 1e-5 --crease-deg 40
  chamfer bake part.obj -o part.chamfer --timings
  chamfer bake assembly.glb -o assembly.chamfer --intersections")]
pub struct BakeArgs {
    /// Mesh files: .obj, .gltf, .glb, .ply or .ply.gz.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Output file, or a directory (required for several inputs; created if missing).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    options: OptionArgs,
    /// Print the time of each bake step and the peak memory.
    #[arg(long)]
    timings: bool,
}

/// The bake settings as command-line flags (shared with `chamfer demo`).
#[derive(Args, Clone)]
pub struct OptionArgs {
    /// Weld positions closer than this distance; 0 welds only identical positions.
    #[arg(long, default_value_t = BakeOptions::DEFAULT.weld_epsilon, value_name = "DIST")]
    weld_epsilon: f32,
    /// Drop interior edges whose faces are coplanar within this many degrees.
    #[arg(long, default_value_t = BakeOptions::DEFAULT.coplanar_deg, value_name = "DEG")]
    coplanar_deg: f32,
    /// Edges whose faces meet at this many degrees or more are creases.
    #[arg(long, default_value_t = BakeOptions::DEFAULT.crease_deg, value_name = "DEG")]
    crease_deg: f32,
    /// Give ridge creases (and marked edges without a radius) this chamfer radius, in mesh units.
    /// Radii marked in the file win.
    #[arg(long, value_name = "R", conflicts_with = "radius_rel")]
    radius: Option<f32>,
    /// Like --radius, as a fraction of the bounding box's diagonal (e.g. 0.005).
    #[arg(long, value_name = "F")]
    radius_rel: Option<f32>,
    /// Give valley creases the radius too.
    #[arg(long)]
    radius_valleys: bool,
    /// Also find intersection edges, where triangles cut through each other (within one mesh and
    /// between the objects, primitives and instances of the file), and store them in the asset.
    #[arg(long)]
    intersections: bool,
}

impl OptionArgs {
    /// The options, checked.
    pub fn to_options(&self) -> anyhow::Result<BakeOptions> {
        let options = BakeOptions::DEFAULT
            .with_weld_epsilon(self.weld_epsilon)
            .with_coplanar_deg(self.coplanar_deg)
            .with_crease_deg(self.crease_deg)
            .with_radius(match (self.radius, self.radius_rel) {
                (Some(r), _) => Radius::Absolute(r),
                (None, Some(f)) => Radius::Relative(f),
                (None, None) => Radius::None,
            })
            .with_radius_valleys(self.radius_valleys)
            .with_intersections(self.intersections);
        options.validate()?;
        Ok(options)
    }
}

pub fn run(args: &BakeArgs) -> anyhow::Result<()> {
    let options = args.options.to_options()?;
    let jobs = plan(&args.inputs, &args.output)?;
    let progress = Progress::start(jobs.len());
    let results: Vec<anyhow::Result<String>> = jobs
        .par_iter()
        .map(|(input, output)| {
            let result = bake_one(input, output, &options, args.timings);
            progress.done_one();
            result
        })
        .collect();
    progress.finish();

    let mut failed = 0;
    for result in results {
        match result {
            Ok(report) => println!("{report}"),
            Err(e) => {
                failed += 1;
                eprintln!("error: {}", crate::describe(&e));
            }
        }
    }
    if failed > 0 {
        bail!("{failed} of {} inputs failed", jobs.len());
    }
    Ok(())
}

/// Pairs every input with its output path and refuses clashes before any work starts.
fn plan(inputs: &[PathBuf], output: &Path) -> anyhow::Result<Vec<(PathBuf, PathBuf)>> {
    let to_dir = inputs.len() > 1
        || output.is_dir()
        || output
            .to_string_lossy()
            .ends_with(std::path::MAIN_SEPARATOR);
    let jobs: Vec<(PathBuf, PathBuf)> = if to_dir {
        std::fs::create_dir_all(output)
            .with_context(|| format!("{}: cannot create output directory", output.display()))?;
        inputs
            .iter()
            .map(|i| (i.clone(), output.join(format!("{}.chamfer", stem(i)))))
            .collect()
    } else {
        vec![(inputs[0].clone(), output.to_owned())]
    };
    let mut seen = std::collections::HashMap::new();
    for (input, out) in &jobs {
        if let Some(other) = seen.insert(out.clone(), input.clone()) {
            bail!(
                "{} and {} would both be written to {}",
                other.display(),
                input.display(),
                out.display()
            );
        }
    }
    let input_refs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    for (_, out) in &jobs {
        ensure_not_an_input(out, &input_refs)?;
    }
    Ok(jobs)
}

/// The file name without `.gz` and the mesh extension: `scan.ply.gz` -> `scan`.
fn stem(path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = name.strip_suffix(".gz").unwrap_or(&name);
    Path::new(name)
        .file_stem()
        .map_or_else(|| name.to_owned(), |s| s.to_string_lossy().into_owned())
}

fn bake_one(
    input: &Path,
    output: &Path,
    options: &BakeOptions,
    timings: bool,
) -> anyhow::Result<String> {
    let baked = bake_file(input, options)?;
    let start = Instant::now();
    write_atomically(output, |out| baked.asset.encode(out))?;
    let write = start.elapsed();
    Ok(report(input, output, &baked, write, timings))
}

fn report(input: &Path, output: &Path, baked: &Baked, write: Duration, timings: bool) -> String {
    let stats = &baked.asset.header.stats;
    let mut text = format!(
        "{} -> {}: {} triangles, {} edges kept of {} ({} creases, {} boundary, {} coplanar dropped), {} bytes",
        input.display(),
        output.display(),
        baked.asset.triangle_count(),
        stats.edges.kept,
        stats.edges.total,
        stats.edges.crease,
        stats.edges.boundary,
        stats.edges.coplanar_dropped,
        baked.asset.encoded_len(),
    );
    if let Some(found) = &baked.intersections {
        text += &format!(
            "\n  intersections: {} segments in {} polylines ({} closed), length {:.6}; {} candidate pairs, {} coplanar, {} triangles skipped",
            found.segments,
            found.polylines,
            found.closed_polylines,
            found.length,
            found.candidate_pairs,
            found.coplanar_pairs,
            found.skipped_triangles,
        );
    }
    for warning in &baked.warnings {
        text += &format!("\n  warning: {}: {warning}", input.display());
    }
    if timings {
        let t = &baked.timings;
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let triangles = stats.input_triangles as f64;
        text += &format!(
            "\n  parse {:.1} ms | weld {:.1} | adjacency {:.1} | classify {:.1} | caps {:.1} | intersections {:.1} | normals {:.1} | assemble {:.1} | write {:.1} ms\n  processing (all but parse): {:.1} ms = {:.2} M triangles/s; mesh {:.1} MB, peak RSS {}",
            ms(t.parse),
            ms(t.weld),
            ms(t.adjacency),
            ms(t.classify),
            ms(t.caps),
            ms(t.intersections),
            ms(t.normals),
            ms(t.assemble),
            ms(write),
            ms(t.processing() + write),
            triangles / (t.processing() + write).as_secs_f64() / 1e6,
            baked.mesh_bytes as f64 / 1e6,
            peak_rss_bytes().map_or("unknown".into(), |b| format!("{:.1} MB", b as f64 / 1e6)),
        );
    }
    text
}

/// A progress bar that appears only when baking takes more than half a second.
struct Progress {
    bar: indicatif::ProgressBar,
    finished: Arc<AtomicBool>,
}

impl Progress {
    fn start(total: usize) -> Self {
        let bar = indicatif::ProgressBar::with_draw_target(
            Some(total as u64),
            indicatif::ProgressDrawTarget::hidden(),
        );
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{spinner} baking {pos}/{len} [{elapsed}] {wide_bar}",
        ) {
            bar.set_style(style);
        }
        let finished = Arc::new(AtomicBool::new(false));
        let (late_bar, late_finished) = (bar.clone(), finished.clone());
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(500));
            if !late_finished.load(Ordering::Relaxed) {
                late_bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
                late_bar.enable_steady_tick(Duration::from_millis(120));
            }
        });
        Self { bar, finished }
    }

    fn done_one(&self) {
        self.bar.inc(1);
    }

    fn finish(&self) {
        self.finished.store(true, Ordering::Relaxed);
        self.bar.finish_and_clear();
    }
}
