//! glTF / GLB out: per triangle primitive, `extras.chamfer` and, if asked, the
//! `EXT_mesh_primitive_edge_visibility` and `CESIUM_primitive_outline` extensions, whose data is
//! appended in new buffer views (the existing buffer bytes are never moved or changed). The
//! buffer and image files it refers to are copied beside the output (`companions.rs`).

use std::borrow::Cow;
use std::collections::HashSet;
use std::path::Path;

use base64::Engine;
use glam::Vec3;
use serde_json::{Map, Value, json};

use super::{Annotated, EdgeKind, EdgeKinds, GltfEdges, MarkedEdges, companions};
use crate::Error;
use crate::load::gltf::PrimitiveSpan;
use crate::load::gltf::marks::SCHEMA_VERSION;
use crate::write::write_atomically;

const GLB_MAGIC: &[u8; 4] = b"glTF";
const JSON_CHUNK: u32 = 0x4E4F_534A;
const BIN_CHUNK: u32 = 0x004E_4942;
const VISIBILITY: &str = "EXT_mesh_primitive_edge_visibility";
const OUTLINE: &str = "CESIUM_primitive_outline";

/// The bake's edges and how the loaded mesh maps back to the file's primitives.
pub(super) struct BakedEdges<'a> {
    pub marked: &'a MarkedEdges,
    /// Every kept edge; `None` when no extension is written.
    pub kinds: Option<&'a EdgeKinds>,
    /// Loaded vertex -> welded vertex.
    pub remap: &'a [u32],
    /// The loaded mesh's triangles.
    pub triangles: &'a [[u32; 3]],
    pub spans: &'a [PrimitiveSpan],
}

pub(super) fn write(
    input: &Path,
    bytes: &[u8],
    output: &Path,
    baked: &BakedEdges,
    dialects: &GltfEdges,
    limit: u64,
) -> Result<Annotated, Error> {
    let invalid = |message: String| Error::Parse {
        path: input.to_owned(),
        format: "glTF",
        message,
    };
    let glb = bytes.starts_with(GLB_MAGIC);
    let chunks = if glb {
        split_glb(bytes).map_err(invalid)?
    } else {
        Chunks {
            json: bytes,
            bin: None,
            rest: &[],
        }
    };
    let mut document: Value =
        serde_json::from_slice(chunks.json).map_err(|e| invalid(e.to_string()))?;
    let mut annotated = Annotated::default();
    let companions = companions::plan(input, output, &document, limit, &mut annotated.warnings)?;
    let mut data = Appended::new(&document);
    let mut used = Vec::new();

    for span in baked.spans {
        let pointer = format!("/meshes/{}/primitives/{}", span.mesh, span.primitive);
        let triangles = local_triangles(baked.triangles, span);
        let welded = |v: u32| baked.remap[(span.first_vertex + v) as usize];
        let primitive = document
            .pointer_mut(&pointer)
            .and_then(Value::as_object_mut)
            .ok_or_else(|| invalid(format!("{pointer} vanished")))?;
        if dialects.extras {
            // Beside the extensions an empty list is written too: extras.chamfer is what Chamfer
            // reads when a primitive has it, and the extensions' hard edges are no marks.
            let keep_empty = dialects.extensions();
            annotated.edges +=
                write_extras(primitive, &triangles, baked.marked, welded, keep_empty)
                    .map_err(|e| invalid(format!("{pointer}: {e}")))?;
        }
        let Some(kinds) = baked.kinds else { continue };
        let mut extensions: Vec<(&str, Value)> = Vec::new();
        if dialects.edge_visibility {
            let encoded = edge_visibility(&triangles, kinds, welded);
            if encoded.hard + encoded.silhouettes > 0 {
                let visibility =
                    data.accessor(&encoded.bits, 5121, encoded.bits.len(), "SCALAR", false);
                let mut extension = json!({ "visibility": visibility });
                if !encoded.normals.is_empty() {
                    let normals = data.accessor(
                        &encoded.normals,
                        5120,
                        encoded.normals.len() / 3,
                        "VEC3",
                        true,
                    );
                    extension["silhouetteNormals"] = json!(normals);
                }
                extensions.push((VISIBILITY, extension));
                annotated.hard_edges += encoded.hard;
                annotated.silhouette_edges += encoded.silhouettes;
            }
        }
        if dialects.primitive_outline {
            let mode = primitive.get("mode").and_then(Value::as_u64).unwrap_or(4);
            if mode != 4 {
                annotated.warnings.push(format!(
                    "{pointer}: {OUTLINE} applies to TRIANGLES primitives only; not written for mode {mode}"
                ));
            } else {
                let pairs = outline(&triangles, kinds, welded);
                if !pairs.is_empty() {
                    let wide = pairs.iter().any(|&i| i > u32::from(u16::MAX));
                    let bytes: Vec<u8> = if wide {
                        pairs.iter().flat_map(|i| i.to_le_bytes()).collect()
                    } else {
                        pairs
                            .iter()
                            .flat_map(|&i| (i as u16).to_le_bytes())
                            .collect()
                    };
                    let component = if wide { 5125 } else { 5123 };
                    let indices = data.accessor(&bytes, component, pairs.len(), "SCALAR", false);
                    extensions.push((OUTLINE, json!({ "indices": indices })));
                    if !dialects.edge_visibility {
                        annotated.hard_edges += pairs.len() / 2;
                    }
                }
            }
        }
        if !extensions.is_empty() {
            let object = primitive
                .entry("extensions")
                .or_insert_with(|| json!({}))
                .as_object_mut()
                .ok_or_else(|| invalid(format!("{pointer}: extensions is not an object")))?;
            for (name, extension) in extensions {
                object.insert(name.into(), extension);
                if !used.contains(&name) {
                    used.push(name);
                }
            }
        }
    }

    let root = document
        .as_object_mut()
        .ok_or_else(|| invalid("the document is not a JSON object".into()))?;
    for name in used {
        let list = root
            .entry("extensionsUsed")
            .or_insert_with(|| json!([]))
            .as_array_mut()
            .ok_or_else(|| invalid("extensionsUsed is not an array".into()))?;
        if !list.iter().any(|n| n == name) {
            list.push(json!(name));
        }
    }
    let bin = data
        .place(root, glb, chunks.bin)
        .map_err(|e| invalid(e.to_string()))?;

    let text = serde_json::to_vec_pretty(&document).map_err(|e| invalid(e.to_string()))?;
    // The files it refers to first: an output is never left naming files that are not there.
    annotated.copied = companions::copy(input, &companions, limit)?;
    write_atomically(output, |out| {
        use std::io::Write;
        if !glb {
            return out.write_all(&text);
        }
        let mut json_chunk = text;
        json_chunk.resize(json_chunk.len().next_multiple_of(4), b' ');
        let bin_chunk_bytes = bin.as_ref().map_or(0, |b| 8 + b.len());
        let total = 12 + 8 + json_chunk.len() + bin_chunk_bytes + chunks.rest.len();
        let too_big = || std::io::Error::other("GLB larger than 4 GiB");
        let total = u32::try_from(total).map_err(|_| too_big())?;
        out.write_all(GLB_MAGIC)?;
        out.write_all(&2u32.to_le_bytes())?;
        out.write_all(&total.to_le_bytes())?;
        out.write_all(&(json_chunk.len() as u32).to_le_bytes())?;
        out.write_all(&JSON_CHUNK.to_le_bytes())?;
        out.write_all(&json_chunk)?;
        if let Some(bin) = &bin {
            out.write_all(&(bin.len() as u32).to_le_bytes())?;
            out.write_all(&BIN_CHUNK.to_le_bytes())?;
            out.write_all(bin)?;
        }
        out.write_all(chunks.rest)
    })?;
    Ok(annotated)
}

/// One primitive's triangles as the file has them: its own vertex numbers, and its corners in the
/// specification's order (the loader swaps two corners of a mirrored instance).
fn local_triangles(triangles: &[[u32; 3]], span: &PrimitiveSpan) -> Vec<[u32; 3]> {
    let first = span.first_triangle as usize;
    triangles[first..first + span.triangle_count as usize]
        .iter()
        .map(|t| {
            let t = if span.mirrored {
                [t[0], t[2], t[1]]
            } else {
                *t
            };
            t.map(|v| v - span.first_vertex)
        })
        .collect()
}

/// Sets the primitive's `extras.chamfer`, each welded edge once at its first occurrence (removes it
/// when there is no edge, unless `keep_empty`); returns the edges written.
fn write_extras(
    primitive: &mut Map<String, Value>,
    triangles: &[[u32; 3]],
    marked: &MarkedEdges,
    welded: impl Fn(u32) -> u32,
    keep_empty: bool,
) -> Result<usize, String> {
    let mut seen = HashSet::new();
    let mut edges = Vec::new();
    for tri in triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (wa, wb) = (welded(a), welded(b));
            let Some((_, radius)) = marked.get(wa, wb) else {
                continue;
            };
            // Once per welded edge: a soup (STL) or split-normal mesh has several vertex pairs
            // for it, and the reader welds them back into one.
            if seen.insert((wa.min(wb), wa.max(wb))) {
                edges.push(if radius > 0.0 {
                    json!([a, b, shortest(radius)])
                } else {
                    json!([a, b])
                });
            }
        }
    }
    let written = edges.len();
    let extras = primitive.entry("extras").or_insert_with(|| json!({}));
    let Some(object) = extras.as_object_mut() else {
        return Err("extras is not an object".into());
    };
    if edges.is_empty() && !keep_empty {
        object.remove("chamfer");
    } else {
        object.insert(
            "chamfer".into(),
            json!({ "version": SCHEMA_VERSION, "edges": edges }),
        );
    }
    if object.is_empty() {
        primitive.remove("extras");
    }
    Ok(written)
}

/// One primitive's `EXT_mesh_primitive_edge_visibility` data.
struct Visibility {
    /// 2 bits per triangle edge, `v0:v1, v1:v2, v2:v0` of each triangle, low bits first.
    bits: Vec<u8>,
    /// Two snorm8 normals (3 bytes each) per silhouette, in the order of their 1 values.
    normals: Vec<u8>,
    hard: usize,
    silhouettes: usize,
}

fn edge_visibility(
    triangles: &[[u32; 3]],
    kinds: &EdgeKinds,
    welded: impl Fn(u32) -> u32,
) -> Visibility {
    let mut encoded = Visibility {
        bits: vec![0; (6 * triangles.len()).div_ceil(8)],
        normals: Vec::new(),
        hard: 0,
        silhouettes: 0,
    };
    let mut seen = HashSet::new();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (welded(tri[k]), welded(tri[(k + 1) % 3]));
            let first = seen.insert((a.min(b), a.max(b)));
            let value = match kinds.get(a, b) {
                Some(EdgeKind::Hard) if first => {
                    encoded.hard += 1;
                    2
                }
                Some(EdgeKind::Hard) => 3,
                Some(EdgeKind::Silhouette(normals)) if first => {
                    encoded.silhouettes += 1;
                    encoded
                        .normals
                        .extend(normals.iter().flat_map(|&n| snorm8(n)));
                    1
                }
                Some(EdgeKind::Silhouette(_)) | None => 0,
            };
            let bit = 2 * (3 * t + k);
            encoded.bits[bit / 8] |= value << (bit % 8);
        }
    }
    encoded
}

/// A unit vector as three normalized signed bytes.
fn snorm8(n: Vec3) -> [u8; 3] {
    n.to_array()
        .map(|c| ((c.clamp(-1.0, 1.0) * 127.0).round() as i8) as u8)
}

/// One primitive's hard edges as index pairs, each welded edge once (at its first occurrence).
fn outline(triangles: &[[u32; 3]], kinds: &EdgeKinds, welded: impl Fn(u32) -> u32) -> Vec<u32> {
    let mut seen = HashSet::new();
    let mut pairs = Vec::new();
    for tri in triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (wa, wb) = (welded(a), welded(b));
            if kinds.get(wa, wb) == Some(EdgeKind::Hard) && seen.insert((wa.min(wb), wa.max(wb))) {
                pairs.extend([a, b]);
            }
        }
    }
    pairs
}

/// Binary data for new accessors, gathered before it is known which buffer it goes to.
#[derive(Default)]
struct Appended {
    bytes: Vec<u8>,
    /// Per new buffer view: (offset in `bytes`, length).
    views: Vec<(usize, usize)>,
    /// Per new accessor: its JSON (with `bufferView` the index in `views`).
    accessors: Vec<Value>,
    /// The document's accessor count before any is added: the first new accessor's index.
    first_accessor: usize,
}

impl Appended {
    fn new(document: &Value) -> Self {
        let first_accessor = document
            .get("accessors")
            .and_then(Value::as_array)
            .map_or(0, Vec::len);
        Self {
            first_accessor,
            ..Self::default()
        }
    }

    /// Adds an accessor over `data` in its own buffer view; returns its index in the document.
    fn accessor(
        &mut self,
        data: &[u8],
        component_type: u32,
        count: usize,
        kind: &str,
        normalized: bool,
    ) -> usize {
        let offset = self.bytes.len();
        self.bytes.extend_from_slice(data);
        self.bytes.resize(self.bytes.len().next_multiple_of(4), 0);
        self.views.push((offset, data.len()));
        let mut accessor = json!({
            "bufferView": self.views.len() - 1,
            "componentType": component_type,
            "count": count,
            "type": kind,
        });
        if normalized {
            accessor["normalized"] = json!(true);
        }
        self.accessors.push(accessor);
        self.first_accessor + self.accessors.len() - 1
    }

    /// Adds the buffer views and accessors to the document and returns the GLB binary chunk to write
    /// (`None`: keep the input's chunks as they are). A GLB's data goes after its binary chunk's
    /// bytes (those stay where they are); a `.gltf` gets a new embedded buffer.
    fn place<'a>(
        self,
        root: &mut Map<String, Value>,
        glb: bool,
        bin: Option<&'a [u8]>,
    ) -> Result<Option<Cow<'a, [u8]>>, String> {
        if self.accessors.is_empty() {
            return Ok(bin.map(Cow::Borrowed));
        }
        let buffers = array(root, "buffers")?;
        let glb_buffer = glb && buffers.first().is_none_or(|b| b.get("uri").is_none());
        let (buffer, base, chunk) = if glb_buffer {
            let mut chunk = bin.map(<[u8]>::to_vec).unwrap_or_default();
            chunk.resize(chunk.len().next_multiple_of(4), 0);
            let base = chunk.len();
            chunk.extend_from_slice(&self.bytes);
            let length = chunk.len();
            if buffers.is_empty() {
                buffers.push(json!({ "byteLength": length }));
            } else {
                buffers[0]["byteLength"] = json!(length);
            }
            (0, base, Some(Cow::Owned(chunk)))
        } else {
            let uri = format!(
                "data:application/octet-stream;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(&self.bytes)
            );
            buffers.push(json!({ "byteLength": self.bytes.len(), "uri": uri }));
            (buffers.len() - 1, 0, bin.map(Cow::Borrowed))
        };
        let views = array(root, "bufferViews")?;
        let first_view = views.len();
        for &(offset, length) in &self.views {
            views.push(json!({
                "buffer": buffer,
                "byteOffset": base + offset,
                "byteLength": length,
            }));
        }
        let accessors = array(root, "accessors")?;
        let first_accessor = accessors.len();
        for mut accessor in self.accessors {
            let view = accessor["bufferView"].as_u64().unwrap_or(0) as usize;
            accessor["bufferView"] = json!(first_view + view);
            accessors.push(accessor);
        }
        debug_assert_eq!(first_accessor, self.first_accessor);
        Ok(chunk)
    }
}

/// `root[key]` as an array, created if missing.
fn array<'a>(root: &'a mut Map<String, Value>, key: &str) -> Result<&'a mut Vec<Value>, String> {
    root.entry(key)
        .or_insert_with(|| json!([]))
        .as_array_mut()
        .ok_or_else(|| format!("{key} is not an array"))
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

/// A GLB's chunks: JSON, the binary chunk if it follows, and everything after (verbatim).
struct Chunks<'a> {
    json: &'a [u8],
    bin: Option<&'a [u8]>,
    rest: &'a [u8],
}

fn split_glb(bytes: &[u8]) -> Result<Chunks<'_>, String> {
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
    let json = &bytes[20..json_end];
    let after = &bytes[json_end..length];
    if after.len() >= 8 && word(json_end + 4)? == BIN_CHUNK as usize {
        let bin_end = (json_end + 8)
            .checked_add(word(json_end)?)
            .filter(|&end| end <= length)
            .ok_or("GLB binary chunk runs past the file")?;
        return Ok(Chunks {
            json,
            bin: Some(&bytes[json_end + 8..bin_end]),
            rest: &bytes[bin_end..length],
        });
    }
    Ok(Chunks {
        json,
        bin: None,
        rest: after,
    })
}
