//! Next-index rings (thesis §13) and cap heads (§10.5) stored as the order of each vertex's ring:
//! the loader knows which edge ends lie at a vertex (from the corner bits of the edges, see
//! [`CornerBits::ends_at`]; rings are coded only beside corner-coded edges), so a ring of `d` ends is one of
//! `(d - 1)!` cycles, plus which end is its head: `log2(d!)` bits, about 10 bits for the six ends of a
//! typical vertex against 6 × 32 bits of next indices and a head.
//!
//! The code of a vertex's ring lists its ends from the head, each as its rank among the ends not
//! yet listed (in increasing order), in `ceil(log2(n))` bits when `n` are left; the last end needs
//! none. Vertices with one end have no code (the end is its own next, and there is no head).
//! Bits are packed from the low bit of little-endian 64-bit words; the section is whole words.

use super::super::MAX_RING;
use super::edges::{CornerBits, VertexCorners};

fn rank_bits(candidates: usize) -> u32 {
    usize::BITS - (candidates - 1).leading_zeros()
}

/// Why a ring code is refused.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum RingError {
    /// A vertex has more ends than a ring may have.
    TooLong { vertex: u32, ends: u64 },
    /// The code does not fit the ends.
    Code(&'static str),
}

/// The code of `next` and `heads` over the edges of `bits`, or `None`
/// when they are not one ring per vertex with two or more ends, each with one head, heads by
/// increasing vertex (as the bake builds them). Also returns the number of bits of code.
pub(crate) fn encode(
    next: &[u32],
    heads: &[u32],
    bits: &CornerBits,
    corners: &VertexCorners,
) -> Option<(Vec<u8>, u64)> {
    let mut writer = BitWriter::default();
    let mut heads = heads.iter();
    let mut left = Vec::new();
    for v in 0..corners.vertex_count() as u32 {
        bits.ends_at(v, corners, &mut left);
        match left.len() {
            0 => continue,
            1 => {
                if *next.get(left[0] as usize)? != left[0] {
                    return None;
                }
                continue;
            }
            _ => {}
        }
        let head = *heads.next()?;
        let mut end = head;
        while left.len() > 1 {
            let rank = left.binary_search(&end).ok()?;
            writer.put(rank as u64, rank_bits(left.len()));
            left.remove(rank);
            end = *next.get(end as usize)?;
        }
        // The ring must close on the head after visiting every end once.
        if end != left[0] || *next.get(end as usize)? != head {
            return None;
        }
    }
    heads.next().is_none().then(|| {
        let bits = writer.bits;
        (writer.finish(), bits)
    })
}

/// Rebuilds the rings (a next end per end, `end_count` of them) and heads over the edges of
/// `bits` from their code of `code_bits` bits.
pub(crate) fn decode(
    bytes: &[u8],
    code_bits: u64,
    bits: &CornerBits,
    corners: &VertexCorners,
    end_count: usize,
) -> Result<(Vec<u32>, Vec<u32>), RingError> {
    if !bytes.len().is_multiple_of(8) {
        return Err(RingError::Code("not a whole number of 64-bit words"));
    }
    let mut reader = BitReader::new(bytes);
    let mut next: Vec<u32> = (0..end_count as u32).collect();
    let mut heads = Vec::new();
    let mut left = Vec::new();
    for v in 0..corners.vertex_count() as u32 {
        bits.ends_at(v, corners, &mut left);
        if left.len() < 2 {
            continue;
        }
        if left.len() > MAX_RING as usize {
            return Err(RingError::TooLong {
                vertex: v,
                ends: left.len() as u64,
            });
        }
        let mut previous = None;
        while left.len() > 1 {
            let rank = reader
                .take(rank_bits(left.len()))
                .ok_or(RingError::Code("the code ends before the last ring"))?
                as usize;
            if rank >= left.len() {
                return Err(RingError::Code(
                    "a rank is beyond the ends left at its vertex",
                ));
            }
            let end = left.remove(rank);
            match previous {
                None => heads.push(end),
                Some(p) => next[p as usize] = end,
            }
            previous = Some(end);
        }
        if let Some(p) = previous {
            next[p as usize] = left[0];
        }
        next[left[0] as usize] = *heads.last().ok_or(RingError::Code("a ring has no head"))?;
    }
    if reader.consumed != code_bits || !reader.rest_is_padding() {
        return Err(RingError::Code(
            "the code's length is not that of its rings",
        ));
    }
    Ok((next, heads))
}

#[derive(Default)]
struct BitWriter {
    bits: u64,
    words: Vec<u64>,
    current: u64,
    filled: u32,
}

impl BitWriter {
    fn put(&mut self, value: u64, bits: u32) {
        if bits == 0 {
            return;
        }
        self.bits += u64::from(bits);
        self.current |= value << self.filled;
        if self.filled + bits >= 64 {
            self.words.push(self.current);
            let used = 64 - self.filled;
            self.current = if used < 64 { value >> used } else { 0 };
            self.filled = self.filled + bits - 64;
        } else {
            self.filled += bits;
        }
    }

    fn finish(mut self) -> Vec<u8> {
        if self.filled > 0 {
            self.words.push(self.current);
        }
        self.words.iter().flat_map(|w| w.to_le_bytes()).collect()
    }
}

struct BitReader<'a> {
    words: std::slice::ChunksExact<'a, u8>,
    current: u64,
    available: u32,
    consumed: u64,
}

impl<'a> BitReader<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        Self {
            words: bytes.chunks_exact(8),
            current: 0,
            available: 0,
            consumed: 0,
        }
    }

    fn word(&mut self) -> Option<u64> {
        self.words
            .next()
            .map(|w| u64::from_le_bytes([w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7]]))
    }

    /// The next `bits` bits (at most 32).
    fn take(&mut self, bits: u32) -> Option<u64> {
        if bits == 0 {
            return Some(0);
        }
        self.consumed += u64::from(bits);
        let mask = (1u64 << bits) - 1;
        if self.available >= bits {
            let v = self.current & mask;
            self.current = self.current.checked_shr(bits).unwrap_or(0);
            self.available -= bits;
            return Some(v);
        }
        let word = self.word()?;
        let low = self.current;
        let from_new = bits - self.available;
        let v = (low | (word << self.available)) & mask;
        self.current = word.checked_shr(from_new).unwrap_or(0);
        self.available = 64 - from_new;
        Some(v)
    }

    fn rest_is_padding(&mut self) -> bool {
        self.current == 0 && self.words.len() == 0
    }
}
