//! What an asset holds, as one JSON report: the numbers `chamfer inspect` shows (`--json` prints
//! exactly this) and the Python package's `Asset.stats` returns. Its keys are stable: pipelines
//! read them.

use chamfer_runtime::asset::{Asset, Precision, SectionKind};
use serde_json::json;

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

/// The report of `asset`, whose file is `total_bytes` long (its [`encoded_len`](Asset::encoded_len)
/// when it was never written) and stores positions and normals with `precision` (read from the
/// file with [`Asset::precision`]; `None`: exact): counts, edge classes, chamfer radii,
/// intersections, bounds, the precision, and bytes per section as stored (the file's own section
/// table when the asset was decoded from one, else what encoding it writes) and as decoded (the
/// GPU-ready arrays, what an uncompressed file stores).
pub fn summary(asset: &Asset, total_bytes: u64, precision: Option<Precision>) -> serde_json::Value {
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
    // The arrays a load hands the renderer: the raw kinds, whatever the file stored.
    let decoded: serde_json::Map<String, serde_json::Value> = SectionKind::ALL
        .iter()
        .filter(|k| k.is_gpu_ready())
        .map(|&k| (k.name().to_owned(), json!(asset.section_bytes(k).len())))
        .collect();
    let decoded_total: u64 = decoded.values().filter_map(|v| v.as_u64()).sum();
    let precision = precision.unwrap_or(Precision::EXACT);
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
        "stitch": stitch_report(asset),
        "caps": asset.cap_heads.len(),
        "intersections": {
            "segments": asset.intersection_segments.len(),
            "polylines": asset.intersection_starts.len(),
            "closed": asset.intersection_polylines().filter(|p| p.first().map(|s| s[0]) == p.last().map(|s| s[1])).count(),
            "length": asset.intersection_length(),
        },
        "motion": motion_report(asset),
        "bounds": { "min": asset.header.bounds_min, "max": asset.header.bounds_max },
        "precision": {
            "position_bits": precision.position_bits,
            "position_error": precision.position_error,
            "normal_bits": precision.normal_bits,
            "normal_error_radians": precision.normal_error,
        },
        "bytes": {
            "total": total_bytes,
            "per_section": per_section,
            "decoded_per_section": decoded,
            "decoded_total": decoded_total,
            "per_edge": per_edge,
        },
    })
}

/// What moves an animated asset (all zero and empty for a still one): its joints, the topology
/// vertices they move, the morph targets (names, entries), the animations (number, name, length,
/// channels), as `--animation` and `--animation-name` take them.
fn motion_report(asset: &Asset) -> serde_json::Value {
    let motion = &asset.motion;
    let rig = &motion.rig;
    json!({
        "joints": rig.joints.len(),
        "skinned_vertices": motion.weights.iter().filter(|w| w.iter().any(|&x| x != 0.0)).count(),
        "morph_targets": rig.morph_names,
        "morph_entries": motion.morph_vertices.len(),
        "animations": rig.animations.iter().enumerate().map(|(i, a)| json!({
            "index": i,
            "name": a.name,
            "duration": a.duration(),
            "channels": a.channels.len(),
        })).collect::<Vec<_>>(),
    })
}

/// What stitching did, from the settings the bake recorded: its tolerance (`"off"`, or absent in
/// assets baked before stitching existed), the boundary edges before it and those left.
fn stitch_report(asset: &Asset) -> serde_json::Value {
    let setting = |key: &str| {
        asset
            .header
            .settings
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.clone())
    };
    let remaining = asset.header.stats.edges.boundary;
    let before = setting(crate::bake::STITCH_BOUNDARY_BEFORE).and_then(|v| v.parse::<u64>().ok());
    json!({
        "tolerance": setting("stitch"),
        "boundary_before": before,
        "stitched": before.map(|b| b.saturating_sub(remaining)),
        "remaining": remaining,
    })
}
