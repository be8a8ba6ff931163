//! `chamfer annotate`: write a PLY or glTF back with its marked and chamfer edges embedded.

use std::path::PathBuf;

use clap::Args;

use crate::bake::OptionArgs;

/// Write the mesh back in its own format with its chamfer marks and radii embedded (PLY `edge`
/// element; glTF `extras.chamfer` per primitive), for artists and other tools to read and edit.
#[derive(Args)]
#[command(after_help = format!("Examples:
  chamfer annotate part.ply --radius-rel 0.005 -o part-marked.ply
  chamfer annotate scene.glb --radius 0.01 -o scene-marked.glb
  chamfer bake part-marked.ply -o part.chamfer     (the marks are read back)

{}", crate::bake::SAFETY_HELP))]
pub struct AnnotateArgs {
    /// The mesh (PLY, glTF or GLB).
    input: PathBuf,
    /// Where to write the annotated copy (same format as the input).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    options: OptionArgs,
}

pub fn run(args: &AnnotateArgs) -> anyhow::Result<()> {
    let options = args.options.to_options()?;
    let annotated = chamfer_preprocess::annotate::annotate(&args.input, &args.output, &options)?;
    for warning in &annotated.warnings {
        crate::warn(format_args!("warning: {}: {warning}", args.input.display()));
    }
    crate::say(format_args!(
        "{} -> {}: {} marked or chamfer edges written",
        args.input.display(),
        args.output.display(),
        annotated.edges
    ))
}
