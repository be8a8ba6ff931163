//! Reading the coded sections, one function each. Every count a section declares is checked
//! against a limit (three elements per triangle the file's index stream can hold, and at least
//! 65 536) and every stream against the bytes it needs before anything is allocated, so a compact
//! file's decoded size is at most a fixed multiple of its own.

use super::super::clusters::{EdgeCluster, cluster_count};
use super::super::{DecodeError, MAX_RING, SectionKind};
use super::edges::{CornerBits, VertexCorners};
use super::quantize::{self, Grid};
use super::rings::{self, RingError};
use super::vertex_codec::{self, CodecError};
use super::{LOSSLESS_BITS, Precision, bounds, index_codec};

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

/// The most triangles a coded index section of this length can hold (a code byte each, after a
/// header byte and before a 16-byte table).
pub(crate) fn triangle_capacity(bytes: &[u8]) -> usize {
    bytes.len().saturating_sub(4 + 1 + 16)
}

/// Reads coded sections within a limit.
pub(crate) struct Reader {
    /// The most elements any coded section may declare.
    pub(crate) limit: usize,
}

impl Reader {
    /// The limit of a file whose triangles are at most `triangles`.
    pub(crate) fn for_triangles(triangles: usize) -> Self {
        Self {
            limit: triangles.saturating_mul(3).max(1 << 16),
        }
    }

    /// The number of elements a coded section (other than [`SectionKind::RingOrders`] and
    /// [`SectionKind::MeshIndicesCoded`]) declares, within the limit.
    pub(crate) fn declared(&self, kind: SectionKind, bytes: &[u8]) -> Result<usize, DecodeError> {
        Ok(self.count(kind, bytes)?.0)
    }

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
    pub(crate) fn mesh_indices(&self, bytes: &[u8]) -> Result<Vec<u32>, DecodeError> {
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
            return floats(kind, rest, count);
        }
        let (grid, rest) = read_grid(bits, rest)?;
        // The grid points (8 bytes) are decoded into the front of the positions (12 bytes) and
        // widened in place from the back, so the points need no buffer of their own.
        vertex_codec::fits(rest, count, 8).map_err(codec_error(kind))?;
        let mut positions = vec![[0.0f32; 3]; count];
        let bytes: &mut [u8] = bytemuck::cast_slice_mut(&mut positions);
        vertex_codec::decode_into(rest, &mut bytes[..8 * count], 8).map_err(codec_error(kind))?;
        let top = (1u32 << bits) - 1;
        for i in (0..count).rev() {
            let p = &bytes[8 * i..8 * i + 6];
            let q = [0, 2, 4].map(|k| u16::from_le_bytes([p[k], p[k + 1]]));
            // A grid point past `2^bits - 1`, or one whose position overflows, is not a position.
            let point = grid.position(q);
            if q.iter().any(|&v| u32::from(v) > top) || !point.iter().all(|v| v.is_finite()) {
                return Err(DecodeError::Invalid {
                    kind,
                    position: i as u64,
                    reason: format!("grid point beyond {bits} bits or not finite"),
                });
            }
            bytes[12 * i..12 * i + 12].copy_from_slice(bytemuck::bytes_of(&point));
        }
        Ok(positions)
    }

    /// Unit normals from octahedral codes, or lossless.
    pub(crate) fn normals(&self, bytes: &[u8]) -> Result<Vec<[f32; 3]>, DecodeError> {
        let kind = SectionKind::RenderNormalsCoded;
        let (count, rest) = self.count(kind, bytes)?;
        let (bits, rest) = split_u32(kind, rest)?;
        if bits == LOSSLESS_BITS {
            return floats(kind, rest, count);
        }
        if !(2..=16).contains(&bits) {
            return Err(coding_error(
                kind,
                format!("{bits} bits per component (2 to 16, or 32)"),
            ));
        }
        // Codes (4 bytes) decoded into the front of the normals and widened in place from the back.
        vertex_codec::fits(rest, count, 4).map_err(codec_error(kind))?;
        let mut normals = vec![[0.0f32; 3]; count];
        let bytes: &mut [u8] = bytemuck::cast_slice_mut(&mut normals);
        vertex_codec::decode_into(rest, &mut bytes[..4 * count], 4).map_err(codec_error(kind))?;
        let scale = (1i32 << (bits - 1)) - 1;
        for i in (0..count).rev() {
            let c = &bytes[4 * i..4 * i + 4];
            let code = [
                i16::from_le_bytes([c[0], c[1]]),
                i16::from_le_bytes([c[2], c[3]]),
            ];
            if code.iter().any(|&v| i32::from(v).abs() > scale) {
                return Err(DecodeError::Invalid {
                    kind,
                    position: i as u64,
                    reason: format!("octahedral code beyond {bits} bits"),
                });
            }
            let normal = quantize::decode_octahedral(code, bits);
            bytes[12 * i..12 * i + 12].copy_from_slice(bytemuck::bytes_of(&normal));
        }
        Ok(normals)
    }

    /// The edge attribute words.
    pub(crate) fn words(&self, kind: SectionKind, bytes: &[u8]) -> Result<Vec<u32>, DecodeError> {
        let (count, rest) = self.count(kind, bytes)?;
        vertex_codec::decode(rest, count).map_err(codec_error(kind))
    }

    /// The render vertex counts.
    pub(crate) fn counts(&self, bytes: &[u8]) -> Result<Vec<u8>, DecodeError> {
        let kind = SectionKind::RenderVertexCountsCoded;
        let (count, rest) = self.count(kind, bytes)?;
        let words: Vec<[u8; 4]> =
            vertex_codec::decode(rest, count.div_ceil(4)).map_err(codec_error(kind))?;
        let mut counts: Vec<u8> = bytemuck::cast_vec(words);
        if counts[count..].iter().any(|&c| c != 0) {
            return Err(coding_error(
                kind,
                "padding after the last count is not zero",
            ));
        }
        counts.truncate(count);
        Ok(counts)
    }

    /// The corner bits of the corners of `triangles`, and the number of edges they hold.
    pub(crate) fn corner_bits(
        &self,
        bytes: &[u8],
        triangles: &[u32],
    ) -> Result<(usize, CornerBits), DecodeError> {
        let kind = SectionKind::EdgeCorners;
        let (edges, bits) = self.count(kind, bytes)?;
        let bits =
            CornerBits::new(bits, triangles, edges).map_err(|reason| coding_error(kind, reason))?;
        Ok((edges, bits))
    }

    /// The bounds of the clusters of `edge_attributes`.
    pub(crate) fn clusters(
        &self,
        bytes: &[u8],
        edge_attributes: &[u32],
    ) -> Result<Vec<EdgeCluster>, DecodeError> {
        let kind = SectionKind::EdgeClustersCoded;
        let (count, rest) = self.count(kind, bytes)?;
        let expected = cluster_count(edge_attributes.len());
        if count != expected {
            return Err(coding_error(
                kind,
                format!(
                    "{count} clusters for {} edges (must be {expected})",
                    edge_attributes.len()
                ),
            ));
        }
        let (prefix, rest) = rest
            .split_first_chunk::<{ bounds::PREFIX_BYTES }>()
            .ok_or_else(|| coding_error(kind, "shorter than its grid"))?;
        let records: Vec<[u8; bounds::RECORD_BYTES]> =
            vertex_codec::decode(rest, count).map_err(codec_error(kind))?;
        bounds::decode(prefix, records.as_flattened(), edge_attributes)
            .map_err(|reason| coding_error(kind, reason))
    }
}

/// The next ends and cap heads of the ring code over the edges of `bits`, `ends` edge ends.
pub(crate) fn rings(
    bytes: &[u8],
    bits: &CornerBits,
    corners: &VertexCorners,
    ends: usize,
) -> Result<(Vec<u32>, Vec<u32>), DecodeError> {
    let kind = SectionKind::RingOrders;
    let (code_bits, code) = bytes
        .split_first_chunk::<8>()
        .ok_or_else(|| coding_error(kind, "shorter than its 8-byte prefix"))?;
    let code_bits = u64::from_le_bytes(*code_bits);
    if code_bits.div_ceil(64) * 8 != code.len() as u64 {
        return Err(coding_error(
            kind,
            format!("{code_bits} bits of code in {} bytes", code.len()),
        ));
    }
    rings::decode(code, code_bits, bits, corners, ends).map_err(|e| match e {
        RingError::TooLong { vertex, ends } => DecodeError::RingTooLong {
            vertex,
            ends,
            limit: MAX_RING,
        },
        RingError::Code(reason) => coding_error(kind, reason),
    })
}

fn read_grid(bits: u32, bytes: &[u8]) -> Result<(Grid, &[u8]), DecodeError> {
    let kind = SectionKind::TopologyPositionsCoded;
    if !(1..=16).contains(&bits) {
        return Err(coding_error(
            kind,
            format!("{bits} bits per axis (1 to 16, or 32)"),
        ));
    }
    let (numbers, rest) = bytes
        .split_first_chunk::<24>()
        .ok_or_else(|| coding_error(kind, "shorter than its grid"))?;
    let grid = Grid::from_bytes(bits, numbers)
        .ok_or_else(|| coding_error(kind, "grid origin or step not finite, or a step negative"))?;
    Ok((grid, rest))
}

fn floats(kind: SectionKind, rest: &[u8], count: usize) -> Result<Vec<[f32; 3]>, DecodeError> {
    let values: Vec<[f32; 3]> = vertex_codec::decode(rest, count).map_err(codec_error(kind))?;
    match values.iter().position(|v| !v.iter().all(|x| x.is_finite())) {
        Some(position) => Err(DecodeError::NonFinite {
            kind,
            position: position as u64,
        }),
        None => Ok(values),
    }
}

/// The bits of a coded position or normal section (lossless when it is empty: raw), and the rest.
fn bits_of(kind: SectionKind, bytes: &[u8]) -> Result<(u32, &[u8]), DecodeError> {
    if bytes.is_empty() {
        return Ok((LOSSLESS_BITS, bytes));
    }
    let (_, rest) = split_u32(kind, bytes)?;
    split_u32(kind, rest)
}

/// The precision of coded positions and normals (either section may be empty: raw, hence exact).
pub(crate) fn precision(positions: &[u8], normals: &[u8]) -> Result<Precision, DecodeError> {
    let (position_bits, rest) = bits_of(SectionKind::TopologyPositionsCoded, positions)?;
    let position_error = if position_bits == LOSSLESS_BITS {
        0.0
    } else {
        read_grid(position_bits, rest)?.0.error_bound()
    };
    let (normal_bits, _) = bits_of(SectionKind::RenderNormalsCoded, normals)?;
    let normal_error = match normal_bits {
        LOSSLESS_BITS => 0.0,
        2..=16 => quantize::octahedral_error_bound(normal_bits),
        _ => {
            return Err(coding_error(
                SectionKind::RenderNormalsCoded,
                format!("{normal_bits} bits per component (2 to 16, or 32)"),
            ));
        }
    };
    Ok(Precision {
        position_bits,
        position_error,
        normal_bits,
        normal_error,
    })
}
