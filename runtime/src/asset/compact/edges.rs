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

pub(crate) use crate::asset::corners::VertexCorners;

/// The corner before `c` in its triangle.
fn corner_before(c: usize) -> usize {
    if c.is_multiple_of(3) { c + 2 } else { c - 1 }
}

/// The vertex opposite `v1` in the first of `corners` (corners at `v0`) whose triangle holds `v1`.
fn opposite(corners: &[u32], v1: u32, triangles: &[u32]) -> Option<u32> {
    corners
        .iter()
        .map(|&other| other as usize)
        .find_map(|other| {
            let next = triangles[other / 3 * 3 + (other + 1) % 3];
            let before = triangles[corner_before(other)];
            if next == v1 {
                Some(before)
            } else if before == v1 {
                Some(next)
            } else {
                None
            }
        })
}

/// The edge whose face a has corner `c`: `v3` is the vertex opposite it in the lowest other
/// triangle at `v0` that holds `v1`. (Face a is the lowest triangle that holds the edge, so the
/// search starts after `c` in `v0`'s corners, which are in increasing order.)
fn edge_at(c: usize, triangles: &[u32], corners: &VertexCorners) -> [u32; 4] {
    let (t, k) = (c / 3, c % 3);
    let at = |i: usize| triangles[3 * t + (k + i) % 3];
    let (a, b) = (at(0), at(1));
    let fan = corners.of(a);
    let after = fan.partition_point(|&other| other as usize <= c);
    let v3 = opposite(&fan[after..], b, triangles).unwrap_or(a);
    [a, b, at(2), v3]
}

/// One bit per corner of `triangles` (three indices each), or `None` if `edges` (four vertices
/// each) are not the mesh's edges in the order of their face-a triangles and `v0`: each edge must be
/// the one [`edge_at`] rebuilds from its corner.
pub(crate) fn encode(edges: &[u32], triangles: &[u32], corners: &VertexCorners) -> Option<Vec<u8>> {
    let mut bits = vec![0u8; triangles.len().div_ceil(8)];
    let mut previous = None;
    let next_of = |c: usize| triangles[c / 3 * 3 + (c + 1) % 3];
    for edge in edges.chunks_exact(4) {
        let [v0, v1, v2, v3] = [edge[0], edge[1], edge[2], edge[3]];
        // One pass over v0's fan: the face-a corner `(v0, v1, v2)`, then, as `edge_at` searches
        // after it, the first triangle that holds `v1`.
        let fan = corners.of(v0);
        let at = fan.iter().position(|&c| {
            let c = c as usize;
            next_of(c) == v1 && triangles[corner_before(c)] == v2
        })?;
        let c = fan[at] as usize;
        let v3_found = opposite(&fan[at + 1..], v1, triangles).unwrap_or(v0);
        let key = (c / 3, v0);
        if previous.is_some_and(|p| p >= key) || v3_found != v3 {
            return None;
        }
        previous = Some(key);
        bits[c / 8] |= 1 << (c % 8);
    }
    Some(bits)
}

/// The corner bits of a mesh, checked, and the edge that starts at each corner.
pub(crate) struct CornerBits {
    words: Vec<u64>,
    /// Per corner, the edge that starts there, or `NONE`.
    edge_of_corner: Vec<u32>,
}

const NONE: u32 = u32::MAX;

impl CornerBits {
    /// Reads the bits of the corners of `triangles`, which must be `edge_count` set bits, none past
    /// the last corner. `Err` says what is wrong.
    pub(crate) fn new(bytes: &[u8], triangles: &[u32], edge_count: usize) -> Result<Self, String> {
        let corners = triangles.len();
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
        // One spare word, so that the three bits of a triangle are always two words' reach.
        let mut words: Vec<u64> = Vec::with_capacity(bytes.len() / 8 + 2);
        words.extend(bytes.chunks(8).map(|chunk| {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            u64::from_le_bytes(word)
        }));
        words.push(0);
        let set: u64 = words.iter().map(|w| u64::from(w.count_ones())).sum();
        if set != edge_count as u64 {
            return Err(format!("{set} corners set for {edge_count} edges"));
        }
        let mut bits = Self {
            words,
            edge_of_corner: Vec::new(),
        };
        // Set corners come in corner order; within a triangle the edges go by `v0`, so each
        // triangle's set corners are numbered together once its last one is seen.
        let mut edge_of_corner = vec![NONE; corners];
        let mut next = 0u32;
        let mut group: ([usize; 3], usize) = ([0; 3], 0);
        let mut flush = |(members, n): ([usize; 3], usize), edge_of_corner: &mut [u32]| {
            let members = &mut { members }[..n];
            if n > 1 {
                members.sort_unstable_by_key(|&c| (triangles[c], c));
            }
            for &c in members.iter() {
                edge_of_corner[c] = next;
                next += 1;
            }
        };
        for (w, &word) in bits.words.iter().enumerate() {
            let mut rest = word;
            while rest != 0 {
                let c = w * 64 + rest.trailing_zeros() as usize;
                rest &= rest - 1;
                if group.1 > 0 && group.0[0] / 3 != c / 3 {
                    flush(group, &mut edge_of_corner);
                    group.1 = 0;
                }
                group.0[group.1] = c;
                group.1 += 1;
            }
        }
        flush(group, &mut edge_of_corner);
        bits.edge_of_corner = edge_of_corner;
        Ok(bits)
    }

    /// The edge ends (`2 * edge + end`) at vertex `v`, ascending, into `out`: the `v0` end of the
    /// edge at each of its corners, and the `v1` end of the edge at the corner before each one.
    pub(crate) fn ends_at(&self, v: u32, corners: &VertexCorners, out: &mut Vec<u32>) {
        out.clear();
        for &c in corners.of(v) {
            let c = c as usize;
            let starting = self.edge_of_corner[c];
            if starting != NONE {
                out.push(2 * starting);
            }
            let ending = self.edge_of_corner[corner_before(c)];
            if ending != NONE {
                out.push(2 * ending + 1);
            }
        }
        out.sort_unstable();
    }

    /// The set corners of triangle `t`, in the order of their edges: by `v0`, then by corner.
    fn set_in(&self, t: usize, triangles: &[u32]) -> [Option<usize>; 3] {
        let c = 3 * t;
        let (w, shift) = (c / 64, c % 64);
        let mut three = self.words[w] >> shift;
        if shift > 61 {
            three |= self.words[w + 1] << (64 - shift);
        }
        let key = |k: usize| (triangles[c + k], k);
        match three & 7 {
            0 => [None; 3],
            1 => [Some(c), None, None],
            2 => [Some(c + 1), None, None],
            4 => [Some(c + 2), None, None],
            pair @ (3 | 5 | 6) => {
                let (x, y) = match pair {
                    3 => (0, 1),
                    5 => (0, 2),
                    _ => (1, 2),
                };
                let (x, y) = if key(x) < key(y) { (x, y) } else { (y, x) };
                [Some(c + x), Some(c + y), None]
            }
            _ => {
                let mut order = [0, 1, 2];
                order.sort_unstable_by_key(|&k| key(k));
                order.map(|k| Some(c + k))
            }
        }
    }

    /// The number of edges before those of triangle `t` (`t` at most the triangle count).
    pub(crate) fn edges_before(&self, t: usize) -> usize {
        let c = 3 * t;
        let whole: usize = self.words[..c / 64]
            .iter()
            .map(|w| w.count_ones() as usize)
            .sum();
        let part = self
            .words
            .get(c / 64)
            .map_or(0, |w| (w & ((1u64 << (c % 64)) - 1)).count_ones() as usize);
        whole + part
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
        for c in bits.set_in(t, triangles).into_iter().flatten() {
            if let Some(edge) = edges.next() {
                edge.copy_from_slice(&edge_at(c, triangles, corners));
            }
        }
    }
}
