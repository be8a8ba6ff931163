//! `chamfer inspect`: what an asset holds, as a table or as JSON for pipelines.

use std::path::PathBuf;

use anyhow::Context;
use chamfer_preprocess::Limits;
use chamfer_preprocess::inspect::summary;
use chamfer_runtime::asset::{Asset, SectionKind};
use clap::Args;

/// Show the counts, edge classes and section sizes of a .chamfer asset.
#[derive(Args)]
#[command(after_help = "Examples:
  chamfer inspect model.chamfer
  chamfer inspect model.chamfer --json | jq .edges.crease")]
pub struct InspectArgs {
    /// The asset.
    asset: PathBuf,
    /// Print JSON (stable keys: vertices, welded_vertices, triangles, degenerate_triangles, edges, stitch, intersections, bytes).
    #[arg(long)]
    json: bool,
}

impl InspectArgs {
    /// Inspect `asset` as a table.
    pub fn for_path(asset: PathBuf) -> Self {
        Self { asset, json: false }
    }
}

pub fn run(args: &InspectArgs) -> anyhow::Result<()> {
    let bytes = chamfer_preprocess::load::read(&args.asset, &Limits::DEFAULT)?;
    let asset = Asset::decode(&bytes)
        .with_context(|| format!("{}: not a valid .chamfer asset", args.asset.display()))?;
    let report = summary(&asset, bytes.len() as u64);
    if args.json {
        crate::say(serde_json::to_string_pretty(&report)?)
    } else {
        let mut text = String::new();
        table(
            &mut text,
            &args.asset.display().to_string(),
            &asset,
            &report,
        )?;
        crate::say(text.trim_end())
    }
}

/// The readable report: the same numbers as `--json`.
fn table(out: &mut String, name: &str, asset: &Asset, r: &serde_json::Value) -> std::fmt::Result {
    use std::fmt::Write;
    writeln!(
        out,
        "{name}  ({}, baked from {})",
        asset.header.generator, asset.header.source
    )?;
    let settings: Vec<String> = asset
        .header
        .settings
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect();
    writeln!(out, "  settings       {}", settings.join(" "))?;
    writeln!(
        out,
        "  vertices       {} input, {} welded, {} render",
        r["vertices"], r["welded_vertices"], r["render_vertices"]
    )?;
    writeln!(
        out,
        "  triangles      {} ({} input, {} degenerate skipped)",
        r["triangles"], r["input_triangles"], r["degenerate_triangles"]
    )?;
    let e = &r["edges"];
    writeln!(
        out,
        "  edges          {} unique, {} kept, {} coplanar dropped",
        e["total"], e["kept"], e["coplanar_dropped"]
    )?;
    for class in [
        "boundary",
        "crease",
        "ridge",
        "valley",
        "marked",
        "material",
        "non_manifold",
        "smooth",
        "flipped",
        "marks_unmatched",
    ] {
        writeln!(out, "    {class:<14} {}", e[class])?;
    }
    let st = &r["stitch"];
    match st["tolerance"].as_str() {
        None | Some("off") => writeln!(out, "  stitch         off")?,
        Some(tolerance) => writeln!(
            out,
            "  stitch         within {tolerance}: {} boundary edges stitched, {} remain",
            st["stitched"], st["remaining"]
        )?,
    }
    let c = &r["chamfer"];
    writeln!(
        out,
        "  chamfer        {} edges with a radius ({} clamped), radius {:.6} .. {:.6}",
        c["edges"],
        c["clamped"],
        c["radius_min"].as_f64().unwrap_or(0.0),
        c["radius_max"].as_f64().unwrap_or(0.0)
    )?;
    writeln!(
        out,
        "  caps           {} vertices where two or more kept edges meet",
        r["caps"]
    )?;
    let i = &r["intersections"];
    writeln!(
        out,
        "  intersections  {} segments in {} polylines ({} closed), length {:.6}",
        i["segments"],
        i["polylines"],
        i["closed"],
        i["length"].as_f64().unwrap_or(0.0)
    )?;
    let b = &r["bytes"];
    writeln!(
        out,
        "  bytes          {} total, {:.1} per kept edge (edge + attribute + next + cap sections)",
        b["total"],
        b["per_edge"].as_f64().unwrap_or(0.0)
    )?;
    let derived = b["per_section"][SectionKind::RenderVertexCounts.name()]
        .as_u64()
        .is_some_and(|n| n > 0);
    for kind in SectionKind::ALL {
        let note = if derived && kind == SectionKind::RenderPositions {
            "  (repeated from topology_positions by render_vertex_counts)"
        } else {
            ""
        };
        writeln!(
            out,
            "    {:<18} {}{note}",
            kind.name(),
            b["per_section"][kind.name()]
        )?;
    }
    Ok(())
}
