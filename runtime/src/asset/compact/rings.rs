//! Next-index rings (thesis §13) and cap heads (§10.5) stored as the order of each vertex's ring:
//! the loader knows which edge ends lie at a vertex (from the edges), so a ring of `d` ends is one of
//! `(d - 1)!` cycles, plus which end is its head: `log2(d!)` bits, about 10 bits for the six ends of a
//! typical vertex against 6 × 32 bits of next indices and a head.
//!
//! The code of a vertex's ring lists its ends from the head, each as its rank among the ends not
//! yet listed (in increasing order), in `ceil(log2(n))` bits when `n` are left; the last end needs
//! none. Vertices with one end have no code (the end is its own next, and there is no head).
//! Bits are packed from the low bit of little-endian 64-bit words; the section is whole words.

use super::super::MAX_RING;

/// The edge ends at each vertex in increasing order, as a compressed list.
pub(crate) struct VertexEnds {
    starts: Vec<u32>,
    ends: Vec<u32>,
}

impl VertexEnds {
    /// `end_vertices[end]` is the vertex of each end. Fails with the first vertex that has more than
    /// [`MAX_RING`] ends (and its count).
    pub(crate) fn new(end_vertices: &[u32], vertex_count: usize) -> Result<Self, (u32, u64)> {
        let mut starts = vec![0u32; vertex_count + 1];
        for &v in end_vertices {
            starts[v as usize + 1] += 1;
        }
        if let Some(v) = starts.iter().position(|&c| c > MAX_RING) {
            return Err(((v - 1) as u32, u64::from(starts[v])));
        }
        for v in 0..vertex_count {
            starts[v + 1] += starts[v];
        }
        let mut cursor = starts.clone();
        let mut ends = vec![0u32; end_vertices.len()];
        for (end, &v) in end_vertices.iter().enumerate() {
            ends[cursor[v as usize] as usize] = end as u32;
            cursor[v as usize] += 1;
        }
        Ok(Self { starts, ends })
    }

    fn of(&self, v: usize) -> &[u32] {
        &self.ends[self.starts[v] as usize..self.starts[v + 1] as usize]
    }

    fn vertex_count(&self) -> usize {
        self.starts.len() - 1
    }
}

fn rank_bits(candidates: usize) -> u32 {
    usize::BITS - (candidates - 1).leading_zeros()
}

/// The code of `next` and `heads`, or `None` when they are not one ring per vertex with two or more
/// ends, each with one head, heads by increasing vertex (as the bake builds them).
/// Also returns the number of bits of code.
pub(crate) fn encode(next: &[u32], heads: &[u32], ends: &VertexEnds) -> Option<(Vec<u8>, u64)> {
    let mut writer = BitWriter::default();
    let mut heads = heads.iter();
    let mut left = Vec::new();
    for v in 0..ends.vertex_count() {
        let at = ends.of(v);
        match at.len() {
            0 => continue,
            1 => {
                if next[at[0] as usize] != at[0] {
                    return None;
                }
                continue;
            }
            _ => {}
        }
        let head = *heads.next()?;
        left.clear();
        left.extend_from_slice(at);
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

/// Rebuilds the rings and heads from their code. `Err` says why the code is refused.
pub(crate) fn decode(
    bytes: &[u8],
    bits: u64,
    ends: &VertexEnds,
    end_count: usize,
) -> Result<(Vec<u32>, Vec<u32>), &'static str> {
    if !bytes.len().is_multiple_of(8) {
        return Err("not a whole number of 64-bit words");
    }
    let mut reader = BitReader::new(bytes);
    let mut next: Vec<u32> = (0..end_count as u32).collect();
    let mut heads = Vec::new();
    let mut left = Vec::new();
    for v in 0..ends.vertex_count() {
        let at = ends.of(v);
        if at.len() < 2 {
            continue;
        }
        left.clear();
        left.extend_from_slice(at);
        let mut previous = None;
        while left.len() > 1 {
            let rank = reader
                .take(rank_bits(left.len()))
                .ok_or("the code ends before the last ring")? as usize;
            if rank >= left.len() {
                return Err("a rank is beyond the ends left at its vertex");
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
        next[left[0] as usize] = *heads.last().ok_or("a ring has no head")?;
    }
    if reader.consumed != bits || !reader.rest_is_padding() {
        return Err("the code's length is not that of its rings");
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
