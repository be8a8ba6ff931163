//! Reading the sections of an animated asset ([`motion`](crate::asset::motion), format 6): every
//! length, index and number checked against the rig and the topology vertices.

use super::raw::length_error;
use crate::asset::motion::{Motion, WEIGHT_SUM_TOLERANCE};
use crate::asset::{DecodeError, SectionKind, envelope};
use crate::rig::INFLUENCES;

/// Reads and checks the motion sections of a file whose asset has `vertices` topology vertices;
/// `section` gives a section's bytes (empty for a kind the file's version lacks).
pub(super) fn read<'a>(
    section: &dyn Fn(SectionKind) -> &'a [u8],
    vertices: usize,
) -> Result<Motion, DecodeError> {
    let rig = envelope::decode_rig(section(SectionKind::Rig))?;
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
