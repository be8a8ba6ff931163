//! Intersection edges: the curves along which triangles cut through each other (thesis §2.2,
//! "Intersection/Self-Intersection/Collision Edge"; §6.1 notes that object-space edge tests cannot find
//! them, because they follow no mesh edge, so the bake finds them once, for static geometry).
//!
//! One entry, [`find_intersections`], over the welded mesh the bake builds (the loaders flatten every
//! OBJ object and every glTF primitive and node instance into that one mesh, so self-intersections
//! and intersections between parts are the same search):
//!
//! 1. **Candidates.** An obvhs BVH2 over the triangles' bounding boxes; each triangle's box is
//!    traversed with `Bvh2::aabb_traverse`, and a pair is tested once, from its lower-numbered
//!    triangle.
//! 2. **Pair test.** Which side of each plane every vertex of the other triangle lies on is decided
//!    exactly (Shewchuk's adaptive `orient3d`, from the `robust` crate, on the f32 inputs widened to f64).
//!    - Pairs sharing two vertices (an edge of the welded mesh) meet only along that edge: skipped.
//!    - Pairs sharing one vertex are tested like any other: they touch at the shared vertex, which is
//!      no curve, but one can still pierce the other starting from that vertex (a fold-over), and that
//!      segment is an intersection edge.
//!    - Coplanar pairs give no curve (rule: coplanar overlap is a coincident surface, not a cut); they
//!      are counted.
//!    - Otherwise each triangle meets the other's plane in a segment on the planes' common line; the
//!      intersection is the overlap of the two segments. Overlaps of zero length (touching at a
//!      point) give nothing.
//! 3. **Points.** Each end is a vertex, or the crossing of a mesh edge with the other triangle's plane,
//!    computed from the edge's vertices in index order and the plane's triangle as stored, so the
//!    same crossing found from the two triangles of that edge is the same f32 point, bit for bit.
//! 4. **Weld and chain.** End points are welded (bitwise, then within 1e-6 of the largest coordinate,
//!    for the rounding of degenerate edge–edge crossings), repeated segments (a curve running along a
//!    mesh edge is found from both of its faces) are dropped, and the segments are chained into
//!    polylines, which end where three or more segments meet.
//!
//! Triangles with a vertex index out of range, a non-finite position, a repeated vertex or zero area
//! are skipped and counted. The result depends only on the input, never on the thread count or the
//! BVH's shape: segments are sorted before they are welded and chained.

use std::collections::HashMap;

use glam::{DVec3, Vec3};
use obvhs::aabb::Aabb;
use obvhs::bvh2::node::Bvh2Node;
use rayon::prelude::*;

use crate::degenerate::is_degenerate;
use crate::polylines;

/// The intersection curves of a mesh, as the asset stores them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Intersections {
    /// Segments as end-point pairs, polyline after polyline; within a polyline each segment starts
    /// exactly (bitwise) where the previous one ends.
    pub segments: Vec<[[f32; 3]; 2]>,
    /// Index of each polyline's first segment, strictly increasing from 0.
    pub starts: Vec<u32>,
    /// What the search saw.
    pub stats: IntersectionStats,
}

/// Counts of the search, for reports and tests.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IntersectionStats {
    /// Triangles skipped: an index out of range, a non-finite position, a repeated vertex or zero area.
    pub skipped_triangles: u64,
    /// Pairs of triangles whose bounding boxes overlap (each unordered pair once).
    pub candidate_pairs: u64,
    /// Candidate pairs that share an edge of the welded mesh, skipped.
    pub neighbour_pairs: u64,
    /// Candidate pairs in one plane, which give no curve.
    pub coplanar_pairs: u64,
    /// Pairs that cross along a segment of non-zero length.
    pub crossing_pairs: u64,
    /// Segments after welding and removing repeats.
    pub segments: u64,
    /// Polylines.
    pub polylines: u64,
    /// Polylines whose last point is their first.
    pub closed_polylines: u64,
    /// Total length, in mesh units.
    pub length: f64,
}

/// Finds where the triangles cut through each other; see the module documentation.
///
/// `triangles` index `positions`; pairs that share an edge are recognised by index, so weld the
/// positions first (the bake does). Bad triangles are skipped and counted, never a panic.
pub fn find_intersections(positions: &[Vec3], triangles: &[[u32; 3]]) -> Intersections {
    let usable: Vec<[u32; 3]> = triangles
        .iter()
        .copied()
        .filter(|&t| is_usable(t, positions))
        .collect();
    let mut stats = IntersectionStats {
        skipped_triangles: (triangles.len() - usable.len()) as u64,
        ..IntersectionStats::default()
    };
    let (raw, counts) = crossing_segments(positions, &usable);
    stats.candidate_pairs = counts.candidates;
    stats.neighbour_pairs = counts.neighbours;
    stats.coplanar_pairs = counts.coplanar;
    stats.crossing_pairs = raw.len() as u64;
    let (points, edges) = join_segment_ends(raw);
    let (segments, starts, closed) = chain(&points, &edges);
    stats.segments = segments.len() as u64;
    stats.polylines = starts.len() as u64;
    stats.closed_polylines = closed;
    stats.length = segments
        .iter()
        .map(|[a, b]| (Vec3::from(*b).as_dvec3() - Vec3::from(*a).as_dvec3()).length())
        .sum::<f64>()
        + 0.0; // an empty sum is -0.0
    Intersections {
        segments,
        starts,
        stats,
    }
}

/// The exact pair test alone, as [`find_intersections`] runs it on every candidate pair: where
/// triangles `a` and `b` (vertex indices into `positions`) cross, if along a segment of non-zero
/// length (end points in a fixed order). Pairs sharing an edge, coplanar pairs, pairs that only
/// touch, and bad triangles give `None`.
pub fn intersect_triangles(positions: &[Vec3], a: [u32; 3], b: [u32; 3]) -> Option<[Vec3; 2]> {
    if !is_usable(a, positions) || !is_usable(b, positions) {
        return None;
    }
    match intersect_pair(&Face::new(a, positions), &Face::new(b, positions)) {
        Pair::Crossing(segment) => Some(segment),
        _ => None,
    }
}

fn is_usable(t: [u32; 3], positions: &[Vec3]) -> bool {
    t.iter()
        .all(|&i| positions.get(i as usize).is_some_and(|p| p.is_finite()))
        && !is_degenerate(t, positions)
}

#[derive(Clone, Copy, Default)]
struct PairCounts {
    candidates: u64,
    neighbours: u64,
    coplanar: u64,
}

impl std::ops::Add for PairCounts {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            candidates: self.candidates + o.candidates,
            neighbours: self.neighbours + o.neighbours,
            coplanar: self.coplanar + o.coplanar,
        }
    }
}

/// One segment per crossing pair, sorted, each with its end points in ascending order.
fn crossing_segments(positions: &[Vec3], triangles: &[[u32; 3]]) -> (Vec<[Vec3; 2]>, PairCounts) {
    if triangles.len() < 2 {
        return (Vec::new(), PairCounts::default());
    }
    let boxes: Vec<Aabb> = triangles
        .par_iter()
        .map(|t| {
            let p = t.map(|i| positions[i as usize]);
            Aabb::new(
                p[0].min(p[1]).min(p[2]).into(),
                p[0].max(p[1]).max(p[2]).into(),
            )
        })
        .collect();
    let bvh = crate::bvh::build(&boxes);
    let overlaps = SelfOverlaps {
        nodes: &bvh.nodes,
        // The triangles in leaf order, so a leaf's triangles lie together in memory.
        leaf_order: bvh
            .primitive_indices
            .iter()
            .map(|&t| (t, triangles[t as usize], boxes[t as usize]))
            .collect(),
        positions,
    };
    let (mut segments, counts) = overlaps
        .tasks()
        .into_par_iter()
        .fold(
            || (Vec::new(), PairCounts::default()),
            |(mut found, mut counts), task| {
                overlaps.visit(task, &mut found, &mut counts);
                (found, counts)
            },
        )
        .reduce(
            || (Vec::new(), PairCounts::default()),
            |(mut a, ca), (b, cb)| {
                a.extend(b);
                (a, ca + cb)
            },
        );
    segments.par_sort_unstable_by(|x, y| segment_key(x).cmp(&segment_key(y)));
    (segments, counts)
}

/// The pairs of a BVH2's leaves whose boxes overlap, found by traversing the tree against itself
/// (obvhs has no self-overlap query): a node pair `(x, x)` stands for the pairs within `x`'s subtree,
/// and becomes `(l, l)`, `(r, r)` and `(l, r)`; a pair of distinct nodes whose boxes overlap descends
/// into the larger (an inner node before a leaf). Every unordered pair of triangles in overlapping
/// leaves is met exactly once, and each node pair is visited once, unlike one box query per
/// triangle, which walks from the root every time and meets every pair twice.
struct SelfOverlaps<'a> {
    nodes: &'a [Bvh2Node],
    /// Per leaf slot: the triangle's index in the input, its vertices and its box.
    leaf_order: Vec<(u32, [u32; 3], Aabb)>,
    positions: &'a [Vec3],
}

impl SelfOverlaps<'_> {
    /// Node pairs to visit, independent of each other: the tree's top expanded into enough pairs
    /// for every thread to have many.
    fn tasks(&self) -> Vec<(u32, u32)> {
        let mut tasks = vec![(0u32, 0u32)];
        for _ in 0..8 {
            let mut next = Vec::with_capacity(tasks.len() * 3);
            for &(x, y) in &tasks {
                match self.children(x, y) {
                    Some(pairs) => next.extend(pairs.into_iter().flatten()),
                    None => next.push((x, y)),
                }
            }
            tasks = next;
        }
        tasks
    }

    /// The node pairs that `(x, y)` stands for, if it can be split (`None` for two leaves or a
    /// leaf with itself); pairs whose boxes do not overlap are left out.
    fn children(&self, x: u32, y: u32) -> Option<[Option<(u32, u32)>; 3]> {
        let (nx, ny) = (&self.nodes[x as usize], &self.nodes[y as usize]);
        let keep = |a: u32, b: u32| {
            (a == b
                || self.nodes[a as usize]
                    .aabb()
                    .intersect_aabb(self.nodes[b as usize].aabb()))
            .then_some((a, b))
        };
        if x == y {
            if nx.is_leaf() {
                return None;
            }
            let (l, r) = (nx.first_index, nx.first_index + 1);
            return Some([keep(l, l), keep(r, r), keep(l, r)]);
        }
        let split_x =
            !nx.is_leaf() && (ny.is_leaf() || nx.aabb().half_area() >= ny.aabb().half_area());
        if split_x {
            Some([keep(nx.first_index, y), keep(nx.first_index + 1, y), None])
        } else if !ny.is_leaf() {
            Some([keep(x, ny.first_index), keep(x, ny.first_index + 1), None])
        } else {
            None
        }
    }

    /// Tests every triangle pair under the node pair `task`.
    fn visit(&self, task: (u32, u32), found: &mut Vec<[Vec3; 2]>, counts: &mut PairCounts) {
        let mut stack = vec![task];
        while let Some((x, y)) = stack.pop() {
            match self.children(x, y) {
                Some(pairs) => stack.extend(pairs.into_iter().flatten()),
                None => self.test_leaves(x, y, found, counts),
            }
        }
    }

    fn test_leaves(&self, x: u32, y: u32, found: &mut Vec<[Vec3; 2]>, counts: &mut PairCounts) {
        let slots = |n: u32| {
            let node = &self.nodes[n as usize];
            node.first_index as usize..(node.first_index + node.prim_count) as usize
        };
        for i in slots(x) {
            let (ti, vi, bi) = self.leaf_order[i];
            let others = if x == y {
                i + 1..slots(y).end
            } else {
                slots(y)
            };
            let mut face = None;
            for j in others {
                let (tj, vj, bj) = self.leaf_order[j];
                if !bi.intersect_aabb(&bj) {
                    continue;
                }
                counts.candidates += 1;
                let face = face.get_or_insert_with(|| Face::new(vi, self.positions));
                let other = Face::new(vj, self.positions);
                // The lower-numbered triangle goes first, so the result does not depend on the tree.
                let pair = if ti < tj {
                    intersect_pair(face, &other)
                } else {
                    intersect_pair(&other, face)
                };
                match pair {
                    Pair::Neighbours => counts.neighbours += 1,
                    Pair::Coplanar => counts.coplanar += 1,
                    Pair::Apart => {}
                    Pair::Crossing(s) => found.push(s),
                }
            }
        }
    }
}

/// A total order on segments by their coordinates' bits (the end points are already ordered).
fn segment_key(s: &[Vec3; 2]) -> [u32; 6] {
    let [a, b] = s.map(point_key);
    [a[0], a[1], a[2], b[0], b[1], b[2]]
}

/// Order-preserving bits of a finite point (+0.0 and -0.0 are one point).
fn point_key(p: Vec3) -> [u32; 3] {
    p.to_array().map(|x| {
        let bits = (x + 0.0).to_bits();
        if bits >> 31 == 1 {
            !bits
        } else {
            bits | 1 << 31
        }
    })
}

enum Pair {
    /// No common point, or only one.
    Apart,
    /// Sharing an edge of the mesh.
    Neighbours,
    /// In one plane.
    Coplanar,
    /// Crossing along this segment (end points in ascending [`point_key`] order).
    Crossing([Vec3; 2]),
}

/// A triangle ready for pair tests: its vertex indices, positions and plane.
struct Face {
    indices: [u32; 3],
    points: [Vec3; 3],
    plane: Plane,
}

impl Face {
    fn new(indices: [u32; 3], positions: &[Vec3]) -> Self {
        let points = indices.map(|i| positions[i as usize]);
        Self {
            indices,
            points,
            plane: Plane::new(&points),
        }
    }

    /// The exact side of each vertex of `other` relative to this face's plane. A shared vertex lies
    /// on both planes: that is known without the predicate (whose exact, slow path an exact zero
    /// would always take).
    fn sides_of(&self, other: &Face) -> [i8; 3] {
        std::array::from_fn(|k| {
            if self.indices.contains(&other.indices[k]) {
                0
            } else {
                self.plane.side(&self.points, other.points[k])
            }
        })
    }
}

/// A triangle's plane in f64, with what bounds the rounding of a side test against it.
struct Plane {
    origin: DVec3,
    /// `(b - a) × (c - a)`, not normalised.
    normal: DVec3,
    /// Per component, the sum of the absolute values of the two products in `normal`'s component.
    magnitude: DVec3,
}

impl Plane {
    fn new(t: &[Vec3; 3]) -> Self {
        let [a, b, c] = t.map(Vec3::as_dvec3);
        let (u, v) = (b - a, c - a);
        Self {
            origin: a,
            normal: u.cross(v),
            magnitude: DVec3::new(
                (u.y * v.z).abs() + (u.z * v.y).abs(),
                (u.z * v.x).abs() + (u.x * v.z).abs(),
                (u.x * v.y).abs() + (u.y * v.x).abs(),
            ),
        }
    }

    /// Signed distance of `q` times the normal's length, rounded.
    fn distance(&self, q: Vec3) -> f64 {
        self.normal.dot(q.as_dvec3() - self.origin)
    }

    /// The exact side of `q` (1, -1, or 0 on the plane of `t`, whose plane this is).
    ///
    /// The f64 value is trusted when it exceeds its error bound: every term of the determinant
    /// carries at most 8 roundings of relative size 2^-53 (three differences, two products, one
    /// difference, one product, the sum), so the error is below 8 · 2^-53 · Σ|terms| < 1e-15 · Σ|terms|;
    /// the bound used is twice that. Otherwise Shewchuk's adaptive `orient3d` decides exactly.
    fn side(&self, t: &[Vec3; 3], q: Vec3) -> i8 {
        let w = q.as_dvec3() - self.origin;
        let value = self.normal.dot(w);
        let bound = 2e-15 * w.abs().dot(self.magnitude);
        let exact = || {
            let c = |p: Vec3| robust::Coord3D {
                x: f64::from(p.x),
                y: f64::from(p.y),
                z: f64::from(p.z),
            };
            // orient3d is positive below the plane, where `value` is negative.
            -robust::orient3d(c(t[0]), c(t[1]), c(t[2]), c(q))
        };
        let decided = if value.abs() > bound { value } else { exact() };
        if decided > 0.0 {
            1
        } else if decided < 0.0 {
            -1
        } else {
            0
        }
    }
}

fn intersect_pair(a: &Face, b: &Face) -> Pair {
    let shared = a.indices.iter().filter(|v| b.indices.contains(v)).count();
    if shared >= 2 {
        return Pair::Neighbours;
    }
    let side_b = a.sides_of(b);
    if side_b == [0; 3] {
        return Pair::Coplanar;
    }
    if touches_at_most_a_point(side_b) {
        return Pair::Apart;
    }
    let side_a = b.sides_of(a);
    if touches_at_most_a_point(side_a) {
        return Pair::Apart;
    }
    let (Some(cut_a), Some(cut_b)) = (cut_by_plane(a, side_a, b), cut_by_plane(b, side_b, a))
    else {
        return Pair::Apart; // one triangle only touches the other's plane at a vertex
    };
    // Both cuts lie on the planes' common line: their overlap along it is the intersection.
    let along = a.plane.normal.cross(b.plane.normal);
    let at = |p: Vec3| along.dot(p.as_dvec3());
    let order = |[p, q]: [Vec3; 2]| if at(p) <= at(q) { [p, q] } else { [q, p] };
    let ([a0, a1], [b0, b1]) = (order(cut_a), order(cut_b));
    let start = if at(a0) >= at(b0) { a0 } else { b0 };
    let end = if at(a1) <= at(b1) { a1 } else { b1 };
    if at(end) <= at(start) || start == end {
        return Pair::Apart;
    }
    Pair::Crossing(if point_key(start) <= point_key(end) {
        [start, end]
    } else {
        [end, start]
    })
}

/// No vertex on one side of the plane, and at most one on it: the triangle meets the plane in at
/// most a point (or not at all).
fn touches_at_most_a_point(s: [i8; 3]) -> bool {
    let zeros = s.iter().filter(|&&x| x == 0).count();
    zeros <= 1 && (s.iter().all(|&x| x >= 0) || s.iter().all(|&x| x <= 0))
}

/// Where triangle `t` (with vertex sides `s` of the plane of `other`) meets that plane: a segment,
/// or `None` if it only touches it at one vertex.
fn cut_by_plane(t: &Face, s: [i8; 3], other: &Face) -> Option<[Vec3; 2]> {
    let crossing = |j: usize, k: usize| {
        edge_crossing(
            (t.indices[j], t.points[j]),
            (t.indices[k], t.points[k]),
            &other.plane,
        )
    };
    let on_plane = |k: usize| s[k] == 0;
    match (0..3).filter(|&k| on_plane(k)).count() {
        // One vertex alone on its side: the two edges from it cross the plane.
        0 => {
            let lone = (0..3).find(|&k| s[k] != s[(k + 1) % 3] && s[k] != s[(k + 2) % 3])?;
            Some([
                crossing(lone, (lone + 1) % 3),
                crossing(lone, (lone + 2) % 3),
            ])
        }
        // A vertex on the plane: a segment only if the opposite edge crosses it.
        1 => {
            let z = (0..3).find(|&k| on_plane(k))?;
            let (j, k) = ((z + 1) % 3, (z + 2) % 3);
            (s[j] != s[k]).then(|| [t.points[z], crossing(j, k)])
        }
        // An edge in the plane.
        2 => {
            let off = (0..3).find(|&k| !on_plane(k))?;
            Some([t.points[(off + 1) % 3], t.points[(off + 2) % 3]])
        }
        _ => None,
    }
}

/// The point where edge `(u, v)` crosses `plane`, computed the same way whichever triangle of the
/// edge asks (vertices in index order; the plane is built the same way from the same triangle).
fn edge_crossing(u: (u32, Vec3), v: (u32, Vec3), plane: &Plane) -> Vec3 {
    let ((_, p), (_, q)) = if u.0 <= v.0 { (u, v) } else { (v, u) };
    let (dp, dq) = (plane.distance(p), plane.distance(q));
    // The exact sides differ, so dp - dq is non-zero unless rounding flattened both to 0.
    let t = if dp == dq {
        0.5
    } else {
        (dp / (dp - dq)).clamp(0.0, 1.0)
    };
    (p.as_dvec3() + (q.as_dvec3() - p.as_dvec3()) * t).as_vec3()
}

/// Joins segment ends that coincide (bitwise, then within 1e-6 of the largest coordinate: a rule of
/// its own, not `crate::weld`'s); returns the points and each distinct segment as a pair of point indices
/// (ascending, sorted).
fn join_segment_ends(segments: Vec<[Vec3; 2]>) -> (Vec<Vec3>, Vec<[u32; 2]>) {
    let mut unique: Vec<Vec3> = segments.iter().flatten().copied().collect();
    unique.sort_unstable_by_key(|p| point_key(*p));
    unique.dedup_by_key(|p| point_key(*p));
    let largest = unique
        .iter()
        .fold(0.0f32, |m, p| m.max(p.abs().max_element()));
    let tolerance = (largest * 1e-6).max(f32::MIN_POSITIVE);
    // Each point joins the first (in sorted order) representative within the tolerance.
    let cell = |p: Vec3| (p / tolerance).floor().as_ivec3();
    let mut grid: HashMap<glam::IVec3, Vec<u32>> = HashMap::new();
    let mut points: Vec<Vec3> = Vec::new();
    let mut representative: HashMap<[u32; 3], u32> = HashMap::with_capacity(unique.len());
    for &p in &unique {
        let home = cell(p);
        let mut found = None;
        'search: for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let near = grid.get(&(home + glam::IVec3::new(dx, dy, dz)));
                    for &r in near.into_iter().flatten() {
                        if (points[r as usize] - p).abs().max_element() <= tolerance {
                            found = Some(r);
                            break 'search;
                        }
                    }
                }
            }
        }
        let r = found.unwrap_or_else(|| {
            points.push(p);
            let r = (points.len() - 1) as u32;
            grid.entry(home).or_default().push(r);
            r
        });
        representative.insert(point_key(p), r);
    }
    let mut edges: Vec<[u32; 2]> = segments
        .iter()
        .filter_map(|s| {
            let [a, b] = s.map(|p| representative[&point_key(p)]);
            (a != b).then(|| [a.min(b), a.max(b)])
        })
        .collect();
    edges.sort_unstable();
    edges.dedup();
    (points, edges)
}

/// The welded segments as chained polylines: oriented segments, the polyline starts and how many
/// polylines are closed.
fn chain(points: &[Vec3], edges: &[[u32; 2]]) -> (Vec<[[f32; 3]; 2]>, Vec<u32>, u64) {
    let mut segments = Vec::with_capacity(edges.len());
    let mut starts = Vec::new();
    let mut closed = 0;
    for polyline in polylines::chain(points.len(), edges) {
        starts.push(segments.len() as u32);
        closed += u64::from(polyline.closed);
        segments.extend(polyline.points.windows(2).map(|w| {
            [
                points[w[0] as usize].to_array(),
                points[w[1] as usize].to_array(),
            ]
        }));
    }
    (segments, starts, closed)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn find(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Intersections {
        let p: Vec<Vec3> = positions.iter().map(|&p| Vec3::from(p)).collect();
        find_intersections(&p, triangles)
    }

    #[test]
    fn two_crossing_triangles_meet_in_one_segment() {
        // A horizontal triangle and a vertical one through it along x in [0.25, 0.75] at y = 0.25.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.25, 0.25, -1.0],
            [0.75, 0.25, -1.0],
            [0.5, 0.25, 1.0],
        ];
        let found = find(&p, &[[0, 1, 2], [3, 4, 5]]);
        assert_eq!(found.stats.segments, 1);
        let [a, b] = found.segments[0];
        // The vertical triangle's cut at z = 0 spans x in [0.375, 0.625]; the other's at y = 0.25
        // spans x in [0, 0.75]: the overlap is [0.375, 0.625].
        assert_eq!(a, [0.375, 0.25, 0.0]);
        assert_eq!(b, [0.625, 0.25, 0.0]);
    }

    #[test]
    fn shared_edge_neighbours_never_count_at_any_fold() {
        for fold in [0.3f32, 1.0, 2.0, 3.1, -0.5] {
            let p = [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.5, 1.0, 0.0],
                [0.5, fold.cos(), fold.sin()],
            ];
            let found = find(&p, &[[0, 1, 2], [1, 0, 3]]);
            assert_eq!(found.stats.segments, 0, "fold {fold}");
            assert_eq!(found.stats.neighbour_pairs, 1);
        }
        // Folded flat onto each other: the same plane, still neighbours.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, 0.5, 0.0],
        ];
        assert_eq!(find(&p, &[[0, 1, 2], [1, 0, 3]]).stats.segments, 0);
    }

    #[test]
    fn shared_vertex_neighbours_count_only_where_one_pierces_the_other() {
        // A fan around vertex 0 on a bent surface: the shared vertex is no intersection.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.3],
            [0.0, -1.0, 0.3],
        ];
        let found = find(&p, &[[0, 1, 2], [0, 3, 4]]);
        assert_eq!(found.stats.segments, 0);
        assert_eq!(found.stats.candidate_pairs, 1);
        // Triangle [0, 5, 6] starts at the shared vertex and passes through [0, 1, 2]: it pierces it
        // along the line x = y from the shared vertex to where its own edge crosses z = 0.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.4, 0.4, -0.5],
            [0.4, 0.4, 0.5],
        ];
        let found = find(&p, &[[0, 1, 2], [0, 3, 4]]);
        assert_eq!(found.stats.segments, 1);
        assert_eq!(found.segments[0], [[0.0, 0.0, 0.0], [0.4, 0.4, 0.0]]);
    }

    #[test]
    fn coplanar_overlap_and_point_contacts_give_nothing() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.2, 0.2, 0.0],
            [1.2, 0.2, 0.0],
            [0.2, 1.2, 0.0],
            // A tetrahedron's apex resting on the first triangle.
            [0.2, 0.2, 0.0001],
            [0.5, 0.1, 1.0],
            [0.1, 0.5, 1.0],
        ];
        let found = find(&p, &[[0, 1, 2], [3, 4, 5]]);
        assert_eq!((found.stats.coplanar_pairs, found.stats.segments), (1, 0));
        let touching = [[0.2, 0.2, 0.0], [0.5, 0.1, 1.0], [0.1, 0.5, 1.0]];
        let mut q = p.to_vec();
        q[6..9].copy_from_slice(&touching);
        assert_eq!(find(&q, &[[0, 1, 2], [6, 7, 8]]).stats.segments, 0);
    }

    #[test]
    fn degenerate_and_non_finite_triangles_are_skipped_and_counted() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [f32::NAN, 0.0, 0.0],
            [0.25, 0.25, -1.0],
            [0.25, 0.25, 1.0],
            [0.3, 0.2, 1.0],
        ];
        let triangles = [
            [0, 1, 2],
            [0, 1, 3],  // collinear
            [0, 0, 2],  // repeated vertex
            [4, 1, 2],  // NaN
            [0, 1, 99], // out of range
            [5, 6, 7],  // crosses the first
        ];
        let found = find(&p, &triangles);
        assert_eq!(found.stats.skipped_triangles, 4);
        assert_eq!(found.stats.segments, 1);
    }

    #[test]
    fn the_filtered_side_test_agrees_with_exact_orient3d_near_the_plane() {
        // Points on (or a few ulps off) a triangle's plane, where the f64 filter must hand over.
        let mut seed = 0x9e37_79b9_u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            f64::from(seed) / f64::from(u32::MAX) * 2.0 - 1.0
        };
        let exact_sign = |t: &[Vec3; 3], q: Vec3| {
            let c = |p: Vec3| robust::Coord3D {
                x: f64::from(p.x),
                y: f64::from(p.y),
                z: f64::from(p.z),
            };
            let d = -robust::orient3d(c(t[0]), c(t[1]), c(t[2]), c(q));
            (d > 0.0) as i8 - (d < 0.0) as i8
        };
        let (mut on_plane, mut handed_over) = (0, 0);
        for round in 0..20_000 {
            // Integer coordinates times a power of two: the point a + i (b - a) + j (c - a) is then
            // exactly on the plane (the exact path), and a nudge of a few ulps puts it just off it.
            let scale = 2f32.powi((next() * 20.0) as i32);
            let int = |r: f64| (r * 1000.0).round() as f32 * scale;
            let t: [Vec3; 3] =
                std::array::from_fn(|_| Vec3::new(int(next()), int(next()), int(next())));
            let (i, j) = ((next() * 4.0).round() as f32, (next() * 4.0).round() as f32);
            let mut q = t[0] + (t[1] - t[0]) * i + (t[2] - t[0]) * j;
            if round % 2 == 1 {
                let k = (next().abs() * 2.99) as usize;
                let nudge = (next() * 3.0) as i32;
                q[k] = f32::from_bits((q[k].to_bits() as i32 + nudge) as u32);
            }
            let plane = Plane::new(&t);
            let filtered = plane.side(&t, q);
            assert_eq!(filtered, exact_sign(&t, q), "{t:?} {q:?}");
            on_plane += usize::from(filtered == 0);
            let w = q.as_dvec3() - plane.origin;
            handed_over +=
                usize::from(plane.normal.dot(w).abs() <= 2e-15 * w.abs().dot(plane.magnitude));
        }
        assert!(
            on_plane > 1000 && handed_over > 1000,
            "{on_plane} {handed_over}"
        );
    }

    #[test]
    fn ends_a_rounding_apart_are_welded_into_one_polyline() {
        let a = Vec3::new(0.3, 0.7, 0.1);
        let nudged = Vec3::new(f32::from_bits(a.x.to_bits() + 2), a.y, a.z);
        let raw = vec![[Vec3::ZERO, a], [nudged, Vec3::ONE]];
        let (points, edges) = join_segment_ends(raw);
        assert_eq!(points.len(), 3);
        let (segments, starts, closed) = chain(&points, &edges);
        assert_eq!((segments.len(), starts.len(), closed), (2, 1, 0));
        assert_eq!(segments[0][1], segments[1][0]);
    }

    #[test]
    fn segments_chain_into_one_closed_loop_in_a_fixed_order() {
        // A square tube of 8 triangles pierced by a horizontal square at z = 0.5: a 4-edge loop.
        let mut p = Vec::new();
        let mut t = Vec::new();
        for (k, (x, y)) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .iter()
            .enumerate()
        {
            p.push([*x, *y, 0.0]);
            p.push([*x, *y, 1.0]);
            let (a, b) = (2 * k as u32, 2 * ((k as u32 + 1) % 4));
            t.push([a, b, b + 1]);
            t.push([a, b + 1, a + 1]);
        }
        let base = p.len() as u32;
        p.extend([
            [-1.0, -1.0, 0.5],
            [2.0, -1.0, 0.5],
            [2.0, 2.0, 0.5],
            [-1.0, 2.0, 0.5],
        ]);
        t.push([base, base + 1, base + 2]);
        t.push([base, base + 2, base + 3]);
        let found = find(&p, &t);
        assert_eq!(found.stats.polylines, 1);
        assert_eq!(found.stats.closed_polylines, 1);
        assert!(
            (found.stats.length - 4.0).abs() < 1e-6,
            "{}",
            found.stats.length
        );
        let s = &found.segments;
        assert_eq!(s[0][0], s[s.len() - 1][1]);
        assert!(s.windows(2).all(|w| w[0][1] == w[1][0]));
        // Any triangle order gives the same result.
        let mut reversed = t.clone();
        reversed.reverse();
        assert_eq!(find(&p, &reversed).segments, found.segments);
    }
}
