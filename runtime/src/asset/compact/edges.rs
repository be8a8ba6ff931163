//! Edges stored relative to the mesh's triangles: an edge `v0 v1 v2 v3` (thesis §8.1) is a corner
//! of its face a, the triangle `(v0, v1, v2)` in its own winding, and `v3` is the vertex opposite
//! the edge in its face b, the lowest-numbered other triangle that holds both `v0` and `v1` (`v0`
//! when there is none: a boundary edge). These are the rules of the bake's adjacency step, and the
//! bake orders edges by their face a and, within it, by `v0` (an order the index codec's rotation
//! of a triangle's corners does not change), so the edges of an asset are one bit per corner of
//! the mesh: set where an edge starts.
//!
//! Contract: [`encode`] returns the bits only when [`decode`] rebuilds exactly the given edges;
//! [`decode`] checks the bits against the mesh and otherwise cannot fail.

/// The corners (`3 * triangle + k`) at each vertex, in increasing order.
pub(crate) struct VertexCorners {
    starts: Vec<u32>,
    corners: Vec<u32>,
}

impl VertexCorners {
    /// Every index of `triangles` must be below `vertex_count`.
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

    fn of(&self, v: u32) -> &[u32] {
        &self.corners[self.starts[v as usize] as usize..self.starts[v as usize + 1] as usize]
    }
}

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
/// each) are not the mesh's edges in the order of their face-a corners.
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

/// The edges (four vertices each) of the set bits, which must be `edge_count` and all name corners.
pub(crate) fn decode(
    bits: &[u8],
    edge_count: usize,
    triangles: &[u32],
    corners: &VertexCorners,
) -> Result<Vec<u32>, String> {
    if bits.len() != triangles.len().div_ceil(8) {
        return Err(format!(
            "{} bytes of corner bits for {} corners (must be {})",
            bits.len(),
            triangles.len(),
            triangles.len().div_ceil(8)
        ));
    }
    let set: usize = bits.iter().map(|b| b.count_ones() as usize).sum();
    if set != edge_count {
        return Err(format!("{set} corners set for {edge_count} edges"));
    }
    let spare = bits.len() * 8 - triangles.len();
    if spare > 0 && bits[bits.len() - 1] >> (8 - spare) != 0 {
        return Err("bits set past the last corner".into());
    }
    let bit = |c: usize| bits[c / 8] >> (c % 8) & 1 != 0;
    let mut edges = Vec::with_capacity(4 * edge_count);
    for t in 0..triangles.len() / 3 {
        let first = 3 * t;
        if bits.get(first / 8).is_some_and(|&b| b == 0) && first % 8 < 6 {
            continue; // no corner of this triangle is set (the common case of a zero byte)
        }
        let mut set: [(u32, usize); 3] = [(0, 0); 3];
        let mut n = 0;
        for c in first..first + 3 {
            if bit(c) {
                set[n] = (triangles[c], c);
                n += 1;
            }
        }
        set[..n].sort_unstable();
        for &(_, c) in &set[..n] {
            edges.extend_from_slice(&edge_at(c, triangles, corners));
        }
    }
    Ok(edges)
}
