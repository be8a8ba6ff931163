//! Classify: decide what each edge is — crease (ridge or valley), boundary, marked, material seam or
//! smooth — and drop the coplanar ones (thesis §6.1, §6.2).
//!
//! Smooth interior edges stay: any of them can become a contour at run time. Only edges whose faces
//! are coplanar within a small angle can never matter (Lander's optimization, thesis §6.2): a flat
//! region produces contours only on its outline, and no crease.

use chamfer_runtime::asset::{EdgeFlags, EdgeStats};
use glam::Vec3;
use rayon::prelude::*;

use crate::adjacency::Edges;
use crate::mesh::Mark;

/// Angle between the normals of an edge's two faces, in radians: 0 when coplanar, π when folded flat.
///
/// `v` is the edge's `v0 v1 v2 v3`; `flipped` says face b winds the edge like face a
/// ([`EdgeFlags::FLIPPED`]). Uses atan2(|na × nb|, na · nb), which is accurate at small angles
/// (unlike acos of a dot product) and needs no normalization.
pub fn dihedral_angle(positions: &[Vec3], v: [u32; 4], flipped: bool) -> f32 {
    let (sin, cos) = dihedral_sin_cos(positions, v, flipped);
    sin.atan2(cos)
}

/// The dihedral angle as an unnormalized (sine, cosine) pair: (|na × nb|, na · nb).
fn dihedral_sin_cos(positions: &[Vec3], v: [u32; 4], flipped: bool) -> (f32, f32) {
    let p = v.map(|i| positions[i as usize]);
    let na = (p[1] - p[0]).cross(p[2] - p[0]);
    let nb = (p[3] - p[0]).cross(p[1] - p[0]);
    let nb = if flipped { -nb } else { nb };
    (na.cross(nb).length(), na.dot(nb))
}

/// [`dihedral_sin_cos`] in f64.
fn dihedral_sin_cos_f64(positions: &[Vec3], v: [u32; 4], flipped: bool) -> (f64, f64) {
    let p = v.map(|i| positions[i as usize].as_dvec3());
    let na = (p[1] - p[0]).cross(p[2] - p[0]);
    let nb = (p[3] - p[0]).cross(p[1] - p[0]);
    let nb = if flipped { -nb } else { nb };
    (na.cross(nb).length(), na.dot(nb))
}

/// "Angle >= threshold" for angles in [0, π] given as (sine, cosine) of any common scale:
/// the point (cos, sin) lies on or beyond the threshold's ray, so no atan2 is needed per edge.
#[derive(Clone, Copy)]
struct AngleThreshold {
    cos: f32,
    sin: f32,
}

impl AngleThreshold {
    fn degrees(threshold: f32) -> Self {
        let (sin, cos) = threshold.to_radians().sin_cos();
        Self { cos, sin }
    }

    fn reached_by(self, sin: f32, cos: f32) -> bool {
        self.cos * sin - self.sin * cos >= 0.0
    }

    fn reached_by_f64(self, sin: f64, cos: f64) -> bool {
        f64::from(self.cos) * sin - f64::from(self.sin) * cos >= 0.0
    }
}

/// True if the edge is convex: face b's far vertex lies below face a's plane (thesis §6.1).
fn is_ridge(positions: &[Vec3], v: [u32; 4]) -> bool {
    let p = v.map(|i| positions[i as usize]);
    let na = (p[1] - p[0]).cross(p[2] - p[0]);
    (p[3] - p[2]).dot(na) <= 0.0
}

/// Classifies every edge in place, applies the file's marks, and removes coplanar edges.
///
/// Sets [`EdgeFlags::RIDGE`] / [`EdgeFlags::VALLEY`] on manifold edges whose dihedral angle is at
/// least `crease_deg`, [`EdgeFlags::MARKED`] on edges named by `marks` (and
/// [`EdgeFlags::CHAMFER`] with the radius, when a mark has one), then drops manifold edges below
/// `coplanar_deg` that are neither marked nor a material seam.
///
/// Contract: `edges` comes from [`adjacency`](crate::adjacency::adjacency) over `positions`;
/// marks use the same vertex numbering. Returns the class counts, counting each edge in every class
/// it belongs to, before the drop (except `kept` and `smooth`, which count what remains).
pub fn classify(
    positions: &[Vec3],
    edges: &mut Edges,
    marks: &[Mark],
    coplanar_deg: f32,
    crease_deg: f32,
) -> EdgeStats {
    classify_moving(positions, edges, marks, coplanar_deg, crease_deg, None)
}

/// [`classify`] for a mesh that moves: `rigid[v]` numbers the group of vertices that always move
/// together (the same joints and weights, no morph target), and an edge is dropped as coplanar
/// only when its four vertices are in one group, since faces that bend apart can become a contour.
pub fn classify_moving(
    positions: &[Vec3],
    edges: &mut Edges,
    marks: &[Mark],
    coplanar_deg: f32,
    crease_deg: f32,
    rigid: Option<&[u32]>,
) -> EdgeStats {
    let mut stats = EdgeStats {
        total: edges.len() as u64,
        ..EdgeStats::default()
    };
    for mark in marks {
        let Some(e) = edges.find(mark.vertices[0], mark.vertices[1]) else {
            stats.marks_unmatched += 1;
            continue;
        };
        edges.flags[e] |= EdgeFlags::MARKED;
        if let Some(radius) = mark.radius.filter(|&r| r > 0.0) {
            if edges.radii.is_empty() {
                edges.radii = vec![0.0; edges.len()];
            }
            edges.radii[e] = radius;
            edges.flags[e] |= EdgeFlags::CHAMFER;
        }
    }

    let (coplanar, crease) = (
        AngleThreshold::degrees(coplanar_deg),
        AngleThreshold::degrees(crease_deg),
    );
    let keep: Vec<bool> = edges
        .vertices
        .par_iter()
        .zip(edges.flags.par_iter_mut())
        .map(|(&v, flags)| {
            if flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD) {
                return true;
            }
            let (sin, cos) = dihedral_sin_cos(positions, v, flags.contains(EdgeFlags::FLIPPED));
            if crease.reached_by(sin, cos) {
                *flags |= if is_ridge(positions, v) {
                    EdgeFlags::RIDGE
                } else {
                    EdgeFlags::VALLEY
                };
            }
            // In f64: at a threshold of a thousandth of a degree, f32's rounding of the cross
            // products decides, and it depends on which face is face a (the triangle order).
            let (sin, cos) = dihedral_sin_cos_f64(positions, v, flags.contains(EdgeFlags::FLIPPED));
            let bends = rigid
                .is_some_and(|group| v.iter().any(|&u| group[u as usize] != group[v[0] as usize]));
            bends
                || coplanar.reached_by_f64(sin, cos)
                || flags.intersects(EdgeFlags::MARKED | EdgeFlags::MATERIAL)
        })
        .collect();

    for (flags, &kept) in edges.flags.iter().zip(&keep) {
        let count = |class: EdgeFlags| u64::from(flags.intersects(class));
        stats.boundary += count(EdgeFlags::BOUNDARY);
        stats.non_manifold += count(EdgeFlags::NON_MANIFOLD);
        stats.crease += count(EdgeFlags::CREASE);
        stats.ridge += count(EdgeFlags::RIDGE);
        stats.valley += count(EdgeFlags::VALLEY);
        stats.marked += count(EdgeFlags::MARKED);
        stats.material += count(EdgeFlags::MATERIAL);
        stats.flipped += u64::from(
            flags.contains(EdgeFlags::FLIPPED) && !flags.contains(EdgeFlags::NON_MANIFOLD),
        );
        stats.kept += u64::from(kept);
        stats.smooth += u64::from(kept && !flags.intersects(EdgeFlags::STATIC));
    }
    stats.coplanar_dropped = stats.total - stats.kept;
    edges.retain(&keep);
    stats
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::adjacency::adjacency;

    /// A unit cube, two triangles per face, outward winding.
    pub(crate) fn cube() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let p = (0..8)
            .map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2 & 1) as f32))
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let t = quads
            .iter()
            .flat_map(|q: &[u32; 4]| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        (p, t)
    }

    #[test]
    fn cube_keeps_twelve_ridges_and_drops_six_diagonals() {
        let (p, t) = cube();
        let mut edges = adjacency(&t, &[], p.len());
        let stats = classify(&p, &mut edges, &[], 0.01, 30.0);
        assert_eq!(
            (stats.total, stats.kept, stats.coplanar_dropped),
            (18, 12, 6)
        );
        assert_eq!(
            (stats.crease, stats.ridge, stats.valley, stats.smooth),
            (12, 12, 0, 0)
        );
        assert!(edges.flags.iter().all(|f| f.contains(EdgeFlags::RIDGE)));
    }

    #[test]
    fn a_fold_is_a_ridge_from_one_side_and_a_valley_from_the_other() {
        // Faces in the planes z = 0 (through 2) and y = 0 (through 3) meet at 90 degrees along 0-1.
        // Wound [0 1 2], [1 0 3] their normals are +z and +y, facing each other: an inside corner.
        let p = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.5, 1.0, 0.0),
            Vec3::new(0.5, 0.0, 1.0),
        ];
        let mut valley = adjacency(&[[0, 1, 2], [1, 0, 3]], &[], 4);
        classify(&p, &mut valley, &[], 0.01, 30.0);
        let mut ridge = adjacency(&[[0, 2, 1], [1, 3, 0]], &[], 4);
        classify(&p, &mut ridge, &[], 0.01, 30.0);
        let (r, v) = (
            ridge.find(0, 1).expect("edge"),
            valley.find(0, 1).expect("edge"),
        );
        assert!(
            ridge.flags[r].contains(EdgeFlags::RIDGE),
            "{:?}",
            ridge.flags[r]
        );
        assert!(
            valley.flags[v].contains(EdgeFlags::VALLEY),
            "{:?}",
            valley.flags[v]
        );
    }

    #[test]
    fn marks_keep_coplanar_edges_and_carry_their_radius() {
        let (p, t) = cube();
        let mut edges = adjacency(&t, &[], p.len());
        let marks = [
            Mark {
                vertices: [0, 3],
                radius: Some(0.25),
            },
            Mark {
                vertices: [0, 7],
                radius: None,
            },
        ];
        let stats = classify(&p, &mut edges, &marks, 0.01, 30.0);
        assert_eq!(
            (stats.kept, stats.marked, stats.marks_unmatched),
            (13, 1, 1)
        );
        let e = edges.find(3, 0).expect("marked diagonal kept");
        assert!(edges.flags[e].contains(EdgeFlags::MARKED | EdgeFlags::CHAMFER));
        assert_eq!(edges.radii[e], 0.25);
    }

    #[test]
    fn dihedral_angle_is_accurate_for_tiny_folds() {
        let tiny = 1e-4_f32; // radians
        let p = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.5, 1.0, 0.0),
            Vec3::new(0.5, -tiny.cos(), tiny.sin()),
        ];
        let angle = dihedral_angle(&p, [0, 1, 2, 3], false);
        assert!((angle - tiny).abs() < 1e-6, "{angle}");
    }
}
