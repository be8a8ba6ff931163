//! Radii: which edges carry a chamfer and with what radius r_e (seed 000 §3.2), clamped to what the
//! geometry allows.
//!
//! Marks from the file keep their radius. A rule ([`Radius`]) gives a radius to every ridge crease
//! (and, if asked, every valley) and to marked edges without one. A fillet of radius r between faces
//! whose normals differ by θ cuts `r · tan(θ / 2)` into each face; when that is more than the distance
//! from the edge to a face's opposite vertex, the rounded strip would run off the face, so the radius
//! is clamped to `height / tan(θ / 2)` (the triangle's height is a conservative stand-in for the
//! flat region beside the edge).

use chamfer_runtime::asset::{ChamferStats, EdgeFlags};
use glam::Vec3;

use crate::adjacency::Edges;
use crate::options::Radius;

/// Assigns and clamps radii in place and sets [`EdgeFlags::CHAMFER`] on every edge with one.
///
/// Contract: `edges` are classified ([`classify`](crate::classify::classify)): marks carry their
/// file radius in `edges.radii` (or it is empty). `positions` are the welded positions.
pub fn assign_radii(
    positions: &[Vec3],
    edges: &mut Edges,
    rule: Radius,
    valleys: bool,
) -> ChamferStats {
    let rule_radius = match rule {
        Radius::None => None,
        Radius::Absolute(r) => Some(r),
        Radius::Relative(f) => {
            let (lo, hi) = crate::mesh::bounds(positions);
            Some(f * (hi - lo).length())
        }
    };
    let ruled = EdgeFlags(EdgeFlags::RIDGE.0 | if valleys { EdgeFlags::VALLEY.0 } else { 0 });
    let mut stats = ChamferStats::default();
    if rule_radius.is_none() && edges.radii.is_empty() {
        return stats;
    }
    if edges.radii.is_empty() {
        edges.radii = vec![0.0; edges.len()];
    }
    let (mut lo, mut hi) = (f32::INFINITY, 0.0f32);
    for e in 0..edges.len() {
        let flags = edges.flags[e];
        let mut radius = edges.radii[e];
        if let Some(r) =
            rule_radius.filter(|_| radius == 0.0 && flags.intersects(ruled | EdgeFlags::MARKED))
        {
            radius = r;
        }
        if radius <= 0.0 {
            continue;
        }
        if let Some(limit) = radius_limit(positions, edges.vertices[e], flags) {
            if radius > limit {
                radius = limit;
                stats.clamped += 1;
            }
        }
        edges.radii[e] = radius;
        edges.flags[e] |= EdgeFlags::CHAMFER;
        stats.edges += 1;
        lo = lo.min(radius);
        hi = hi.max(radius);
    }
    if stats.edges > 0 {
        (stats.radius_min, stats.radius_max) = (lo, hi);
    }
    stats
}

/// The largest radius whose fillet stays on both faces, or `None` when nothing limits it
/// (boundary and non-manifold edges, nearly flat edges).
fn radius_limit(positions: &[Vec3], v: [u32; 4], flags: EdgeFlags) -> Option<f32> {
    if flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD) {
        return None;
    }
    let p = v.map(|i| positions[i as usize]);
    let edge = p[1] - p[0];
    let length = edge.length();
    let (na, nb) = (edge.cross(p[2] - p[0]), (p[3] - p[0]).cross(edge));
    let nb = if flags.contains(EdgeFlags::FLIPPED) {
        -nb
    } else {
        nb
    };
    // Heights of the opposite vertices over the edge line: |n| = |edge| * height.
    let height = na.length().min(nb.length()) / length;
    // tan(θ/2) = sin θ / (1 + cos θ), from the unnormalized normals.
    let (sin, cos) = (na.cross(nb).length(), na.dot(nb));
    let scale = na.length() * nb.length();
    let tan_half = sin / (scale + cos);
    (tan_half > 1e-6).then(|| height / tan_half)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adjacency::adjacency;
    use crate::classify::classify;

    fn cube_edges() -> (Vec<Vec3>, Edges) {
        let (p, t) = crate::classify::tests::cube();
        let mut edges = adjacency(&t, &[], p.len());
        classify(&p, &mut edges, &[], 0.01, 30.0);
        (p, edges)
    }

    #[test]
    fn a_rule_gives_every_cube_ridge_a_radius() {
        let (p, mut edges) = cube_edges();
        let stats = assign_radii(&p, &mut edges, Radius::Absolute(0.1), false);
        assert_eq!((stats.edges, stats.clamped), (12, 0));
        assert_eq!((stats.radius_min, stats.radius_max), (0.1, 0.1));
        assert!(edges.flags.iter().all(|f| f.contains(EdgeFlags::CHAMFER)));
    }

    #[test]
    fn relative_radius_is_a_fraction_of_the_diagonal() {
        let (p, mut edges) = cube_edges();
        let stats = assign_radii(&p, &mut edges, Radius::Relative(0.01), false);
        assert!((stats.radius_max - 0.01 * 3f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn radii_too_large_for_the_faces_are_clamped() {
        // A right angle: tan(45°) = 1, so the fillet fits while r <= the triangle height (1 for the unit cube).
        let (p, mut edges) = cube_edges();
        let stats = assign_radii(&p, &mut edges, Radius::Absolute(5.0), false);
        assert_eq!((stats.edges, stats.clamped), (12, 12));
        assert!(
            (stats.radius_max - 1.0).abs() < 1e-5,
            "{}",
            stats.radius_max
        );
    }

    #[test]
    fn no_rule_and_no_marks_means_no_chamfer() {
        let (p, mut edges) = cube_edges();
        assert_eq!(
            assign_radii(&p, &mut edges, Radius::None, false),
            ChamferStats::default()
        );
        assert!(edges.radii.is_empty());
    }
}
