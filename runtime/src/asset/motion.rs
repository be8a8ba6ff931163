//! The sections of an animated asset (format 6, issue 41): each topology vertex's joints and
//! weights, the morph targets' position deltas, and the [`Rig`] that poses them.
//!
//! | section | element | count |
//! |---|---|---|
//! | [`SkinJoints`](SectionKind::SkinJoints) | `[u16; 4]` joint < J | V, or empty |
//! | [`SkinWeights`](SectionKind::SkinWeights) | `[f32; 4]`, ≥ 0, summing to 1 (or all 0: not skinned) | V, or empty (with the joints) |
//! | [`MorphStarts`](SectionKind::MorphStarts) | `u32` first delta of each target, from 0, non-decreasing | M targets |
//! | [`MorphVertices`](SectionKind::MorphVertices) | `u32` topology vertex, increasing within a target | D deltas |
//! | [`MorphDeltas`](SectionKind::MorphDeltas) | `[f32; 3]` position delta | D |
//! | [`Rig`](SectionKind::Rig) | [`Rig`], bincode 2 like the header | one, or empty |
//!
//! Morph targets are sparse: a target lists only the vertices it moves. Render vertices copy their
//! topology vertex's position, so they are posed through it; their normals are turned by the
//! same joints (the morph targets' normal deltas are not kept: the bake computes its own normals).

use glam::{Mat4, Vec3};

use super::SectionKind;
use crate::rig::{INFLUENCES, Pose, Rig};

/// How far a vertex's weights may sum from 1 (the bake normalizes them in f32).
pub const WEIGHT_SUM_TOLERANCE: f32 = 1e-3;

/// The per-vertex data that moves an asset, and its rig; empty for a still asset.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Motion {
    /// Per topology vertex, the joints of [`Rig::joints`] it follows; empty if nothing is skinned.
    pub joints: Vec<[u16; INFLUENCES]>,
    /// Per topology vertex, how much it follows each of its joints.
    pub weights: Vec<[f32; INFLUENCES]>,
    /// Per morph target, the index of its first entry in `morph_vertices`.
    pub morph_starts: Vec<u32>,
    /// The topology vertex each morph entry moves.
    pub morph_vertices: Vec<u32>,
    /// How far each morph entry moves its vertex at weight 1.
    pub morph_deltas: Vec<[f32; 3]>,
    /// Nodes, joints, morph weights and animations.
    pub rig: Rig,
}

impl Motion {
    /// True for a still asset.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty() && self.morph_starts.is_empty() && self.rig.is_empty()
    }

    /// Whether the vertices have joints.
    pub fn is_skinned(&self) -> bool {
        !self.joints.is_empty()
    }

    /// The entries of morph target `target`: (vertices, deltas).
    pub fn morph_target(&self, target: usize) -> (&[u32], &[[f32; 3]]) {
        let start = self.morph_starts[target] as usize;
        let end = self
            .morph_starts
            .get(target + 1)
            .map_or(self.morph_vertices.len(), |&s| s as usize);
        (
            &self.morph_vertices[start..end],
            &self.morph_deltas[start..end],
        )
    }

    /// `positions` (the asset's topology positions) in `pose`: morph targets first, then the skin.
    ///
    /// The CPU's answer to what the runtime's posing pass computes, in f32.
    /// Contract: the motion belongs to the asset whose positions these are (decoding checks it),
    /// and `pose` has a matrix per joint and a weight per morph target.
    pub fn pose_positions(&self, positions: &[[f32; 3]], pose: &Pose) -> Vec<[f32; 3]> {
        let mut posed: Vec<Vec3> = positions.iter().map(|&p| Vec3::from(p)).collect();
        for (target, &weight) in pose.weights.iter().enumerate() {
            if weight == 0.0 {
                continue;
            }
            let (vertices, deltas) = self.morph_target(target);
            for (&v, &d) in vertices.iter().zip(deltas) {
                posed[v as usize] += weight * Vec3::from(d);
            }
        }
        if self.is_skinned() {
            for (p, (joints, weights)) in
                posed.iter_mut().zip(self.joints.iter().zip(&self.weights))
            {
                *p = skinned(*p, joints, weights, &pose.joints);
            }
        }
        posed.iter().map(Vec3::to_array).collect()
    }

    /// The bytes of one of this module's sections as held in memory (the rig is encoded by the
    /// asset's envelope, not here).
    pub(super) fn section_bytes(&self, kind: SectionKind) -> &[u8] {
        match kind {
            SectionKind::SkinJoints => bytemuck::cast_slice(&self.joints),
            SectionKind::SkinWeights => bytemuck::cast_slice(&self.weights),
            SectionKind::MorphStarts => bytemuck::cast_slice(&self.morph_starts),
            SectionKind::MorphVertices => bytemuck::cast_slice(&self.morph_vertices),
            SectionKind::MorphDeltas => bytemuck::cast_slice(&self.morph_deltas),
            _ => &[],
        }
    }
}

/// `p` moved by its joints: `Σ wᵢ · Jᵢ · p`, or `p` itself when all weights are 0.
fn skinned(
    p: Vec3,
    joints: &[u16; INFLUENCES],
    weights: &[f32; INFLUENCES],
    matrices: &[Mat4],
) -> Vec3 {
    if weights.iter().all(|&w| w == 0.0) {
        return p;
    }
    let mut sum = Vec3::ZERO;
    for (&j, &w) in joints.iter().zip(weights) {
        if w != 0.0 {
            sum += w * matrices[usize::from(j)].transform_point3(p);
        }
    }
    sum
}
