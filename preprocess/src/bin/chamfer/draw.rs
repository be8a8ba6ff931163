//! `chamfer draw`: a hidden-line drawing of an asset, or of a mesh baked on the fly, as SVG.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::bail;
use chamfer_preprocess::draw::svg::{SvgOptions, mm_per_px, write_svg};
use chamfer_preprocess::draw::{DrawOptions, LineClass, hidden_lines};
use chamfer_preprocess::write::{ensure_not_an_input, write_atomically};
use clap::{Args, ValueEnum};

use crate::flags::BakeFlags;
use crate::render::CameraArgs;

/// Draw the visible contours, boundaries, marked edges, creases and intersection edges of an asset
/// (`.chamfer`) or a mesh (baked on the fly with the bake flags, intersections included) as an SVG
/// line drawing, hidden lines removed exactly. The camera flags are `chamfer render`'s: the same
/// flags give a drawing that lies on the render pixel for pixel.
#[derive(Args)]
#[command(after_help = "Examples:
  chamfer draw part.obj -o part.svg
  chamfer draw assembly.chamfer -o front.svg --azimuth 0 --elevation 0 --ortho --scale 20
  chamfer draw part.glb -o part.svg --hidden --classes contour,crease")]
pub struct DrawArgs {
    /// A `.chamfer` asset, or an OBJ, glTF/GLB or PLY mesh.
    input: PathBuf,
    /// The SVG to write.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    camera: CameraArgs,
    /// Also draw the hidden parts, dashed, in their own group.
    #[arg(long)]
    hidden: bool,
    /// Line classes to draw.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "contour,boundary,marked,crease,intersection"
    )]
    classes: Vec<Class>,
    /// Paper millimetres per model unit (in the plane through the model's centre facing the camera;
    /// everywhere with --ortho). Default: 1 px of the frame is 1/96 inch.
    #[arg(long, value_name = "MM")]
    scale: Option<f64>,
    /// Print the time of each step.
    #[arg(long)]
    timings: bool,
    #[command(flatten)]
    options: BakeFlags,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Class {
    Contour,
    Boundary,
    Marked,
    Crease,
    Intersection,
}

pub fn run(args: &DrawArgs) -> anyhow::Result<()> {
    args.camera.check()?;
    if args.scale.is_some_and(|s| !(s.is_finite() && s > 0.0)) {
        bail!("--scale must be a positive number of millimetres per model unit");
    }
    ensure_not_an_input(&args.output, &[&args.input])?;
    let start = Instant::now();
    let options = args.options.to_options()?.with_intersections(true);
    let read = chamfer_preprocess::input::read_asset(&args.input, &options)?;
    for warning in &read.warnings {
        crate::warn(format_args!("warning: {}: {warning}", args.input.display()));
    }
    let asset = read.asset;
    let loaded = start.elapsed();

    let camera = args
        .camera
        .camera([asset.header.bounds_min, asset.header.bounds_max]);
    let classes: Vec<LineClass> = args
        .classes
        .iter()
        .map(|c| match c {
            Class::Contour => LineClass::Contour,
            Class::Boundary => LineClass::Boundary,
            Class::Marked => LineClass::Marked,
            Class::Crease => LineClass::Crease,
            Class::Intersection => LineClass::Intersection,
        })
        .collect();
    let options = DrawOptions::DEFAULT
        .with_classes(&classes)
        .with_hidden(args.hidden);
    let start = Instant::now();
    let drawing = hidden_lines(&asset, &camera, &options);
    let drawn = start.elapsed();

    let name = args.input.file_name().map_or_else(
        || args.input.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let svg = SvgOptions::DEFAULT
        .with_mm_per_unit(args.scale)
        .with_title(name)
        .with_description(format!(
            "Camera: chamfer render {}.",
            args.camera.describe()
        ));
    let start = Instant::now();
    write_atomically(&args.output, |out| write_svg(&drawing, &svg, out))?;
    let written = start.elapsed();
    let count = |hidden: bool| -> usize {
        drawing
            .lines
            .iter()
            .filter(|s| s.hidden == hidden)
            .map(|s| s.polylines.len())
            .sum()
    };
    println!(
        "{} ({} triangles, {} edges, {} intersection segments) -> {}: {} visible polylines{}, {} mm per px",
        args.input.display(),
        asset.triangle_count(),
        asset.edge_count(),
        asset.intersection_segments.len(),
        args.output.display(),
        count(false),
        if args.hidden {
            format!(", {} hidden", count(true))
        } else {
            String::new()
        },
        mm_per_px(&drawing, &svg) as f32,
    );
    if args.timings {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        println!(
            "  load/bake {:.1} ms | hidden lines {:.1} ms ({} lines, {} occlusion tests) | write {:.1} ms",
            ms(loaded),
            ms(drawn),
            drawing.stats.lines,
            drawing.stats.occlusion_tests,
            ms(written)
        );
    }
    Ok(())
}
