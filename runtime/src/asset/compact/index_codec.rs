//! A decoder of meshoptimizer's index codec (`meshopt_decodeIndexBuffer`, versions 0 and 1, glTF
//! `EXT_meshopt_compression` "triangles" mode), in safe Rust like [`super::vertex_codec`].
//!
//! Each triangle is one code byte: most reuse an edge of the last 16 triangles (an edge FIFO) and
//! name the third vertex as the next new one or one of the last 16 vertices (a vertex FIFO); the
//! rest read a byte of a 16-entry table or of the stream, and vertices that are neither new nor
//! recent are stored as zigzag deltas from the last such vertex (variable-length bytes).
//!
//! Contract: [`decode`] returns exactly `triangles` triangles or an error, reads only `encoded`
//! and runs in time linear in `triangles`. The values are not checked against any bound here:
//! the caller validates them like any other index section.

use super::vertex_codec::CodecError;

const HEADER: u8 = 0xe0;
const TABLE_BYTES: usize = 16;

struct Fifos {
    edges: [[u32; 2]; 16],
    edge_at: usize,
    vertices: [u32; 16],
    vertex_at: usize,
}

impl Fifos {
    fn edge(&self, back: usize) -> [u32; 2] {
        self.edges[(self.edge_at.wrapping_sub(1 + back)) & 15]
    }

    fn push_edge(&mut self, a: u32, b: u32) {
        self.edges[self.edge_at] = [a, b];
        self.edge_at = (self.edge_at + 1) & 15;
    }

    /// The vertex `back` places before the newest (0 is the newest).
    fn vertex(&self, back: usize) -> u32 {
        self.vertices[(self.vertex_at.wrapping_sub(1 + back)) & 15]
    }

    fn push_vertex(&mut self, v: u32, advance: bool) {
        self.vertices[self.vertex_at] = v;
        self.vertex_at = (self.vertex_at + usize::from(advance)) & 15;
    }
}

/// Decodes `triangles` triangles (three indices each).
pub(crate) fn decode(encoded: &[u8], triangles: usize) -> Result<Vec<u32>, CodecError> {
    // A header, one code byte per triangle and the table: checked before allocating.
    if encoded.len() < 1 + TABLE_BYTES || triangles > encoded.len() - 1 - TABLE_BYTES {
        return Err(CodecError::Truncated);
    }
    if encoded[0] & 0xf0 != HEADER || encoded[0] & 0x0f > 1 {
        return Err(CodecError::Header);
    }
    let version = encoded[0] & 0x0f;
    let fec_max = if version >= 1 { 13 } else { 15 };
    let codes = &encoded[1..1 + triangles];
    let data_end = encoded.len() - TABLE_BYTES;
    let table = &encoded[data_end..];
    let mut data = Data {
        bytes: &encoded[..data_end],
        at: 1 + triangles,
    };
    let mut fifo = Fifos {
        edges: [[u32::MAX; 2]; 16],
        edge_at: 0,
        vertices: [u32::MAX; 16],
        vertex_at: 0,
    };
    let (mut next, mut last) = (0u32, 0u32);
    let mut out = Vec::with_capacity(3 * triangles);
    for &code in codes {
        if code < 0xf0 {
            let [a, b] = fifo.edge(usize::from(code >> 4));
            let fec = code & 15;
            let c = if fec < fec_max {
                let c = if fec == 0 {
                    next
                } else {
                    fifo.vertex(usize::from(fec))
                };
                next = next.wrapping_add(u32::from(fec == 0));
                fifo.push_vertex(c, fec == 0);
                c
            } else {
                last = if fec == 15 {
                    data.index(last)?
                } else {
                    // 13 and 14 are the last free vertex -1 and +1.
                    last.wrapping_add(u32::from(fec) * 2).wrapping_sub(27)
                };
                fifo.push_vertex(last, true);
                last
            };
            fifo.push_edge(c, b);
            fifo.push_edge(a, c);
            out.extend_from_slice(&[a, b, c]);
        } else {
            // `back` 1..=15 names the vertex that many places before the next FIFO slot; 0 takes
            // the next new vertex. Every vertex takes its number from `next` before any free one
            // is read, as the encoder counts them.
            let vertex = |back: u8, next: &mut u32| {
                if back == 0 {
                    *next = next.wrapping_add(1);
                    next.wrapping_sub(1)
                } else {
                    fifo.vertex(usize::from(back) - 1)
                }
            };
            let triangle = if code < 0xfe {
                // The table's entries never hold a free vertex (15): it reads as a FIFO entry.
                let aux = table[usize::from(code & 15)];
                let (feb, fec) = (aux >> 4, aux & 15);
                let a = vertex(0, &mut next);
                let b = vertex(feb, &mut next);
                let c = vertex(fec, &mut next);
                fifo.push_vertex(a, true);
                fifo.push_vertex(b, feb == 0);
                fifo.push_vertex(c, fec == 0);
                [a, b, c]
            } else {
                let aux = data.byte()?;
                let (feb, fec) = (aux >> 4, aux & 15);
                if aux == 0 {
                    next = 0; // a reset
                }
                let free_a = code == 0xff;
                let mut a = if free_a { 0 } else { vertex(0, &mut next) };
                let mut b = vertex(feb, &mut next);
                let mut c = vertex(fec, &mut next);
                if free_a {
                    last = data.index(last)?;
                    a = last;
                }
                if feb == 15 {
                    last = data.index(last)?;
                    b = last;
                }
                if fec == 15 {
                    last = data.index(last)?;
                    c = last;
                }
                fifo.push_vertex(a, true);
                fifo.push_vertex(b, feb == 0 || feb == 15);
                fifo.push_vertex(c, fec == 0 || fec == 15);
                [a, b, c]
            };
            let [a, b, c] = triangle;
            out.extend_from_slice(&triangle);
            fifo.push_edge(b, a);
            fifo.push_edge(c, b);
            fifo.push_edge(a, c);
        }
    }
    if data.at != data_end {
        return Err(CodecError::Malformed);
    }
    Ok(out)
}

struct Data<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Data<'_> {
    fn byte(&mut self) -> Result<u8, CodecError> {
        let b = *self.bytes.get(self.at).ok_or(CodecError::Truncated)?;
        self.at += 1;
        Ok(b)
    }

    /// A free vertex: a zigzag delta from `last` in up to five 7-bit groups.
    fn index(&mut self, last: u32) -> Result<u32, CodecError> {
        let mut v = 0u32;
        for shift in (0..35).step_by(7) {
            let group = self.byte()?;
            v |= u32::from(group & 127).wrapping_shl(shift);
            if group < 128 {
                break;
            }
        }
        Ok(last.wrapping_add((v >> 1) ^ (v & 1).wrapping_neg()))
    }
}
