//! Rounded corners (issue 29, beyond seed 000, which lets the strips end in a notch): where the chamfer
//! edges at a convex vertex all have one radius r, the rounded solid is the sharp one eroded by r and
//! dilated by a ball of r. Near a vertex with three face planes that is a sphere of radius r centred
//! at the point r inside all three planes, the edges' cylinders running from it, and the flat faces.
//! This module finds those corners once per asset; `shaders/corners.wgsl` draws each one by tracing
//! that local solid per sub-sample, and the strips hand the pixels near a drawn corner over to it.
//!
//! A vertex qualifies when its ring (the kept edges around it, which the bake links) holds two or
//! three edges, at least two of them chamfer edges of one radius and any other a nearly flat facet
//! edge, whose faces lie in exactly three planes meeting convexly: a box's corner (three chamfer
//! edges), or the rim of a faceted cylinder (two rim edges and the facet edge between the sides).
//! Other vertices keep the seed's strip ends.

use glam::Vec3;

use crate::asset::{Asset, EdgeFlags};

/// `Corner` in `shaders/corners.wgsl`: one rounded corner, in model space.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Corner {
    /// The sphere's centre and radius.
    pub(crate) sphere: [f32; 4],
    /// The sharp vertex; w: how far each cylinder is followed from the centre (the shortest edge at
    /// the vertex: which pixels a corner traces is the hand-over's to decide, so where two corners
    /// split an edge between them neither leaves a gap).
    pub(crate) vertex: [f32; 4],
    /// The three planes' outward normals (unit); `normals[0].w`: the corner's reach around the
    /// vertex (model units) within which the strips hand their pixels over.
    pub(crate) normals: [[f32; 4]; 3],
    /// Per plane pair (k, k + 1): the far end of the kept edge between them (w = 1), or w = 0 where
    /// the pair meets at a dropped edge (no strip to hand over).
    pub(crate) far: [[f32; 4]; 3],
}

/// `vec4<u32>` words per [`Corner`] in the corner buffer.
pub(crate) const CORNER_WORDS: u32 = (std::mem::size_of::<Corner>() / 16) as u32;

/// Two normals closer than this (1 − cos) are one plane (a face split into triangles).
const SAME_PLANE: f32 = 1e-6;
/// Radii that differ by more than this share are not one corner (a variable fillet).
const RADIUS_TOLERANCE: f32 = 1e-3;
/// A kept edge that is no chamfer edge may meet a corner only where its faces turn by less than this
/// (cos 5°): a facet edge of a smooth surface (a faceted cylinder's side), which the rounding leaves
/// as it is to within a sliver.
const NEARLY_FLAT: f32 = 0.996_194_7;

/// The corners of an asset and, per edge end, the corner at its vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Corners {
    pub(crate) corners: Vec<Corner>,
    /// Per edge end (`2 * edge + k`), its corner's index + 1, or 0.
    pub(crate) ends: Vec<u32>,
}

impl Corners {
    /// Finds the rounded corners of `asset` (none without rings: the bake links ends by them).
    pub(crate) fn find(asset: &Asset) -> Self {
        let mut found = Self {
            corners: Vec::new(),
            ends: vec![0; 2 * asset.edge_count()],
        };
        if asset.next_ends.len() != found.ends.len() {
            return found;
        }
        let mut ring = Vec::new();
        for head in asset.cap_heads.iter() {
            ring.clear();
            let mut end = head;
            // Rings are validated on decode; the bound keeps a hand-built one from looping.
            while ring.len() < 4 {
                ring.push(end);
                end = asset.next_ends.get(end as usize);
                if end == head || end as usize >= found.ends.len() {
                    break;
                }
            }
            if end != head {
                continue;
            }
            if let Some(corner) = corner_at(asset, &ring) {
                found.corners.push(corner);
                let index = found.corners.len() as u32;
                for &end in &ring {
                    found.ends[end as usize] = index;
                }
            }
        }
        found
    }

    /// The GPU buffer's words: the count, the corners, then the ends four to a word.
    pub(crate) fn words(&self) -> Vec<[u32; 4]> {
        let mut words = vec![[self.corners.len() as u32, 0, 0, 0]];
        words.extend_from_slice(bytemuck::cast_slice(&self.corners));
        words.extend(self.ends.chunks(4).map(|c| {
            let mut word = [0; 4];
            word[..c.len()].copy_from_slice(c);
            word
        }));
        words
    }
}

/// The corner at the vertex whose kept edge ends are `ring`, if it is one.
fn corner_at(asset: &Asset, ring: &[u32]) -> Option<Corner> {
    if !(2..=3).contains(&ring.len()) {
        return None;
    }
    let position = |v: u32| Vec3::from(asset.topology_positions[v as usize]);
    let vertex = position(asset.end_vertex(ring[0]));
    let radius = ring
        .iter()
        .map(|&end| asset.edge_radius(end as usize / 2))
        .fold(0.0, f32::max);
    let mut planes: Vec<Vec3> = Vec::with_capacity(3);
    let mut edges = Vec::with_capacity(3);
    let mut shortest = f32::INFINITY;
    let mut chamfers = 0;
    for &end in ring {
        let e = end as usize / 2;
        let flags = asset.edge_flags(e);
        if flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD) {
            return None;
        }
        let [v0, v1, v2, v3] = asset.edge(e).map(position);
        let a = (v1 - v0).cross(v2 - v0).normalize_or_zero();
        let b = (v0 - v1).cross(v3 - v1).normalize_or_zero();
        let b = if flags.contains(EdgeFlags::FLIPPED) {
            -b
        } else {
            b
        };
        let r = asset.edge_radius(e);
        if flags.contains(EdgeFlags::CHAMFER) && r > 0.0 {
            if (r - radius).abs() > RADIUS_TOLERANCE * radius {
                return None;
            }
            chamfers += 1;
        } else if a.dot(b) < NEARLY_FLAT {
            // A sharp edge that is no chamfer: the solid is not rounded there.
            return None;
        }
        let far = if end % 2 == 0 { v1 } else { v0 };
        shortest = shortest.min(far.distance(vertex));
        let mut pair = [0; 2];
        for (slot, n) in pair.iter_mut().zip([a, b]) {
            if n == Vec3::ZERO {
                return None;
            }
            *slot = match planes.iter().position(|p| 1.0 - p.dot(n) < SAME_PLANE) {
                Some(k) => k,
                None if planes.len() < 3 => {
                    planes.push(n);
                    planes.len() - 1
                }
                None => return None,
            };
        }
        if flags.contains(EdgeFlags::CHAMFER) && r > 0.0 {
            edges.push((pair, far));
        }
    }
    if chamfers < 2 {
        return None;
    }
    let [n0, n1, n2] = <[Vec3; 3]>::try_from(planes).ok()?;
    // The centre c lies r inside every plane: n_k · (vertex − c) = r, so c = vertex − r w with
    // n_k · w = 1, w = Σ m_k for the dual basis m_k = (n_{k+1} × n_{k+2}) / det.
    let det = n0.dot(n1.cross(n2));
    if det.abs() < 1e-6 {
        return None;
    }
    let duals = [n1.cross(n2) / det, n2.cross(n0) / det, n0.cross(n1) / det];
    let w = duals[0] + duals[1] + duals[2];
    // Convex: vertex − c is a non-negative mix of the normals (w's coordinates in them, w · m_k ≥ 0).
    if duals.iter().any(|m| w.dot(*m) < -1e-4) {
        return None;
    }
    let center = vertex - radius * w;
    if !center.is_finite() {
        return None;
    }
    let normals = [n0, n1, n2];
    let mut far = [[0.0; 4]; 3];
    for (pair, end) in edges {
        // Pair k is planes (k, k + 1).
        let k = match (pair[0].min(pair[1]), pair[0].max(pair[1])) {
            (0, 1) => 0,
            (1, 2) => 1,
            (0, 2) => 2,
            _ => return None,
        };
        far[k] = end.extend(1.0).to_array();
    }
    let reach = radius * (w.length() + 2.0);
    let mut packed_normals = normals.map(|n| n.extend(0.0).to_array());
    packed_normals[0][3] = reach;
    Some(Corner {
        sphere: center.extend(radius).to_array(),
        vertex: vertex.extend(shortest).to_array(),
        normals: packed_normals,
        far,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::{Header, Indices, pack_attributes};

    /// One corner of the box [-1, 1]³, built by hand as the bake would write it: its vertex's ring
    /// of three edges (the real bakes are tested in tests/highlight.rs).
    fn box_corner(radius: [f32; 3], chamfer: [bool; 3]) -> Asset {
        // The corner (1, 1, 1) with its three edges along −x, −y, −z, and one face triangle per
        // side: x = 1, y = 1, z = 1.
        let positions = vec![
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, -1.0],
        ];
        // Edge (v0, v1, v2, v3): face a = (v0, v1, v2), face b = (v1, v0, v3), both outward.
        let edges = [[0, 1, 2, 3], [0, 2, 3, 1], [0, 3, 1, 2]];
        let scale = 1.0 / 1024.0;
        let attributes = (0..3)
            .map(|k| {
                let flags = if chamfer[k] {
                    EdgeFlags::RIDGE | EdgeFlags::CHAMFER
                } else {
                    EdgeFlags::RIDGE
                };
                pack_attributes(flags, radius[k], scale)
            })
            .collect();
        // The three v0 ends form one ring; the far ends are alone.
        let next = vec![2, 1, 4, 3, 0, 5];
        Asset {
            header: Header {
                radius_scale: scale,
                ..Header::default()
            },
            topology_positions: positions,
            edge_vertices: Indices::with_bound(edges.concat(), 4),
            edge_attributes: attributes,
            next_ends: Indices::with_bound(next, 6),
            cap_heads: Indices::with_bound(vec![0], 6),
            ..Asset::default()
        }
    }

    #[test]
    fn a_box_corner_is_a_sphere_r_inside_its_three_faces() {
        let corners = Corners::find(&box_corner([0.1; 3], [true; 3]));
        assert_eq!(corners.corners.len(), 1);
        assert_eq!(corners.ends, vec![1, 0, 1, 0, 1, 0]);
        let corner = corners.corners[0];
        let center = Vec3::from_slice(&corner.sphere);
        assert!(center.distance(Vec3::splat(0.9)) < 1e-3, "{center}");
        assert!((corner.sphere[3] - 0.1).abs() < 1e-4);
        // Every face plane is r from the centre.
        for n in corner.normals {
            let n = Vec3::from_slice(&n);
            assert!((n.dot(Vec3::ONE - center) - 0.1).abs() < 1e-4);
        }
        // Each pair has its edge's far end; cylinders are followed as far as the shortest edge.
        assert!(corner.far.iter().all(|f| f[3] == 1.0));
        assert_eq!(corner.vertex[3], 2.0);
        assert!((corner.normals[0][3] - 0.1 * (3f32.sqrt() + 2.0)).abs() < 1e-3);
    }

    #[test]
    fn a_sharp_edge_or_another_radius_at_the_vertex_leaves_the_strips_as_they_are() {
        let sharp = Corners::find(&box_corner([0.1; 3], [true, true, false]));
        assert!(sharp.corners.is_empty() && sharp.ends.iter().all(|&e| e == 0));
        let varied = Corners::find(&box_corner([0.1, 0.1, 0.2], [true; 3]));
        assert!(varied.corners.is_empty());
    }

    #[test]
    fn a_vertex_with_non_finite_positions_is_no_corner() {
        let mut asset = box_corner([0.1; 3], [true; 3]);
        asset.topology_positions[0] = [f32::NAN, 1.0, 1.0];
        assert!(Corners::find(&asset).corners.is_empty());
        let mut asset = box_corner([0.1; 3], [true; 3]);
        asset.topology_positions[1] = [f32::INFINITY, 1.0, 1.0];
        assert!(Corners::find(&asset).corners.is_empty());
    }

    #[test]
    fn the_buffer_holds_the_count_the_corners_and_the_ends() {
        let corners = Corners::find(&box_corner([0.1; 3], [true; 3]));
        let words = corners.words();
        assert_eq!(words[0][0], 1);
        assert_eq!(words.len(), 1 + CORNER_WORDS as usize + 2);
        assert_eq!(words[1 + CORNER_WORDS as usize], [1, 0, 1, 0]);
        assert_eq!(words[2 + CORNER_WORDS as usize], [1, 0, 0, 0]);
    }
}
