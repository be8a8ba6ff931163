//! Caps: the next-index rings (thesis §13, Peters) and the cap heads (§10.2, compacted) that let the
//! runtime fill the gap where two drawn edges meet at a vertex.
//!
//! Every kept edge has two *ends* (`2 * edge + 0` at `v0`, `+ 1` at `v1`). For each end, `next`
//! names the next kept edge end at the same vertex, so that following `next` from any end visits
//! every kept edge at that vertex once and comes back: one ring per vertex.
//!
//! # Ordering rule
//!
//! Around a vertex, edges are met in the order the triangles turn: in a triangle `(v, a, b)` (its
//! own winding) edge `v-a` comes before `v-b`. Triangles are chained into *fans* through edges that
//! have exactly one triangle on each side, wound consistently; a fan is open where it reaches a
//! boundary, non-manifold or inconsistently wound edge, and starts there. The ring lists the fans
//! one after the other, in the order of their first corner (triangle order), each from its start
//! (or, if closed, from its first corner), skipping edges that were not kept and edges already
//! listed, and closes back to its first end. Runtime capping therefore joins each drawn edge to the
//! next drawn edge turning around the vertex, as Peters' method asks, also where coplanar edges
//! were dropped in between.
//!
//! The cap buffer of §10.2 lists every pair of edges that meet at a vertex; its pairs are exactly
//! the pairs of one ring, so the asset stores only the ring's first end for each vertex with two or
//! more kept edges (`heads`) and the runtime enumerates the pairs by walking from it.

use std::sync::atomic::{AtomicU32, Ordering};

use rayon::prelude::*;

use crate::adjacency::Edges;
use chamfer_runtime::asset::corners::VertexCorners;

/// Next-index rings and cap heads.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Rings {
    /// Per edge end, the next end around the same vertex (itself for an edge alone at its vertex).
    pub next: Vec<u32>,
    /// One end per vertex that has two or more kept edges, by increasing vertex.
    pub heads: Vec<u32>,
}

const VERTICES_PER_CHUNK: usize = 4096;
/// Up to this many corners at a vertex, corners are linked by a quadratic scan instead of a sort.
const SMALL_FAN: usize = 16;

/// Builds the rings of the kept `edges` of `triangles` (see the module's ordering rule).
///
/// Contract: `edges` are edges of `triangles` (coplanar ones may be missing); every vertex index is
/// below `vertex_count`. The result does not depend on the thread count.
pub fn rings(triangles: &[[u32; 3]], edges: &Edges, vertex_count: usize) -> Rings {
    rings_around(
        &VertexCorners::new(triangles.as_flattened(), vertex_count),
        triangles,
        edges,
        vertex_count,
    )
}

pub(crate) fn rings_around(
    corners: &VertexCorners,
    triangles: &[[u32; 3]],
    edges: &Edges,
    vertex_count: usize,
) -> Rings {
    let ends = VertexEnds::new(edges, vertex_count);
    let next: Vec<AtomicU32> = (0..2 * edges.len() as u32).map(AtomicU32::new).collect();
    let chunks = vertex_count.div_ceil(VERTICES_PER_CHUNK);
    let heads: Vec<Vec<u32>> = (0..chunks)
        .into_par_iter()
        .map(|chunk| {
            let mut walk = Walk::default();
            let mut heads = Vec::new();
            let first = chunk * VERTICES_PER_CHUNK;
            for v in first..(first + VERTICES_PER_CHUNK).min(vertex_count) {
                let ring = walk.ring(v as u32, corners, triangles, &ends);
                for (k, &end) in ring.iter().enumerate() {
                    next[end as usize].store(ring[(k + 1) % ring.len()], Ordering::Relaxed);
                }
                if ring.len() >= 2 {
                    heads.push(ring[0]);
                }
            }
            heads
        })
        .collect();
    Rings {
        next: next.into_iter().map(AtomicU32::into_inner).collect(),
        heads: heads.concat(),
    }
}

/// The kept edge ends at each vertex, as (other vertex, end): a counting sort of the `2E` ends by
/// vertex that also keeps the neighbour, so walks never fetch edges at random.
struct VertexEnds {
    starts: Vec<u32>,
    ends: Vec<(u32, u32)>,
}

impl VertexEnds {
    fn new(edges: &Edges, vertex_count: usize) -> Self {
        let mut starts = vec![0u32; vertex_count + 1];
        for v in &edges.vertices {
            starts[v[0] as usize + 1] += 1;
            starts[v[1] as usize + 1] += 1;
        }
        for v in 0..vertex_count {
            starts[v + 1] += starts[v];
        }
        let mut cursor = starts.clone();
        let mut ends = vec![(0u32, 0u32); 2 * edges.len()];
        for (e, v) in edges.vertices.iter().enumerate() {
            for end in 0..2 {
                let slot = &mut cursor[v[end] as usize];
                ends[*slot as usize] = (v[1 - end], (2 * e + end) as u32);
                *slot += 1;
            }
        }
        Self { starts, ends }
    }

    fn of(&self, v: u32) -> &[(u32, u32)] {
        &self.ends[self.starts[v as usize] as usize..self.starts[v as usize + 1] as usize]
    }
}

/// Reused per-thread buffers for ordering one vertex's edges.
#[derive(Default)]
struct Walk {
    /// (neighbour, role, local corner): role 0 when the neighbour is the corner's `a`, 1 for `b`.
    links: Vec<(u32, u8, u32)>,
    /// (a, b) per local corner.
    pairs: Vec<(u32, u32)>,
    /// Per local corner: the corner that follows it through its `b` edge, or `u32::MAX`.
    succ: Vec<u32>,
    has_pred: Vec<bool>,
    visited: Vec<bool>,
    /// Neighbours in turning order, with repeats.
    order: Vec<u32>,
    /// Kept ends at the vertex: (neighbour, end), sorted; and whether each is listed yet.
    kept: Vec<(u32, u32)>,
    listed: Vec<bool>,
    ring: Vec<u32>,
}

impl Walk {
    fn ring(
        &mut self,
        v: u32,
        corners: &VertexCorners,
        triangles: &[[u32; 3]],
        ends: &VertexEnds,
    ) -> &[u32] {
        self.ring.clear();
        let at_v = ends.of(v);
        if at_v.len() <= 1 {
            self.ring.extend(at_v.iter().map(|&(_, end)| end));
            return &self.ring;
        }
        let around = corners.of(v);
        // Link corner i to corner j when i's b edge is j's a edge and no other corner uses that edge.
        self.succ.clear();
        self.succ.resize(around.len(), u32::MAX);
        self.has_pred.clear();
        self.has_pred.resize(around.len(), false);
        self.pairs.clear();
        self.pairs
            .extend(around.iter().map(|&c| corner_neighbours(triangles, c)));
        if around.len() <= SMALL_FAN {
            // Typical valence (about 6): a quadratic scan beats sorting.
            for (i, &(_, x)) in self.pairs.iter().enumerate() {
                let mut to = u32::MAX;
                let (mut as_a, mut as_b) = (0, 0);
                for (j, &(a, b)) in self.pairs.iter().enumerate() {
                    if a == x {
                        as_a += 1;
                        to = j as u32;
                    }
                    as_b += u32::from(b == x);
                }
                if as_a == 1 && as_b == 1 {
                    self.succ[i] = to;
                    self.has_pred[to as usize] = true;
                }
            }
        } else {
            self.links.clear();
            for (local, &(a, b)) in self.pairs.iter().enumerate() {
                self.links.push((a, 0, local as u32));
                self.links.push((b, 1, local as u32));
            }
            self.links.sort_unstable();
            let mut i = 0;
            while i < self.links.len() {
                let mut j = i + 1;
                while j < self.links.len() && self.links[j].0 == self.links[i].0 {
                    j += 1;
                }
                if j - i == 2 && self.links[i].1 == 0 && self.links[i + 1].1 == 1 {
                    let (to, from) = (self.links[i].2, self.links[i + 1].2);
                    self.succ[from as usize] = to;
                    self.has_pred[to as usize] = true;
                }
                i = j;
            }
        }
        // Walk the open fans from their starts, then the closed ones, in corner order.
        self.order.clear();
        self.visited.clear();
        self.visited.resize(around.len(), false);
        for pass in 0..2 {
            for start in 0..around.len() {
                if self.visited[start] || (pass == 0 && self.has_pred[start]) {
                    continue;
                }
                self.order.push(self.pairs[start].0);
                let mut c = start as u32;
                while c != u32::MAX && !self.visited[c as usize] {
                    self.visited[c as usize] = true;
                    self.order.push(self.pairs[c as usize].1);
                    c = self.succ[c as usize];
                }
            }
        }
        // Keep the kept edges, each once, in walking order; anything never met goes last.
        self.kept.clear();
        self.kept.extend_from_slice(at_v);
        self.kept.sort_unstable();
        self.listed.clear();
        self.listed.resize(self.kept.len(), false);
        for &n in &self.order {
            let at = if self.kept.len() <= SMALL_FAN {
                self.kept
                    .iter()
                    .position(|&(m, _)| m == n)
                    .unwrap_or(self.kept.len())
            } else {
                self.kept.partition_point(|&(m, _)| m < n)
            };
            // Several kept edges to one neighbour cannot happen: edges are unique.
            if at < self.kept.len() && self.kept[at].0 == n && !self.listed[at] {
                self.listed[at] = true;
                self.ring.push(self.kept[at].1);
            }
        }
        for (k, &(_, end)) in self.kept.iter().enumerate() {
            if !self.listed[k] {
                self.ring.push(end);
            }
        }
        &self.ring
    }
}

/// The two other vertices of corner `c`'s triangle, in winding order after the corner's vertex.
fn corner_neighbours(triangles: &[[u32; 3]], c: u32) -> (u32, u32) {
    let t = triangles[c as usize / 3];
    let k = c as usize % 3;
    (t[(k + 1) % 3], t[(k + 2) % 3])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::adjacency;

    /// The neighbours of `v` in ring order, starting from the ring's first end at `v`.
    fn ring_neighbours(triangles: &[[u32; 3]], edges: &Edges, v: u32) -> Vec<u32> {
        let vertex_count = triangles
            .as_flattened()
            .iter()
            .max()
            .map_or(0, |&m| m as usize + 1);
        let rings = rings(triangles, edges, vertex_count);
        let other = |end: u32| edges.vertices[end as usize / 2][1 - end as usize % 2];
        let here = |end: u32| edges.vertices[end as usize / 2][end as usize % 2];
        let Some(start) = (0..rings.next.len() as u32).find(|&end| here(end) == v) else {
            return Vec::new();
        };
        let mut out = vec![other(start)];
        let mut end = rings.next[start as usize];
        while end != start {
            assert_eq!(here(end), v, "ring left the vertex");
            out.push(other(end));
            end = rings.next[end as usize];
            assert!(out.len() <= rings.next.len(), "ring does not close");
        }
        out
    }

    /// Rotates a ring so it starts at its smallest neighbour, for comparison.
    fn canonical(mut ring: Vec<u32>) -> Vec<u32> {
        if let Some(at) = ring
            .iter()
            .enumerate()
            .min_by_key(|&(_, &n)| n)
            .map(|(k, _)| k)
        {
            ring.rotate_left(at);
        }
        ring
    }

    /// Apex 0 over the square 1 2 3 4 (counter-clockwise seen from above), closed below.
    const PYRAMID: [[u32; 3]; 6] = [
        [0, 1, 2],
        [0, 2, 3],
        [0, 3, 4],
        [0, 4, 1],
        [1, 3, 2],
        [1, 4, 3],
    ];

    #[test]
    fn closed_fan_rings_turn_with_the_triangles() {
        let triangles = PYRAMID;
        let edges = adjacency(&triangles, &[], 5);
        assert_eq!(
            canonical(ring_neighbours(&triangles, &edges, 0)),
            vec![1, 2, 3, 4]
        );
    }

    #[test]
    fn open_fans_start_at_their_boundary_edge() {
        // Half a fan around 0: boundary edges 0-1 and 0-4, turning 1 -> 2 -> 3 -> 4.
        let triangles = [[0, 3, 4], [0, 1, 2], [0, 2, 3]];
        let edges = adjacency(&triangles, &[], 5);
        assert_eq!(ring_neighbours(&triangles, &edges, 0), vec![1, 2, 3, 4]);
        let rings = rings(&triangles, &edges, 5);
        // Vertex 0 has 4 edges, vertices 1..4 have 2 or 3: every vertex has a head.
        assert_eq!(rings.heads.len(), 5);
    }

    #[test]
    fn dropped_edges_are_skipped_in_turning_order() {
        let triangles = PYRAMID;
        let mut edges = adjacency(&triangles, &[], 5);
        let keep: Vec<bool> = edges
            .vertices
            .iter()
            .map(|v| v[0].min(v[1]) != 0 || v[0].max(v[1]) != 2)
            .collect();
        edges.retain(&keep);
        assert_eq!(
            canonical(ring_neighbours(&triangles, &edges, 0)),
            vec![1, 3, 4]
        );
    }

    #[test]
    fn non_manifold_vertices_list_every_fan_once() {
        // Three triangles on edge 0-1 (a book with three pages) plus a second fan at 0.
        let triangles = [[0, 1, 2], [1, 0, 3], [0, 1, 4], [0, 5, 6]];
        let edges = adjacency(&triangles, &[], 7);
        let mut ring = ring_neighbours(&triangles, &edges, 0);
        ring.sort_unstable();
        assert_eq!(ring, vec![1, 2, 3, 4, 5, 6]);
    }

    #[test]
    fn a_lone_edge_is_its_own_next_and_has_no_head() {
        let triangles = [[0, 1, 2]];
        let mut edges = adjacency(&triangles, &[], 3);
        edges.retain(&[true, false, false]); // keep only edge 0-1
        let rings = rings(&triangles, &edges, 3);
        assert_eq!(rings.next, vec![0, 1]);
        assert!(rings.heads.is_empty());
    }
}
