//! Per-asset data some techniques need beyond the asset's sections, derived on the CPU when the asset
//! is uploaded with the matching [`AssetExtras`] (the default technique needs none of it).
//!
//! The asset links its two vertex sets only through positions: a render vertex sits exactly on its
//! topology vertex (the bake copies the position), so [`render_to_topology`] recovers the link by
//! position bits, and everything else here follows from it.

use std::collections::HashMap;

use glam::Vec3;

use crate::asset::{Asset, EdgeFlags, attribute_flags};

/// Which per-asset extras an upload derives; combine with `|`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct AssetExtras(pub u32);

impl AssetExtras {
    /// Nothing beyond what [`Technique::Joined`](super::Technique::Joined) needs.
    pub const NONE: Self = Self(0);
    /// One smooth (area-weighted) normal per topology vertex, shared by every edge at it: the
    /// `n0`, `n1` of McGuire–Hughes' edge mesh (thesis §8.1), and each render vertex's topology
    /// vertex (for the smooth inverted hull). 16 bytes per welded vertex, 4 per render vertex.
    pub const VERTEX_NORMALS: Self = Self(1);
    /// Per edge, the render vertices of each face's corners at `v0` and `v1`, so a fin can extrude
    /// along its own face's (crease-split) normals (seed 003). 16 bytes per edge.
    pub const FIN_CORNERS: Self = Self(2);
    /// Per triangle, which of its three edges are drawn feature edges (kept by the bake and not
    /// smooth), for the barycentric wireframe's feature-only mode (seed 001). 4 bytes per triangle.
    pub const TRIANGLE_EDGES: Self = Self(4);
    /// Everything.
    pub const ALL: Self = Self(7);

    /// The extras a pass over `bindings` reads.
    pub(crate) fn read_by(bindings: &super::bindings::Bindings) -> Self {
        use super::bindings::asset;
        [
            (asset::VERTEX_NORMALS, Self::VERTEX_NORMALS),
            (asset::RENDER_TO_TOPOLOGY, Self::VERTEX_NORMALS),
            (asset::FIN_CORNERS, Self::FIN_CORNERS),
            (asset::TRIANGLE_EDGES, Self::TRIANGLE_EDGES),
        ]
        .into_iter()
        .filter(|(binding, _)| bindings.contains(*binding))
        .fold(Self::NONE, |all, (_, extra)| all | extra)
    }

    /// True if every extra of `other` is in `self`.
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }
}

impl std::ops::BitOr for AssetExtras {
    type Output = Self;
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

/// No corner: the edge has no such face.
pub(crate) const NO_CORNER: u32 = u32::MAX;

/// The topology vertex each render vertex sits on; `None` if some render vertex sits on none (an
/// asset not made by the bake).
pub(crate) fn render_to_topology(asset: &Asset) -> Option<Vec<u32>> {
    let bits = |p: &[f32; 3]| p.map(f32::to_bits);
    let mut by_position: HashMap<[u32; 3], u32> =
        HashMap::with_capacity(asset.topology_positions.len());
    for (v, p) in asset.topology_positions.iter().enumerate() {
        by_position.entry(bits(p)).or_insert(v as u32);
    }
    asset
        .render_positions
        .iter()
        .map(|p| by_position.get(&bits(p)).copied())
        .collect()
}

/// The triangles in topology vertices.
fn topology_triangles(asset: &Asset, map: &[u32]) -> Vec<[u32; 3]> {
    let indices = &asset.mesh_indices;
    (0..indices.len() / 3)
        .map(|t| std::array::from_fn(|k| map[indices.get(3 * t + k) as usize]))
        .collect()
}

/// A smooth normal per topology vertex: the sum of its triangles' area-weighted normals,
/// normalized (zero where a vertex has no triangle), as `vec4`s for the GPU.
pub(crate) fn vertex_normals(asset: &Asset, map: &[u32]) -> Vec<[f32; 4]> {
    let mut sums = vec![Vec3::ZERO; asset.topology_positions.len()];
    let position = |v: u32| Vec3::from(asset.topology_positions[v as usize]);
    for [a, b, c] in topology_triangles(asset, map) {
        let n = (position(b) - position(a)).cross(position(c) - position(a));
        for v in [a, b, c] {
            sums[v as usize] += n;
        }
    }
    sums.into_iter()
        .map(|n| n.normalize_or_zero().extend(0.0).to_array())
        .collect()
}

/// Edge lookup by unordered vertex pair.
fn edge_index(asset: &Asset) -> HashMap<(u32, u32), u32> {
    let vertices = &asset.edge_vertices;
    (0..asset.edge_count())
        .map(|e| {
            let (a, b) = (vertices.get(4 * e), vertices.get(4 * e + 1));
            ((a.min(b), a.max(b)), e as u32)
        })
        .collect()
}

/// Per edge `[a0, a1, b0, b1]`: the render vertices at `v0` and `v1` of face `a` (`v0 v1 v2`) and
/// face `b` (`v1 v0 v3`), [`NO_CORNER`] where a face is missing.
pub(crate) fn fin_corners(asset: &Asset, map: &[u32]) -> Vec<[u32; 4]> {
    let edges = edge_index(asset);
    let vertices = &asset.edge_vertices;
    let mut corners = vec![[NO_CORNER; 4]; asset.edge_count()];
    let indices = &asset.mesh_indices;
    for (t, tri) in topology_triangles(asset, map).into_iter().enumerate() {
        for k in 0..3 {
            let (from, to, opposite) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let Some(&e) = edges.get(&(from.min(to), from.max(to))) else {
                continue; // a coplanar edge the bake dropped
            };
            let e = e as usize;
            let [v0, v2, v3] = [0, 2, 3].map(|i| vertices.get(4 * e + i));
            let render = |offset: usize| indices.get(3 * t + (k + offset) % 3);
            // Which face of the edge this triangle is, by its third vertex; the first two faces only.
            let (slot, at_v0) = if opposite == v2 && corners[e][0] == NO_CORNER {
                (0, from == v0)
            } else if opposite == v3 && corners[e][2] == NO_CORNER {
                (2, from == v0)
            } else {
                continue;
            };
            let (c0, c1) = if at_v0 {
                (render(0), render(1))
            } else {
                (render(1), render(0))
            };
            corners[e][slot] = c0;
            corners[e][slot + 1] = c1;
        }
    }
    corners
}

/// Per triangle, bit `k` set if its edge from corner `k` to corner `k + 1` is a feature edge: kept
/// by the bake with a class (boundary, crease, marked, material), not a smooth edge kept only as a
/// possible contour and not a coplanar edge the bake dropped.
pub(crate) fn triangle_edges(asset: &Asset, map: &[u32]) -> Vec<u32> {
    let edges = edge_index(asset);
    topology_triangles(asset, map)
        .into_iter()
        .map(|tri| {
            (0..3).fold(0, |mask, k| {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let feature = edges.get(&(a.min(b), a.max(b))).is_some_and(|&e| {
                    attribute_flags(asset.edge_attributes[e as usize]).intersects(EdgeFlags::STATIC)
                });
                mask | (u32::from(feature) << k)
            })
        })
        .collect()
}
