//! OBJ out: a loaded mesh as a new PLY or glTF / GLB (in memory), which `annotate` then marks like
//! any file of that format. Positions are written bit for bit, so the copy welds and bakes as the
//! OBJ does.
//!
//! - PLY (binary little endian): `vertex` (`x y z`, `nx ny nz` and `s t` when the OBJ has them) and
//!   `face` (`vertex_indices`, the triangles the bake uses). PLY has no materials.
//! - glTF / GLB: one node, one mesh, one TRIANGLES primitive per material (each with its own
//!   vertices, unsigned-int indices, unit normals when the OBJ's are usable, and finite texture
//!   coordinates with `v` flipped to glTF's top-left origin), one plain material per OBJ material.

use std::collections::HashMap;

use base64::Engine;
use serde_json::{Value, json};

use crate::mesh::Mesh;

/// The mesh as a binary PLY.
pub(super) fn to_ply(mesh: &Mesh) -> Result<Vec<u8>, String> {
    let mut header = String::from(
        "ply\nformat binary_little_endian 1.0\ncomment written by chamfer annotate from an OBJ\n",
    );
    header += &format!("element vertex {}\n", mesh.positions.len());
    header += "property float x\nproperty float y\nproperty float z\n";
    if mesh.normals.is_some() {
        header += "property float nx\nproperty float ny\nproperty float nz\n";
    }
    if mesh.uvs.is_some() {
        header += "property float s\nproperty float t\n";
    }
    header += &format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.triangles.len()
    );
    let mut out = header.into_bytes();
    for (i, p) in mesh.positions.iter().enumerate() {
        let mut floats = p.to_array().to_vec();
        if let Some(n) = mesh.normals.as_ref().and_then(|n| n.get(i)) {
            floats.extend(n.to_array());
        }
        if let Some(t) = mesh.uvs.as_ref().and_then(|t| t.get(i)) {
            floats.extend(t.to_array());
        }
        out.extend(floats.iter().flat_map(|f| f.to_le_bytes()));
    }
    for triangle in &mesh.triangles {
        out.push(3);
        for &v in triangle {
            let v = i32::try_from(v).map_err(|_| format!("vertex {v} does not fit a PLY int"))?;
            out.extend(v.to_le_bytes());
        }
    }
    Ok(out)
}

/// The mesh as a `.gltf` (buffer embedded) or a GLB.
pub(super) fn to_gltf(mesh: &Mesh, glb: bool) -> Result<Vec<u8>, String> {
    let mut buffer = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut add = |data: Vec<u8>, target: u32, accessor: Value| {
        let offset = buffer.len();
        buffer.extend_from_slice(&data);
        buffer.resize(buffer.len().next_multiple_of(4), 0);
        views.push(json!({
            "buffer": 0, "byteOffset": offset, "byteLength": data.len(), "target": target,
        }));
        let mut accessor = accessor;
        accessor["bufferView"] = json!(views.len() - 1);
        accessors.push(accessor);
        accessors.len() - 1
    };
    let floats = |values: &mut dyn Iterator<Item = f32>| -> Vec<u8> {
        values.flat_map(f32::to_le_bytes).collect()
    };
    // Normals must be unit length in glTF; the OBJ's are used only if every one can be.
    let normals = mesh
        .normals
        .as_ref()
        .filter(|n| n.iter().all(|v| v.is_finite() && v.length_squared() > 0.0));

    let mut materials: Vec<u32> = Vec::new();
    let mut primitives = Vec::new();
    for material in material_groups(mesh) {
        let (id, triangles) = material;
        // The group's own vertices, numbered by first use.
        let mut local: HashMap<u32, u32> = HashMap::new();
        let mut used = Vec::new();
        let mut indices = Vec::with_capacity(3 * triangles.len());
        for &t in &triangles {
            for &v in &mesh.triangles[t] {
                let next = used.len() as u32;
                let k = *local.entry(v).or_insert(next);
                if k == next {
                    used.push(v as usize);
                }
                indices.push(k);
            }
        }
        let positions: Vec<_> = used.iter().map(|&v| mesh.positions[v]).collect();
        let (lo, hi) = positions.iter().fold(
            ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
            |(lo, hi), p| {
                let p = p.to_array();
                (
                    std::array::from_fn(|k| lo[k].min(p[k])),
                    std::array::from_fn(|k| hi[k].max(p[k])),
                )
            },
        );
        let mut attributes = json!({
            "POSITION": add(
                floats(&mut positions.iter().flat_map(|p| p.to_array())),
                34962,
                json!({ "componentType": 5126, "count": used.len(), "type": "VEC3", "min": lo, "max": hi }),
            ),
        });
        if let Some(normals) = normals {
            attributes["NORMAL"] = json!(add(
                floats(&mut used.iter().flat_map(|&v| normals[v].normalize().to_array())),
                34962,
                json!({ "componentType": 5126, "count": used.len(), "type": "VEC3" }),
            ));
        }
        if let Some(uvs) = mesh
            .uvs
            .as_ref()
            .filter(|t| t.iter().all(|t| t.is_finite()))
        {
            attributes["TEXCOORD_0"] = json!(add(
                floats(&mut used.iter().flat_map(|&v| [uvs[v].x, 1.0 - uvs[v].y])),
                34962,
                json!({ "componentType": 5126, "count": used.len(), "type": "VEC2" }),
            ));
        }
        let indices = add(
            indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
            34963,
            json!({ "componentType": 5125, "count": indices.len(), "type": "SCALAR" }),
        );
        let material_index = materials.len();
        materials.push(id);
        primitives.push(json!({
            "attributes": attributes, "indices": indices, "mode": 4, "material": material_index,
        }));
    }
    let mut document = json!({
        "asset": { "version": "2.0", "generator": "chamfer annotate" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": primitives }],
        "materials": materials.iter().map(|id| json!({ "name": format!("OBJ material {id}") })).collect::<Vec<_>>(),
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{ "byteLength": buffer.len() }],
    });
    if !glb {
        document["buffers"][0]["uri"] = json!(format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&buffer)
        ));
        return serde_json::to_vec_pretty(&document).map_err(|e| e.to_string());
    }
    let mut json_chunk = serde_json::to_vec(&document).map_err(|e| e.to_string())?;
    json_chunk.resize(json_chunk.len().next_multiple_of(4), b' ');
    let total = 12 + 8 + json_chunk.len() + 8 + buffer.len();
    let too_big = |_| "the mesh is larger than a GLB can hold (4 GiB)".to_string();
    let total = u32::try_from(total).map_err(too_big)?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend(total.to_le_bytes());
    out.extend((json_chunk.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend_from_slice(&json_chunk);
    out.extend((buffer.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend_from_slice(&buffer);
    Ok(out)
}

/// The triangles of each material, materials in order of first use.
fn material_groups(mesh: &Mesh) -> Vec<(u32, Vec<usize>)> {
    let mut groups: Vec<(u32, Vec<usize>)> = Vec::new();
    let mut index: HashMap<u32, usize> = HashMap::new();
    for t in 0..mesh.triangles.len() {
        let id = mesh.materials.get(t).copied().unwrap_or(0);
        let k = *index.entry(id).or_insert_with(|| {
            groups.push((id, Vec::new()));
            groups.len() - 1
        });
        groups[k].1.push(t);
    }
    groups
}
