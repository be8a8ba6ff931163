//! `chamfer bake`: one or many meshes to `.chamfer` assets, in parallel, written atomically.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use chamfer_preprocess::write::{ensure_not_an_input, ensure_replaceable, write_atomically};
use chamfer_preprocess::{BakeOptions, Baked, Error, bake_file, build, compact};
use chamfer_runtime::asset::CompactOptions;
use clap::Args;
use rayon::prelude::*;

use crate::flags::{BakeFlags, EncodingFlags};
use crate::memory::peak_rss_bytes;

/// What every command that reads a mesh says about limits and companion files.
pub const SAFETY_HELP: &str = "Limits: a file asking for more than --max-triangles, --max-vertices, \
--max-instances (glTF primitives through the node graph, 3MF objects through components and build items) \
or --max-input-bytes (per file, after inflating .gz; per 3MF part, as it inflates) is refused before the work \
is done (a .ply.gz or binary .stl.gz as soon as its header is inflated). Files a mesh refers to \
(OBJ mtllib, glTF buffer uri) are read only when they are regular files inside the mesh's folder (after \
following links); an mtllib that is not read is a warning (its faces get the default material), a buffer \
an error. Outputs replace only \
regular files (never a FIFO or device), keep the mode of the file they replace, and are otherwise \
created with the usual mode (0666 minus the umask).";

/// Bake meshes into .chamfer edge assets.
#[derive(Args)]
#[command(after_help = format!("Examples:
  chamfer bake model.obj -o model.chamfer
  chamfer bake assets/*.glb -o baked/            (many inputs: OUT is a directory)
  chamfer bake assets/ -o baked/                 (a folder: every mesh under it, as build::bake_dir)
  chamfer bake scan.ply.gz -o scan.chamfer --weld-epsilon 1e-5 --crease-deg 40
  chamfer bake bracket.stl -o bracket.chamfer    (STL soup: welded, then cracks stitched)
  chamfer bake engine.glb -o engine.chamfer --stitch-rel 1e-3   (wider cracks between CAD faces)
  chamfer bake plate.3mf --scene -o baked/       (one asset per 3MF object, its build items as instances)
  chamfer bake part.obj -o part.chamfer --timings
  chamfer bake assembly.glb -o assembly.chamfer --intersections

{SAFETY_HELP}"))]
pub struct BakeArgs {
    /// Mesh files (.obj, .gltf, .glb, .ply, .stl, .3mf; .ply.gz, .stl.gz) or folders of them.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Output file, or a directory (required for several inputs; created if missing).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    options: BakeFlags,
    /// Print the time of each bake step and the peak memory.
    #[arg(long)]
    timings: bool,
    /// Keep a glTF/GLB (or 3MF) scene's structure: one asset per mesh (`STEM.meshN.chamfer`) and
    /// `STEM.scene.json` listing its instances and their transforms, written into OUTPUT (a
    /// folder), instead of one flattened asset. `chamfer render` draws the scene file.
    #[arg(long)]
    scene: bool,
    #[command(flatten)]
    compact: EncodingFlags,
}

pub fn run(args: &BakeArgs) -> anyhow::Result<()> {
    let options = args.options.to_options()?;
    let compact = args.compact.to_options()?;
    if args.scene {
        return run_scenes(args, &options, compact.as_ref());
    }
    let jobs = plan(&args.inputs, &args.output)?;
    let progress = Progress::start(jobs.len());
    let results: Vec<anyhow::Result<(Baked, Duration, u64)>> = jobs
        .par_iter()
        .map(|(input, output)| {
            let result = bake_one(input, output, &options, compact.as_ref());
            progress.done_one();
            result
        })
        .collect();
    progress.finish();

    let mut failed = 0;
    let mut stdout = Ok(());
    for ((input, output), result) in jobs.iter().zip(results) {
        match result {
            Ok((baked, write, bytes)) => {
                for warning in &baked.warnings {
                    crate::warn(format_args!("warning: {}: {warning}", input.display()));
                }
                if stdout.is_ok() {
                    stdout = crate::say(report(input, output, &baked, write, bytes, args.timings));
                }
            }
            Err(e) => {
                failed += 1;
                crate::warn(format_args!("error: {}", crate::describe(&e)));
            }
        }
    }
    if failed > 0 {
        bail!("{failed} of {} inputs failed", jobs.len());
    }
    stdout
}

/// `bake --scene`: each input's meshes and scene file into the output folder.
fn run_scenes(
    args: &BakeArgs,
    options: &BakeOptions,
    compact: Option<&CompactOptions>,
) -> anyhow::Result<()> {
    let folder = &args.output;
    if folder.exists() && !folder.is_dir() {
        bail!(
            "{}: --scene writes several files; give a folder as the output",
            folder.display()
        );
    }
    std::fs::create_dir_all(folder)
        .with_context(|| format!("{}: cannot create output directory", folder.display()))?;
    let mut stems = std::collections::HashMap::new();
    for input in &args.inputs {
        if let Some(first) = stems.insert(stem(input), input) {
            bail!(
                "{} and {} would both write {}.scene.json",
                first.display(),
                input.display(),
                stem(input)
            );
        }
    }
    for input in &args.inputs {
        let name = stem(input);
        let baked = chamfer_preprocess::scene::bake_scene(input, &name, options)?;
        for warning in &baked.warnings {
            crate::warn(format_args!("warning: {}: {warning}", input.display()));
        }
        let written = chamfer_preprocess::scene::write_scene(&baked, folder, &name, compact)?;
        crate::say(format_args!(
            "{} -> {}: {} instances of {} assets",
            input.display(),
            written.display(),
            baked.scene.instances.len(),
            baked.assets.len()
        ))?;
    }
    Ok(())
}

/// Pairs every input with its output path and refuses clashes, inputs named as outputs and
/// outputs that are not regular files, before anything is created or baked. A folder among the
/// inputs contributes every mesh under it, named by its path inside the folder.
fn plan(inputs: &[PathBuf], output: &Path) -> anyhow::Result<Vec<(PathBuf, PathBuf)>> {
    let to_dir = inputs.len() > 1
        || inputs.iter().any(|i| i.is_dir())
        || output.is_dir()
        || output
            .to_string_lossy()
            .ends_with(std::path::MAIN_SEPARATOR);
    let mut jobs: Vec<(PathBuf, PathBuf)> = Vec::new();
    if to_dir {
        for input in inputs {
            if input.is_dir() {
                jobs.extend(build::plan_dir(input, output, &mut |_| ())?);
            } else {
                jobs.push((
                    input.clone(),
                    output.join(format!("{}.chamfer", stem(input))),
                ));
            }
        }
        if jobs.is_empty() {
            bail!(
                "no mesh files (.obj, .gltf, .glb, .ply, .stl, .3mf; .ply.gz, .stl.gz) among the inputs"
            );
        }
    } else {
        jobs.push((inputs[0].clone(), output.to_owned()));
    }
    let mut seen = std::collections::HashMap::new();
    for (input, out) in &jobs {
        if let Some(first) = seen.insert(out.clone(), input.clone()) {
            return Err(Error::OutputClash {
                first,
                second: input.clone(),
                output: out.clone(),
            }
            .into());
        }
    }
    let input_refs: Vec<&Path> = jobs.iter().map(|(i, _)| i.as_path()).collect();
    for (_, out) in &jobs {
        ensure_not_an_input(out, &input_refs)?;
        ensure_replaceable(out)?;
    }
    if to_dir {
        // The output folder, and the sub-folders (`props/`) of folder inputs under it.
        for folder in jobs.iter().filter_map(|(_, out)| out.parent()) {
            std::fs::create_dir_all(folder)
                .with_context(|| format!("{}: cannot create output directory", folder.display()))?;
        }
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
    compact: Option<&CompactOptions>,
) -> anyhow::Result<(Baked, Duration, u64)> {
    let baked = bake_file(input, options)?;
    let start = Instant::now();
    write_atomically(output, |out| compact::encode(&baked.asset, compact, out))?;
    let bytes = std::fs::metadata(output).map_or(0, |m| m.len());
    Ok((baked, start.elapsed(), bytes))
}

fn report(
    input: &Path,
    output: &Path,
    baked: &Baked,
    write: Duration,
    bytes: u64,
    timings: bool,
) -> String {
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
        bytes,
    );
    let stitched = &baked.stitched;
    if stitched.boundary_before > stitched.boundary_after {
        text += &format!(
            "\n  stitched: {} boundary edges closed ({} vertices joined, {} edges split at T-junctions), {} remain",
            stitched.boundary_before - stitched.boundary_after,
            stitched.joined_vertices,
            stitched.split_edges,
            stitched.boundary_after,
        );
    }
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
    if timings {
        let t = &baked.timings;
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let triangles = stats.input_triangles as f64;
        text += &format!(
            "\n  parse {:.1} ms | weld {:.1} | adjacency {:.1} | stitch {:.1} | classify {:.1} | caps {:.1} | intersections {:.1} | normals {:.1} | assemble {:.1} | write {:.1} ms\n  processing (all but parse): {:.1} ms = {:.2} M triangles/s; mesh {:.1} MB, peak RSS {}",
            ms(t.parse),
            ms(t.weld),
            ms(t.adjacency),
            ms(t.stitch),
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
