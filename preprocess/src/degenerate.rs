//! Degenerate triangles: those that repeat a vertex or have exactly zero area have no normal and
//! would only add zero-length or doubled edges, so the bake drops them before building adjacency.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// True if the triangle repeats a vertex or its three positions are collinear.
///
/// The area test is exact: differences of f32s and their products are exact in f64.
pub fn is_degenerate(triangle: [u32; 3], positions: &[Vec3]) -> bool {
    let [a, b, c] = triangle;
    if a == b || b == c || c == a {
        return true;
    }
    let p = |i: u32| positions[i as usize].as_dvec3();
    let n: DVec3 = (p(b) - p(a)).cross(p(c) - p(a));
    n == DVec3::ZERO
}

/// Removes degenerate triangles (and their materials) in place, keeping the others in order.
/// Returns how many were removed.
///
/// Contract: every index is below `positions.len()`; `materials` is empty (one material) or has
/// one entry per triangle.
pub fn remove_degenerate(
    triangles: &mut Vec<[u32; 3]>,
    materials: &mut Vec<u32>,
    positions: &[Vec3],
) -> usize {
    // Most meshes have none: the test alone runs in parallel, the compaction only when needed.
    if !triangles.par_iter().any(|&t| is_degenerate(t, positions)) {
        return 0;
    }
    let before = triangles.len();
    let mut write = 0;
    for read in 0..before {
        if !is_degenerate(triangles[read], positions) {
            triangles[write] = triangles[read];
            if !materials.is_empty() {
                materials[write] = materials[read];
            }
            write += 1;
        }
    }
    triangles.truncate(write);
    materials.truncate(write.min(materials.len()));
    before - write
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drops_repeated_indices_and_zero_area_keeps_the_rest() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X * 2.0];
        let mut t = vec![[0, 1, 2], [0, 0, 1], [0, 1, 3], [2, 1, 0]];
        let mut m = vec![7, 8, 9, 10];
        assert_eq!(remove_degenerate(&mut t, &mut m, &p), 2);
        assert_eq!(t, [[0, 1, 2], [2, 1, 0]]);
        assert_eq!(m, [7, 10]);
    }

    #[test]
    fn a_thin_but_nonzero_triangle_is_kept() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::new(0.5, 1e-30, 0.0)];
        assert!(!is_degenerate([0, 1, 2], &p));
    }
}
