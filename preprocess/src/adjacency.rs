//! Adjacency: the unique undirected edges of a triangle mesh, each with the opposite vertices of its
//! first two faces — the edge mesh of thesis §8.1 / §10.2.
//!
//! ```text
//!      v2
//!     /  \        face a = (v0, v1, v2) in its own winding
//!   v0 -- v1      face b = the other face; v3 is its vertex opposite the edge
//!     \  /        boundary edge: no face b, v3 = v0 (thesis §6.2)
//!      v3
//! ```
//!
//! ```
//! use chamfer_preprocess::adjacency::adjacency;
//! // Two triangles sharing edge 0-2 of the quad 0 1 2 3.
//! let edges = adjacency(&[[0, 1, 2], [0, 2, 3]], &[], 4);
//! assert_eq!(edges.len(), 5);
//! assert_eq!(edges.vertices[1], [2, 0, 1, 3]); // edge {0, 2}: wound 2 -> 0 by face a = [0, 1, 2]
//! ```

use chamfer_runtime::asset::EdgeFlags;
use rayon::prelude::*;

/// Unique edges as parallel arrays, sorted by (lower vertex, higher vertex).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Edges {
    /// `v0 v1 v2 v3` per edge: `v0 -> v1` in the winding of face a, `v2` opposite in face a,
    /// `v3` opposite in face b (`v0` for a boundary edge).
    pub vertices: Vec<[u32; 4]>,
    /// Per edge: [`EdgeFlags::BOUNDARY`], [`EdgeFlags::NON_MANIFOLD`], [`EdgeFlags::FLIPPED`] and
    /// [`EdgeFlags::MATERIAL`] from here; later steps add the rest.
    pub flags: Vec<EdgeFlags>,
    /// Chamfer radius per edge, or empty when no edge has one.
    pub radii: Vec<f32>,
}

impl Edges {
    /// Number of edges.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// The edge joining `a` and `b` (either order), found by binary search.
    pub fn find(&self, a: u32, b: u32) -> Option<usize> {
        let key = (a.min(b), a.max(b));
        let at = self
            .vertices
            .partition_point(|v| (v[0].min(v[1]), v[0].max(v[1])) < key);
        (at < self.len()
            && (
                self.vertices[at][0].min(self.vertices[at][1]),
                self.vertices[at][0].max(self.vertices[at][1]),
            ) == key)
            .then_some(at)
    }

    /// Keeps the edges for which `keep[e]` is true, in order.
    pub fn retain(&mut self, keep: &[bool]) {
        let mut write = 0;
        for (read, _) in keep
            .iter()
            .enumerate()
            .take(self.len())
            .filter(|&(_, &k)| k)
        {
            {
                self.vertices[write] = self.vertices[read];
                self.flags[write] = self.flags[read];
                if !self.radii.is_empty() {
                    self.radii[write] = self.radii[read];
                }
                write += 1;
            }
        }
        self.vertices.truncate(write);
        self.flags.truncate(write);
        self.radii.truncate(write.min(self.radii.len()));
    }
}

/// Vertices per parallel work item: large enough to amortize scheduling, small enough to balance.
const VERTICES_PER_CHUNK: usize = 8192;

/// Builds the unique edges of `triangles`.
///
/// Face a of an edge is its face with the lowest triangle index; face b the next. An edge with one
/// face is [`EdgeFlags::BOUNDARY`]; with more than two, [`EdgeFlags::NON_MANIFOLD`] (kept, with the
/// first two faces). [`EdgeFlags::FLIPPED`] means faces a and b traverse the edge in the same
/// direction, so face b's normal must be negated to orient it like face a.
/// [`EdgeFlags::MATERIAL`] means two of its faces have different `materials` (pass an empty slice
/// when there is one material).
///
/// Contract: indices are below `vertex_count`, no triangle repeats a vertex (see
/// [`degenerate`](crate::degenerate)), fewer than 2^31 / 3 triangles, and `materials` is empty or
/// has one entry per triangle. The output is sorted by `(min(v0, v1), max(v0, v1))` and is the
/// same for any thread count. Memory: 8 bytes per corner plus 4 per vertex, freed on return.
pub fn adjacency(triangles: &[[u32; 3]], materials: &[u32], vertex_count: usize) -> Edges {
    // Half-edges bucketed by their lower vertex (a counting sort); each entry packs the higher vertex
    // (so sorting a bucket groups the half-edges of one edge), the corner, and the direction bit.
    let mut ends = vec![0u32; vertex_count + 1];
    for t in triangles {
        for k in 0..3 {
            ends[t[k].min(t[(k + 1) % 3]) as usize] += 1;
        }
    }
    let mut total = 0;
    for e in ends.iter_mut() {
        total += *e;
        *e = total - *e; // bucket start for now; becomes the bucket's end while filling
    }
    let mut entries = vec![0u64; triangles.len() * 3];
    for (ti, t) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let slot = &mut ends[a.min(b) as usize];
            entries[*slot as usize] =
                (u64::from(a.max(b)) << 32) | ((ti * 3 + k) as u64) << 1 | u64::from(a > b);
            *slot += 1;
        }
    }
    // Now ends[v] is where v's bucket ends (and v + 1's starts).
    let bucket = |v: usize| if v == 0 { 0 } else { ends[v - 1] as usize }..ends[v] as usize;

    // Split the buckets into chunks of whole vertices, sort each bucket, count its distinct edges.
    let chunk_ranges: Vec<std::ops::Range<usize>> = (0..vertex_count)
        .step_by(VERTICES_PER_CHUNK)
        .map(|start| start..(start + VERTICES_PER_CHUNK).min(vertex_count))
        .collect();
    let mut chunks: Vec<(std::ops::Range<usize>, &mut [u64])> =
        Vec::with_capacity(chunk_ranges.len());
    let mut rest = entries.as_mut_slice();
    for r in &chunk_ranges {
        let len = if r.is_empty() {
            0
        } else {
            bucket(r.end - 1).end - bucket(r.start).start
        };
        let (head, tail) = rest.split_at_mut(len);
        chunks.push((r.clone(), head));
        rest = tail;
    }
    let counts: Vec<usize> = chunks
        .par_iter_mut()
        .map(|(range, slice)| {
            let base = bucket(range.start).start;
            range
                .clone()
                .map(|v| {
                    let b = bucket(v);
                    let edges = &mut slice[b.start - base..b.end - base];
                    edges.sort_unstable();
                    edges.chunk_by(same_edge).count()
                })
                .sum()
        })
        .collect();

    // Emit every edge into its chunk's part of the output.
    let edge_count: usize = counts.iter().sum();
    let mut vertices = vec![[0u32; 4]; edge_count];
    let mut flags = vec![EdgeFlags::default(); edge_count];
    let mut outputs = Vec::with_capacity(chunks.len());
    let (mut rest_v, mut rest_f) = (vertices.as_mut_slice(), flags.as_mut_slice());
    for &count in &counts {
        let (v, tail_v) = rest_v.split_at_mut(count);
        let (f, tail_f) = rest_f.split_at_mut(count);
        outputs.push((v, f));
        (rest_v, rest_f) = (tail_v, tail_f);
    }
    chunks
        .into_par_iter()
        .zip(outputs)
        .for_each(|((range, slice), (out_v, out_f))| {
            let base = bucket(range.start).start;
            let mut write = 0;
            for v in range {
                let b = bucket(v);
                let half_edges = &slice[b.start - base..b.end - base];
                for group in half_edges.chunk_by(same_edge) {
                    (out_v[write], out_f[write]) = edge_from_group(group, triangles, materials);
                    write += 1;
                }
            }
        });
    Edges {
        vertices,
        flags,
        radii: Vec::new(),
    }
}

/// Half-edges with the same higher vertex form one edge (buckets are sorted, so they are adjacent).
fn same_edge(x: &u64, y: &u64) -> bool {
    x >> 32 == y >> 32
}

/// Builds one edge from the half-edges that share it, sorted by corner.
fn edge_from_group(
    group: &[u64],
    triangles: &[[u32; 3]],
    materials: &[u32],
) -> ([u32; 4], EdgeFlags) {
    let corner = |entry: u64| ((entry >> 1) & 0x7fff_ffff) as usize;
    let reversed = |entry: u64| entry & 1;
    let (ta, ka) = (corner(group[0]) / 3, corner(group[0]) % 3);
    let face_a = triangles[ta];
    let (v0, v1, v2) = (face_a[ka], face_a[(ka + 1) % 3], face_a[(ka + 2) % 3]);
    let mut flags = EdgeFlags::default();
    let v3 = match group {
        [_] => {
            flags |= EdgeFlags::BOUNDARY;
            v0
        }
        [a, b, rest @ ..] => {
            if !rest.is_empty() {
                flags |= EdgeFlags::NON_MANIFOLD;
            }
            if reversed(*a) == reversed(*b) {
                flags |= EdgeFlags::FLIPPED;
            }
            let (tb, kb) = (corner(*b) / 3, corner(*b) % 3);
            triangles[tb][(kb + 2) % 3]
        }
        [] => unreachable!("a group holds at least one half-edge"),
    };
    if !materials.is_empty()
        && group
            .iter()
            .any(|&h| materials[corner(h) / 3] != materials[ta])
    {
        flags |= EdgeFlags::MATERIAL;
    }
    ([v0, v1, v2, v3], flags)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flags_of(edges: &Edges, a: u32, b: u32) -> EdgeFlags {
        edges.flags[edges.find(a, b).expect("edge exists")]
    }

    #[test]
    fn open_quad() {
        // 3 --- 2
        // |   / |    [0, 1, 2] and [0, 2, 3] share the diagonal 0-2
        // | /   |
        // 0 --- 1
        let edges = adjacency(&[[0, 1, 2], [0, 2, 3]], &[], 4);
        assert_eq!(
            edges.vertices,
            [
                [0, 1, 2, 0],
                [2, 0, 1, 3],
                [3, 0, 2, 3],
                [1, 2, 0, 1],
                [2, 3, 0, 2]
            ]
        );
        let boundary: Vec<bool> = edges
            .flags
            .iter()
            .map(|f| f.contains(EdgeFlags::BOUNDARY))
            .collect();
        assert_eq!(boundary, [true, false, true, true, true]);
        assert!(
            edges
                .flags
                .iter()
                .all(|f| !f.intersects(EdgeFlags::FLIPPED | EdgeFlags::NON_MANIFOLD))
        );
    }

    #[test]
    fn closed_tetrahedron_has_six_interior_edges() {
        let t = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let edges = adjacency(&t, &[], 4);
        assert_eq!(edges.len(), 6);
        assert!(edges.flags.iter().all(|f| *f == EdgeFlags::default()));
        // Every edge's v2 and v3 are the two vertices not on it.
        for v in &edges.vertices {
            let mut all = *v;
            all.sort();
            assert_eq!(all, [0, 1, 2, 3]);
        }
    }

    #[test]
    fn non_manifold_fan_keeps_the_edge_and_flags_it() {
        //   2   3   4      three triangles on edge 0-1
        //    \  |  /
        //     0---1
        let edges = adjacency(&[[0, 1, 2], [1, 0, 3], [0, 1, 4]], &[], 5);
        let e = edges.find(0, 1).expect("shared edge");
        assert_eq!(edges.vertices[e], [0, 1, 2, 3]);
        assert!(edges.flags[e].contains(EdgeFlags::NON_MANIFOLD));
        assert_eq!(edges.len(), 7);
        assert_eq!(
            edges
                .flags
                .iter()
                .filter(|f| f.contains(EdgeFlags::BOUNDARY))
                .count(),
            6
        );
    }

    #[test]
    fn inconsistent_winding_is_flagged() {
        let edges = adjacency(&[[0, 1, 2], [0, 1, 3]], &[], 4);
        assert!(flags_of(&edges, 0, 1).contains(EdgeFlags::FLIPPED));
        assert!(!flags_of(&edges, 1, 2).contains(EdgeFlags::FLIPPED));
    }

    #[test]
    fn material_seams_are_flagged() {
        let edges = adjacency(&[[0, 1, 2], [0, 2, 3]], &[0, 1], 4);
        assert!(flags_of(&edges, 0, 2).contains(EdgeFlags::MATERIAL));
        assert!(!flags_of(&edges, 0, 1).contains(EdgeFlags::MATERIAL));
    }

    #[test]
    fn output_is_the_same_across_chunk_boundaries_and_thread_counts() {
        // A strip long enough to span several chunks.
        let n = 3 * VERTICES_PER_CHUNK as u32;
        let tris: Vec<[u32; 3]> = (0..n - 2)
            .map(|i| {
                if i % 2 == 0 {
                    [i, i + 1, i + 2]
                } else {
                    [i + 1, i, i + 2]
                }
            })
            .collect();
        let a = adjacency(&tris, &[], n as usize);
        let single = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("pool");
        let b = single.install(|| adjacency(&tris, &[], n as usize));
        assert_eq!(a, b);
        assert_eq!(a.len(), 2 * (n as usize - 2) + 1);
        let keys: Vec<(u32, u32)> = a
            .vertices
            .iter()
            .map(|v| (v[0].min(v[1]), v[0].max(v[1])))
            .collect();
        assert!(keys.windows(2).all(|w| w[0] < w[1]), "sorted and unique");
    }
}
