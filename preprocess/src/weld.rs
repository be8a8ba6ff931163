//! Weld: map vertices that share a position to one topology vertex.
//!
//! Render vertices split at seams (normals, uvs) become one topology vertex, so edges connect across
//! seams while the render buffers keep them apart, like meshoptimizer's shadow index buffer
//! (`meshopt_generateShadowIndexBuffer`).
//!
//! ```
//! use chamfer_preprocess::weld::weld;
//! use glam::Vec3;
//! let p = [Vec3::ZERO, Vec3::X, Vec3::ZERO, Vec3::new(1.0, 1e-7, 0.0)];
//! assert_eq!(weld(&p, 0.0).remap, [0, 1, 0, 2]); // exact
//! assert_eq!(weld(&p, 1e-6).remap, [0, 1, 0, 1]); // within a tolerance
//! ```

use glam::Vec3;

/// The result of [`weld`].
#[derive(Clone, Debug, PartialEq)]
pub struct Weld {
    /// For every input vertex, its topology vertex.
    pub remap: Vec<u32>,
    /// One position per topology vertex: that of the first input vertex welded into it.
    pub positions: Vec<Vec3>,
}

/// Welds `positions`: exactly (bit-identical, with -0.0 equal to 0.0) when `epsilon == 0`, otherwise
/// every vertex within `epsilon` (Euclidean) of an earlier kept vertex joins the earliest such one.
///
/// Topology vertices are numbered in order of first appearance; the result depends only on the input
/// (never on hashing or thread count). Kept vertices are more than `epsilon` apart, and every vertex
/// is within `epsilon` of its topology vertex, so clusters never chain further than that.
///
/// The bake passes [`WeldTolerance::distance`](crate::WeldTolerance::distance) of its options (by
/// default 1e-6 of the distance from the origin to the bounding box's farthest corner).
///
/// Contract: positions are finite and `epsilon` is finite and non-negative (checked by
/// [`Mesh::validate`](crate::mesh::Mesh::validate) and [`BakeOptions::validate`](crate::BakeOptions::validate)).
/// Runs in O(n) expected time; the tolerance weld probes 8 grid cells per unique position.
pub fn weld(positions: &[Vec3], epsilon: f32) -> Weld {
    let exact = weld_exact(positions);
    if epsilon == 0.0 {
        return exact;
    }
    let near = weld_near(&exact.positions, epsilon);
    Weld {
        remap: exact
            .remap
            .iter()
            .map(|&i| near.remap[i as usize])
            .collect(),
        positions: near.positions,
    }
}

/// Bits of a coordinate with the two zeros made equal.
fn key(p: Vec3) -> [u32; 3] {
    p.to_array().map(|c| if c == 0.0 { 0 } else { c.to_bits() })
}

/// murmur2's mixing step over three words (as in meshoptimizer's vertex hasher).
fn hash(words: [u32; 3]) -> u32 {
    const M: u32 = 0x5bd1_e995;
    words.iter().fold(0u32, |h, &w| {
        let mut k = w.wrapping_mul(M);
        k ^= k >> 24;
        k = k.wrapping_mul(M);
        h.wrapping_mul(M) ^ k
    })
}

/// Open-addressing table of vertex ids, sized for `n` entries at most half full.
struct Table {
    slots: Vec<u32>,
    mask: usize,
}

const EMPTY: u32 = u32::MAX;

impl Table {
    fn new(n: usize) -> Self {
        let size = (n * 2).next_power_of_two().max(16);
        Self {
            slots: vec![EMPTY; size],
            mask: size - 1,
        }
    }

    /// Finds the slot holding an id for which `same` is true, or the empty slot where it belongs.
    fn find(&mut self, hash: u32, mut same: impl FnMut(u32) -> bool) -> &mut u32 {
        let mut slot = hash as usize & self.mask;
        let mut step = 0;
        // Triangular probing visits every slot of a power-of-two table.
        while self.slots[slot] != EMPTY && !same(self.slots[slot]) {
            step += 1;
            slot = (slot + step) & self.mask;
        }
        &mut self.slots[slot]
    }
}

fn weld_exact(positions: &[Vec3]) -> Weld {
    let mut table = Table::new(positions.len());
    let mut unique: Vec<Vec3> = Vec::new();
    let mut unique_keys: Vec<[u32; 3]> = Vec::new();
    let remap = positions
        .iter()
        .map(|&p| {
            let k = key(p);
            let slot = table.find(hash(k), |id| unique_keys[id as usize] == k);
            if *slot == EMPTY {
                *slot = unique.len() as u32;
                unique.push(p);
                unique_keys.push(k);
            }
            *slot
        })
        .collect();
    Weld {
        remap,
        positions: unique,
    }
}

/// Tolerance weld of positions that are already unique.
///
/// Cells are `2 * epsilon` wide, so the ball of radius `epsilon` around a point overlaps at most two
/// cells per axis: the point's own and the neighbour on the side of the cell's nearer half. Probing
/// those 8 cells finds every kept vertex within `epsilon`, including those across a cell boundary.
fn weld_near(positions: &[Vec3], epsilon: f32) -> Weld {
    let cell_size = 2.0 * epsilon;
    let cell_of = |p: Vec3| (p / cell_size).floor().to_array().map(|c| c as i64);
    let mut cells: Table = Table::new(positions.len());
    let mut cell_keys: Vec<[i64; 3]> = Vec::new();
    let mut cell_head: Vec<u32> = Vec::new(); // first kept vertex in the cell
    let mut next_in_cell: Vec<u32> = Vec::new(); // per kept vertex
    let mut kept: Vec<Vec3> = Vec::new();
    let epsilon_sq = f64::from(epsilon) * f64::from(epsilon);
    let cell_hash = |c: [i64; 3]| hash(c.map(|v| (v ^ (v >> 32)) as u32));

    let mut remap = Vec::with_capacity(positions.len());
    for &p in positions {
        let base = cell_of(p);
        let scaled = p / cell_size;
        // The neighbour to probe on each axis: below if p is in its cell's lower half.
        let side = [0, 1, 2].map(|a| {
            if scaled[a] - scaled[a].floor() < 0.5 {
                -1
            } else {
                1
            }
        });
        let mut best = EMPTY;
        for corner in 0..8 {
            let c = [0, 1, 2]
                .map(|a| base[a].saturating_add(if corner >> a & 1 == 1 { side[a] } else { 0 }));
            let slot = cells.find(cell_hash(c), |id| cell_keys[id as usize] == c);
            let mut v = if *slot == EMPTY {
                EMPTY
            } else {
                cell_head[*slot as usize]
            };
            while v != EMPTY {
                let d = (kept[v as usize].as_dvec3() - p.as_dvec3()).length_squared();
                if d <= epsilon_sq && v < best {
                    best = v;
                }
                v = next_in_cell[v as usize];
            }
        }
        if best == EMPTY {
            best = kept.len() as u32;
            kept.push(p);
            let slot = cells.find(cell_hash(base), |id| cell_keys[id as usize] == base);
            if *slot == EMPTY {
                *slot = cell_keys.len() as u32;
                cell_keys.push(base);
                cell_head.push(EMPTY);
            }
            let cell = *slot as usize;
            next_in_cell.push(cell_head[cell]);
            cell_head[cell] = best;
        }
        remap.push(best);
    }
    Weld {
        remap,
        positions: kept,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_weld_joins_bitwise_equal_and_both_zeros() {
        let p = [
            Vec3::new(0.0, 1.0, 2.0),
            Vec3::new(-0.0, 1.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0000002),
        ];
        let w = weld(&p, 0.0);
        assert_eq!(w.remap, [0, 0, 1]);
        assert_eq!(w.positions, [p[0], p[2]]);
    }

    #[test]
    fn tolerance_weld_finds_neighbours_across_cell_boundaries() {
        // Cells are 2e wide with boundaries at multiples of 0.2; each pair straddles one on some axis.
        let e = 0.1;
        for boundary in [
            Vec3::X * 0.2,
            Vec3::Y * -0.4,
            Vec3::Z * 0.6,
            Vec3::splat(0.2),
        ] {
            let a = boundary - Vec3::splat(0.02);
            let b = boundary + Vec3::splat(0.02); // |a - b| = 0.069 < e
            let w = weld(&[a, b], e);
            assert_eq!(w.remap, [0, 0], "pair around {boundary}");
        }
    }

    #[test]
    fn tolerance_weld_keeps_points_just_beyond_epsilon() {
        let w = weld(&[Vec3::ZERO, Vec3::new(0.1001, 0.0, 0.0)], 0.1);
        assert_eq!(w.remap, [0, 1]);
    }

    #[test]
    fn tolerance_weld_picks_the_earliest_kept_vertex_and_does_not_chain() {
        // 0 and 2 are 0.18 apart: 1 joins 0 (earliest), 2 is too far from 0 and becomes its own.
        let p = [Vec3::ZERO, Vec3::X * 0.09, Vec3::X * 0.18];
        assert_eq!(weld(&p, 0.1).remap, [0, 0, 1]);
    }

    #[test]
    fn tolerance_weld_matches_brute_force_on_a_jittered_grid() {
        // Deterministic pseudo-random points on a grid with jitter, many of them near cell boundaries.
        let mut state = 0x1234_5678u32;
        let mut rand = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32
        };
        let points: Vec<Vec3> = (0..2000)
            .map(|_| {
                Vec3::new(rand(), rand(), rand()) * 0.5 + Vec3::splat((rand() * 4.0).floor() * 0.05)
            })
            .collect();
        let e = 0.013;
        let w = weld(&points, e);
        // Reference: the same greedy rule, by brute force.
        let mut kept: Vec<usize> = Vec::new();
        let mut expected = Vec::new();
        for (i, &p) in points.iter().enumerate() {
            match kept.iter().position(|&k| {
                points[k].as_dvec3().distance_squared(p.as_dvec3()) <= f64::from(e) * f64::from(e)
            }) {
                Some(cluster) => expected.push(cluster as u32),
                None => {
                    expected.push(kept.len() as u32);
                    kept.push(i);
                }
            }
        }
        assert_eq!(w.remap, expected);
        assert!(
            w.positions.len() < points.len(),
            "the test must actually weld something"
        );
    }
}
