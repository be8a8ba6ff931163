//! Edges stored relative to the mesh's triangles: an edge `v0 v1 v2 v3` (thesis §8.1) is a corner
//! of its face a, the triangle `(v0, v1, v2)` in its own winding, and `v3` is the vertex opposite
//! the edge in its face b, the lowest-numbered other triangle that holds both `v0` and `v1` (`v0`
//! when there is none: a boundary edge). These are the rules of the bake's adjacency step, and the
//! bake orders edges by their face a and, within it, by `v0` (an order the index codec's rotation
//! of a triangle's corners does not change), so the edges of an asset are one bit per corner of
//! the mesh: set where an edge starts.
//!
//! The decoder works on a range of triangles, so that two threads can each take half a mesh, and
//! [`CornerBits::ends_at`] lists the edge ends at a vertex from the bits alone, so that the rings
//! ([`super::rings`]) decode beside the edges rather than after them.
//!
//! Contract: [`encode`] returns the bits only when [`decode_range`] rebuilds exactly the given
//! edges; [`CornerBits::new`] checks the bits against the mesh, after which decoding cannot fail.

use std::ops::Range;

/// The corners (`3 * triangle + k`) at each vertex, in increasing order.
pub(crate) struct VertexCorners {
    starts: Vec<u32>,
    corners: Vec<u32>,
}

impl VertexCorners {
    /// Every index of `triangles` must be below `vertex_count`, and there are fewer than 2^32
    /// corners.
    pub(crate) fn new(triangles: &[u32], vertex_count: usize) -> Self {
        let mut starts = vec![0u32; vertex_count + 1];
        for &v in triangles {
            starts[v as usize + 1] += 1;
        }
        for v in 0..vertex_count {
            starts[v + 1] += starts[v];
        }
        let mut cursor = starts.clone();
        let mut corners = vec![0u32; triangles.len()];
        for (c, &v) in triangles.iter().enumerate() {
            corners[cursor[v as usize] as usize] = c as u32;
            cursor[v as usize] += 1;
        }
        Self { starts, corners }
    }

    pub(crate) fn of(&self, v: u32) -> &[u32] {
        &self.corners[self.starts[v as usize] as usize..self.starts[v as usize + 1] as usize]
    }

    pub(crate) fn vertex_count(&self) -> usize {
        self.starts.len() - 1
    }
}

/// Corner `c`'s triangle's corners starting at `c`: `c`, the next, the previous.
fn rotation(c: usize) -> [usize; 3] {
    let (t, k) = (c / 3 * 3, c % 3);
    [t + k, t + (k + 1) % 3, t + (k + 2) % 3]
}

/// The edge whose face a has corner `c`.
fn edge_at(c: usize, triangles: &[u32], corners: &VertexCorners) -> [u32; 4] {
    let [a, b, o] = rotation(c).map(|i| triangles[i]);
    let face = c / 3;
    let v3 = corners
        .of(a)
        .iter()
        .filter(|&&other| other as usize / 3 != face)
        .find_map(|&other| {
            let [_, next, previous] = rotation(other as usize).map(|i| triangles[i]);
            if next == b {
                Some(previous)
            } else if previous == b {
                Some(next)
            } else {
                None
            }
        })
        .unwrap_or(a);
    [a, b, o, v3]
}

/// One bit per corner of `triangles` (three indices each), or `None` if `edges` (four vertices
/// each) are not the mesh's edges in the order of their face-a triangles and `v0`.
pub(crate) fn encode(edges: &[u32], triangles: &[u32], corners: &VertexCorners) -> Option<Vec<u8>> {
    let mut bits = vec![0u8; triangles.len().div_ceil(8)];
    let mut previous = None;
    for edge in edges.chunks_exact(4) {
        let (v0, v1, v2) = (edge[0], edge[1], edge[2]);
        let c = corners.of(v0).iter().copied().find(|&c| {
            let [_, next, opposite] = rotation(c as usize).map(|i| triangles[i]);
            next == v1 && opposite == v2
        })? as usize;
        let key = (c / 3, v0);
        if previous.is_some_and(|p| p >= key) || edge_at(c, triangles, corners) != *edge {
            return None;
        }
        previous = Some(key);
        bits[c / 8] |= 1 << (c % 8);
    }
    Some(bits)
}

/// The corner bits of a mesh, checked, with the number of set bits before every 64 corners: the
/// edge that starts at a corner is its rank among the set corners.
pub(crate) struct CornerBits {
    words: Vec<u64>,
    ranks: Vec<u32>,
}

impl CornerBits {
    /// Reads the bits of `corners` corners, which must be `edge_count` set bits, none past the
    /// last corner. `Err` says what is wrong.
    pub(crate) fn new(bytes: &[u8], corners: usize, edge_count: usize) -> Result<Self, String> {
        if bytes.len() != corners.div_ceil(8) {
            return Err(format!(
                "{} bytes of corner bits for {corners} corners (must be {})",
                bytes.len(),
                corners.div_ceil(8)
            ));
        }
        let spare = bytes.len() * 8 - corners;
        if spare > 0 && bytes[bytes.len() - 1] >> (8 - spare) != 0 {
            return Err("bits set past the last corner".into());
        }
        let words: Vec<u64> = bytes
            .chunks(8)
            .map(|chunk| {
                let mut word = [0u8; 8];
                word[..chunk.len()].copy_from_slice(chunk);
                u64::from_le_bytes(word)
            })
            .collect();
        let mut ranks = Vec::with_capacity(words.len() + 1);
        let mut set = 0u64;
        for word in &words {
            ranks.push(set as u32);
            set += u64::from(word.count_ones());
        }
        if set != edge_count as u64 {
            return Err(format!("{set} corners set for {edge_count} edges"));
        }
        Ok(Self { words, ranks })
    }

    fn is_set(&self, c: usize) -> bool {
        self.words[c / 64] >> (c % 64) & 1 != 0
    }

    /// The number of set corners before corner `c` (`c` at most the corner count).
    pub(crate) fn rank(&self, c: usize) -> usize {
        let Some(&before) = self.ranks.get(c / 64) else {
            return self.ranks.last().map_or(0, |&r| r as usize)
                + self.words.last().map_or(0, |w| w.count_ones() as usize);
        };
        let below = self.words[c / 64] & ((1u64 << (c % 64)) - 1);
        before as usize + below.count_ones() as usize
    }

    /// The edge ends (`2 * edge + end`) at vertex `v`, ascending, into `out`: the `v0` end of the
    /// edge at each of its corners, and the `v1` end of the edge at the corner before each one.
    pub(crate) fn ends_at(&self, v: u32, corners: &VertexCorners, out: &mut Vec<u32>) {
        out.clear();
        for &c in corners.of(v) {
            let c = c as usize;
            if self.is_set(c) {
                out.push(2 * self.rank(c) as u32);
            }
            let previous = rotation(c)[2];
            if self.is_set(previous) {
                out.push(2 * self.rank(previous) as u32 + 1);
            }
        }
        out.sort_unstable();
    }
}

/// Writes the edges (four vertices each) of the set corners of `range` triangles into `out`,
/// which holds exactly those edges.
pub(crate) fn decode_range(
    bits: &CornerBits,
    triangles: &[u32],
    corners: &VertexCorners,
    range: Range<usize>,
    out: &mut [u32],
) {
    let mut edges = out.chunks_exact_mut(4);
    for t in range {
        let first = 3 * t;
        let mut set = [(0u32, 0usize); 3];
        let mut n = 0;
        for c in first..first + 3 {
            if bits.is_set(c) {
                set[n] = (triangles[c], c);
                n += 1;
            }
        }
        set[..n].sort_unstable();
        for &(_, c) in &set[..n] {
            if let Some(edge) = edges.next() {
                edge.copy_from_slice(&edge_at(c, triangles, corners));
            }
        }
    }
}
