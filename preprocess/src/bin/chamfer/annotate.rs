//! `chamfer annotate`: write a PLY or glTF back (or an OBJ as a PLY or glTF) with its marked and
//! chamfer edges embedded.

use std::path::PathBuf;

use chamfer_preprocess::annotate::GltfEdges;
use clap::{Args, ValueEnum};

use crate::flags::BakeFlags;

/// Write the mesh back with its chamfer marks and radii embedded (PLY `edge` element; glTF
/// `extras.chamfer` per primitive, and if asked the EXT_mesh_primitive_edge_visibility and
/// CESIUM_primitive_outline extensions other viewers read), for artists and other tools to read and
/// edit. A PLY or glTF keeps its format; an OBJ becomes the PLY, glTF or GLB the output names.
#[derive(Args)]
#[command(after_help = format!("Examples:
  chamfer annotate part.ply --radius-rel 0.005 -o part-marked.ply
  chamfer annotate scene.glb --radius 0.01 -o scene-marked.glb
  chamfer annotate part.obj -o part.glb --gltf-edges extras,edge-visibility,outline
  chamfer bake part-marked.ply -o part.chamfer     (the marks are read back)

glTF edge dialects (--gltf-edges, comma-separated; default extras):
  extras           extras.chamfer: the marked and chamfer edges with their radii (what chamfer reads back)
  edge-visibility  EXT_mesh_primitive_edge_visibility: every always-drawn edge (crease, boundary, mark,
                   material seam) hard, every kept smooth edge a silhouette with its faces' normals
  outline          CESIUM_primitive_outline: the same hard edges as index pairs (TRIANGLES primitives)
When a primitive has extras.chamfer, chamfer reads its marks from there and not from the extensions.

{}", crate::bake::SAFETY_HELP))]
pub struct AnnotateArgs {
    /// The mesh (PLY, glTF, GLB or OBJ).
    input: PathBuf,
    /// Where to write the annotated copy: the input's format, or for an OBJ .ply, .glb or .gltf.
    #[arg(short, long)]
    output: PathBuf,
    /// The glTF edge dialects to write (see below).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "extras",
        value_name = "LIST"
    )]
    gltf_edges: Vec<Dialect>,
    #[command(flatten)]
    options: BakeFlags,
}

/// One glTF edge dialect.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Dialect {
    /// extras.chamfer
    Extras,
    /// EXT_mesh_primitive_edge_visibility
    #[value(alias = "EXT_mesh_primitive_edge_visibility")]
    EdgeVisibility,
    /// CESIUM_primitive_outline
    #[value(alias = "CESIUM_primitive_outline")]
    Outline,
}

pub fn run(args: &AnnotateArgs) -> anyhow::Result<()> {
    let options = args.options.to_options()?;
    let has = |d: Dialect| args.gltf_edges.contains(&d);
    let dialects = GltfEdges::DEFAULT
        .with_extras(has(Dialect::Extras))
        .with_edge_visibility(has(Dialect::EdgeVisibility))
        .with_primitive_outline(has(Dialect::Outline));
    let annotated = chamfer_preprocess::annotate::annotate_with(
        &args.input,
        &args.output,
        &options,
        &dialects,
    )?;
    for warning in &annotated.warnings {
        crate::warn(format_args!("warning: {}: {warning}", args.input.display()));
    }
    let mut written = format!("{} marked or chamfer edges", annotated.edges);
    if dialects.edge_visibility || dialects.primitive_outline {
        written += &format!(
            ", {} hard and {} silhouette edges in the extensions",
            annotated.hard_edges, annotated.silhouette_edges
        );
    }
    if !annotated.copied.is_empty() {
        written += &format!(
            "; {} file(s) it refers to copied beside it",
            annotated.copied.len()
        );
    }
    crate::say(format_args!(
        "{} -> {}: {written} written",
        args.input.display(),
        args.output.display(),
    ))
}
