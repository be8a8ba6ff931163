//! The raw sections: plain little-endian arrays, read and checked as they are (every format
//! version), and the checks that need a whole asset.

use super::super::clusters::{self, CLUSTER_BYTES, EdgeCluster};
use super::super::{
    Asset, DecodeError, EdgeFlags, IndexWidth, Indices, MAX_RING, SectionKind, attribute_flags,
};

/// Bytes of one intersection segment: two `[f32; 3]` end points.
const SEGMENT_BYTES: usize = 24;

/// The stored next ends and cap heads (of `ends` edge ends).
pub(super) fn raw_rings(
    next_bytes: &[u8],
    head_bytes: &[u8],
    ends: usize,
) -> Result<(Indices, Indices), DecodeError> {
    let next_ends = read_indices(SectionKind::NextEnds, next_bytes, ends, 1)?;
    if !next_ends.is_empty() && next_ends.len() != ends {
        return Err(length_error(
            SectionKind::NextEnds,
            format!(
                "{} entries for {} edge ends (must be 0 or one per end)",
                next_ends.len(),
                ends
            ),
        ));
    }
    let cap_heads = read_indices(SectionKind::CapHeads, head_bytes, ends, 1)?;
    // A head is where the walk around its vertex's ring starts: without rings it means nothing.
    if next_ends.is_empty() && !cap_heads.is_empty() {
        return Err(length_error(
            SectionKind::CapHeads,
            format!(
                "{} cap heads but no next ends (the runtime walks a head's ring)",
                cap_heads.len()
            ),
        ));
    }
    Ok((next_ends, cap_heads))
}

/// Decoded indices that must be below `bound`.
pub(super) fn checked_indices(
    kind: SectionKind,
    values: Vec<u32>,
    bound: usize,
) -> Result<Indices, DecodeError> {
    if let Some((position, &value)) = values
        .iter()
        .enumerate()
        .find(|&(_, &v)| v as usize >= bound)
    {
        return Err(DecodeError::IndexOutOfRange {
            kind,
            position: position as u64,
            value,
            bound: bound as u64,
        });
    }
    Ok(Indices::with_bound(values, bound))
}

/// The render positions: the stored ones, one per normal, or, when the file has render vertex
/// counts instead (one per topology vertex, summing to the number of normals), the topology
/// positions repeated as the counts say.
pub(super) fn read_render_positions(
    stored: &[u8],
    counts: &[u8],
    topology_positions: &[[f32; 3]],
    render_vertices: usize,
) -> Result<Vec<[f32; 3]>, DecodeError> {
    if counts.is_empty() {
        let positions = read_vec3s(SectionKind::RenderPositions, stored)?;
        if positions.len() != render_vertices {
            return Err(length_error(
                SectionKind::RenderNormals,
                format!(
                    "{render_vertices} normals for {} render vertices",
                    positions.len()
                ),
            ));
        }
        return Ok(positions);
    }
    if !stored.is_empty() {
        return Err(length_error(
            SectionKind::RenderVertexCounts,
            format!(
                "present beside {} bytes of render positions (a file holds one or the other)",
                stored.len()
            ),
        ));
    }
    if counts.len() != topology_positions.len() {
        return Err(length_error(
            SectionKind::RenderVertexCounts,
            format!(
                "{} counts for {} topology vertices",
                counts.len(),
                topology_positions.len()
            ),
        ));
    }
    let total: usize = counts.iter().map(|&c| usize::from(c)).sum();
    if total != render_vertices {
        return Err(length_error(
            SectionKind::RenderVertexCounts,
            format!("counts sum to {total} render vertices, the normals to {render_vertices}"),
        ));
    }
    let mut positions = Vec::with_capacity(total);
    for (p, &count) in topology_positions.iter().zip(counts) {
        positions.extend(std::iter::repeat_n(*p, usize::from(count)));
    }
    Ok(positions)
}

pub(super) fn length_error(kind: SectionKind, reason: String) -> DecodeError {
    DecodeError::BadSectionLength { kind, reason }
}

pub(super) fn read_u32s(kind: SectionKind, bytes: &[u8]) -> Result<Vec<u32>, DecodeError> {
    if !bytes.len().is_multiple_of(4) {
        return Err(length_error(
            kind,
            format!("{} bytes is not a whole number of u32", bytes.len()),
        ));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect())
}

pub(super) fn read_vec3s(kind: SectionKind, bytes: &[u8]) -> Result<Vec<[f32; 3]>, DecodeError> {
    if !bytes.len().is_multiple_of(12) {
        return Err(length_error(
            kind,
            format!("{} bytes is not a whole number of 3 × f32", bytes.len()),
        ));
    }
    let values: Vec<[f32; 3]> = bytes
        .chunks_exact(12)
        .map(|c| {
            std::array::from_fn(|k| {
                f32::from_le_bytes([c[4 * k], c[4 * k + 1], c[4 * k + 2], c[4 * k + 3]])
            })
        })
        .collect();
    if let Some(position) = values.iter().position(|v| !v.iter().all(|x| x.is_finite())) {
        return Err(DecodeError::NonFinite {
            kind,
            position: position as u64,
        });
    }
    Ok(values)
}

pub(super) fn read_segments(bytes: &[u8]) -> Result<Vec<[[f32; 3]; 2]>, DecodeError> {
    let kind = SectionKind::IntersectionSegments;
    if !bytes.len().is_multiple_of(SEGMENT_BYTES) {
        return Err(length_error(
            kind,
            format!("{} bytes is not a whole number of 2 × 3 × f32", bytes.len()),
        ));
    }
    let points = read_vec3s(kind, bytes)?;
    Ok(points.chunks_exact(2).map(|p| [p[0], p[1]]).collect())
}

/// Reads the clusters of an asset of `edges` edges: one per 64, finite, radii non-negative, cosines
/// within [-1, 1] and only known flag bits.
pub(super) fn read_clusters(bytes: &[u8], edges: usize) -> Result<Vec<EdgeCluster>, DecodeError> {
    let kind = SectionKind::EdgeClusters;
    let expected = clusters::cluster_count(edges);
    if bytes.len() != expected * CLUSTER_BYTES {
        return Err(length_error(
            kind,
            format!(
                "{} bytes for {edges} edges (must be {expected} clusters of {CLUSTER_BYTES} bytes)",
                bytes.len()
            ),
        ));
    }
    let words = read_u32s(kind, bytes)?;
    let clusters: Vec<EdgeCluster> = words
        .chunks_exact(CLUSTER_BYTES / 4)
        .map(|c| bytemuck::pod_read_unaligned(bytemuck::cast_slice(c)))
        .collect();
    for (position, c) in clusters.iter().enumerate() {
        let invalid = |reason: &str| DecodeError::Invalid {
            kind,
            position: position as u64,
            reason: reason.to_owned(),
        };
        let numbers = c
            .center
            .iter()
            .chain(&c.axis)
            .chain([&c.radius, &c.cos_angle]);
        if !numbers.into_iter().all(|v| v.is_finite()) {
            return Err(DecodeError::NonFinite {
                kind,
                position: position as u64,
            });
        }
        if c.radius < 0.0 || !(-1.0..=1.0).contains(&c.cos_angle) {
            return Err(invalid(
                "radius must be non-negative and the cone's cosine within [-1, 1]",
            ));
        }
        if c.flags & !u32::from(EdgeFlags::ALL.0) != 0 {
            return Err(invalid("unknown flag bits"));
        }
    }
    Ok(clusters)
}

/// Reads an index section whose values must be below `bound`, in groups of `group`.
pub(super) fn read_indices(
    kind: SectionKind,
    bytes: &[u8],
    bound: usize,
    group: usize,
) -> Result<Indices, DecodeError> {
    let width = IndexWidth::for_bound(bound);
    let stride = width.bytes() * group;
    if !bytes.len().is_multiple_of(stride) {
        return Err(length_error(
            kind,
            format!(
                "{} bytes is not a whole number of groups of {group} {}-bit indices",
                bytes.len(),
                8 * width.bytes()
            ),
        ));
    }
    let indices = match width {
        IndexWidth::U16 => Indices::U16(
            bytes
                .chunks_exact(2)
                .map(|c| u16::from_le_bytes([c[0], c[1]]))
                .collect(),
        ),
        IndexWidth::U32 => Indices::U32(read_u32s(kind, bytes)?),
    };
    if let Some((position, value)) = indices
        .iter()
        .enumerate()
        .find(|&(_, v)| v as usize >= bound)
    {
        return Err(DecodeError::IndexOutOfRange {
            kind,
            position: position as u64,
            value,
            bound: bound as u64,
        });
    }
    Ok(indices)
}

/// Only known flag bits, and radii finite and non-negative.
pub(super) fn validate_attributes(words: &[u32], kind: SectionKind) -> Result<(), DecodeError> {
    for (position, &word) in words.iter().enumerate() {
        let flags = attribute_flags(word);
        let invalid = |reason: String| DecodeError::Invalid {
            kind,
            position: position as u64,
            reason,
        };
        if flags.0 & !EdgeFlags::ALL.0 != 0 {
            return Err(invalid(format!(
                "unknown flag bits {:#06x}",
                flags.0 & !EdgeFlags::ALL.0
            )));
        }
        let radius = half::f16::from_bits((word >> 16) as u16);
        if !radius.is_finite() || radius.is_sign_negative() && radius.to_f32() != 0.0 {
            return Err(invalid(format!(
                "radius {radius} is not finite and non-negative"
            )));
        }
    }
    Ok(())
}

/// No vertex may have more kept edge ends than the join walk follows ([`MAX_RING`]), whether or
/// not the asset carries rings: the cap-buffer walk has the same bound.
pub(super) fn validate_ring_lengths(asset: &Asset) -> Result<(), DecodeError> {
    let mut ends = vec![0u32; asset.topology_positions.len()];
    for end in 0..2 * asset.edge_count() as u32 {
        let vertex = asset.end_vertex(end);
        let count = &mut ends[vertex as usize];
        *count += 1;
        if *count > MAX_RING {
            let total = (0..2 * asset.edge_count() as u32)
                .filter(|&e| asset.end_vertex(e) == vertex)
                .count();
            return Err(DecodeError::RingTooLong {
                vertex,
                ends: total as u64,
                limit: MAX_RING,
            });
        }
    }
    Ok(())
}

/// Every next-index ring must stay at one vertex and be a permutation, so walks always return.
pub(super) fn validate_rings(asset: &Asset) -> Result<(), DecodeError> {
    let kind = SectionKind::NextEnds;
    let mut seen = vec![false; asset.next_ends.len()];
    for (end, next) in asset.next_ends.iter().enumerate() {
        let invalid = |reason: String| DecodeError::Invalid {
            kind,
            position: end as u64,
            reason,
        };
        if asset.end_vertex(next) != asset.end_vertex(end as u32) {
            return Err(invalid(format!("next end {next} is at another vertex")));
        }
        if std::mem::replace(&mut seen[next as usize], true) {
            return Err(invalid(format!(
                "end {next} is the next of two ends (rings must be cycles)"
            )));
        }
    }
    Ok(())
}

/// Polyline starts must begin at 0, increase strictly and stay below the segment count; within a
/// polyline each segment must start exactly where the previous one ends, and no segment is a point.
pub(super) fn validate_intersections(
    segments: &[[[f32; 3]; 2]],
    starts: &[u32],
) -> Result<(), DecodeError> {
    let kind = SectionKind::IntersectionPolylines;
    if segments.is_empty() != starts.is_empty() {
        return Err(length_error(
            kind,
            format!(
                "{} polylines for {} segments (both or neither must be empty)",
                starts.len(),
                segments.len()
            ),
        ));
    }
    for (position, &start) in starts.iter().enumerate() {
        let previous = if position == 0 {
            None
        } else {
            Some(starts[position - 1])
        };
        let ok = match previous {
            None => start == 0,
            Some(p) => start > p && (start as usize) < segments.len(),
        };
        if !ok {
            return Err(DecodeError::Invalid {
                kind,
                position: position as u64,
                reason: format!(
                    "polyline start {start} must be 0 for the first polyline and then increase, below {}",
                    segments.len()
                ),
            });
        }
    }
    let kind = SectionKind::IntersectionSegments;
    let invalid = |position: usize, reason: &str| DecodeError::Invalid {
        kind,
        position: position as u64,
        reason: reason.to_owned(),
    };
    let bits = |p: &[f32; 3]| p.map(f32::to_bits);
    for (position, segment) in segments.iter().enumerate() {
        if segment[0] == segment[1] {
            return Err(invalid(position, "segment has zero length"));
        }
    }
    // Every segment but the first of each polyline continues the one before it.
    let mut polyline_starts = starts.iter().skip(1).peekable();
    for position in 1..segments.len() {
        if polyline_starts
            .next_if(|&&s| s as usize == position)
            .is_some()
        {
            continue;
        }
        if bits(&segments[position - 1][1]) != bits(&segments[position][0]) {
            return Err(invalid(
                position,
                "segment does not start where the previous segment of its polyline ends",
            ));
        }
    }
    Ok(())
}
