//! glTF / GLB out: the JSON gains `extras.chamfer` per primitive; buffers stay as they are.

use std::collections::HashSet;
use std::path::Path;

use serde_json::{Value, json};

use super::MarkedEdges;
use crate::Error;
use crate::load::gltf::PrimitiveSpan;
use crate::load::gltf::marks::SCHEMA_VERSION;
use crate::write::write_atomically;

const GLB_MAGIC: &[u8; 4] = b"glTF";
const JSON_CHUNK: u32 = 0x4E4F_534A;

pub(super) fn write(
    input: &Path,
    bytes: &[u8],
    output: &Path,
    marked: &MarkedEdges,
    remap: &[u32],
    triangles: &[[u32; 3]],
    spans: &[PrimitiveSpan],
) -> Result<usize, Error> {
    let invalid = |message: String| Error::Parse {
        path: input.to_owned(),
        format: "glTF",
        message,
    };
    let glb = bytes.starts_with(GLB_MAGIC);
    let (json_bytes, rest) = if glb {
        split_glb(bytes).map_err(invalid)?
    } else {
        (bytes, &[][..])
    };
    let mut document: Value =
        serde_json::from_slice(json_bytes).map_err(|e| invalid(e.to_string()))?;

    let mut written = 0;
    for span in spans {
        let mut seen = HashSet::new();
        let mut edges = Vec::new();
        let first = span.first_triangle as usize;
        for tri in &triangles[first..first + span.triangle_count as usize] {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let Some((_, radius)) = marked.get(remap[a as usize], remap[b as usize]) else {
                    continue;
                };
                let local = [a - span.first_vertex, b - span.first_vertex];
                if seen.insert((local[0].min(local[1]), local[0].max(local[1]))) {
                    edges.push(if radius > 0.0 {
                        json!([local[0], local[1], shortest(radius)])
                    } else {
                        json!([local[0], local[1]])
                    });
                }
            }
        }
        written += edges.len();
        let primitive = document
            .pointer_mut(&format!(
                "/meshes/{}/primitives/{}",
                span.mesh, span.primitive
            ))
            .and_then(Value::as_object_mut)
            .ok_or_else(|| {
                invalid(format!(
                    "mesh {} primitive {} vanished",
                    span.mesh, span.primitive
                ))
            })?;
        let extras = primitive.entry("extras").or_insert_with(|| json!({}));
        if !extras.is_object() {
            return Err(invalid(format!(
                "mesh {} primitive {}: extras is not an object",
                span.mesh, span.primitive
            )));
        }
        if let Some(extras) = extras.as_object_mut() {
            if edges.is_empty() {
                extras.remove("chamfer");
            } else {
                extras.insert(
                    "chamfer".into(),
                    json!({ "version": SCHEMA_VERSION, "edges": edges }),
                );
            }
        }
        if primitive
            .get("extras")
            .and_then(Value::as_object)
            .is_some_and(|e| e.is_empty())
        {
            primitive.remove("extras");
        }
    }

    let text = serde_json::to_vec_pretty(&document).map_err(|e| invalid(e.to_string()))?;
    write_atomically(output, |out| {
        use std::io::Write;
        if !glb {
            return out.write_all(&text);
        }
        let mut json_chunk = text;
        json_chunk.resize(json_chunk.len().next_multiple_of(4), b' ');
        let total = 12 + 8 + json_chunk.len() + rest.len();
        let total =
            u32::try_from(total).map_err(|_| std::io::Error::other("GLB larger than 4 GiB"))?;
        out.write_all(GLB_MAGIC)?;
        out.write_all(&2u32.to_le_bytes())?;
        out.write_all(&total.to_le_bytes())?;
        out.write_all(&(json_chunk.len() as u32).to_le_bytes())?;
        out.write_all(&JSON_CHUNK.to_le_bytes())?;
        out.write_all(&json_chunk)?;
        out.write_all(rest)
    })?;
    Ok(written)
}

/// An f32 as the shortest decimal that reads back as the same f32 (0.05, not 0.05000000074505806).
fn shortest(value: f32) -> Value {
    value
        .to_string()
        .parse::<f64>()
        .ok()
        .and_then(serde_json::Number::from_f64)
        .map_or(Value::Null, Value::Number)
}

/// The JSON chunk of a GLB and everything after it (the binary chunk and any others, verbatim).
fn split_glb(bytes: &[u8]) -> Result<(&[u8], &[u8]), String> {
    let word = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
            .ok_or("truncated GLB header")
    };
    let length = word(8)?.min(bytes.len());
    let (json_length, kind) = (word(12)?, word(16)?);
    if kind != JSON_CHUNK as usize {
        return Err("the first GLB chunk is not JSON".into());
    }
    let json_end = 20usize
        .checked_add(json_length)
        .filter(|&end| end <= length)
        .ok_or("GLB JSON chunk runs past the file")?;
    Ok((&bytes[20..json_end], &bytes[json_end..length]))
}
