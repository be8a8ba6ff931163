//! Marked edges stored in a glTF primitive, in three dialects (all in the primitive's own vertex
//! indices):
//!
//! - Chamfer's own `extras`: `{"chamfer": {"version": 1, "edges": [[a, b, radius], [a, b], ...]}}`;
//!   a missing or null radius means "marked, radius from the bake's rule". `chamfer annotate` writes it.
//! - `CESIUM_primitive_outline`: `{"indices": accessor}`, index pairs of outline edges.
//! - `EXT_mesh_primitive_edge_visibility`: `{"visibility": accessor}`, 2 bits per triangle edge
//!   (edges `v0-v1`, `v1-v2`, `v2-v0` of each triangle in order, low bits first): 0 hidden,
//!   1 silhouette, 2 hard, 3 hard and already listed by another triangle. Hard edges become marks;
//!   silhouettes are left to the runtime's contour test.
//!
//! `extras.chamfer`, when a primitive has it, is the whole truth for that primitive: `chamfer
//! annotate` writes the two extensions beside it for other viewers (every always-drawn edge is hard
//! there, creases included), so reading them too would turn every crease into a mark.

use gltf::json;
use serde::Deserialize;

use super::accessor::Accessors;
use crate::mesh::Mark;

/// The `extras.chamfer` schema version this crate reads and writes.
pub const SCHEMA_VERSION: u32 = 1;

#[derive(Deserialize)]
struct Extras {
    chamfer: Option<ChamferExtras>,
}

#[derive(Deserialize)]
struct ChamferExtras {
    version: u32,
    edges: Vec<Vec<Option<f64>>>,
}

/// The marks of one primitive; `triangles` are its triangles (local indices), `vertex_count` its
/// number of vertices. Marks outside the primitive are errors; an unknown schema version is a warning.
pub(super) fn read(
    accessors: &Accessors,
    primitive: &json::mesh::Primitive,
    triangles: &[[u32; 3]],
    vertex_count: usize,
    warnings: &mut Vec<String>,
    name: &str,
) -> Result<Vec<Mark>, String> {
    let mut marks = Vec::new();
    let check = |v: f64, what: &str| -> Result<u32, String> {
        if v.fract() == 0.0 && v >= 0.0 && (v as usize) < vertex_count {
            Ok(v as u32)
        } else {
            Err(format!(
                "{what}: vertex {v} is not one of the primitive's {vertex_count} vertices"
            ))
        }
    };
    let mut has_chamfer_extras = false;
    if let Some(raw) = &primitive.extras {
        let extras: Extras = serde_json::from_str(raw.get()).map_err(|e| {
            format!("extras.chamfer does not follow schema version {SCHEMA_VERSION}: {e}")
        })?;
        if let Some(chamfer) = extras.chamfer {
            if chamfer.version != SCHEMA_VERSION {
                warnings.push(format!(
                    "{name}: extras.chamfer version {} is not {SCHEMA_VERSION}; its marks are ignored",
                    chamfer.version
                ));
            } else {
                has_chamfer_extras = true;
                for (k, edge) in chamfer.edges.iter().enumerate() {
                    let what = format!("extras.chamfer.edges[{k}]");
                    let (Some(Some(a)), Some(Some(b))) = (edge.first(), edge.get(1)) else {
                        return Err(format!("{what}: expected [a, b] or [a, b, radius]"));
                    };
                    let radius = edge.get(2).copied().flatten().map(|r| r as f32);
                    if radius.is_some_and(|r| !r.is_finite() || r < 0.0) || edge.len() > 3 {
                        return Err(format!("{what}: expected [a, b] or [a, b, radius >= 0]"));
                    }
                    marks.push(Mark {
                        vertices: [check(*a, &what)?, check(*b, &what)?],
                        radius,
                    });
                }
            }
        }
    }
    if has_chamfer_extras {
        return Ok(marks);
    }
    let extension = |key: &str| {
        primitive
            .extensions
            .as_ref()
            .and_then(|e| e.others.get(key))
    };
    let accessor_of = |value: &serde_json::Value, field: &str, ext: &str| {
        value
            .get(field)
            .and_then(serde_json::Value::as_u64)
            .map(|a| a as usize)
            .ok_or_else(|| format!("{ext}: no \"{field}\" accessor"))
    };
    const OUTLINE: &str = "CESIUM_primitive_outline";
    // Mark accessors are bounded by the primitive's own size before they are read, so a huge one
    // cannot cost more than the geometry the limits already allow.
    let bounded = |index: usize, most: usize, ext: &str| {
        let count = accessors.count(index).unwrap_or(0);
        if count > most as u64 {
            Err(format!(
                "{ext}: accessor {index} has {count} elements, more than the {most} that {} triangles can use",
                triangles.len()
            ))
        } else {
            Ok(index)
        }
    };
    if let Some(outline) = extension(OUTLINE) {
        let index = accessor_of(outline, "indices", OUTLINE)?;
        // An outline edge is a triangle edge: at most three pairs per triangle.
        let index = bounded(index, 6 * triangles.len(), OUTLINE)?;
        let pairs = accessors.read_indices(index)?;
        for pair in pairs.chunks_exact(2) {
            let [a, b] = [pair[0], pair[1]].map(f64::from);
            marks.push(Mark {
                vertices: [check(a, OUTLINE)?, check(b, OUTLINE)?],
                radius: None,
            });
        }
    }
    const VISIBILITY: &str = "EXT_mesh_primitive_edge_visibility";
    if let Some(visibility) = extension(VISIBILITY) {
        let needed = (triangles.len() * 6).div_ceil(8);
        let index = accessor_of(visibility, "visibility", VISIBILITY)?;
        let bytes = accessors.read_indices(bounded(index, 2 * needed + 4, VISIBILITY)?)?;
        if bytes.len() < needed {
            return Err(format!(
                "{VISIBILITY}: {} bytes for {} triangles (needs {needed})",
                bytes.len(),
                triangles.len()
            ));
        }
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                let bit = 2 * (3 * t + k);
                let value = (bytes[bit / 8] >> (bit % 8)) & 3;
                if value >= 2 {
                    marks.push(Mark {
                        vertices: [tri[k], tri[(k + 1) % 3]],
                        radius: None,
                    });
                }
            }
        }
    }
    Ok(marks)
}
