//! `chamfer demo`: bake the bundled fandisk (a CAD part with creases and flat regions), render it
//! headless to a PNG and show what the asset holds.

use std::path::{Path, PathBuf};

use anyhow::Context;
use chamfer_preprocess::bake_bytes;
use chamfer_preprocess::write::write_atomically;
use clap::Args;

use crate::flags::BakeFlags;

/// The bundled mesh: Hoppe's fandisk, 12,946 triangles (see fixtures/meshes/SOURCES.md). `assets/fandisk.obj`
/// is a link to the fixture, so the file lives once in the repository and travels in the package.
const FANDISK: &[u8] = include_bytes!("../../../assets/fandisk.obj");

/// Bake the bundled fandisk mesh, render it to a PNG beside the asset, and print what the asset holds.
#[derive(Args)]
pub struct DemoArgs {
    /// Where to write the asset.
    #[arg(short, long, default_value = "demo-output/fandisk.chamfer")]
    output: PathBuf,
    #[command(flatten)]
    options: BakeFlags,
    #[command(flatten)]
    view: crate::render::ViewArgs,
}

pub fn run(args: &DemoArgs) -> anyhow::Result<()> {
    let options = args.options.to_options()?;
    let baked = bake_bytes(Path::new("fandisk.obj"), FANDISK, &options)?;
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create directory", dir.display()))?;
    }
    write_atomically(&args.output, |out| baked.asset.encode(out))?;
    crate::say(format_args!(
        "baked the bundled fandisk.obj in {:.1} ms -> {}\n",
        baked.timings.processing().as_secs_f64() * 1e3,
        args.output.display()
    ))?;
    let picture = args.output.with_extension("png");
    let (image, adapter) = crate::render::render(&baked.asset, &args.view)
        .with_context(|| "fandisk.obj: cannot render")?;
    crate::render::write_png(&image, &picture)?;
    crate::say(format_args!(
        "rendered it on {adapter} -> {}\n",
        picture.display()
    ))?;
    crate::inspect::run(&crate::inspect::InspectArgs::for_path(args.output.clone()))
}
