//! `chamfer inspect`: what an asset holds, as a table or as JSON for pipelines.

use std::path::PathBuf;

use anyhow::Context;
use chamfer_preprocess::Limits;
use chamfer_runtime::asset::{Asset, SectionKind};
use clap::Args;
use serde_json::json;

/// Show the counts, edge classes and section sizes of a .chamfer asset.
#[derive(Args)]
#[command(after_help = "Examples:
  chamfer inspect model.chamfer
  chamfer inspect model.chamfer --json | jq .edges.crease")]
pub struct InspectArgs {
    /// The asset.
    asset: PathBuf,
    /// Print JSON (stable keys: vertices, welded_vertices, triangles, degenerate_triangles, edges, intersections, bytes).
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

/// Bytes of the sections that describe edges, per kept edge: the figure the thesis compares (§11.2).
pub fn edge_bytes(asset: &Asset) -> u64 {
    [
        SectionKind::EdgeVertices,
        SectionKind::EdgeAttributes,
        SectionKind::NextEnds,
        SectionKind::CapHeads,
    ]
    .iter()
    .map(|&k| asset.section_bytes(k).len() as u64)
    .sum()
}

/// The report `--json` prints; the table shows the same numbers.
pub fn summary(asset: &Asset, total_bytes: u64) -> serde_json::Value {
    let s = &asset.header.stats;
    let e = &s.edges;
    // The file's own table when the asset was read from one, else what encoding it writes.
    let table = if asset.header.sections.is_empty() {
        asset.encoded_sections()
    } else {
        asset.header.sections.clone()
    };
    let length = |k: SectionKind| {
        table
            .iter()
            .find(|s| s.kind == k as u32)
            .map_or(0, |s| s.length)
    };
    let per_section: serde_json::Map<String, serde_json::Value> = SectionKind::ALL
        .iter()
        .map(|&k| (k.name().to_owned(), json!(length(k))))
        .collect();
    let per_edge = if asset.edge_count() == 0 {
        0.0
    } else {
        edge_bytes(asset) as f64 / asset.edge_count() as f64
    };
    json!({
        "source": asset.header.source,
        "generator": asset.header.generator,
        "settings": asset.header.settings.iter().cloned().collect::<std::collections::BTreeMap<_, _>>(),
        "vertices": s.input_vertices,
        "welded_vertices": s.welded_vertices,
        "render_vertices": asset.render_positions.len(),
        "input_triangles": s.input_triangles,
        "triangles": asset.triangle_count(),
        "degenerate_triangles": s.degenerate_triangles,
        "edges": {
            "total": e.total,
            "kept": e.kept,
            "boundary": e.boundary,
            "crease": e.crease,
            "ridge": e.ridge,
            "valley": e.valley,
            "marked": e.marked,
            "material": e.material,
            "non_manifold": e.non_manifold,
            "smooth": e.smooth,
            "coplanar_dropped": e.coplanar_dropped,
            "flipped": e.flipped,
            "marks_unmatched": e.marks_unmatched,
        },
        "chamfer": {
            "edges": s.chamfer.edges,
            "clamped": s.chamfer.clamped,
            "radius_min": s.chamfer.radius_min,
            "radius_max": s.chamfer.radius_max,
        },
        "caps": asset.cap_heads.len(),
        "intersections": {
            "segments": asset.intersection_segments.len(),
            "polylines": asset.intersection_starts.len(),
            "closed": asset.intersection_polylines().filter(|p| p.first().map(|s| s[0]) == p.last().map(|s| s[1])).count(),
            "length": asset.intersection_length(),
        },
        "bounds": { "min": asset.header.bounds_min, "max": asset.header.bounds_max },
        "bytes": { "total": total_bytes, "per_section": per_section, "per_edge": per_edge },
    })
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
