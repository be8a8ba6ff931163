//! The compact sections of format 5 (issue 24): what a shipped asset stores instead of the raw
//! arrays, and how they turn back into the same GPU-ready arrays.
//!
//! | coded section | replaces | payload (little-endian) |
//! |---|---|---|
//! | [`MeshIndicesCoded`](SectionKind::MeshIndicesCoded) | mesh indices | `u32` triangles, then meshoptimizer's index codec |
//! | [`TopologyPositionsCoded`](SectionKind::TopologyPositionsCoded) | topology positions | `u32` count, `u32` bits; for 1–16 bits a [`Grid`] (origin, step: 6 × `f32`) and `[u16; 4]` grid points, for 32 the `[f32; 3]` themselves; meshoptimizer's vertex codec |
//! | [`RenderNormalsCoded`](SectionKind::RenderNormalsCoded) | render normals | `u32` count, `u32` bits; for 2–16 bits `[i16; 2]` octahedral codes, for 32 the `[f32; 3]`; vertex codec |
//! | [`EdgeCorners`](SectionKind::EdgeCorners) | edge vertices | `u32` edges, then one bit per mesh corner ([`edges`]) |
//! | [`EdgeAttributesCoded`](SectionKind::EdgeAttributesCoded) | edge attributes | `u32` count; vertex codec of the words |
//! | [`RingOrders`](SectionKind::RingOrders) | next ends and cap heads | `u64` bits of code, then the ring codes in whole `u64` words ([`rings`]) |
//! | [`RenderVertexCountsCoded`](SectionKind::RenderVertexCountsCoded) | render vertex counts | `u32` count; vertex codec of the bytes, four per element |
//!
//! Edge clusters are not stored: the loader computes them from the decoded edges (an empty
//! [`EdgeClusters`](SectionKind::EdgeClusters) section in format 5 means "compute them").
//! Corner-relative edges need the mesh's topology triangles, which the render vertex counts give.
//!
//! The codecs are meshoptimizer's (zeux), whose reference encoder the bake calls through the
//! [`Codecs`] it is given; the decoders here are safe Rust ([`vertex_codec`], [`index_codec`]).

mod edges;
mod index_codec;
pub mod quantize;
mod rings;
mod vertex_codec;

use super::{Asset, DecodeError, SectionKind};
pub use quantize::Grid;
use vertex_codec::CodecError;

/// The stored value of `bits` that keeps the `f32` numbers themselves (lossless).
pub const LOSSLESS_BITS: u32 = 32;

/// How [`Asset::encode_compact`] stores the lossy sections.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CompactOptions {
    /// Bits per axis of the topology positions' grid (1 to 16), or [`LOSSLESS_BITS`].
    pub position_bits: u32,
    /// Bits per component of the normals' octahedral codes (2 to 16), or [`LOSSLESS_BITS`].
    pub normal_bits: u32,
}

impl Default for CompactOptions {
    fn default() -> Self {
        Self {
            position_bits: 16,
            normal_bits: 12,
        }
    }
}

impl CompactOptions {
    /// Every number lossless: the decoded asset equals the encoded one.
    pub const LOSSLESS: Self = Self {
        position_bits: LOSSLESS_BITS,
        normal_bits: LOSSLESS_BITS,
    };

    /// Why these options cannot be used, if they cannot.
    pub fn check(&self) -> Result<(), String> {
        if !(1..=16).contains(&self.position_bits) && self.position_bits != LOSSLESS_BITS {
            return Err(format!(
                "position bits must be 1 to 16, or {LOSSLESS_BITS} for lossless; got {}",
                self.position_bits
            ));
        }
        if !(2..=16).contains(&self.normal_bits) && self.normal_bits != LOSSLESS_BITS {
            return Err(format!(
                "normal bits must be 2 to 16, or {LOSSLESS_BITS} for lossless; got {}",
                self.normal_bits
            ));
        }
        Ok(())
    }
}

/// The reference encoders of the two meshoptimizer codecs (the bake passes the `meshopt` crate's).
pub trait Codecs {
    /// `meshopt_encodeVertexBuffer` of `data`, vertices of `stride` bytes (a multiple of 4).
    fn encode_vertices(&self, data: &[u8], stride: usize) -> Vec<u8>;
    /// `meshopt_encodeIndexBuffer` of a triangle list whose indices are below `vertex_count`.
    fn encode_triangles(&self, indices: &[u32], vertex_count: usize) -> Vec<u8>;
}

/// The coded sections of `asset`, each with the raw section it replaces; sections that cannot be
/// coded (see each encoder) stay raw.
pub(crate) fn encode(
    asset: &Asset,
    options: &CompactOptions,
    render_counts: Option<&[u8]>,
    codecs: &dyn Codecs,
) -> Vec<(SectionKind, Vec<u8>)> {
    let mut coded = Vec::new();
    let mut triangles = asset.mesh_indices.to_u32_vec();
    if !triangles.is_empty() {
        let stream = codecs.encode_triangles(&triangles, asset.render_normals.len());
        // The codec may rotate a triangle's corners: the edges are coded against the triangles
        // the loader will see.
        match index_codec::decode(&stream, triangles.len() / 3) {
            Ok(decoded) => triangles = decoded,
            Err(e) => panic!(
                "chamfer: the index codec's output does not decode ({e:?}); please report this"
            ),
        }
        let mut bytes = count_prefix(triangles.len() / 3);
        bytes.extend(stream);
        coded.push((SectionKind::MeshIndicesCoded, bytes));
    }
    coded.push((
        SectionKind::TopologyPositionsCoded,
        encode_positions(asset, options.position_bits, codecs),
    ));
    coded.push((
        SectionKind::RenderNormalsCoded,
        encode_normals(&asset.render_normals, options.normal_bits, codecs),
    ));
    coded.push((
        SectionKind::EdgeAttributesCoded,
        encode_words(&asset.edge_attributes, codecs),
    ));
    let Some(counts) = render_counts else {
        return coded;
    };
    let mut padded = counts.to_vec();
    padded.resize(counts.len().next_multiple_of(4), 0);
    let mut bytes = count_prefix(counts.len());
    bytes.extend(codecs.encode_vertices(&padded, 4));
    coded.push((SectionKind::RenderVertexCountsCoded, bytes));

    let topology = topology_triangles(&triangles, counts);
    let vertex_count = asset.topology_positions.len();
    let corners = edges::VertexCorners::new(&topology, vertex_count);
    let edge_vertices = asset.edge_vertices.to_u32_vec();
    if let Some(bits) = edges::encode(&edge_vertices, &topology, &corners) {
        let mut bytes = count_prefix(asset.edge_count());
        bytes.extend(bits);
        coded.push((SectionKind::EdgeCorners, bytes));
    }
    if asset.next_ends.is_empty() {
        return coded;
    }
    let end_vertices = end_vertices(&edge_vertices);
    let code = rings::VertexEnds::new(&end_vertices, vertex_count)
        .ok()
        .and_then(|ends| {
            rings::encode(
                &asset.next_ends.to_u32_vec(),
                &asset.cap_heads.to_u32_vec(),
                &ends,
            )
        });
    if let Some((code, bits)) = code {
        let mut bytes = bits.to_le_bytes().to_vec();
        bytes.extend(code);
        coded.push((SectionKind::RingOrders, bytes));
    }
    coded
}

fn count_prefix(count: usize) -> Vec<u8> {
    (count as u32).to_le_bytes().to_vec()
}

fn encode_positions(asset: &Asset, bits: u32, codecs: &dyn Codecs) -> Vec<u8> {
    let positions = &asset.topology_positions;
    let mut bytes = count_prefix(positions.len());
    bytes.extend(bits.to_le_bytes());
    if bits == LOSSLESS_BITS {
        bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(positions), 12));
        return bytes;
    }
    let grid = Grid::spanning(bits, asset.header.bounds_min, asset.header.bounds_max);
    for v in grid.origin.iter().chain(&grid.step) {
        bytes.extend(v.to_le_bytes());
    }
    let points: Vec<[u16; 4]> = positions
        .iter()
        .map(|&p| {
            let [x, y, z] = grid.quantize(p);
            [x, y, z, 0]
        })
        .collect();
    bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(&points), 8));
    bytes
}

fn encode_normals(normals: &[[f32; 3]], bits: u32, codecs: &dyn Codecs) -> Vec<u8> {
    let mut bytes = count_prefix(normals.len());
    bytes.extend(bits.to_le_bytes());
    if bits == LOSSLESS_BITS {
        bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(normals), 12));
        return bytes;
    }
    let codes: Vec<[i16; 2]> = normals
        .iter()
        .map(|&n| quantize::encode_octahedral(n, bits))
        .collect();
    bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(&codes), 4));
    bytes
}

fn encode_words(words: &[u32], codecs: &dyn Codecs) -> Vec<u8> {
    let mut bytes = count_prefix(words.len());
    bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(words), 4));
    bytes
}

/// The topology triangles: each render vertex of `triangles` replaced by the topology vertex whose
/// position it repeats (`counts[v]` render vertices per topology vertex, in order). Every index must
/// be below the counts' sum.
fn topology_triangles(triangles: &[u32], counts: &[u8]) -> Vec<u32> {
    let mut topology_of = Vec::with_capacity(counts.iter().map(|&c| usize::from(c)).sum());
    for (v, &count) in counts.iter().enumerate() {
        topology_of.extend(std::iter::repeat_n(v as u32, usize::from(count)));
    }
    triangles.iter().map(|&r| topology_of[r as usize]).collect()
}

/// The vertex of every edge end (`2 * edge + end`: `v0`, then `v1`).
fn end_vertices(edge_vertices: &[u32]) -> Vec<u32> {
    edge_vertices
        .chunks_exact(4)
        .flat_map(|e| [e[0], e[1]])
        .collect()
}

/// Reads coded sections; every count is checked against what the stream can hold, and against
/// `limit` (elements), before it is allocated.
pub(crate) struct Reader {
    /// The most elements any coded section may declare: three per triangle, and at least 65 536.
    pub(crate) limit: usize,
}

fn coding_error(kind: SectionKind, reason: impl Into<String>) -> DecodeError {
    DecodeError::BadCoding {
        kind,
        reason: reason.into(),
    }
}

fn codec_error(kind: SectionKind) -> impl Fn(CodecError) -> DecodeError {
    move |e| coding_error(kind, e.reason())
}

fn split_u32(kind: SectionKind, bytes: &[u8]) -> Result<(u32, &[u8]), DecodeError> {
    let (head, rest) = bytes
        .split_first_chunk::<4>()
        .ok_or_else(|| coding_error(kind, "shorter than its 4-byte prefix"))?;
    Ok((u32::from_le_bytes(*head), rest))
}

impl Reader {
    fn count<'a>(
        &self,
        kind: SectionKind,
        bytes: &'a [u8],
    ) -> Result<(usize, &'a [u8]), DecodeError> {
        let (count, rest) = split_u32(kind, bytes)?;
        let count = count as usize;
        if count > self.limit {
            return Err(coding_error(
                kind,
                format!(
                    "declares {count} elements, more than the {} this asset's triangles allow",
                    self.limit
                ),
            ));
        }
        Ok((count, rest))
    }

    /// Triangle indices (unchecked against the render vertex count: the caller checks them).
    pub(crate) fn mesh_indices(bytes: &[u8]) -> Result<Vec<u32>, DecodeError> {
        let kind = SectionKind::MeshIndicesCoded;
        let (triangles, rest) = split_u32(kind, bytes)?;
        index_codec::decode(rest, triangles as usize).map_err(codec_error(kind))
    }

    /// Positions on a grid, or lossless.
    pub(crate) fn positions(&self, bytes: &[u8]) -> Result<Vec<[f32; 3]>, DecodeError> {
        let kind = SectionKind::TopologyPositionsCoded;
        let (count, rest) = self.count(kind, bytes)?;
        let (bits, rest) = split_u32(kind, rest)?;
        if bits == LOSSLESS_BITS {
            return self.floats(kind, rest, count);
        }
        if !(1..=16).contains(&bits) {
            return Err(coding_error(
                kind,
                format!("{bits} bits per axis (1 to 16, or 32)"),
            ));
        }
        let (numbers, rest) = rest
            .split_first_chunk::<24>()
            .ok_or_else(|| coding_error(kind, "shorter than its grid"))?;
        let number = |k: usize| {
            f32::from_le_bytes([
                numbers[4 * k],
                numbers[4 * k + 1],
                numbers[4 * k + 2],
                numbers[4 * k + 3],
            ])
        };
        let grid = Grid {
            bits,
            origin: std::array::from_fn(number),
            step: std::array::from_fn(|k| number(3 + k)),
        };
        if !grid.origin.iter().chain(&grid.step).all(|v| v.is_finite())
            || grid.step.iter().any(|&s| s < 0.0)
        {
            return Err(coding_error(
                kind,
                "grid origin or step not finite, or a step negative",
            ));
        }
        let points = vertex_codec::decode(rest, count, 8).map_err(codec_error(kind))?;
        let positions: Vec<[f32; 3]> = points
            .chunks_exact(8)
            .map(|p| {
                grid.position([
                    u16::from_le_bytes([p[0], p[1]]),
                    u16::from_le_bytes([p[2], p[3]]),
                    u16::from_le_bytes([p[4], p[5]]),
                ])
            })
            .collect();
        // A grid point past `2^bits - 1`, or one whose position overflows, is not a position.
        let top = (1u32 << bits) - 1;
        if let Some(position) = points.chunks_exact(8).position(|p| {
            [0, 2, 4]
                .iter()
                .any(|&k| u32::from(u16::from_le_bytes([p[k], p[k + 1]])) > top)
        }) {
            return Err(DecodeError::Invalid {
                kind,
                position: position as u64,
                reason: format!("grid point beyond {bits} bits"),
            });
        }
        finite(kind, &positions)?;
        Ok(positions)
    }

    /// Unit normals from octahedral codes, or lossless.
    pub(crate) fn normals(&self, bytes: &[u8]) -> Result<Vec<[f32; 3]>, DecodeError> {
        let kind = SectionKind::RenderNormalsCoded;
        let (count, rest) = self.count(kind, bytes)?;
        let (bits, rest) = split_u32(kind, rest)?;
        if bits == LOSSLESS_BITS {
            return self.floats(kind, rest, count);
        }
        if !(2..=16).contains(&bits) {
            return Err(coding_error(
                kind,
                format!("{bits} bits per component (2 to 16, or 32)"),
            ));
        }
        let codes = vertex_codec::decode(rest, count, 4).map_err(codec_error(kind))?;
        let scale = (1i32 << (bits - 1)) - 1;
        let mut normals = Vec::with_capacity(count);
        for (position, c) in codes.chunks_exact(4).enumerate() {
            let code = [
                i16::from_le_bytes([c[0], c[1]]),
                i16::from_le_bytes([c[2], c[3]]),
            ];
            if code.iter().any(|&v| i32::from(v).abs() > scale) {
                return Err(DecodeError::Invalid {
                    kind,
                    position: position as u64,
                    reason: format!("octahedral code beyond {bits} bits"),
                });
            }
            normals.push(quantize::decode_octahedral(code, bits));
        }
        Ok(normals)
    }

    fn floats(
        &self,
        kind: SectionKind,
        rest: &[u8],
        count: usize,
    ) -> Result<Vec<[f32; 3]>, DecodeError> {
        let bytes = vertex_codec::decode(rest, count, 12).map_err(codec_error(kind))?;
        let values: Vec<[f32; 3]> = bytes
            .chunks_exact(12)
            .map(|c| {
                std::array::from_fn(|k| {
                    f32::from_le_bytes([c[4 * k], c[4 * k + 1], c[4 * k + 2], c[4 * k + 3]])
                })
            })
            .collect();
        finite(kind, &values)?;
        Ok(values)
    }

    /// The edge attribute words.
    pub(crate) fn words(&self, kind: SectionKind, bytes: &[u8]) -> Result<Vec<u32>, DecodeError> {
        let (count, rest) = self.count(kind, bytes)?;
        let bytes = vertex_codec::decode(rest, count, 4).map_err(codec_error(kind))?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// The render vertex counts.
    pub(crate) fn counts(&self, bytes: &[u8]) -> Result<Vec<u8>, DecodeError> {
        let kind = SectionKind::RenderVertexCountsCoded;
        let (count, rest) = self.count(kind, bytes)?;
        let mut counts =
            vertex_codec::decode(rest, count.div_ceil(4), 4).map_err(codec_error(kind))?;
        if counts[count..].iter().any(|&c| c != 0) {
            return Err(coding_error(
                kind,
                "padding after the last count is not zero",
            ));
        }
        counts.truncate(count);
        Ok(counts)
    }

    /// The edges (four topology vertices each) of the corner bits over `topology` triangles.
    pub(crate) fn edges(
        &self,
        bytes: &[u8],
        topology: &[u32],
        vertex_count: usize,
    ) -> Result<Vec<u32>, DecodeError> {
        let kind = SectionKind::EdgeCorners;
        let (count, bits) = self.count(kind, bytes)?;
        let corners = edges::VertexCorners::new(topology, vertex_count);
        edges::decode(bits, count, topology, &corners).map_err(|reason| coding_error(kind, reason))
    }

    /// The next ends and cap heads of the ring code over `edge_vertices`.
    pub(crate) fn rings(
        bytes: &[u8],
        edge_vertices: &[u32],
        vertex_count: usize,
    ) -> Result<(Vec<u32>, Vec<u32>), DecodeError> {
        let kind = SectionKind::RingOrders;
        let (bits, code) = bytes
            .split_first_chunk::<8>()
            .ok_or_else(|| coding_error(kind, "shorter than its 8-byte prefix"))?;
        let bits = u64::from_le_bytes(*bits);
        if bits.div_ceil(64) * 8 != code.len() as u64 {
            return Err(coding_error(
                kind,
                format!("{bits} bits of code in {} bytes", code.len()),
            ));
        }
        let end_vertices = end_vertices(edge_vertices);
        let ends =
            rings::VertexEnds::new(&end_vertices, vertex_count).map_err(|(vertex, ends)| {
                DecodeError::RingTooLong {
                    vertex,
                    ends,
                    limit: super::MAX_RING,
                }
            })?;
        rings::decode(code, bits, &ends, end_vertices.len())
            .map_err(|reason| coding_error(kind, reason))
    }
}

/// The topology triangles of render `triangles` (indices already checked against the counts' sum).
pub(crate) fn topology_of(triangles: &[u32], counts: &[u8]) -> Vec<u32> {
    topology_triangles(triangles, counts)
}

fn finite(kind: SectionKind, values: &[[f32; 3]]) -> Result<(), DecodeError> {
    match values.iter().position(|v| !v.iter().all(|x| x.is_finite())) {
        Some(position) => Err(DecodeError::NonFinite {
            kind,
            position: position as u64,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests;
