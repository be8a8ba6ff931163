//! `chamfer inspect`: what an asset holds, as a table or as JSON for pipelines.

use std::path::PathBuf;

use anyhow::Context;
use chamfer_preprocess::Limits;
use chamfer_preprocess::inspect::summary;
use chamfer_runtime::asset::compact::LOSSLESS_BITS;
use chamfer_runtime::asset::{Asset, SectionKind};
use clap::Args;

/// Show the counts, edge classes and section sizes of a .chamfer asset.
#[derive(Args)]
#[command(after_help = "Examples:
  chamfer inspect model.chamfer
  chamfer inspect model.chamfer --json | jq .edges.crease
  chamfer inspect model.chamfer --timings        (what decoding each section costs)")]
pub struct InspectArgs {
    /// The asset.
    asset: PathBuf,
    /// Print JSON (stable keys: vertices, welded_vertices, triangles, degenerate_triangles, edges, stitch, intersections, motion, precision, bytes).
    #[arg(long)]
    json: bool,
    /// Also decode the file section by section on one thread and print what each section took
    /// (JSON: `decode_ms`).
    #[arg(long)]
    timings: bool,
}

impl InspectArgs {
    /// Inspect `asset` as a table.
    pub fn for_path(asset: PathBuf) -> Self {
        Self {
            asset,
            json: false,
            timings: false,
        }
    }
}

pub fn run(args: &InspectArgs) -> anyhow::Result<()> {
    let bytes = chamfer_preprocess::load::read(&args.asset, &Limits::DEFAULT)?;
    let invalid = || format!("{}: not a valid .chamfer asset", args.asset.display());
    let asset = Asset::decode(&bytes).with_context(invalid)?;
    let precision = Asset::precision(&bytes).with_context(invalid)?;
    let mut report = summary(&asset, bytes.len() as u64, Some(precision));
    if args.timings {
        report["decode_ms"] = decode_times(&bytes).with_context(invalid)?;
    }
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

/// Milliseconds per section of a decode on this thread, in the order the decoder takes them.
fn decode_times(bytes: &[u8]) -> anyhow::Result<serde_json::Value> {
    let times = std::sync::Mutex::new((std::time::Instant::now(), serde_json::Map::new()));
    Asset::decode_observed(bytes, &|kind| {
        if let Ok(mut times) = times.lock() {
            let now = std::time::Instant::now();
            let ms = (now - times.0).as_secs_f64() * 1e3;
            // A section observed twice (checked again once the asset is whole) adds up.
            let entry = times.1.entry(kind.name()).or_insert(0.0.into());
            *entry = (entry.as_f64().unwrap_or(0.0) + ms).into();
            times.0 = now;
        }
    })?;
    let (_, map) = times
        .into_inner()
        .map_err(|_| anyhow::anyhow!("a decode step panicked"))?;
    Ok(map.into())
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
    let m = &r["motion"];
    if let Some(animations) = m["animations"].as_array()
        && (m["joints"].as_u64() > Some(0)
            || !animations.is_empty()
            || m["morph_entries"].as_u64() > Some(0))
    {
        writeln!(
            out,
            "  motion         {} joints moving {} vertices, {} morph targets ({} entries)",
            m["joints"],
            m["skinned_vertices"],
            m["morph_targets"].as_array().map_or(0, Vec::len),
            m["morph_entries"]
        )?;
        for a in animations {
            writeln!(
                out,
                "  animation {}    {} ({:.3} s, {} channels)",
                a["index"],
                a["name"],
                a["duration"].as_f64().unwrap_or(0.0),
                a["channels"]
            )?;
        }
    }
    let p = &r["precision"];
    let exact = |bits: &serde_json::Value| bits.as_u64() == Some(u64::from(LOSSLESS_BITS));
    if exact(&p["position_bits"]) && exact(&p["normal_bits"]) {
        writeln!(
            out,
            "  precision      exact (positions and normals as baked)"
        )?;
    } else {
        writeln!(
            out,
            "  precision      positions on a {}-bit grid, within {:.3e} per axis; normals {}-bit octahedral, within {:.2e} rad",
            p["position_bits"],
            p["position_error"].as_f64().unwrap_or(0.0),
            p["normal_bits"],
            p["normal_error_radians"].as_f64().unwrap_or(0.0)
        )?;
    }
    let b = &r["bytes"];
    writeln!(
        out,
        "  bytes          {} stored ({:.2} per triangle), {} decoded; {:.1} per kept edge (edge + attribute + next + cap sections, decoded)",
        b["total"],
        b["total"].as_f64().unwrap_or(0.0) / r["triangles"].as_f64().unwrap_or(0.0).max(1.0),
        b["decoded_total"],
        b["per_edge"].as_f64().unwrap_or(0.0)
    )?;
    writeln!(
        out,
        "    {:<26} {:>12} {:>12}{}",
        "section",
        "stored",
        "decoded",
        if r.get("decode_ms").is_some() {
            "   decode ms"
        } else {
            ""
        }
    )?;
    let derived = b["per_section"][SectionKind::RenderVertexCounts.name()]
        .as_u64()
        .is_some_and(|n| n > 0)
        || b["per_section"][SectionKind::RenderVertexCountsCoded.name()]
            .as_u64()
            .is_some_and(|n| n > 0);
    for kind in SectionKind::ALL {
        let stored = &b["per_section"][kind.name()];
        let decoded = &b["decoded_per_section"][kind.name()];
        let ms = &r["decode_ms"][kind.name()];
        // Rows for the coded kinds a file does not use are noise.
        if !kind.is_gpu_ready()
            && stored.as_u64() == Some(0)
            && kind != SectionKind::RenderVertexCounts
        {
            continue;
        }
        let note = if derived && kind == SectionKind::RenderPositions {
            "  (repeated from topology_positions by render_vertex_counts)"
        } else {
            ""
        };
        let decoded = if decoded.is_null() {
            "—".to_owned()
        } else {
            decoded.to_string()
        };
        let ms = ms
            .as_f64()
            .map_or(String::new(), |ms| format!(" {ms:>11.2}"));
        writeln!(
            out,
            "    {:<26} {:>12} {:>12}{ms}{note}",
            kind.name(),
            stored.to_string(),
            decoded
        )?;
    }
    Ok(())
}
