//! A decoder of meshoptimizer's vertex codec (`meshopt_decodeVertexBuffer`, bitstream version 0 as
//! glTF's `EXT_meshopt_compression` specifies it, "attributes" mode, and version 1 as
//! `KHR_meshopt_compression` does; docs/format-compact.md restates both), in safe Rust so that
//! the runtime needs no C++ and builds for wasm. The bake encodes with the `meshopt` crate (the
//! reference encoder); the tests check this decoder against the reference decoder.
//!
//! The stream: one header byte `0xA0 | version`, blocks of at most 256 vertices, then a tail that
//! holds the first vertex's predecessor (and, in version 1, a channel mode per 4 bytes). Within a
//! block each byte of the vertex is a column of deltas from the previous vertex, stored in groups of
//! 16 with 0, 1, 2, 4 or 8 bits per value (an all-ones value escapes to a literal byte).
//!
//! Contract: [`decode`] either fills exactly `count * stride` bytes or returns an error; it never
//! reads outside `encoded` and its time is linear in `count * stride`.

/// Why a coded stream was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CodecError {
    /// Not a stream of this codec, or of a version this decoder does not know.
    Header,
    /// The stream ends before the data it announces.
    Truncated,
    /// The stream has bytes left over, or an unknown mode.
    Malformed,
}

impl CodecError {
    pub(crate) const fn reason(self) -> &'static str {
        match self {
            Self::Header => "not a meshopt stream of a known version",
            Self::Truncated => "the coded stream ends early",
            Self::Malformed => "the coded stream is malformed",
        }
    }
}

const HEADER: u8 = 0xa0;
const BLOCK_BYTES: usize = 8192;
const BLOCK_MAX_VERTICES: usize = 256;
const GROUP: usize = 16;
/// The decoder may read this many bytes for one group (8 packed, up to 16 escaped).
const GROUP_READ_LIMIT: usize = 24;
const BITS_V0: [u8; 4] = [0, 2, 4, 8];
const BITS_V1: [u8; 5] = [0, 1, 2, 4, 8];

/// Vertices per block for vertices of `stride` bytes: part of the format.
fn block_vertices(stride: usize) -> usize {
    ((BLOCK_BYTES / stride) & !(GROUP - 1)).min(BLOCK_MAX_VERTICES)
}

/// The stream's version after its header, if `encoded` could hold `count` vertices of `stride`
/// bytes: what a caller checks before allocating the output.
pub(crate) fn fits(encoded: &[u8], count: usize, stride: usize) -> Result<u8, CodecError> {
    if stride == 0 || stride > 256 || !stride.is_multiple_of(4) {
        return Err(CodecError::Malformed);
    }
    let (&header, body) = encoded.split_first().ok_or(CodecError::Truncated)?;
    if header & 0xf0 != HEADER || header & 0x0f > 1 {
        return Err(CodecError::Header);
    }
    let version = header & 0x0f;
    if body.len() < tail_padded(version, stride) {
        return Err(CodecError::Truncated);
    }
    // Every block reads at least a header byte per vertex byte (version 0) or a control byte per
    // four (version 1): a count the stream cannot hold is refused before anything is allocated.
    let least_per_block = if version == 0 { stride } else { stride / 4 };
    if count
        .div_ceil(block_vertices(stride))
        .saturating_mul(least_per_block)
        > body.len()
    {
        return Err(CodecError::Truncated);
    }
    Ok(version)
}

fn tail_len(version: u8, stride: usize) -> usize {
    stride + if version == 0 { 0 } else { stride / 4 }
}

fn tail_padded(version: u8, stride: usize) -> usize {
    tail_len(version, stride).max(if version == 0 { 32 } else { 24 })
}

/// Decodes `count` vertices of type `T` (whose size is the stride: a multiple of 4, at most 256).
pub(crate) fn decode<T: bytemuck::Pod>(encoded: &[u8], count: usize) -> Result<Vec<T>, CodecError> {
    fits(encoded, count, std::mem::size_of::<T>())?;
    let mut out = vec![T::zeroed(); count];
    decode_into(
        encoded,
        bytemuck::cast_slice_mut(&mut out),
        std::mem::size_of::<T>(),
    )?;
    Ok(out)
}

/// Decodes `out.len() / stride` vertices of `stride` bytes into `out` (which the caller sized after
/// [`fits`]).
pub(crate) fn decode_into(encoded: &[u8], out: &mut [u8], stride: usize) -> Result<(), CodecError> {
    let count = out.len() / stride;
    let version = fits(encoded, count, stride)?;
    let body = &encoded[1..];
    let tail = &body[body.len() - tail_len(version, stride)..];
    let mut last = [0u8; 256];
    last[..stride].copy_from_slice(&tail[..stride]);
    let channels = &tail[stride..];
    let mut reader = Reader { data: body, at: 0 };
    for chunk in out[..count * stride].chunks_mut(block_vertices(stride) * stride) {
        reader.block(chunk, stride, &mut last, version, channels)?;
    }
    if body.len() - reader.at != tail_padded(version, stride) {
        return Err(CodecError::Malformed);
    }
    Ok(())
}

struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn remaining(&self) -> usize {
        self.data.len() - self.at
    }

    fn take(&mut self, n: usize) -> Result<&'a [u8], CodecError> {
        if self.remaining() < n {
            return Err(CodecError::Truncated);
        }
        let s = &self.data[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }

    /// One block: `out` holds its vertices; `last` is the vertex before it, and becomes its last.
    fn block(
        &mut self,
        out: &mut [u8],
        stride: usize,
        last: &mut [u8; 256],
        version: u8,
        channels: &[u8],
    ) -> Result<(), CodecError> {
        let count = out.len() / stride;
        let aligned = count.next_multiple_of(GROUP);
        let control: &[u8] = if version == 0 {
            &[]
        } else {
            self.take(stride / 4)?
        };
        let mut columns = [[0u8; BLOCK_MAX_VERTICES]; 4];
        for k in (0..stride).step_by(4) {
            let control_byte = control.get(k / 4).copied().unwrap_or(0);
            for (j, column) in columns.iter_mut().enumerate() {
                match (control_byte >> (2 * j)) & 3 {
                    3 => column[..count].copy_from_slice(self.take(count)?),
                    2 => column[..count].fill(0),
                    mode => {
                        let bits: &[u8] = if version == 0 {
                            &BITS_V0
                        } else {
                            &BITS_V1[usize::from(mode)..]
                        };
                        self.bytes(&mut column[..aligned], bits)?;
                    }
                }
            }
            let channel = channels.get(k / 4).copied().unwrap_or(0);
            undo_deltas(out, &columns, count, stride, k, &last[k..k + 4], channel)?;
        }
        last[..stride].copy_from_slice(&out[(count - 1) * stride..count * stride]);
        Ok(())
    }

    /// One column of a block: a 2-bit header per group of 16, then the groups.
    fn bytes(&mut self, column: &mut [u8], bits: &[u8]) -> Result<(), CodecError> {
        let groups = column.len() / GROUP;
        let header_len = groups.div_ceil(4);
        let header_at = self.at;
        self.take(header_len)?;
        for (g, group) in column.chunks_exact_mut(GROUP).enumerate() {
            if self.remaining() < GROUP_READ_LIMIT {
                return Err(CodecError::Truncated);
            }
            let code = (self.data[header_at + g / 4] >> ((g % 4) * 2)) & 3;
            self.group(group, bits[usize::from(code)]);
        }
        Ok(())
    }

    /// One group of 16 values of `bits` bits; at least [`GROUP_READ_LIMIT`] bytes remain.
    fn group(&mut self, group: &mut [u8], bits: u8) {
        let data = &self.data[self.at..self.at + GROUP_READ_LIMIT];
        match bits {
            0 => {
                group.fill(0);
            }
            8 => {
                group.copy_from_slice(&data[..GROUP]);
                self.at += GROUP;
            }
            _ => {
                let packed = usize::from(2 * bits);
                let sentinel = (1u8 << bits) - 1;
                let mut escaped = packed;
                for (i, value) in group.iter_mut().enumerate() {
                    let bit = i * usize::from(bits);
                    let byte = data[bit / 8];
                    // 1-bit groups are packed from the low bit, the others from the high bits.
                    let v = if bits == 1 {
                        (byte >> (bit % 8)) & 1
                    } else {
                        (byte >> (8 - usize::from(bits) - bit % 8)) & sentinel
                    };
                    *value = if v == sentinel {
                        escaped += 1;
                        data[escaped - 1]
                    } else {
                        v
                    };
                }
                self.at += escaped;
            }
        }
    }
}

/// Rebuilds bytes `k..k + 4` of every vertex of a block from their columns of deltas.
fn undo_deltas(
    out: &mut [u8],
    columns: &[[u8; BLOCK_MAX_VERTICES]; 4],
    count: usize,
    stride: usize,
    k: usize,
    last: &[u8],
    channel: u8,
) -> Result<(), CodecError> {
    match channel & 3 {
        0 => {
            for (j, column) in columns.iter().enumerate() {
                let mut p = last[j];
                for (i, &d) in column[..count].iter().enumerate() {
                    p = p.wrapping_add((d >> 1) ^ (d & 1).wrapping_neg());
                    out[i * stride + k + j] = p;
                }
            }
        }
        1 => {
            for j in [0, 2] {
                let mut p = u16::from_le_bytes([last[j], last[j + 1]]);
                for i in 0..count {
                    let d = u16::from_le_bytes([columns[j][i], columns[j + 1][i]]);
                    p = p.wrapping_add((d >> 1) ^ (d & 1).wrapping_neg());
                    out[i * stride + k + j..i * stride + k + j + 2]
                        .copy_from_slice(&p.to_le_bytes());
                }
            }
        }
        2 => {
            let rotation = (32 - u32::from(channel >> 4)) & 31;
            let mut p = u32::from_le_bytes([last[0], last[1], last[2], last[3]]);
            for i in 0..count {
                let d = u32::from_le_bytes([
                    columns[0][i],
                    columns[1][i],
                    columns[2][i],
                    columns[3][i],
                ]);
                p ^= d.rotate_left(rotation);
                out[i * stride + k..i * stride + k + 4].copy_from_slice(&p.to_le_bytes());
            }
        }
        _ => return Err(CodecError::Malformed),
    }
    Ok(())
}
