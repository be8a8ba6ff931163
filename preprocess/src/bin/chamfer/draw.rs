//! `chamfer draw`: a hidden-line drawing of an asset, or of a mesh baked on the fly, as SVG, PDF
//! or DXF, optionally a section drawing (issue 43).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::bail;
use chamfer_preprocess::draw::dxf::write_dxf;
use chamfer_preprocess::draw::paper::{
    ModelUnit, PaperOptions, mm_per_px, parse_scale, section_note,
};
use chamfer_preprocess::draw::pdf::write_pdf;
use chamfer_preprocess::draw::section::drawing_plane;
use chamfer_preprocess::draw::style::{DrawingStyle, read_style_file};
use chamfer_preprocess::draw::svg::write_svg;
use chamfer_preprocess::draw::{DrawOptions, LineClass, hidden_lines, units_per_px};
use chamfer_preprocess::write::{ensure_not_an_input, write_atomically};
use clap::{Args, ValueEnum};

use crate::flags::{BakeFlags, DrawingStyleFlags, SectionFlags};
use crate::render::CameraArgs;

/// Draw the visible contours, boundaries, marked edges, creases and intersection edges of an asset
/// (`.chamfer`) or a mesh (baked on the fly with the bake flags, intersections included) as an SVG,
/// PDF or DXF line drawing (by the output's extension), hidden lines removed exactly. The camera
/// flags are `chamfer render`'s: the same flags give a drawing that lies on the render pixel for
/// pixel. With --section (one plane: a drawing takes no box) the half the plane keeps is drawn, with the cut outline and hatched cut
/// faces; every line has a role (cut, hatch, silhouette, boundary, visible, intersection, hidden),
/// a layer of its own with the weight, colour and dashes the style flags or --style give.
#[derive(Args)]
#[command(after_help = "Examples:
  chamfer draw part.obj -o part.svg
  chamfer draw assembly.chamfer -o front.svg --azimuth 0 --elevation 0 --ortho --scale 20
  chamfer draw part.glb -o part.svg --hidden --classes contour,crease
  chamfer draw part.obj -o section.pdf --section 1,0,0,0 --hidden --scale 20
  chamfer draw building.glb -o plan.pdf --section 0,1,0,1.2 --elevation 90 --ortho --scale 1:50 --units m
  chamfer draw plan.glb -o plan.dxf --section 0,1,0,1.5 --elevation 90 --ortho --style roles.json")]
pub struct DrawArgs {
    /// A `.chamfer` asset, or an OBJ, glTF/GLB or PLY mesh.
    input: PathBuf,
    /// The drawing to write: `.svg`, `.pdf` or `.dxf`.
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
        default_value = "contour,boundary,marked,crease,intersection,cut,hatch"
    )]
    classes: Vec<Class>,
    #[command(flatten)]
    section: SectionFlags,
    #[command(flatten)]
    style: DrawingStyleFlags,
    /// A JSON file of line styles: an object with the style flags' names in snake_case
    /// (`{"cut_weight": 0.7, "hidden_dash": [2, 1]}`); the style flags given override it.
    #[arg(long = "style", value_name = "FILE")]
    style_file: Option<PathBuf>,
    /// The drawing's scale, in the plane through the model's centre facing the camera (everywhere
    /// with --ortho): paper millimetres per model unit (`20`), or a ratio paper:real (`1:50`) with
    /// the model's unit given by --units. Default: 1 px of the frame is 1/96 inch.
    #[arg(long, value_name = "MM|A:B")]
    scale: Option<String>,
    /// What one model unit is, for a --scale ratio.
    #[arg(long, value_name = "UNIT", default_value = "mm", value_parser = ["mm", "cm", "m", "in", "ft"])]
    units: String,
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
    Cut,
    Hatch,
}

/// The vector formats, by extension.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Svg,
    Pdf,
    Dxf,
}

/// The style file's styles, with the flags that differ from the defaults over them.
fn line_style(args: &DrawArgs) -> anyhow::Result<DrawingStyle> {
    use chamfer_runtime::schema::Schema;
    let mut style = match &args.style_file {
        None => DrawingStyle::default(),
        Some(path) => read_style_file(path)?,
    };
    let (flags, given) = (&args.style.0, &args.style.1);
    // The flags given are set over the file's values.
    for entry in DrawingStyle::ENTRIES {
        if given.contains(&entry.name) {
            if let Some(value) = entry.get(flags) {
                entry.set(&mut style, value)?;
            }
        }
    }
    // The flags alone first, so an error is spelled as the flag or the file's key it came from.
    flags
        .check()
        .map_err(|e| anyhow::anyhow!(e.spelled(chamfer_runtime::schema::flag)))?;
    if let Some(path) = &args.style_file {
        style
            .check()
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    }
    Ok(style)
}

pub fn run(args: &DrawArgs) -> anyhow::Result<()> {
    args.camera.check()?;
    let unit = ModelUnit::named(&args.units).map_err(|e| anyhow::anyhow!("--units: {e}"))?;
    let scale = match &args.scale {
        Some(text) => Some(parse_scale(text, unit).map_err(|e| anyhow::anyhow!("--scale: {e}"))?),
        None => None,
    };
    if unit != ModelUnit::Millimetre && !args.scale.as_deref().is_some_and(|s| s.contains(':')) {
        bail!(
            "--units applies to a --scale ratio (--scale 1:50 --units {})",
            args.units
        );
    }
    let format = match args
        .output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("svg") => Format::Svg,
        Some("pdf") => Format::Pdf,
        Some("dxf") => Format::Dxf,
        _ => bail!(
            "{}: the output must end in .svg, .pdf or .dxf",
            args.output.display()
        ),
    };
    let style = line_style(args)?;
    let plane = drawing_plane(&args.section.0)
        .map_err(|e| anyhow::anyhow!(e.spelled(chamfer_runtime::schema::flag)))?;
    let mut inputs = vec![args.input.as_path()];
    inputs.extend(args.style_file.as_deref());
    ensure_not_an_input(&args.output, &inputs)?;
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
            Class::Cut => LineClass::Cut,
            Class::Hatch => LineClass::Hatch,
        })
        .collect();
    let paper = PaperOptions::DEFAULT.with_mm_per_unit(scale);
    let mm_per_frame_px = paper.mm_per_px_at(units_per_px(&asset, &camera));
    let options = DrawOptions::DEFAULT
        .with_classes(&classes)
        .with_hidden(args.hidden)
        .with_section(plane)
        .with_hatch(style.hatch(mm_per_frame_px));
    let start = Instant::now();
    let drawing = hidden_lines(&asset, &camera, &options);
    let drawn = start.elapsed();

    let name = args.input.file_name().map_or_else(
        || args.input.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let paper = paper.with_title(name).with_description(format!(
        "Camera: chamfer render {}.{}",
        args.camera.describe(),
        plane.as_ref().map(section_note).unwrap_or_default()
    ));
    let start = Instant::now();
    write_atomically(&args.output, |out| match format {
        Format::Svg => write_svg(&drawing, &style, &paper, out),
        Format::Pdf => write_pdf(&drawing, &style, &paper, out),
        Format::Dxf => write_dxf(&drawing, &style, &paper, out),
    })?;
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
        mm_per_px(&drawing, &paper) as f32,
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
