//! Stitch: close the cracks between faces that a CAD or BIM exporter tessellated one by one.
//!
//! Each B-rep face is sampled on its own, so two faces meet along an edge whose vertices do not
//! coincide: some differ by more than the weld joins, others sit in the middle of the neighbour's
//! longer edge (T-junctions). Every such edge is a boundary to adjacency, drawn as one and missing
//! the contour or crease it really is. Stitching works on boundary geometry only, in two steps,
//! both within one tolerance:
//!
//! 1. **Join**: boundary vertices within the tolerance of each other become one topology vertex
//!    (the ordered greedy rule of [`weld`](crate::weld), run on the boundary vertices alone).
//! 2. **Split**: a boundary vertex within the tolerance of another boundary edge, strictly inside
//!    it, splits that edge's triangle into a fan through it, so both sides of the crack have the
//!    same vertices. A triangle splits one edge per pass; at most [`MAX_SPLIT_PASSES`] passes.
//!
//! A split adds triangles but moves no vertex; a join moves a vertex by at most the tolerance. An
//! open boundary wider than the tolerance (a sheet's rim, a hole) is left as it is. Boundary
//! vertices are found through a uniform grid whose cells are as long as the mean boundary edge,
//! each edge walking the cells along it, so the work is linear in the boundary's size; a cell
//! neighbourhood holding more than [`MAX_CANDIDATES`] vertices (only a hostile file packs them
//! that densely) leaves its edge unstitched. The result depends only on the input.

use std::collections::HashMap;

use chamfer_runtime::asset::EdgeFlags;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::adjacency::{Edges, adjacency};
use crate::degenerate::remove_degenerate;
use crate::weld::weld;

/// Split passes: a triangle with T-junctions on all three edges needs three.
pub const MAX_SPLIT_PASSES: usize = 3;
/// The most boundary vertices one edge looks at; more leaves the edge as a boundary.
pub const MAX_CANDIDATES: usize = 1024;

/// What [`stitch`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stitched {
    /// Boundary edges before stitching.
    pub boundary_before: u64,
    /// Boundary edges after.
    pub boundary_after: u64,
    /// Boundary vertices joined into another.
    pub joined_vertices: u64,
    /// Boundary edges split at T-junctions.
    pub split_edges: u64,
    /// Edges left unstitched because too many boundary vertices crowd around them.
    pub crowded_edges: u64,
}

/// Stitches the cracks of `triangles` (over `positions`, with `materials` per triangle or empty)
/// within `tolerance`, given their `edges` from [`adjacency`], and returns the edges of the
/// stitched triangles. Triangles that a join makes degenerate are removed; split triangles keep
/// their material.
///
/// Contract: that of [`adjacency`], and `tolerance` finite and > 0. Closed meshes cost one pass
/// over the edge flags.
pub fn stitch(
    positions: &[Vec3],
    triangles: &mut Vec<[u32; 3]>,
    materials: &mut Vec<u32>,
    mut edges: Edges,
    tolerance: f32,
) -> (Edges, Stitched) {
    let boundary_before = boundary_count(&edges);
    let mut report = Stitched {
        boundary_before,
        boundary_after: boundary_before,
        ..Stitched::default()
    };
    if boundary_before == 0 || !tolerance.is_finite() || tolerance <= 0.0 {
        return (edges, report);
    }
    let joined = join(positions, triangles, &edges, tolerance);
    if joined > 0 {
        report.joined_vertices = joined;
        remove_degenerate(triangles, materials, positions);
        edges = adjacency(triangles, materials, positions.len());
    }
    for _ in 0..MAX_SPLIT_PASSES {
        let (splits, crowded) = t_junctions(positions, &edges, tolerance);
        report.crowded_edges = report.crowded_edges.max(crowded);
        let split = split_triangles(triangles, materials, &edges, &splits);
        if split == 0 {
            break;
        }
        report.split_edges += split;
        edges = adjacency(triangles, materials, positions.len());
    }
    report.boundary_after = boundary_count(&edges);
    (edges, report)
}

fn is_boundary(flags: EdgeFlags) -> bool {
    flags.contains(EdgeFlags::BOUNDARY) && !flags.contains(EdgeFlags::NON_MANIFOLD)
}

fn boundary_count(edges: &Edges) -> u64 {
    edges.flags.par_iter().filter(|&&f| is_boundary(f)).count() as u64
}

/// The vertices of boundary edges, sorted.
fn boundary_vertices(edges: &Edges) -> Vec<u32> {
    let mut vertices: Vec<u32> = edges
        .vertices
        .iter()
        .zip(&edges.flags)
        .filter(|&(_, &f)| is_boundary(f))
        .flat_map(|(v, _)| [v[0], v[1]])
        .collect();
    vertices.par_sort_unstable();
    vertices.dedup();
    vertices
}

/// Joins boundary vertices within `tolerance`; returns how many were joined into another.
fn join(positions: &[Vec3], triangles: &mut [[u32; 3]], edges: &Edges, tolerance: f32) -> u64 {
    let vertices = boundary_vertices(edges);
    let local: Vec<Vec3> = vertices.iter().map(|&v| positions[v as usize]).collect();
    let welded = weld(&local, tolerance);
    if welded.positions.len() == vertices.len() {
        return 0;
    }
    // Each cluster's first member (weld numbers clusters by first appearance) represents it.
    let mut representative = vec![u32::MAX; welded.positions.len()];
    for (k, &cluster) in welded.remap.iter().enumerate() {
        if representative[cluster as usize] == u32::MAX {
            representative[cluster as usize] = vertices[k];
        }
    }
    let mut remap: Vec<u32> = (0..positions.len() as u32).collect();
    for (k, &v) in vertices.iter().enumerate() {
        remap[v as usize] = representative[welded.remap[k] as usize];
    }
    triangles
        .par_iter_mut()
        .for_each(|t| *t = t.map(|i| remap[i as usize]));
    (vertices.len() - welded.positions.len()) as u64
}

/// A uniform grid over points, for "which points are near here".
struct Grid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<u32>>,
}

impl Grid {
    fn key(&self, p: DVec3) -> [i64; 3] {
        // `as` saturates: an enormous coordinate lands in an edge cell, never wraps.
        (p / self.cell).floor().to_array().map(|c| c as i64)
    }
}

/// For each boundary edge with T-junctions: (edge, the vertices strictly inside it, ordered from
/// `v0` to `v1`); and how many edges were too crowded to look at.
fn t_junctions(positions: &[Vec3], edges: &Edges, tolerance: f32) -> (Vec<(usize, Vec<u32>)>, u64) {
    let boundary: Vec<usize> = (0..edges.len())
        .filter(|&e| is_boundary(edges.flags[e]))
        .collect();
    if boundary.is_empty() {
        return (Vec::new(), 0);
    }
    let p = |v: u32| positions[v as usize].as_dvec3();
    let length: f64 = boundary
        .iter()
        .map(|&e| (p(edges.vertices[e][1]) - p(edges.vertices[e][0])).length())
        .sum();
    let tolerance = f64::from(tolerance);
    let mut grid = Grid {
        cell: (length / boundary.len() as f64).max(2.0 * tolerance),
        cells: HashMap::new(),
    };
    for v in boundary_vertices(edges) {
        let key = grid.key(p(v));
        grid.cells.entry(key).or_default().push(v);
    }
    let found: Vec<Option<(usize, Vec<u32>)>> = boundary
        .par_iter()
        .map(|&e| {
            let [a, b, c, _] = edges.vertices[e];
            let (pa, pb) = (p(a), p(b));
            let direction = pb - pa;
            let length_sq = direction.length_squared();
            // Steps no longer than a cell, each probing its 27 cells: every point within the
            // tolerance (less than a cell) of the segment lies in one of them.
            let steps = (length_sq.sqrt() / grid.cell).ceil().min(1e9) as u64;
            let mut candidates = Vec::new();
            for step in 0..=steps {
                let at = pa + direction * (step as f64 / steps.max(1) as f64);
                let [x, y, z] = grid.key(at);
                for key in neighbours(x, y, z) {
                    if let Some(cell) = grid.cells.get(&key) {
                        candidates.extend_from_slice(cell);
                    }
                }
                if candidates.len() > MAX_CANDIDATES * 27 {
                    candidates.sort_unstable();
                    candidates.dedup();
                    if candidates.len() > MAX_CANDIDATES {
                        return Some((e, Vec::new())); // crowded: counted, not split
                    }
                }
            }
            candidates.sort_unstable();
            candidates.dedup();
            if candidates.len() > MAX_CANDIDATES {
                return Some((e, Vec::new()));
            }
            let mut inside: Vec<(f64, u32)> = candidates
                .into_iter()
                .filter(|&v| v != a && v != b && v != c)
                .filter_map(|v| {
                    let q = p(v);
                    let t = (q - pa).dot(direction) / length_sq;
                    let near = (q - (pa + direction * t)).length() <= tolerance;
                    let apart = (q - pa).length() > tolerance && (q - pb).length() > tolerance;
                    (t > 0.0 && t < 1.0 && near && apart).then_some((t, v))
                })
                .collect();
            if inside.is_empty() {
                return None;
            }
            inside.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            Some((e, inside.into_iter().map(|(_, v)| v).collect()))
        })
        .collect();
    let crowded = found
        .iter()
        .filter(|f| f.as_ref().is_some_and(|(_, v)| v.is_empty()))
        .count() as u64;
    let splits = found
        .into_iter()
        .flatten()
        .filter(|(_, v)| !v.is_empty())
        .collect();
    (splits, crowded)
}

fn neighbours(x: i64, y: i64, z: i64) -> impl Iterator<Item = [i64; 3]> {
    (-1i64..=1).flat_map(move |dx| {
        (-1i64..=1).flat_map(move |dy| {
            (-1i64..=1).map(move |dz| {
                [
                    x.saturating_add(dx),
                    y.saturating_add(dy),
                    z.saturating_add(dz),
                ]
            })
        })
    })
}

/// Replaces the triangle of each split edge by the fan through its inside vertices (one edge per
/// triangle; the others wait for the next pass). Returns how many edges were split.
fn split_triangles(
    triangles: &mut Vec<[u32; 3]>,
    materials: &mut Vec<u32>,
    edges: &Edges,
    splits: &[(usize, Vec<u32>)],
) -> u64 {
    if splits.is_empty() {
        return 0;
    }
    // A boundary edge's only face runs v0 -> v1 (adjacency's face a).
    let wanted: HashMap<(u32, u32), usize> = splits
        .iter()
        .enumerate()
        .map(|(k, (e, _))| ((edges.vertices[*e][0], edges.vertices[*e][1]), k))
        .collect();
    let owners: Vec<(usize, usize, usize)> = triangles
        .par_iter()
        .enumerate()
        .filter_map(|(t, tri)| {
            (0..3).find_map(|r| wanted.get(&(tri[r], tri[(r + 1) % 3])).map(|&k| (t, r, k)))
        })
        .collect();
    for &(t, rotation, k) in &owners {
        let tri = triangles[t];
        let (a, b, c) = (
            tri[rotation],
            tri[(rotation + 1) % 3],
            tri[(rotation + 2) % 3],
        );
        let inside = &splits[k].1;
        let material = materials.get(t).copied();
        let mut from = a;
        for (i, &v) in inside.iter().chain(std::iter::once(&b)).enumerate() {
            let piece = [from, v, c];
            if i == 0 {
                triangles[t] = piece;
            } else {
                triangles.push(piece);
                if let Some(m) = material {
                    materials.push(m);
                }
            }
            from = v;
        }
    }
    owners.len() as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two squares side by side in z = 0, x in [0, 1] and [1, 2]: the left one is two triangles,
    /// the right one is tessellated with an extra vertex at (1, 0.5) on the shared side (a
    /// T-junction), and its copies of the shared corners are `gap` away from the left one's.
    fn cracked(gap: f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0 + gap, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(1.0 + gap, 1.0, 0.0),
            Vec3::new(1.0 + gap, 0.5, 0.0),
        ];
        let triangles = vec![[0, 1, 2], [0, 2, 3], [4, 5, 8], [5, 6, 8], [6, 7, 8]];
        (positions, triangles)
    }

    fn run(positions: &[Vec3], triangles: &mut Vec<[u32; 3]>, tolerance: f32) -> Stitched {
        let edges = adjacency(triangles, &[], positions.len());
        stitch(positions, triangles, &mut Vec::new(), edges, tolerance).1
    }

    #[test]
    fn a_crack_with_a_t_junction_closes_to_the_outer_rim() {
        let (positions, mut triangles) = cracked(1e-4);
        let report = run(&positions, &mut triangles, 1e-3);
        // 4 sides of the left square, 5 of the right one (its left side is two edges).
        assert_eq!(report.boundary_before, 9);
        assert_eq!(report.joined_vertices, 2);
        assert_eq!(report.split_edges, 1);
        // The outer rim of the 2 x 1 rectangle alone: its long sides are two edges each.
        assert_eq!(report.boundary_after, 6, "{report:?}");
    }

    #[test]
    fn a_gap_wider_than_the_tolerance_stays_open() {
        let (positions, mut triangles) = cracked(1e-2);
        let before = triangles.clone();
        let report = run(&positions, &mut triangles, 1e-3);
        assert_eq!(report.boundary_after, report.boundary_before);
        assert_eq!(triangles, before);
    }

    #[test]
    fn split_triangles_keep_their_winding_and_material() {
        let (positions, mut triangles) = cracked(0.0);
        let mut materials = vec![0, 0, 7, 7, 7];
        let edges = adjacency(&triangles, &materials, positions.len());
        let (_, report) = stitch(&positions, &mut triangles, &mut materials, edges, 1e-3);
        assert_eq!(report.split_edges, 1);
        assert_eq!(materials.len(), triangles.len());
        let normal = |t: [u32; 3]| {
            let p = |i: u32| positions[i as usize];
            (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])).z
        };
        assert!(triangles.iter().all(|&t| normal(t) > 0.0), "{triangles:?}");
    }

    #[test]
    fn a_closed_mesh_is_left_alone() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let mut triangles = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let report = run(&positions, &mut triangles, 0.1);
        assert_eq!(report, Stitched::default());
    }
}
