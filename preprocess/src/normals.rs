//! Split normals: per-corner, angle-weighted vertex normals that do not smooth across creases or
//! marked edges (thesis §9.2), as the render vertex and index buffers of the asset.
//!
//! The corners around a vertex fall into *fans* joined through smooth edges; each fan becomes one
//! render vertex whose normal is the angle-weighted sum of its faces' normals (Thürmer & Wüthrich).
//!
//! ```text
//!   crease      corners on either side of a crease get separate render vertices,
//!   ----v----   each with the normal of its own side; across smooth or coplanar edges
//!   a  | b      the corners share one render vertex
//! ```

use std::sync::atomic::{AtomicU32, Ordering};

use chamfer_runtime::asset::EdgeFlags;
use glam::Vec3;
use rayon::prelude::*;

use crate::adjacency::Edges;
use chamfer_runtime::asset::corners::VertexCorners;

/// Render buffers with normals split at creases.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderMesh {
    /// Position of each render vertex (its topology vertex's position).
    pub positions: Vec<[f32; 3]>,
    /// Unit normal of each render vertex.
    pub normals: Vec<[f32; 3]>,
    /// Three render vertex indices per triangle, in the order and winding of the input triangles.
    pub indices: Vec<u32>,
}

/// Edges that end a fan: normals are not averaged across them.
const SPLIT: EdgeFlags = EdgeFlags(
    EdgeFlags::CREASE.0 | EdgeFlags::MARKED.0 | EdgeFlags::NON_MANIFOLD.0 | EdgeFlags::FLIPPED.0,
);

const VERTICES_PER_CHUNK: usize = 4096;

/// Builds render vertices, one per (topology vertex, fan), and their angle-weighted normals.
///
/// Two corners at a vertex are in the same fan when their triangles share an edge at that vertex
/// that has exactly two faces and is not a crease, marked, non-manifold or inconsistently wound.
/// Edges missing from `edges` (dropped as coplanar) are smooth.
///
/// Contract: `triangles` index `positions` and have no degenerate triangle; `edges` are the
/// classified edges of `triangles`, in any order. Render vertices are numbered by topology vertex,
/// then by each fan's first corner, so the output is the same for any thread count.
pub fn split_normals(positions: &[Vec3], triangles: &[[u32; 3]], edges: &Edges) -> RenderMesh {
    let corners = VertexCorners::new(triangles.as_flattened(), positions.len());
    split_normals_around(corners, positions, triangles, edges)
}

/// [`split_normals`] with the corner lists already built; frees them as soon as it is done with them.
pub(crate) fn split_normals_around(
    corners: VertexCorners,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    edges: &Edges,
) -> RenderMesh {
    let vertex_count = positions.len();
    let split = SplitLookup::new(edges, vertex_count);

    // Per vertex: how many fans; per corner: its fan (local to the vertex); per fan: its normal.
    let corner_fan: Vec<AtomicU32> = (0..triangles.len() * 3)
        .map(|_| AtomicU32::new(0))
        .collect();
    let mut fan_count = vec![0u32; vertex_count];
    let chunk_normals: Vec<Vec<[f32; 3]>> = fan_count
        .par_chunks_mut(VERTICES_PER_CHUNK)
        .enumerate()
        .map(|(chunk, counts)| {
            let mut normals = Vec::new();
            let mut scratch = FanScratch::default();
            for (i, count) in counts.iter_mut().enumerate() {
                let v = (chunk * VERTICES_PER_CHUNK + i) as u32;
                *count = scratch.fans(
                    v,
                    &corners,
                    triangles,
                    positions,
                    &split,
                    &corner_fan,
                    &mut normals,
                );
            }
            normals
        })
        .collect();
    drop((corners, split));

    // Number render vertices: vertex by vertex, fan by fan.
    let mut first_render = Vec::with_capacity(vertex_count);
    let mut render_positions = Vec::new();
    for (v, &count) in fan_count.iter().enumerate() {
        first_render.push(render_positions.len() as u32);
        render_positions.extend(std::iter::repeat_n(positions[v].to_array(), count as usize));
    }
    drop(fan_count);
    // Each corner's fan becomes its render vertex in place.
    let mut indices: Vec<u32> = corner_fan.into_iter().map(AtomicU32::into_inner).collect();
    indices
        .par_iter_mut()
        .enumerate()
        .for_each(|(c, fan)| *fan += first_render[triangles[c / 3][c % 3] as usize]);
    RenderMesh {
        positions: render_positions,
        normals: chunk_normals.concat(),
        indices,
    }
}

/// Finds whether the edge between two vertices ends a fan.
///
/// Split edges are few (creases and marks), so they are kept apart in a sorted list, and a bit per
/// vertex says whether any touches it: almost every query is answered by two bit tests.
struct SplitLookup {
    touched: Vec<u64>,
    split: Vec<(u32, u32)>,
}

impl SplitLookup {
    fn new(edges: &Edges, vertex_count: usize) -> Self {
        let mut touched = vec![0u64; vertex_count.div_ceil(64)];
        let mut split = Vec::new();
        for (v, flags) in edges.vertices.iter().zip(&edges.flags) {
            if flags.intersects(SPLIT) {
                split.push((v[0].min(v[1]), v[0].max(v[1])));
                for &x in &v[..2] {
                    touched[x as usize / 64] |= 1 << (x % 64);
                }
            }
        }
        // Few, and the edges may come in any order (the bake writes them in cluster order).
        split.sort_unstable();
        Self { touched, split }
    }

    fn touches(&self, v: u32) -> bool {
        self.touched[v as usize / 64] & (1 << (v % 64)) != 0
    }

    fn is_split(&self, a: u32, b: u32) -> bool {
        self.touches(a)
            && self.touches(b)
            && self.split.binary_search(&(a.min(b), a.max(b))).is_ok()
    }
}

/// Reused per-thread buffers for grouping one vertex's corners.
#[derive(Default)]
struct FanScratch {
    /// (neighbour vertex, local corner) for both neighbours of every corner.
    links: Vec<(u32, u32)>,
    parent: Vec<u32>,
    fan_of_root: Vec<u32>,
}

impl FanScratch {
    /// Groups the corners of `v` into fans, writes each corner's fan, appends each fan's normal.
    #[allow(clippy::too_many_arguments)]
    fn fans(
        &mut self,
        v: u32,
        corners: &VertexCorners,
        triangles: &[[u32; 3]],
        positions: &[Vec3],
        split: &SplitLookup,
        corner_fan: &[AtomicU32],
        normals: &mut Vec<[f32; 3]>,
    ) -> u32 {
        let around = corners.of(v);
        self.links.clear();
        for (local, &c) in around.iter().enumerate() {
            let t = triangles[c as usize / 3];
            let k = c as usize % 3;
            self.links.push((t[(k + 1) % 3], local as u32));
            self.links.push((t[(k + 2) % 3], local as u32));
        }
        self.links.sort_unstable();
        self.parent.clear();
        self.parent.extend(0..around.len() as u32);
        // Corners sharing a neighbour share an edge; join them if it has exactly two faces and is smooth.
        let mut i = 0;
        while i < self.links.len() {
            let mut j = i + 1;
            while j < self.links.len() && self.links[j].0 == self.links[i].0 {
                j += 1;
            }
            if j - i == 2 && !split.is_split(v, self.links[i].0) {
                union(&mut self.parent, self.links[i].1, self.links[i + 1].1);
            }
            i = j;
        }
        // Fans are numbered by their first corner; accumulate angle-weighted face normals.
        let first_fan = normals.len();
        self.fan_of_root.clear();
        self.fan_of_root.resize(around.len(), u32::MAX);
        for (local, &c) in around.iter().enumerate() {
            let root = find(&mut self.parent, local as u32) as usize;
            if self.fan_of_root[root] == u32::MAX {
                self.fan_of_root[root] = (normals.len() - first_fan) as u32;
                normals.push([0.0; 3]);
            }
            let fan = self.fan_of_root[root];
            corner_fan[c as usize].store(fan, Ordering::Relaxed);
            let sum = &mut normals[first_fan + fan as usize];
            *sum = (Vec3::from(*sum) + corner_weighted_normal(triangles, positions, c as usize))
                .to_array();
        }
        for n in &mut normals[first_fan..] {
            // Opposite faces cancel (only possible at a pinch): any unit vector beats a NaN.
            *n = Vec3::from(*n).try_normalize().unwrap_or(Vec3::Z).to_array();
        }
        (normals.len() - first_fan) as u32
    }
}

/// The face's unit normal weighted by the corner's angle.
fn corner_weighted_normal(triangles: &[[u32; 3]], positions: &[Vec3], c: usize) -> Vec3 {
    let t = triangles[c / 3];
    let k = c % 3;
    let p = |i: usize| positions[t[(k + i) % 3] as usize];
    let (e1, e2) = (p(1) - p(0), p(2) - p(0));
    let n = e1.cross(e2);
    let length = n.length();
    if length == 0.0 {
        return Vec3::ZERO;
    }
    n * (fast_atan2(length, e1.dot(e2)) / length)
}

/// atan2 for `y >= 0` within 1e-5 radians: plenty for a weight, and four times cheaper than libm's.
fn fast_atan2(y: f32, x: f32) -> f32 {
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    if hi == 0.0 {
        return 0.0;
    }
    let a = lo / hi;
    let s = a * a;
    // Minimax polynomial for atan on [0, 1] (max error about 1e-5 rad): plenty for a weight.
    let mut r = a
        * (0.999_977_26
            + s * (-0.332_623_47
                + s * (0.193_543_46 + s * (-0.116_432_87 + s * (0.052_653_32 - 0.011_721_2 * s)))));
    if ay > ax {
        r = std::f32::consts::FRAC_PI_2 - r;
    }
    if x < 0.0 { std::f32::consts::PI - r } else { r }
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        parent[x as usize] = parent[parent[x as usize] as usize];
        x = parent[x as usize];
    }
    x
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    // The lower root wins, so fan numbering never depends on the order of unions.
    let (lo, hi) = (ra.min(rb), ra.max(rb));
    parent[hi as usize] = lo;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::adjacency;
    use crate::classify::classify;

    fn render(p: &[Vec3], t: &[[u32; 3]]) -> RenderMesh {
        let mut edges = adjacency(t, &[], p.len());
        classify(p, &mut edges, &[], 0.01, 30.0);
        split_normals(p, t, &edges)
    }

    #[test]
    fn cube_corners_split_into_three_fans_with_axis_normals() {
        let (p, t) = crate::classify::tests::cube();
        let r = render(&p, &t);
        assert_eq!(r.positions.len(), 24, "8 corners x 3 faces");
        for n in &r.normals {
            let axes = n.iter().filter(|c| c.abs() > 0.999).count();
            assert_eq!(axes, 1, "normal {n:?} is an axis");
        }
        // Each triangle's three render vertices share its face normal.
        for tri in r.indices.chunks(3) {
            let n = r.normals[tri[0] as usize];
            assert!(tri.iter().all(|&i| r.normals[i as usize] == n));
        }
    }

    #[test]
    fn edges_in_any_order_give_the_same_render_mesh() {
        // The bake hands the edges over in cluster order, not sorted by vertex.
        let (p, t) = crate::classify::tests::cube();
        let mut edges = adjacency(&t, &[], p.len());
        classify(&p, &mut edges, &[], 0.01, 30.0);
        let sorted = split_normals(&p, &t, &edges);
        edges.vertices.reverse();
        edges.flags.reverse();
        assert_eq!(split_normals(&p, &t, &edges), sorted);
        assert_eq!(sorted.positions.len(), 24);
    }

    #[test]
    fn fast_atan2_is_within_its_error_bound() {
        for i in 0..=2000 {
            let angle = std::f32::consts::PI * i as f32 / 2000.0;
            let (y, x) = (angle.sin() * 3.0, angle.cos() * 3.0);
            assert!(
                (fast_atan2(y.max(0.0), x) - y.max(0.0).atan2(x)).abs() < 2e-5,
                "{angle}"
            );
        }
    }

    #[test]
    fn smooth_fold_shares_one_normal_per_vertex() {
        // A shallow roof (10 degrees) stays smooth: 4 render vertices, shared normals on the ridge.
        let h = 10f32.to_radians().tan() * 0.5;
        let p = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.5, 1.0, 0.0).with_z(0.0),
            Vec3::new(0.5, -1.0, 0.0),
        ];
        let p = [p[0].with_z(h), p[1].with_z(h), p[2], p[3]];
        let r = render(&p, &[[0, 1, 2], [1, 0, 3]]);
        assert_eq!(r.positions.len(), 4);
        let up = Vec3::from(r.normals[0]);
        assert!(up.z > 0.99 && up.x.abs() < 1e-6, "{up}");
    }
}
