//! The order triangles, vertices and edges are written in.
//!
//! Triangles are sorted by a cell of a cube map of their normal (six faces of 6 × 6 cells, each at
//! most about 19° across) and then along a Morton curve through their centroids, and each run of
//! up to 48 of them is then walked across shared edges (issue 44: the compact format's index codec
//! codes a triangle that shares an edge with a recent one in a few bits); vertices are
//! numbered in the order the sorted triangles first use them; edges follow the corner of their
//! first face (face a, `adjacency`). So a run of 64 consecutive edges covers a small patch of
//! surface that faces one way, within a few tens of degrees, and the runtime's cluster test
//! (`chamfer_runtime::asset::clusters`, issue 14) can skip whole runs that cannot be drawn from a
//! camera; and the compact asset (format 5, issue 24) can store each edge as one bit of its face-a
//! corner and code indices and positions as deltas between neighbours. The order changes nothing
//! the runtime draws.

use std::sync::atomic::{AtomicU32, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use crate::adjacency::Edges;
use crate::caps::Rings;
use chamfer_runtime::asset::corners::VertexCorners;

/// Bits per axis of the Morton code (24 in all, above them the direction cell; the low 31 bits of
/// a `u64` key hold the triangle index).
const MORTON_BITS: u32 = 8;
/// Cells per side of each face of the normal cube map.
const DIRECTION_CELLS: u32 = 6;
/// Bits of a direction cell's number.
const DIRECTION_BITS: u32 = (6 * DIRECTION_CELLS * DIRECTION_CELLS)
    .next_power_of_two()
    .ilog2();
const _: () = assert!(DIRECTION_BITS + 3 * MORTON_BITS + 31 <= 64);

/// The coherent triangle order: `order[new] = old` triangle index, sorted by direction cell and
/// Morton code, then walked across shared edges in small blocks ([`walk_blocks`]). Deterministic
/// for any thread count (ties keep the input order).
pub(crate) fn triangle_order(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<u32> {
    let (lo, hi) = crate::mesh::bounds(positions);
    let cells = ((1u32 << MORTON_BITS) - 1) as f32;
    let scale = (hi - lo).max(Vec3::splat(f32::MIN_POSITIVE)).recip() * cells;
    let mut keys: Vec<u64> = triangles
        .par_iter()
        .enumerate()
        .map(|(t, tri)| {
            let [p0, p1, p2] = tri.map(|v| positions[v as usize]);
            let normal = (p1 - p0).cross(p2 - p0).normalize_or_zero();
            let cell = ((p0 + p1 + p2) * (1.0 / 3.0) - lo) * scale;
            let cell = cell.clamp(Vec3::ZERO, Vec3::splat(cells)).as_uvec3();
            // (Sorting by region first, then direction, culled less on every mesh tried.)
            let key = (direction(normal) << (3 * MORTON_BITS)) | morton(cell.x, cell.y, cell.z);
            (key << 31) | t as u64
        })
        .collect();
    keys.par_sort_unstable();
    let cells: Vec<u64> = keys.iter().map(|k| k >> (31 + 3 * MORTON_BITS)).collect();
    let order: Vec<u32> = keys.iter().map(|k| (k & ((1 << 31) - 1)) as u32).collect();
    walk_blocks(triangles, &order, &cells)
}

/// Triangles per block that [`walk_blocks`] reorders within: about one edge cluster's worth (64
/// edges, some 43 triangles), so the culling keeps as many clusters (measured, BENCHMARKS.md "Compact assets, second
/// step": larger blocks code the indices a little smaller and keep more clusters).
const WALK_BLOCK: usize = 48;
/// How many of the last triangles a walk looks back at for an unvisited neighbour before it starts
/// again from the next unvisited triangle of its block.
const WALK_LOOKBACK: usize = 8;

/// `order`, the coherent order, with each block of up to [`WALK_BLOCK`] consecutive triangles of
/// one direction cell (`cells`, per position of `order`) walked across shared edges (issue 44): each
/// triangle is followed by an unvisited neighbour of itself or of one of the last
/// [`WALK_LOOKBACK`] triangles, where there is one. The index codec codes a triangle that shares
/// an edge with a recent one in a few bits (its edge FIFO), and it meets its vertices while they
/// are recent; a block stays a small patch facing one way, so the edge runs the culling tests
/// (issue 14) stay as small and flat. Deterministic.
fn walk_blocks(triangles: &[[u32; 3]], order: &[u32], cells: &[u64]) -> Vec<u32> {
    let mut blocks = Vec::new();
    let mut start = 0;
    while start < order.len() {
        let mut end = start + 1;
        while end < order.len() && end - start < WALK_BLOCK && cells[end] == cells[start] {
            end += 1;
        }
        blocks.push(start..end);
        start = end;
    }
    let walked: Vec<Vec<u32>> = blocks
        .par_iter()
        .map(|block| walk(triangles, &order[block.clone()]))
        .collect();
    walked.concat()
}

/// The triangles of `block` (indices into `triangles`) in the order of one walk across their
/// shared edges (see [`walk_blocks`]).
fn walk(triangles: &[[u32; 3]], block: &[u32]) -> Vec<u32> {
    const NONE: u32 = u32::MAX;
    // Each edge's first two triangles of the block (a third, non-manifold, is left out).
    let mut faces: std::collections::HashMap<(u32, u32), [u32; 2]> =
        std::collections::HashMap::with_capacity(block.len() * 2);
    for (k, &t) in block.iter().enumerate() {
        let [a, b, c] = triangles[t as usize];
        for (u, v) in [(a, b), (b, c), (c, a)] {
            let slot = faces.entry((u.min(v), u.max(v))).or_insert([NONE; 2]);
            if let Some(free) = slot.iter_mut().find(|s| **s == NONE) {
                *free = k as u32;
            }
        }
    }
    let neighbours = |k: usize| {
        let [a, b, c] = triangles[block[k] as usize];
        [(a, b), (b, c), (c, a)].map(|(u, v)| {
            faces
                .get(&(u.min(v), u.max(v)))
                .and_then(|pair| pair.iter().copied().find(|&f| f != NONE && f as usize != k))
        })
    };
    let mut visited = vec![false; block.len()];
    let mut walked: Vec<usize> = Vec::with_capacity(block.len());
    for seed in 0..block.len() {
        if visited[seed] {
            continue;
        }
        let mut current = Some(seed);
        while let Some(k) = current {
            visited[k] = true;
            walked.push(k);
            current = walked.iter().rev().take(WALK_LOOKBACK).find_map(|&recent| {
                neighbours(recent)
                    .into_iter()
                    .flatten()
                    .map(|f| f as usize)
                    .find(|&f| !visited[f])
            });
        }
    }
    walked.into_iter().map(|k| block[k]).collect()
}

/// Puts `triangles` (and their `materials`, when there are any) in `order` and renumbers the
/// vertices in the order the triangles first use them (vertices no triangle uses keep their order,
/// after the used ones). Returns `new_of[old]`, the new number of each vertex.
pub(crate) fn reorder_mesh(
    positions: &mut Vec<Vec3>,
    triangles: &mut Vec<[u32; 3]>,
    materials: &mut Vec<u32>,
    order: &[u32],
) -> Vec<u32> {
    *triangles = gather(triangles, order);
    if !materials.is_empty() {
        *materials = gather(materials, order);
    }
    const UNSEEN: u32 = u32::MAX;
    let mut new_of = vec![UNSEEN; positions.len()];
    let mut next = 0u32;
    for &v in triangles.as_flattened() {
        let slot = &mut new_of[v as usize];
        if *slot == UNSEEN {
            *slot = next;
            next += 1;
        }
    }
    for slot in new_of.iter_mut().filter(|s| **s == UNSEEN) {
        *slot = next;
        next += 1;
    }
    let mut old_of = vec![0u32; positions.len()];
    for (old, &new) in new_of.iter().enumerate() {
        old_of[new as usize] = old as u32;
    }
    *positions = gather(positions, &old_of);
    triangles
        .par_iter_mut()
        .for_each(|t| *t = t.map(|v| new_of[v as usize]));
    new_of
}

/// The edge order that follows the triangles: `order[new] = old` edge index, edges sorted by the
/// triangle of their face a (the lowest corner whose triangle winds `v0 -> v1` with `v2` opposite,
/// see [`face_a_corner`]) and then by `v0`: an order that rotating a triangle's corners (as the
/// compact format's index codec may) does not change.
pub(crate) fn edge_order(
    corners: &VertexCorners,
    triangles: &[[u32; 3]],
    edges: &Edges,
) -> Vec<u32> {
    let mut keys: Vec<(u64, u32)> = edges
        .vertices
        .par_iter()
        .enumerate()
        .map(|(e, v)| {
            // Every edge of the bake has its face a; an edge built elsewhere without one goes last.
            let triangle = face_a_corner(corners, triangles, *v).map_or(u32::MAX, |c| c / 3);
            ((u64::from(triangle) << 32) | u64::from(v[0]), e as u32)
        })
        .collect();
    keys.par_sort_unstable();
    keys.into_iter().map(|(_, e)| e).collect()
}

/// The lowest corner at `v0` whose triangle is `(v0, v1, v2)` in its own winding.
pub(crate) fn face_a_corner(
    corners: &VertexCorners,
    triangles: &[[u32; 3]],
    [v0, v1, v2, _]: [u32; 4],
) -> Option<u32> {
    corners.of(v0).iter().copied().find(|&c| {
        let t = triangles[c as usize / 3];
        let k = c as usize % 3;
        t[(k + 1) % 3] == v1 && t[(k + 2) % 3] == v2
    })
}

/// The cell of the normal cube map that `n` points into: its face (±x, ±y, ±z), then a cell of
/// that face's `DIRECTION_CELLS` × `DIRECTION_CELLS` grid.
fn direction(n: Vec3) -> u64 {
    let a = n.abs();
    let (axis, value, u, v) = if a.x >= a.y && a.x >= a.z {
        (0, n.x, n.y, n.z)
    } else if a.y >= a.z {
        (1, n.y, n.z, n.x)
    } else {
        (2, n.z, n.x, n.y)
    };
    let face = 2 * axis + u64::from(value < 0.0);
    // u / |value| and v / |value| are in [-1, 1] on this face (0 / 0 for a zero normal: cell 0).
    let cells = DIRECTION_CELLS as f32;
    let cell = |c: f32| {
        let t = (c / value.abs() * 0.5 + 0.5) * cells;
        if t.is_nan() {
            0
        } else {
            (t as u64).min(u64::from(DIRECTION_CELLS) - 1)
        }
    };
    (face * u64::from(DIRECTION_CELLS) + cell(u)) * u64::from(DIRECTION_CELLS) + cell(v)
}

/// The Morton code of a cell: the bits of `x`, `y` and `z` interleaved.
fn morton(x: u32, y: u32, z: u32) -> u64 {
    let spread = |v: u32| {
        let mut v = u64::from(v) & ((1 << MORTON_BITS) - 1);
        v = (v | (v << 16)) & 0x0300_00ff;
        v = (v | (v << 8)) & 0x0300_f00f;
        v = (v | (v << 4)) & 0x030c_30c3;
        (v | (v << 2)) & 0x0924_9249
    };
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

/// Rewrites `edges` and `rings` in `order` (`order[new] = old`): every per-edge array, every edge
/// end in the rings and heads.
pub fn reorder(edges: &mut Edges, rings: &mut Rings, order: &[u32]) {
    // The inverse permutation, filled in parallel: every slot is written exactly once.
    let new_of: Vec<AtomicU32> = (0..order.len()).map(|_| AtomicU32::new(0)).collect();
    order
        .par_iter()
        .enumerate()
        .for_each(|(new, &old)| new_of[old as usize].store(new as u32, Ordering::Relaxed));
    let new_of: Vec<u32> = new_of.into_iter().map(AtomicU32::into_inner).collect();
    let end = |old_end: u32| 2 * new_of[(old_end >> 1) as usize] + (old_end & 1);
    edges.vertices = gather(&edges.vertices, order);
    edges.flags = gather(&edges.flags, order);
    if !edges.radii.is_empty() {
        edges.radii = gather(&edges.radii, order);
    }
    if !rings.next.is_empty() {
        let mut next = vec![0u32; rings.next.len()];
        next.par_chunks_mut(2)
            .zip(order.par_iter())
            .for_each(|(pair, &o)| {
                for (k, slot) in pair.iter_mut().enumerate() {
                    *slot = end(rings.next[2 * o as usize + k]);
                }
            });
        rings.next = next;
    }
    rings
        .heads
        .par_iter_mut()
        .for_each(|head| *head = end(*head));
}

/// `values` in `order` (`order[new] = old`).
fn gather<T: Copy + Send + Sync>(values: &[T], order: &[u32]) -> Vec<T> {
    order.par_iter().map(|&o| values[o as usize]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use chamfer_runtime::asset::EdgeFlags;

    #[test]
    fn morton_interleaves_bits() {
        assert_eq!(morton(1, 0, 0), 1);
        assert_eq!(morton(0, 1, 0), 2);
        assert_eq!(morton(0, 0, 1), 4);
        assert_eq!(morton(3, 0, 0), 0b1001);
        assert_eq!(morton(255, 255, 255), (1 << 24) - 1);
        let k = u64::from(DIRECTION_CELLS);
        // +x, in the middle cell of its face; -x, near +y and -z.
        assert_eq!(direction(Vec3::X), (k / 2) * k + k / 2);
        assert_eq!(direction(Vec3::new(-1.0, 0.9, -0.9)), (k + k - 1) * k);
        assert!(direction(Vec3::NEG_Z) < 6 * k * k);
    }

    #[test]
    fn rings_built_on_reordered_edges_are_the_reordered_rings() {
        // The bake reorders the edges before building rings: that must equal building the rings
        // first and renumbering them. A cube with its coplanar diagonals dropped, so rings skip
        // edges, in a scrambled order.
        let (p, t) = crate::classify::tests::cube();
        let mut edges = crate::adjacency::adjacency(&t, &[], p.len());
        crate::classify::classify(&p, &mut edges, &[], 0.01, 30.0);
        let mut order: Vec<u32> = (0..edges.len() as u32).collect();
        order.sort_by_key(|&e| (e * 7) % edges.len() as u32);
        let mut renumbered = crate::caps::rings(&t, &edges, p.len());
        let mut reordered = edges.clone();
        reorder(&mut reordered, &mut renumbered, &order);
        let mut edges_only = edges.clone();
        reorder(&mut edges_only, &mut Rings::default(), &order);
        assert_eq!(edges_only, reordered);
        assert_eq!(crate::caps::rings(&t, &edges_only, p.len()), renumbered);
        assert_ne!(order, (0..edges.len() as u32).collect::<Vec<_>>());
    }

    #[test]
    fn reordering_keeps_rings_pointing_at_the_same_ends() {
        // Three edges around vertex 0 (a fan), rings 0 -> 2 -> 4 -> 0 of the v0 ends.
        let mut edges = Edges {
            vertices: vec![[0, 1, 2, 3], [0, 2, 3, 1], [0, 3, 1, 2]],
            flags: vec![EdgeFlags::RIDGE, EdgeFlags::VALLEY, EdgeFlags::MARKED],
            radii: vec![0.1, 0.2, 0.3],
        };
        let mut rings = Rings {
            next: vec![2, 1, 4, 3, 0, 5],
            heads: vec![0],
        };
        let before = (edges.clone(), rings.clone());
        reorder(&mut edges, &mut rings, &[2, 0, 1]);
        assert_eq!(edges.vertices[0], before.0.vertices[2]);
        assert_eq!(edges.flags[1], EdgeFlags::RIDGE);
        assert_eq!(edges.radii, vec![0.3, 0.1, 0.2]);
        // Old end 0 (edge 0, now edge 1) -> old end 2 (edge 1, now 2) -> old end 4 (edge 2, now 0).
        assert_eq!(rings.next[2], 4);
        assert_eq!(rings.next[4], 0);
        assert_eq!(rings.next[0], 2);
        assert_eq!(rings.heads, vec![2]);
    }
}
