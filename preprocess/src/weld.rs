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

use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use glam::Vec3;
use rayon::prelude::*;

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
/// Runs in O(n) expected time, in parallel: the exact weld is one pass over a shared hash table;
/// the tolerance weld first finds, on a coarse grid, the few positions that have any other within
/// `epsilon`, and runs the ordered greedy rule (8 grid cells probed per position) on those alone.
pub fn weld(positions: &[Vec3], epsilon: f32) -> Weld {
    let exact = weld_exact(positions);
    if epsilon == 0.0 {
        return exact;
    }
    match weld_near(&exact.positions, epsilon) {
        None => exact,
        Some(near) => Weld {
            remap: exact
                .remap
                .par_iter()
                .map(|&i| near.remap[i as usize])
                .collect(),
            positions: near.positions,
        },
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

/// Vertices per parallel work item.
const VERTICES_PER_CHUNK: usize = 16 * 1024;

/// Exact weld, in parallel: a shared open-addressing table (as meshoptimizer's
/// `meshopt_generateVertexRemap`, but filled by every thread at once) keeps, for each distinct
/// position, the lowest index that has it; a prefix count over the chunks then numbers those
/// first appearances in order, so the result is the same for any thread count.
fn weld_exact(positions: &[Vec3]) -> Weld {
    let n = positions.len();
    // At most four fifths full (meshoptimizer's sizing), so probe sequences stay short.
    let size = (n + n / 4).next_power_of_two().max(16);
    let mask = size - 1;
    let table: Vec<AtomicU32> = (0..size)
        .into_par_iter()
        .map(|_| AtomicU32::new(EMPTY))
        .collect();
    // First the slot of each vertex, then (once every vertex is in) its first appearance.
    let mut first: Vec<u32> = vec![0; n];
    first
        .par_chunks_mut(VERTICES_PER_CHUNK)
        .enumerate()
        .for_each(|(chunk, slots)| {
            for (k, slot_of) in slots.iter_mut().enumerate() {
                let i = (chunk * VERTICES_PER_CHUNK + k) as u32;
                let own = key(positions[i as usize]);
                let mut slot = hash(own) as usize & mask;
                let mut step = 0;
                loop {
                    let held = table[slot].load(Ordering::Relaxed);
                    let held = if held == EMPTY {
                        match table[slot].compare_exchange(
                            EMPTY,
                            i,
                            Ordering::Relaxed,
                            Ordering::Relaxed,
                        ) {
                            Ok(_) => break,
                            Err(now) => now,
                        }
                    } else {
                        held
                    };
                    // A slot, once filled, only ever holds indices of one position.
                    if key(positions[held as usize]) == own {
                        // Later copies (the usual case) leave the slot alone, without a write.
                        if i < held {
                            table[slot].fetch_min(i, Ordering::Relaxed);
                        }
                        break;
                    }
                    step += 1;
                    slot = (slot + step) & mask;
                }
                *slot_of = slot as u32;
            }
        });
    first
        .par_iter_mut()
        .for_each(|f| *f = table[*f as usize].load(Ordering::Relaxed));
    drop(table);
    number_first_appearances(positions, first)
}

/// Turns "the first index with my position" (`first[i] <= i`, `first[i] == i` for the first one)
/// into topology vertex numbers in order of first appearance, with their positions.
fn number_first_appearances(positions: &[Vec3], mut first: Vec<u32>) -> Weld {
    let counts: Vec<usize> = first
        .par_chunks(VERTICES_PER_CHUNK)
        .enumerate()
        .map(|(chunk, f)| {
            let base = chunk * VERTICES_PER_CHUNK;
            f.iter()
                .enumerate()
                .filter(|&(k, &f)| f as usize == base + k)
                .count()
        })
        .collect();
    let unique_count: usize = counts.iter().sum();
    let mut unique = vec![Vec3::ZERO; unique_count];
    let mut id = vec![0u32; positions.len()];
    let mut outputs = Vec::with_capacity(counts.len());
    let mut rest = unique.as_mut_slice();
    let mut base = 0u32;
    for &count in &counts {
        let (head, tail) = rest.split_at_mut(count);
        outputs.push((head, base));
        rest = tail;
        base += count as u32;
    }
    id.par_chunks_mut(VERTICES_PER_CHUNK)
        .zip(first.par_chunks(VERTICES_PER_CHUNK))
        .zip(outputs)
        .enumerate()
        .for_each(|(chunk, ((ids, f), (out, base)))| {
            let start = chunk * VERTICES_PER_CHUNK;
            let mut next = 0;
            for (k, (id, &f)) in ids.iter_mut().zip(f).enumerate() {
                if f as usize == start + k {
                    *id = base + next as u32;
                    out[next] = positions[start + k];
                    next += 1;
                }
            }
        });
    // Every first appearance is numbered now; the others take their first's number.
    first.par_iter_mut().for_each(|f| *f = id[*f as usize]);
    Weld {
        remap: first,
        positions: unique,
    }
}

/// Tolerance weld of positions that are already unique; `None` when nothing is within `epsilon`
/// of anything else (the usual case), so the exact weld stands.
///
/// A position with no other within `epsilon` is kept by the greedy rule and never joins or is
/// joined, whatever the order, so the rule only needs to run, in order, on the others: the
/// *crowded* positions that [`crowded`] finds.
fn weld_near(positions: &[Vec3], epsilon: f32) -> Option<Weld> {
    let crowded = crowded(positions, epsilon);
    let subset: Vec<u32> = (0..positions.len() as u32)
        .filter(|&i| crowded[i as usize])
        .collect();
    drop(crowded);
    if subset.is_empty() {
        return None;
    }
    let subset_positions: Vec<Vec3> = subset.iter().map(|&i| positions[i as usize]).collect();
    let greedy = greedy_near(&subset_positions, epsilon);
    if greedy.positions.len() == subset.len() {
        return None; // crowded on the grid, but none within epsilon
    }
    // Renumber in order: lonely positions are kept; crowded ones as the greedy rule says (a
    // cluster's kept position comes before any that join it).
    let mut remap = Vec::with_capacity(positions.len());
    let mut kept = Vec::with_capacity(positions.len() - subset.len() + greedy.positions.len());
    let mut cluster_id = vec![EMPTY; greedy.positions.len()];
    let mut next_in_subset = 0;
    for (i, &p) in positions.iter().enumerate() {
        if subset.get(next_in_subset) == Some(&(i as u32)) {
            let cluster = greedy.remap[next_in_subset] as usize;
            next_in_subset += 1;
            if cluster_id[cluster] == EMPTY {
                cluster_id[cluster] = kept.len() as u32;
                kept.push(p);
            }
            remap.push(cluster_id[cluster]);
        } else {
            remap.push(kept.len() as u32);
            kept.push(p);
        }
    }
    Some(Weld {
        remap,
        positions: kept,
    })
}

/// The weld's distance test, in f64 (exact for the differences of nearby f32s).
fn within(a: Vec3, b: Vec3, epsilon_sq: f64) -> bool {
    (a.as_dvec3() - b.as_dvec3()).length_squared() <= epsilon_sq
}

/// Positions of a bucket beyond which all are taken as crowded without comparing them.
const MOST_COMPARED: usize = 32;

/// Which positions may have another within `epsilon` ([`within`]): every one that does, and a few
/// that do not. Computed in parallel, the same for any thread count.
///
/// Each position is listed under the hash of every cell of a coarse grid (about one position per
/// cell on a surface) that its box of half-width `epsilon` (slightly padded) overlaps: one cell for
/// all but the few near a cell's side. Two positions within `epsilon` are then both listed under
/// the cell of either, so sorting the list and comparing the positions that share a hash pairwise
/// finds them; a run of more than [`MOST_COMPARED`] is crowded as a whole, which keeps the work
/// linear.
fn crowded(positions: &[Vec3], epsilon: f32) -> Vec<bool> {
    let n = positions.len();
    if n < 2 * MOST_COMPARED {
        return vec![true; n];
    }
    let (lo, hi) = positions
        .par_iter()
        .fold(
            || (Vec3::INFINITY, Vec3::NEG_INFINITY),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
        .reduce(
            || (Vec3::INFINITY, Vec3::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
    let diagonal = (hi.as_dvec3() - lo.as_dvec3()).length();
    let epsilon = f64::from(epsilon);
    // The box is padded past any rounding of the distance test, so no pair within it is missed.
    let pad = epsilon * 1.001;
    let cell = (diagonal / (n as f64).sqrt()).max(4.0 * pad);
    let cell_hash = |c: [i64; 3]| {
        let h = c.iter().fold(0x9e37_79b9_7f4a_7c15u64, |h, &v| {
            (h ^ v as u64)
                .wrapping_mul(0xff51_afd7_ed55_8ccd)
                .rotate_left(29)
        });
        h.wrapping_mul(0xc4ce_b9fe_1a85_ec53) >> 32
    };
    // (cell hash << 32 | position) for the 1 to 8 cells a position's padded box overlaps.
    let entries_of = |(i, &p): (usize, &Vec3)| {
        let p = p.as_dvec3().to_array();
        let range = p.map(|x| {
            let margin = pad + x.abs() * 1e-12;
            let first = ((x - margin) / cell).floor() as i64;
            let last = ((x + margin) / cell).floor() as i64;
            (first, last.min(first.saturating_add(1)))
        });
        let mut out = [0u64; 8];
        let mut count = 0;
        for x in range[0].0..=range[0].1 {
            for y in range[1].0..=range[1].1 {
                for z in range[2].0..=range[2].1 {
                    out[count] = cell_hash([x, y, z]) << 32 | i as u64;
                    count += 1;
                }
            }
        }
        out.into_iter().take(count)
    };
    let mut entries: Vec<u64> = positions
        .par_iter()
        .enumerate()
        .flat_map_iter(entries_of)
        .collect();
    entries.par_sort_unstable();
    let epsilon_sq = epsilon * epsilon;
    let crowded: Vec<AtomicBool> = (0..n).map(|_| AtomicBool::new(false)).collect();
    let mark = |i: u32| crowded[i as usize].store(true, Ordering::Relaxed);
    entries
        .par_chunk_by(|a, b| a >> 32 == b >> 32)
        .filter(|run| run.len() > 1)
        .for_each(|run| {
            let members = run.iter().map(|&e| e as u32);
            if run.len() > MOST_COMPARED {
                members.for_each(mark);
                return;
            }
            for (k, a) in members.clone().enumerate() {
                for b in members.clone().skip(k + 1) {
                    if a != b && within(positions[a as usize], positions[b as usize], epsilon_sq) {
                        mark(a);
                        mark(b);
                    }
                }
            }
        });
    crowded.into_iter().map(AtomicBool::into_inner).collect()
}

/// The greedy tolerance weld of positions that are already unique, in their order.
///
/// Cells are `2 * epsilon` wide, so the ball of radius `epsilon` around a point overlaps at most two
/// cells per axis: the point's own and the neighbour on the side of the cell's nearer half. Probing
/// those 8 cells finds every kept vertex within `epsilon`, including those across a cell boundary.
fn greedy_near(positions: &[Vec3], epsilon: f32) -> Weld {
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
                if v < best && within(kept[v as usize], p, epsilon_sq) {
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

    /// Deterministic pseudo-random numbers in [0, 1].
    fn xorshift(seed: u32) -> impl FnMut() -> f32 {
        let mut state = seed;
        move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32
        }
    }

    /// The exact weld by the obvious method: a `HashMap` from the coordinates' bits.
    fn exact_reference(positions: &[Vec3]) -> Weld {
        let mut ids = std::collections::HashMap::new();
        let mut unique = Vec::new();
        let remap = positions
            .iter()
            .map(|&p| {
                *ids.entry(key(p)).or_insert_with(|| {
                    unique.push(p);
                    unique.len() as u32 - 1
                })
            })
            .collect();
        Weld {
            remap,
            positions: unique,
        }
    }

    fn in_pool<T: Send>(threads: usize, run: impl FnOnce() -> T + Send) -> T {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(run)
    }

    #[test]
    fn exact_weld_matches_a_hash_map_across_chunks_and_thread_counts() {
        // Several chunks of vertices, each position repeated up to 6 times far apart in the
        // input (so copies land in different chunks and threads race to insert them), with
        // -0.0 copies of 0.0 coordinates.
        let mut rand = xorshift(0x9e37_79b9);
        let distinct: Vec<Vec3> = (0..20_000)
            .map(|i| {
                let p = Vec3::new(rand(), rand(), rand());
                if i % 7 == 0 {
                    p * Vec3::new(0.0, 1.0, 1.0)
                } else {
                    p
                }
            })
            .collect();
        let positions: Vec<Vec3> = (0..5 * VERTICES_PER_CHUNK)
            .map(|_| {
                let p = distinct[(rand() * (distinct.len() - 1) as f32) as usize];
                if p.x == 0.0 && rand() < 0.5 {
                    p * Vec3::new(-1.0, 1.0, 1.0)
                } else {
                    p
                }
            })
            .collect();
        let expected = exact_reference(&positions);
        assert!(
            expected.positions.len() < positions.len() / 2,
            "the test must weld"
        );
        for threads in [1, 2, 4] {
            assert!(
                in_pool(threads, || weld(&positions, 0.0)) == expected,
                "{threads} threads"
            );
        }
    }

    #[test]
    fn tolerance_weld_matches_the_greedy_rule_on_all_positions_for_any_thread_count() {
        // Surface-like points (a sphere), a fifth of them with a near copy at a random distance
        // just under or over epsilon in a random direction, so pairs straddle coarse cells too.
        let mut rand = xorshift(0x2545_f491);
        let e = 1e-3;
        let mut positions = Vec::new();
        for _ in 0..60_000 {
            let p = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5).normalize_or(Vec3::X);
            positions.push(p);
            if rand() < 0.2 {
                let direction = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5);
                positions.push(p + direction.normalize_or(Vec3::Y) * e * (0.8 + 0.4 * rand()));
            }
        }
        let exact = exact_reference(&positions);
        let near = greedy_near(&exact.positions, e);
        let expected = Weld {
            remap: exact
                .remap
                .iter()
                .map(|&i| near.remap[i as usize])
                .collect(),
            positions: near.positions,
        };
        assert!(
            expected.positions.len() + 5_000 < positions.len(),
            "the test must weld"
        );
        for threads in [1, 2, 4] {
            assert!(
                in_pool(threads, || weld(&positions, e)) == expected,
                "{threads} threads"
            );
        }
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
