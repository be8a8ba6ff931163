//! Reading an asset: every length, index and float is checked before anything is trusted.

use super::clusters::{self, CLUSTER_BYTES, EdgeCluster};
use super::compact;
use super::{
    Asset, DecodeError, EdgeFlags, FORMAT_VERSION, Header, IndexWidth, Indices, MAGIC,
    MAX_HEADER_BYTES, MAX_RING, SECTION_ALIGN, SectionKind, attribute_flags, envelope,
};

/// Bytes of one intersection segment: two `[f32; 3]` end points.
const SEGMENT_BYTES: usize = 24;

impl Asset {
    /// Decodes and validates an asset.
    ///
    /// Reads format versions 1 to 4 (a version-1 file has no intersection edges; the clusters of a
    /// version-1 or 2 file are computed here; a version-4 file's render positions may be derived
    /// from its topology positions and render vertex counts).
    /// Rejects, with a typed error: bad magic, another format version, a header or section table
    /// that does not fit the file, sections whose lengths disagree with each other, indices out of
    /// range, non-finite floats, unknown flag bits, next-index rings that are not closed, cap heads
    /// without rings, vertices with more kept edge ends than [`MAX_RING`] and intersection
    /// polylines that are not chained, and clusters that are not one per 64 edges or whose numbers
    /// are not finite, non-negative radii and cosines within [-1, 1].
    /// Allocates at most about twice the input's size. Never panics.
    pub fn decode(bytes: &[u8]) -> Result<Asset, DecodeError> {
        let (header, kinds) = read_header(bytes)?;
        let ranges = section_ranges(&header, kinds, bytes.len() as u64)?;
        // A section the file's version does not have is empty.
        let section = |kind: SectionKind| match &ranges[kind as usize - 1] {
            Some(range) => &bytes[range.clone()],
            None => &[],
        };
        for (raw, coded) in TWINS {
            if !section(raw).is_empty() && !section(coded).is_empty() {
                return Err(length_error(
                    coded,
                    format!(
                        "present beside {} (a file holds one or the other)",
                        raw.name()
                    ),
                ));
            }
        }
        let coded = |kind: SectionKind| Some(section(kind)).filter(|s| !s.is_empty());

        let coded_triangles = coded(SectionKind::MeshIndicesCoded)
            .map(compact::Reader::mesh_indices)
            .transpose()?;
        let triangle_bound = coded_triangles
            .as_ref()
            .map_or(section(SectionKind::MeshIndices).len() / 2, Vec::len);
        let reader = compact::Reader {
            limit: triangle_bound.max(1 << 16),
        };
        let counts = match coded(SectionKind::RenderVertexCountsCoded) {
            Some(bytes) => reader.counts(bytes)?,
            None => section(SectionKind::RenderVertexCounts).to_vec(),
        };
        let topology_positions = match coded(SectionKind::TopologyPositionsCoded) {
            Some(bytes) => reader.positions(bytes)?,
            None => read_vec3s(
                SectionKind::TopologyPositions,
                section(SectionKind::TopologyPositions),
            )?,
        };
        let render_normals = match coded(SectionKind::RenderNormalsCoded) {
            Some(bytes) => reader.normals(bytes)?,
            None => read_vec3s(
                SectionKind::RenderNormals,
                section(SectionKind::RenderNormals),
            )?,
        };
        let render_vertices = render_normals.len();
        let render_positions = read_render_positions(
            section(SectionKind::RenderPositions),
            &counts,
            &topology_positions,
            render_vertices,
        )?;
        let mesh_indices = match coded_triangles {
            Some(values) => {
                checked_indices(SectionKind::MeshIndicesCoded, values, render_vertices)?
            }
            None => read_indices(
                SectionKind::MeshIndices,
                section(SectionKind::MeshIndices),
                render_vertices,
                3,
            )?,
        };
        let edge_attributes = match coded(SectionKind::EdgeAttributesCoded) {
            Some(bytes) => reader.words(SectionKind::EdgeAttributesCoded, bytes)?,
            None => read_u32s(
                SectionKind::EdgeAttributes,
                section(SectionKind::EdgeAttributes),
            )?,
        };
        let edges = edge_attributes.len();
        let edge_vertices = match coded(SectionKind::EdgeCorners) {
            Some(bytes) => {
                if counts.is_empty() {
                    return Err(length_error(
                        SectionKind::EdgeCorners,
                        "present without render vertex counts (the corners' vertices come from them)".into(),
                    ));
                }
                let topology = compact::topology_of(&mesh_indices.to_u32_vec(), &counts);
                let values = reader.edges(bytes, &topology, topology_positions.len())?;
                Indices::with_bound(values, topology_positions.len())
            }
            None => read_indices(
                SectionKind::EdgeVertices,
                section(SectionKind::EdgeVertices),
                topology_positions.len(),
                4,
            )?,
        };
        if edge_vertices.len() != 4 * edges {
            return Err(length_error(
                SectionKind::EdgeVertices,
                format!(
                    "{} indices for {} edges (4 per edge)",
                    edge_vertices.len(),
                    edges
                ),
            ));
        }
        let ends = 2 * edges;
        let rings_coded = coded(SectionKind::RingOrders);
        let (next_ends, cap_heads) = match rings_coded {
            Some(bytes) => {
                let (next, heads) = compact::Reader::rings(
                    bytes,
                    &edge_vertices.to_u32_vec(),
                    topology_positions.len(),
                )?;
                (
                    Indices::with_bound(next, ends),
                    Indices::with_bound(heads, ends),
                )
            }
            None => raw_rings(&section, ends)?,
        };

        let intersection_segments = read_segments(section(SectionKind::IntersectionSegments))?;
        let intersection_starts = read_u32s(
            SectionKind::IntersectionPolylines,
            section(SectionKind::IntersectionPolylines),
        )?;

        // Format 5 may leave the clusters to the loader; earlier formats store them from version 3.
        let clusters = section(SectionKind::EdgeClusters);
        let stored_clusters = (ranges[SectionKind::EdgeClusters as usize - 1].is_some()
            && (!clusters.is_empty() || kinds.len() < SectionKind::ALL.len()))
        .then(|| read_clusters(clusters, edges))
        .transpose()?;

        let mut asset = Asset {
            header,
            render_positions,
            render_normals,
            mesh_indices,
            topology_positions,
            edge_vertices,
            edge_attributes,
            next_ends,
            cap_heads,
            intersection_segments,
            intersection_starts,
            edge_clusters: Vec::new(),
        };
        validate_attributes(&asset)?;
        // Rings decoded from their orders are cycles within bounds by construction.
        if rings_coded.is_none() {
            validate_ring_lengths(&asset)?;
            validate_rings(&asset)?;
        }
        validate_intersections(&asset)?;
        asset.edge_clusters = stored_clusters.unwrap_or_else(|| clusters::edge_clusters(&asset));
        Ok(asset)
    }
}

/// Each raw section and the coded one that can replace it (format 5).
const TWINS: [(SectionKind, SectionKind); 8] = [
    (SectionKind::MeshIndices, SectionKind::MeshIndicesCoded),
    (
        SectionKind::TopologyPositions,
        SectionKind::TopologyPositionsCoded,
    ),
    (SectionKind::RenderNormals, SectionKind::RenderNormalsCoded),
    (SectionKind::EdgeVertices, SectionKind::EdgeCorners),
    (
        SectionKind::EdgeAttributes,
        SectionKind::EdgeAttributesCoded,
    ),
    (SectionKind::NextEnds, SectionKind::RingOrders),
    (SectionKind::CapHeads, SectionKind::RingOrders),
    (
        SectionKind::RenderVertexCounts,
        SectionKind::RenderVertexCountsCoded,
    ),
];

/// The stored next ends and cap heads (of `ends` edge ends).
fn raw_rings<'a>(
    section: &impl Fn(SectionKind) -> &'a [u8],
    ends: usize,
) -> Result<(Indices, Indices), DecodeError> {
    let next_ends = read_indices(
        SectionKind::NextEnds,
        section(SectionKind::NextEnds),
        ends,
        1,
    )?;
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
    let cap_heads = read_indices(
        SectionKind::CapHeads,
        section(SectionKind::CapHeads),
        ends,
        1,
    )?;
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
fn checked_indices(
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
fn read_render_positions(
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

/// The header and the section kinds of the file's version.
fn read_header(bytes: &[u8]) -> Result<(Header, &'static [SectionKind]), DecodeError> {
    let available = bytes.len() as u64;
    let preamble = bytes.get(..16).ok_or(DecodeError::Truncated {
        what: "preamble",
        needed: 16,
        available,
    })?;
    if preamble[..8] != MAGIC {
        return Err(DecodeError::BadMagic);
    }
    let word = |at: usize| {
        u32::from_le_bytes([
            preamble[at],
            preamble[at + 1],
            preamble[at + 2],
            preamble[at + 3],
        ])
    };
    let version = word(8);
    let kinds = SectionKind::of_version(version).ok_or(DecodeError::UnsupportedVersion {
        found: version,
        supported: FORMAT_VERSION,
    })?;
    let header_len = word(12);
    if header_len > MAX_HEADER_BYTES {
        return Err(DecodeError::BadHeader(format!(
            "header length {header_len} exceeds the limit of {MAX_HEADER_BYTES} bytes"
        )));
    }
    let end = 16 + header_len as usize;
    let header_bytes = bytes.get(16..end).ok_or(DecodeError::Truncated {
        what: "header",
        needed: end as u64,
        available,
    })?;
    let header = envelope::decode_header(header_bytes)?;
    let finite = header
        .bounds_min
        .iter()
        .chain(&header.bounds_max)
        .all(|v| v.is_finite());
    let chamfer = header.stats.chamfer;
    let radii_ok = [header.radius_scale, chamfer.radius_min, chamfer.radius_max]
        .iter()
        .all(|r| r.is_finite() && *r >= 0.0);
    if !finite || !radii_ok {
        return Err(DecodeError::BadHeader(
            "bounds or radii not finite and non-negative".into(),
        ));
    }
    Ok((header, kinds))
}

/// The byte range of every section, indexed by `kind - 1`: one for each of `kinds` (the file's
/// version's), `None` for the kinds of later versions.
fn section_ranges(
    header: &Header,
    kinds: &[SectionKind],
    file_len: u64,
) -> Result<Vec<Option<std::ops::Range<usize>>>, DecodeError> {
    let header_end = 16 + envelope_len(header);
    let mut ranges = vec![None; SectionKind::ALL.len()];
    let mut previous_end = header_end;
    for entry in &header.sections {
        let kind = SectionKind::from_u32(entry.kind)
            .filter(|k| kinds.contains(k))
            .ok_or_else(|| {
                DecodeError::BadSectionTable(format!(
                    "unknown section kind {} for this format version",
                    entry.kind
                ))
            })?;
        if entry.offset % SECTION_ALIGN as u64 != 0 {
            return Err(DecodeError::BadSectionTable(format!(
                "{} starts at {}, not a multiple of {SECTION_ALIGN}",
                kind.name(),
                entry.offset
            )));
        }
        if entry.offset < previous_end {
            return Err(DecodeError::BadSectionTable(format!(
                "{} at {} overlaps what comes before it (ends at {previous_end})",
                kind.name(),
                entry.offset
            )));
        }
        let end = entry.offset.checked_add(entry.length).ok_or_else(|| {
            DecodeError::BadSectionTable(format!(
                "{} length {} overflows",
                kind.name(),
                entry.length
            ))
        })?;
        if end > file_len {
            return Err(DecodeError::Truncated {
                what: kind.name(),
                needed: end,
                available: file_len,
            });
        }
        let slot = &mut ranges[kind as usize - 1];
        if slot.is_some() {
            return Err(DecodeError::BadSectionTable(format!(
                "{} appears twice",
                kind.name()
            )));
        }
        *slot = Some(entry.offset as usize..end as usize);
        previous_end = end;
    }
    if previous_end < file_len {
        return Err(DecodeError::TrailingBytes(file_len - previous_end));
    }
    if let Some(kind) = kinds.iter().find(|k| ranges[**k as usize - 1].is_none()) {
        return Err(DecodeError::BadSectionTable(format!(
            "{} is missing",
            kind.name()
        )));
    }
    Ok(ranges)
}

/// The encoded length of a header that was just decoded (re-encoding is exact and cheap).
fn envelope_len(header: &Header) -> u64 {
    envelope::encode_header(header).map_or(u64::MAX / 2, |b| b.len() as u64)
}

fn length_error(kind: SectionKind, reason: String) -> DecodeError {
    DecodeError::BadSectionLength { kind, reason }
}

fn read_u32s(kind: SectionKind, bytes: &[u8]) -> Result<Vec<u32>, DecodeError> {
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

fn read_vec3s(kind: SectionKind, bytes: &[u8]) -> Result<Vec<[f32; 3]>, DecodeError> {
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

fn read_segments(bytes: &[u8]) -> Result<Vec<[[f32; 3]; 2]>, DecodeError> {
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
fn read_clusters(bytes: &[u8], edges: usize) -> Result<Vec<EdgeCluster>, DecodeError> {
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
fn read_indices(
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

fn validate_attributes(asset: &Asset) -> Result<(), DecodeError> {
    let kind = SectionKind::EdgeAttributes;
    for (position, &word) in asset.edge_attributes.iter().enumerate() {
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
fn validate_ring_lengths(asset: &Asset) -> Result<(), DecodeError> {
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
fn validate_rings(asset: &Asset) -> Result<(), DecodeError> {
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
fn validate_intersections(asset: &Asset) -> Result<(), DecodeError> {
    let segments = &asset.intersection_segments;
    let starts = &asset.intersection_starts;
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
