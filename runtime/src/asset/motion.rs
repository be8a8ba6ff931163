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

use super::{DecodeError, SectionKind};
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

/// Reads and checks the motion sections of a file whose asset has `vertices` topology vertices;
/// `section` gives a section's bytes (empty for a kind the file's version lacks).
pub(super) fn read<'a>(
    section: &dyn Fn(SectionKind) -> &'a [u8],
    vertices: usize,
) -> Result<Motion, DecodeError> {
    let rig = super::envelope::decode_rig(section(SectionKind::Rig))?;
    rig.validate().map_err(|reason| DecodeError::Invalid {
        kind: SectionKind::Rig,
        position: 0,
        reason,
    })?;
    let joints: Vec<[u16; INFLUENCES]> =
        elements(section(SectionKind::SkinJoints), SectionKind::SkinJoints)?;
    let weights: Vec<[f32; INFLUENCES]> =
        elements(section(SectionKind::SkinWeights), SectionKind::SkinWeights)?;
    check_skin(&joints, &weights, vertices, rig.joints.len())?;

    let morph_starts: Vec<u32> =
        elements(section(SectionKind::MorphStarts), SectionKind::MorphStarts)?;
    let morph_vertices: Vec<u32> = elements(
        section(SectionKind::MorphVertices),
        SectionKind::MorphVertices,
    )?;
    let morph_deltas: Vec<[f32; 3]> =
        elements(section(SectionKind::MorphDeltas), SectionKind::MorphDeltas)?;
    let motion = Motion {
        joints,
        weights,
        morph_starts,
        morph_vertices,
        morph_deltas,
        rig,
    };
    check_morphs(&motion, vertices)?;
    Ok(motion)
}

/// A section as an array of plain elements, its length a whole number of them.
fn elements<T: bytemuck::Pod>(bytes: &[u8], kind: SectionKind) -> Result<Vec<T>, DecodeError> {
    let size = std::mem::size_of::<T>();
    if !bytes.len().is_multiple_of(size) {
        return Err(length_error(
            kind,
            format!(
                "{} bytes is not a whole number of {size}-byte elements",
                bytes.len()
            ),
        ));
    }
    // Copied element by element: the file's bytes need not be aligned for `T`.
    Ok(bytes
        .chunks_exact(size)
        .map(bytemuck::pod_read_unaligned)
        .collect())
}

fn length_error(kind: SectionKind, reason: String) -> DecodeError {
    DecodeError::BadSectionLength { kind, reason }
}

fn invalid(kind: SectionKind, position: usize, reason: String) -> DecodeError {
    DecodeError::Invalid {
        kind,
        position: position as u64,
        reason,
    }
}

/// Joints and weights: both or neither, one per topology vertex, joints in range, weights finite,
/// non-negative and summing to 1 (or all 0).
fn check_skin(
    joints: &[[u16; INFLUENCES]],
    weights: &[[f32; INFLUENCES]],
    vertices: usize,
    rig_joints: usize,
) -> Result<(), DecodeError> {
    if joints.is_empty() && weights.is_empty() {
        return Ok(());
    }
    for (kind, len) in [
        (SectionKind::SkinJoints, joints.len()),
        (SectionKind::SkinWeights, weights.len()),
    ] {
        if len != vertices {
            return Err(length_error(
                kind,
                format!("{len} entries for {vertices} topology vertices"),
            ));
        }
    }
    if let Some(v) = joints
        .iter()
        .position(|j| j.iter().any(|&j| usize::from(j) >= rig_joints))
    {
        return Err(DecodeError::IndexOutOfRange {
            kind: SectionKind::SkinJoints,
            position: v as u64,
            value: u32::from(*joints[v].iter().max().unwrap_or(&0)),
            bound: rig_joints as u64,
        });
    }
    for (v, w) in weights.iter().enumerate() {
        if !w.iter().all(|x| x.is_finite()) {
            return Err(DecodeError::NonFinite {
                kind: SectionKind::SkinWeights,
                position: v as u64,
            });
        }
        if w.iter().any(|&x| x < 0.0) {
            return Err(invalid(
                SectionKind::SkinWeights,
                v,
                format!("negative weight in {w:?}"),
            ));
        }
        let sum: f32 = w.iter().sum();
        if sum != 0.0 && (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE {
            return Err(invalid(
                SectionKind::SkinWeights,
                v,
                format!("weights sum to {sum}, not 1"),
            ));
        }
    }
    Ok(())
}

/// Morph targets: one start per rig weight, from 0 and non-decreasing; as many deltas as vertices,
/// each vertex in range and increasing within its target.
fn check_morphs(motion: &Motion, vertices: usize) -> Result<(), DecodeError> {
    let starts = &motion.morph_starts;
    let targets = motion.rig.morph_weights.len();
    if starts.len() != targets {
        return Err(length_error(
            SectionKind::MorphStarts,
            format!(
                "{} targets, the rig has {targets} morph weights",
                starts.len()
            ),
        ));
    }
    let entries = motion.morph_vertices.len();
    if motion.morph_deltas.len() != entries {
        return Err(length_error(
            SectionKind::MorphDeltas,
            format!(
                "{} deltas for {entries} morph vertices",
                motion.morph_deltas.len()
            ),
        ));
    }
    if let Some(&first) = starts.first()
        && first != 0
    {
        return Err(invalid(
            SectionKind::MorphStarts,
            0,
            format!("the first target starts at {first}, not 0"),
        ));
    }
    if let Some(t) = (0..starts.len()).find(|&t| {
        let end = starts.get(t + 1).map_or(entries as u64, |&s| u64::from(s));
        end < u64::from(starts[t]) || end > entries as u64
    }) {
        return Err(invalid(
            SectionKind::MorphStarts,
            t,
            format!("target {t}'s entries do not lie in order within the {entries} entries"),
        ));
    }
    if let Some(d) = motion
        .morph_deltas
        .iter()
        .position(|d| !d.iter().all(|x| x.is_finite()))
    {
        return Err(DecodeError::NonFinite {
            kind: SectionKind::MorphDeltas,
            position: d as u64,
        });
    }
    for (t, &start) in starts.iter().enumerate() {
        let start = start as usize;
        let (list, _) = motion.morph_target(t);
        if let Some(i) = list.iter().position(|&v| v as usize >= vertices) {
            return Err(DecodeError::IndexOutOfRange {
                kind: SectionKind::MorphVertices,
                position: (start + i) as u64,
                value: list[i],
                bound: vertices as u64,
            });
        }
        if let Some(i) = list.windows(2).position(|w| w[1] <= w[0]) {
            return Err(invalid(
                SectionKind::MorphVertices,
                start + i + 1,
                format!("target {t} lists vertex {} after {}", list[i + 1], list[i]),
            ));
        }
    }
    Ok(())
}
