//! Edge clusters: what lets a renderer skip runs of edges that cannot be drawn this frame before it
//! looks at any of them (issue 14; the normal-cone test meshoptimizer's
//! `meshopt_computeClusterBounds` gives meshlets, applied to edges).
//!
//! Cluster `i` is edges `64 i .. 64 i + 64` (the last one shorter): a run in the asset's order, so it
//! needs no index. It holds a sphere around every edge's end points `v0 v1`, a cone around the
//! normals of every face of its edges and the union of their flags. From a camera the cone and the
//! sphere bound `dot(plane, eye)` over all the faces: when every face looks at the camera no edge
//! can be a contour, when none does only boundaries (and every class if back faces are not culled)
//! can be drawn, and a sphere outside the view holds nothing on screen.
//!
//! The bound must hold for the planes the GPU computes in f32 from the same positions, not only
//! for exact ones: each face's normal is widened by a bound on the rounding of its cross product,
//! so a sliver (whose f32 normal is noise) opens its cluster's cone to every direction instead of
//! culling edges the per-edge test would draw. Any edge order is correct; the bake orders edges so
//! that runs are small and flat, which is what makes the test cull.

use glam::DVec3;

use super::{Asset, EdgeFlags, attribute_flags};

/// Edges per cluster (the last cluster of an asset may have fewer).
pub const CLUSTER_EDGES: usize = 64;

/// One cluster's bounds, as stored in [`SectionKind::EdgeClusters`](super::SectionKind) and read by
/// the GPU (`EdgeCluster` in `shaders/compute.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EdgeCluster {
    /// Centre of a sphere holding every edge's `v0` and `v1`, in model space.
    pub center: [f32; 3],
    /// The sphere's radius.
    pub radius: f32,
    /// Unit axis of the cone of face normals (planes oriented as the runtime's per-edge test).
    pub axis: [f32; 3],
    /// Cosine of the cone's half-angle, rounded down; -1 when the faces may look any way.
    pub cos_angle: f32,
    /// The union of the edges' [`EdgeFlags`].
    pub flags: u32,
    pad: [u32; 3],
}

impl EdgeCluster {
    /// A cluster of these bounds and flags.
    pub(crate) fn new(
        center: [f32; 3],
        radius: f32,
        axis: [f32; 3],
        cos_angle: f32,
        flags: EdgeFlags,
    ) -> Self {
        Self {
            center,
            radius,
            axis,
            cos_angle,
            flags: u32::from(flags.0),
            pad: [0; 3],
        }
    }
}

/// Bytes per cluster in the asset and on the GPU.
pub const CLUSTER_BYTES: usize = std::mem::size_of::<EdgeCluster>();

/// The number of clusters of an asset with `edges` edges.
pub const fn cluster_count(edges: usize) -> usize {
    edges.div_ceil(CLUSTER_EDGES)
}

/// The clusters of `asset`, one per [`CLUSTER_EDGES`] edges in its order.
pub fn edge_clusters(asset: &Asset) -> Vec<EdgeCluster> {
    (0..cluster_count(asset.edge_count()))
        .map(|c| cluster_of(asset, c))
        .collect()
}

/// Cluster `index` of `asset` (`index < cluster_count(asset.edge_count())`).
pub fn cluster_of(asset: &Asset, index: usize) -> EdgeCluster {
    let first = index * CLUSTER_EDGES;
    let edges = first..(first + CLUSTER_EDGES).min(asset.edge_count());
    let position = |v: u32| DVec3::from(asset.topology_positions[v as usize].map(f64::from));

    // The sphere: the centre of the end points' box, the farthest end point.
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    for e in edges.clone() {
        for k in 0..2 {
            let p = position(asset.edge_vertices.get(4 * e + k));
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let center = (lo + hi) * 0.5;
    let mut radius: f64 = 0.0;
    let mut flags = EdgeFlags::default();
    // The cone: the faces' unit normals, how far each may turn in f32, and their sum.
    let mut normals = [DVec3::ZERO; 2 * CLUSTER_EDGES];
    let mut count = 0;
    let mut sum = DVec3::ZERO;
    let mut widest_error: f64 = 0.0;
    let mut bounded = true;
    for e in edges {
        let points = asset.edge(e).map(position);
        let [p0, p1, ..] = points;
        radius = radius.max(p0.distance(center)).max(p1.distance(center));
        let edge_flags = attribute_flags(asset.edge_attributes[e]);
        flags |= edge_flags;
        let one_face = edge_flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD);
        let sign = if edge_flags.contains(EdgeFlags::FLIPPED) {
            -1.0
        } else {
            1.0
        };
        // Both faces' bounds use the end points' distances from the origin and the edge's length.
        let lengths = points.map(DVec3::length);
        let shared = (p1 - p0).length();
        let faces = [([0, 1, 2], 1.0), ([1, 0, 3], sign)];
        for &(corners, sign) in &faces[..if one_face { 1 } else { 2 }] {
            match face_normal(corners.map(|k| (points[k], lengths[k])), shared) {
                Some((normal, error)) => {
                    let normal = normal * sign;
                    sum += normal;
                    normals[count] = normal;
                    count += 1;
                    widest_error = widest_error.max(error);
                }
                None => bounded = false,
            }
        }
    }
    let axis = sum.normalize_or_zero();
    let mut half_angle = std::f64::consts::PI;
    if bounded && axis != DVec3::ZERO {
        let narrowest = normals[..count]
            .iter()
            .map(|n| n.dot(axis))
            .fold(1.0f64, f64::min)
            .clamp(-1.0, 1.0);
        // 1e-5 more covers the axis' and the cosine's rounding to f32.
        half_angle = (narrowest.acos() + widest_error + 1e-5).min(std::f64::consts::PI);
    }
    let center_f32 = center.as_vec3();
    // The stored centre moved by its rounding: the radius grows by as much, then rounds up.
    let moved = center_f32.as_dvec3().distance(center);
    let radius_f32 = round_up((radius + moved) * (1.0 + 1e-6) + 1e-30);
    let (axis, cos_angle) = if half_angle >= std::f64::consts::PI {
        ([0.0; 3], -1.0)
    } else {
        (axis.as_vec3().to_array(), round_down(half_angle.cos()))
    };
    EdgeCluster {
        center: center_f32.to_array(),
        radius: radius_f32,
        axis,
        cos_angle,
        flags: u32::from(flags.0),
        pad: [0; 3],
    }
}

/// The unit normal of the face `(a, b, c)` (`cross(b - a, c - a)`), each point given with its
/// distance from the origin and `ab` the length of `b - a`, and a bound, in radians, on how far the
/// f32 cross product of the same f32 positions can point from it; `None` if it can point anywhere
/// (a zero or sliver face).
fn face_normal([(a, la), (b, lb), (c, lc)]: [(DVec3, f64); 3], ab: f64) -> Option<(DVec3, f64)> {
    let (u, v) = (b - a, c - a);
    let n = u.cross(v);
    let length = n.length();
    // Each f32 difference is off by half an ulp of its operands, each product and sum by half an
    // ulp of itself: the cross product's error is a few ulps of |a| |v| + |u| |c| terms. Eight times
    // f32's epsilon over those is a safe bound.
    let epsilon = f64::from(f32::EPSILON);
    let ac = v.length();
    let spread = (la + lb) * ac + (la + lc) * ab + ab * ac;
    let error = 8.0 * epsilon * spread;
    // (Also refuses a NaN length.)
    if length.partial_cmp(&(2.0 * error)) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    // asin(x) <= x * pi / 2 for x in [0, 1]; x <= 1/2 here.
    Some((n / length, error / length * std::f64::consts::FRAC_PI_2))
}

fn round_up(value: f64) -> f32 {
    let rounded = value as f32;
    if f64::from(rounded) < value {
        rounded.next_up()
    } else {
        rounded
    }
}

/// `value` as the largest `f32` not above it.
pub(crate) fn round_down(value: f64) -> f32 {
    let rounded = value as f32;
    if f64::from(rounded) > value {
        rounded.next_down()
    } else {
        rounded
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::{Indices, pack_attributes};

    /// A strip of `n` quads in the plane z = 0, each split into two triangles: the edges between
    /// triangles, with faces a and b.
    fn flat_strip(n: usize, tilt: f32) -> Asset {
        let mut positions = Vec::new();
        for i in 0..=n {
            positions.push([i as f32, 0.0, tilt * i as f32]);
            positions.push([i as f32, 1.0, tilt * i as f32]);
        }
        let mut vertices = Vec::new();
        for i in 0..n as u32 {
            // The diagonal of quad i: v0 = 2i+1, v1 = 2i+2, opposite 2i and 2i+3.
            vertices.extend([2 * i + 1, 2 * i + 2, 2 * i + 3, 2 * i]);
        }
        let edges = vertices.len() / 4;
        Asset {
            topology_positions: positions.clone(),
            edge_vertices: Indices::with_bound(vertices, positions.len()),
            edge_attributes: vec![pack_attributes(EdgeFlags::RIDGE, 0.0, 0.0); edges],
            ..Asset::default()
        }
    }

    #[test]
    fn a_flat_run_has_a_narrow_cone_and_a_sphere_around_its_ends() {
        let asset = flat_strip(10, 0.0);
        let clusters = edge_clusters(&asset);
        assert_eq!(clusters.len(), 1);
        let c = clusters[0];
        // Both faces of each diagonal face the same way: +z or -z, consistently.
        assert!(c.axis[2].abs() > 0.999_999, "{c:?}");
        assert!(c.cos_angle > 0.9999 && c.cos_angle < 1.0, "{c:?}");
        for e in 0..asset.edge_count() {
            for k in 0..2 {
                let p = glam::Vec3::from(
                    asset.topology_positions[asset.edge_vertices.get(4 * e + k) as usize],
                );
                assert!(p.distance(glam::Vec3::from(c.center)) <= c.radius);
            }
        }
        assert_eq!(c.flags, u32::from(EdgeFlags::RIDGE.0));
    }

    #[test]
    fn a_sliver_face_opens_the_cone() {
        let mut asset = flat_strip(4, 0.0);
        // Edge 0's face b becomes a sliver: v3 on the line through v0 and v1, a hair off it.
        let v3 = asset.edge_vertices.get(3) as usize;
        let [x0, y0, _] = asset.topology_positions[asset.edge_vertices.get(0) as usize];
        let [x1, y1, _] = asset.topology_positions[asset.edge_vertices.get(1) as usize];
        asset.topology_positions[v3] = [0.5 * (x0 + x1), 0.5 * (y0 + y1) + 1e-7, 0.0];
        assert_eq!(edge_clusters(&asset)[0].cos_angle, -1.0);
    }

    #[test]
    fn runs_of_64_make_the_clusters() {
        let asset = flat_strip(130, 0.01);
        assert_eq!(cluster_count(asset.edge_count()), 3);
        let clusters = edge_clusters(&asset);
        assert_eq!(clusters.len(), 3);
        assert_eq!(clusters[2], cluster_of(&asset, 2));
        // A tilted strip: a wider but still bounded cone.
        assert!(clusters.iter().all(|c| c.cos_angle > 0.9));
    }
}
