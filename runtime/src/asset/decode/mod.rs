//! Reading an asset: every length, index and float is checked before anything is trusted.
//!
//! A file holds each section raw ([`raw`]) or, in a compact file (format 5), coded
//! ([`compact`](super::compact)). The decoder reads every section's element count first and checks
//! them against each other; then it decodes in two rounds of two jobs, on two threads for a large
//! asset ([`join`]): the triangles and the mesh's corners beside the vertices, attributes and
//! clusters; then the edges beside the rings (coded rings need only the corners, not the edges).

mod motion;
mod raw;

use std::borrow::Cow;
use std::ops::Range;

use super::clusters;
use super::compact::Precision;
use super::compact::edges::{self, CornerBits, VertexCorners};
use super::compact::read::{self, Reader};
use super::join::join;
use super::{
    Asset, DecodeError, FORMAT_VERSION, Header, Indices, MAGIC, MAX_HEADER_BYTES, SECTION_ALIGN,
    SectionKind, envelope,
};
use raw::{
    checked_indices, length_error, raw_rings, read_clusters, read_indices, read_render_positions,
    read_segments, read_u32s, read_vec3s, validate_attributes, validate_intersections,
    validate_ring_lengths, validate_rings,
};

/// Assets with at least this many triangles decode on two threads.
const PARALLEL_TRIANGLES: usize = 1 << 15;

impl Asset {
    /// Decodes and validates an asset.
    ///
    /// Reads format versions 1 to 6 (a version-1 file has no intersection edges; the clusters of a
    /// version-1 or 2 file are computed here; from version 4 the render positions may be derived
    /// from the topology positions and render vertex counts; version 5 may code its sections, see
    /// [`compact`](super::compact); version 6 adds the sections of animated assets, [`motion`](super::motion)).
    /// Rejects, with a typed error: bad magic, another format version, a header or section table
    /// that does not fit the file, sections whose lengths disagree with each other, coded sections
    /// that do not decode or declare more than the file can hold, indices out of range, non-finite
    /// floats, unknown flag bits, next-index rings that are not closed, cap heads without rings,
    /// vertices with more kept edge ends than [`MAX_RING`](super::MAX_RING) and intersection
    /// polylines that are not chained, and clusters that are not one per 64 edges or whose numbers
    /// are not finite, non-negative radii and cosines within [-1, 1]; and, in an animated asset
    /// (version 6), joints or weights that are not one per vertex, joint indices past the rig's
    /// joints, weights that are negative, not finite or do not sum to 1, morph entries out of range
    /// or out of order, and a rig that breaks [`Rig::validate`](crate::rig::Rig::validate).
    /// Allocates at most about twice the input's size for an uncompressed file, and a fixed multiple
    /// (below 200) of it for a compact one. Never panics.
    pub fn decode(bytes: &[u8]) -> Result<Asset, DecodeError> {
        decode(bytes, true, &|_| ())
    }

    /// [`decode`](Self::decode) on this thread alone, calling `observer` with a section the file
    /// holds each time a part of its decoding and checking ends (and with
    /// [`EdgeClusters`](SectionKind::EdgeClusters) after clusters a file does not hold are
    /// computed): the time between two calls is what that part cost, and a section's parts add up
    /// to what it costs (`chamfer inspect --timings`).
    pub fn decode_observed(
        bytes: &[u8],
        observer: &(dyn Fn(SectionKind) + Sync),
    ) -> Result<Asset, DecodeError> {
        decode(bytes, false, observer)
    }

    /// The precision of a file's positions and normals, from its sections' prefixes: what its
    /// quantization may have moved them by (exact for a file that is not compact).
    pub fn precision(bytes: &[u8]) -> Result<Precision, DecodeError> {
        let (header, kinds) = read_header(bytes)?;
        let sections = Sections::new(bytes, &header, kinds)?;
        read::precision(
            sections.get(SectionKind::TopologyPositionsCoded),
            sections.get(SectionKind::RenderNormalsCoded),
        )
    }
}

/// Each raw section and the coded one that can replace it (format 5).
const TWINS: [(SectionKind, SectionKind); 9] = [
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
    (SectionKind::EdgeClusters, SectionKind::EdgeClustersCoded),
];

/// A file's sections by kind.
struct Sections<'a> {
    bytes: &'a [u8],
    /// Indexed by `kind - 1`; `None` for the kinds the file's version does not have.
    ranges: Vec<Option<Range<usize>>>,
}

impl<'a> Sections<'a> {
    fn new(bytes: &'a [u8], header: &Header, kinds: &[SectionKind]) -> Result<Self, DecodeError> {
        let sections = Self {
            bytes,
            ranges: section_ranges(header, kinds, bytes.len() as u64)?,
        };
        for (raw, coded) in TWINS {
            if !sections.get(raw).is_empty() && !sections.get(coded).is_empty() {
                return Err(length_error(
                    coded,
                    format!(
                        "present beside {} (a file holds one or the other)",
                        raw.name()
                    ),
                ));
            }
        }
        Ok(sections)
    }

    /// The section's bytes; empty for a kind the file's version does not have.
    fn get(&self, kind: SectionKind) -> &'a [u8] {
        match &self.ranges[kind as usize - 1] {
            Some(range) => &self.bytes[range.clone()],
            None => &[],
        }
    }

    /// The coded section, if the file holds it.
    fn coded(&self, kind: SectionKind) -> Option<&'a [u8]> {
        Some(self.get(kind)).filter(|s| !s.is_empty())
    }

    /// The section that holds `raw`'s content: its coded twin when the file holds that.
    fn stored(&self, raw: SectionKind) -> SectionKind {
        raw.twin()
            .filter(|&twin| self.coded(twin).is_some())
            .unwrap_or(raw)
    }
}

/// How many of each element a file holds, from its sections' lengths and declared counts, before
/// any of them is decoded (each section's decoder checks its own count again).
struct Shape {
    render_vertices: usize,
    topology_vertices: usize,
    edges: usize,
}

impl Shape {
    fn of(sections: &Sections, reader: &Reader) -> Result<Self, DecodeError> {
        let count =
            |raw: SectionKind, coded: SectionKind, element: usize| match sections.coded(coded) {
                Some(bytes) => reader.declared(coded, bytes),
                None => Ok(sections.get(raw).len() / element),
            };
        Ok(Self {
            render_vertices: count(
                SectionKind::RenderNormals,
                SectionKind::RenderNormalsCoded,
                12,
            )?,
            topology_vertices: count(
                SectionKind::TopologyPositions,
                SectionKind::TopologyPositionsCoded,
                12,
            )?,
            edges: count(
                SectionKind::EdgeAttributes,
                SectionKind::EdgeAttributesCoded,
                4,
            )?,
        })
    }
}

/// The mesh as corners, for coded edges and rings.
struct CornerMesh {
    topology: Vec<u32>,
    corners: VertexCorners,
    bits: CornerBits,
}

/// What the second job of the first round decodes.
struct Vertices {
    topology_positions: Vec<[f32; 3]>,
    render_normals: Vec<[f32; 3]>,
    render_positions: Vec<[f32; 3]>,
    edge_attributes: Vec<u32>,
    intersection_segments: Vec<[[f32; 3]; 2]>,
    intersection_starts: Vec<u32>,
    clusters: Option<Vec<clusters::EdgeCluster>>,
}

fn decode(
    bytes: &[u8],
    parallel: bool,
    observer: &(dyn Fn(SectionKind) + Sync),
) -> Result<Asset, DecodeError> {
    let (header, kinds) = read_header(bytes)?;
    let sections = Sections::new(bytes, &header, kinds)?;
    let triangles = match sections.coded(SectionKind::MeshIndicesCoded) {
        Some(coded) => read::triangle_capacity(coded),
        None => sections.get(SectionKind::MeshIndices).len() / 6,
    };
    let reader = Reader::for_triangles(triangles);
    let shape = Shape::of(&sections, &reader)?;
    let step = |kind: SectionKind| observer(sections.stored(kind));
    let parallel = parallel && triangles >= PARALLEL_TRIANGLES;

    for kind in [
        SectionKind::RenderVertexCountsCoded,
        SectionKind::EdgeCorners,
        SectionKind::EdgeClustersCoded,
    ] {
        if let Some(coded) = sections.coded(kind) {
            reader.declared(kind, coded)?;
        }
    }
    let counts = match sections.coded(SectionKind::RenderVertexCountsCoded) {
        Some(coded) => reader.counts(coded)?,
        None => sections.get(SectionKind::RenderVertexCounts).to_vec(),
    };
    check_counts(
        &counts,
        sections.get(SectionKind::RenderPositions).len() / 12,
        &shape,
    )?;
    step(SectionKind::RenderVertexCounts);

    let (mesh, vertices) = join(
        parallel,
        || -> Result<_, DecodeError> {
            let mesh_indices = mesh_indices(&sections, &reader, &shape)?;
            step(SectionKind::MeshIndices);
            let corner_mesh = match sections.coded(SectionKind::EdgeCorners) {
                Some(coded) => {
                    let mesh = corner_mesh(coded, &reader, &mesh_indices, &counts, &shape)?;
                    step(SectionKind::EdgeVertices);
                    Some(mesh)
                }
                None => None,
            };
            Ok((mesh_indices, corner_mesh))
        },
        || vertices(&sections, &reader, &counts, &shape, kinds, &step),
    );
    let (mesh_indices, corner_mesh) = mesh?;
    let vertices = vertices?;

    let (edge_vertices, (next_ends, cap_heads)) = match &corner_mesh {
        Some(mesh) => coded_edges_and_rings(&sections, mesh, &shape, parallel, &step)?,
        None => {
            let edge_vertices = read_indices(
                SectionKind::EdgeVertices,
                sections.get(SectionKind::EdgeVertices),
                shape.topology_vertices,
                4,
            )?;
            step(SectionKind::EdgeVertices);
            if sections.coded(SectionKind::RingOrders).is_some() {
                return Err(length_error(
                    SectionKind::RingOrders,
                    "present without edge corners (the rings are coded over them)".into(),
                ));
            }
            let rings = raw_rings(
                sections.get(SectionKind::NextEnds),
                sections.get(SectionKind::CapHeads),
                2 * shape.edges,
            )?;
            (edge_vertices, rings)
        }
    };
    if edge_vertices.len() != 4 * shape.edges {
        return Err(length_error(
            SectionKind::EdgeVertices,
            format!(
                "{} indices for {} edges (4 per edge)",
                edge_vertices.len(),
                shape.edges
            ),
        ));
    }

    let mut asset = Asset {
        header,
        render_positions: vertices.render_positions,
        render_normals: vertices.render_normals,
        mesh_indices,
        topology_positions: vertices.topology_positions,
        edge_vertices,
        edge_attributes: vertices.edge_attributes,
        next_ends,
        cap_heads,
        intersection_segments: vertices.intersection_segments,
        intersection_starts: vertices.intersection_starts,
        edge_clusters: Vec::new(),
        motion: motion::read(&|kind| sections.get(kind), shape.topology_vertices)?,
    };
    // Rings decoded from their orders are cycles within bounds by construction.
    if sections.coded(SectionKind::RingOrders).is_none() {
        validate_ring_lengths(&asset)?;
        validate_rings(&asset)?;
        step(SectionKind::NextEnds);
    }
    asset.edge_clusters = match vertices.clusters {
        Some(clusters) => clusters,
        None => {
            let computed = clusters::edge_clusters(&asset);
            observer(SectionKind::EdgeClusters);
            computed
        }
    };
    Ok(asset)
}

/// Render vertex counts, when a file has them, are one per topology vertex and sum to the render
/// vertices; without them, the file stores a position for every normal.
fn check_counts(counts: &[u8], positions: usize, shape: &Shape) -> Result<(), DecodeError> {
    if counts.is_empty() {
        if positions != shape.render_vertices {
            return Err(length_error(
                SectionKind::RenderNormals,
                format!(
                    "{} normals for {positions} render vertices",
                    shape.render_vertices
                ),
            ));
        }
        return Ok(());
    }
    let kind = SectionKind::RenderVertexCounts;
    if counts.len() != shape.topology_vertices {
        return Err(length_error(
            kind,
            format!(
                "{} counts for {} topology vertices",
                counts.len(),
                shape.topology_vertices
            ),
        ));
    }
    let total: usize = counts.iter().map(|&c| usize::from(c)).sum();
    if total != shape.render_vertices {
        return Err(length_error(
            kind,
            format!(
                "counts sum to {total} render vertices, the normals to {}",
                shape.render_vertices
            ),
        ));
    }
    Ok(())
}

fn mesh_indices(
    sections: &Sections,
    reader: &Reader,
    shape: &Shape,
) -> Result<Indices, DecodeError> {
    match sections.coded(SectionKind::MeshIndicesCoded) {
        Some(coded) => checked_indices(
            SectionKind::MeshIndicesCoded,
            reader.mesh_indices(coded)?,
            shape.render_vertices,
        ),
        None => read_indices(
            SectionKind::MeshIndices,
            sections.get(SectionKind::MeshIndices),
            shape.render_vertices,
            3,
        ),
    }
}

/// The corners of the topology triangles and the corner bits of `coded` edges. The mesh indices
/// are checked against the render vertices, and `counts` against both vertex counts.
fn corner_mesh(
    coded: &[u8],
    reader: &Reader,
    mesh_indices: &Indices,
    counts: &[u8],
    shape: &Shape,
) -> Result<CornerMesh, DecodeError> {
    if counts.is_empty() {
        return Err(length_error(
            SectionKind::EdgeCorners,
            "present without render vertex counts (the corners' vertices come from them)".into(),
        ));
    }
    let topology = super::compact::topology_triangles(&u32_indices(mesh_indices), counts);
    let (edges, bits) = reader.corner_bits(coded, &topology)?;
    let corners = VertexCorners::new(&topology, shape.topology_vertices);
    if edges != shape.edges {
        return Err(length_error(
            SectionKind::EdgeCorners,
            format!("{edges} edges for {} edge attributes", shape.edges),
        ));
    }
    Ok(CornerMesh {
        topology,
        corners,
        bits,
    })
}

fn u32_indices(indices: &Indices) -> Cow<'_, [u32]> {
    match indices {
        Indices::U32(values) => Cow::Borrowed(values),
        Indices::U16(_) => Cow::Owned(indices.to_u32_vec()),
    }
}

/// The share of the coded edges the first thread decodes while the second decodes the rings
/// and then the rest of the edges (the rings cost about as much as this share of the edges).
const EDGES_BESIDE_RINGS: f64 = 0.8;

/// The edges of the corner bits, and the rings (coded, or raw when the file stores them raw).
fn coded_edges_and_rings(
    sections: &Sections,
    mesh: &CornerMesh,
    shape: &Shape,
    parallel: bool,
    step: &(dyn Fn(SectionKind) + Sync),
) -> Result<(Indices, (Indices, Indices)), DecodeError> {
    let ends = 2 * shape.edges;
    let triangles = mesh.topology.len() / 3;
    let middle = if parallel {
        (triangles as f64 * EDGES_BESIDE_RINGS) as usize
    } else {
        triangles
    };
    let mut values = vec![0u32; 4 * shape.edges];
    let (first, second) = values.split_at_mut(4 * mesh.bits.edges_before(middle));
    let decode = |range: Range<usize>, out: &mut [u32]| {
        edges::decode_range(&mesh.bits, &mesh.topology, &mesh.corners, range, out)
    };
    // (Only a decode on one thread reports its steps: there each step is the time between them.)
    let ((), rings) = join(
        parallel,
        || {
            decode(0..middle, first);
            step(SectionKind::EdgeVertices);
        },
        || -> Result<_, DecodeError> {
            let rings = match sections.coded(SectionKind::RingOrders) {
                Some(coded) => {
                    let (next, heads) = read::rings(coded, &mesh.bits, &mesh.corners, ends)?;
                    (
                        Indices::with_bound(next, ends),
                        Indices::with_bound(heads, ends),
                    )
                }
                None => raw_rings(
                    sections.get(SectionKind::NextEnds),
                    sections.get(SectionKind::CapHeads),
                    ends,
                )?,
            };
            step(SectionKind::NextEnds);
            decode(middle..triangles, second);
            Ok(rings)
        },
    );
    let rings = rings?;
    Ok((Indices::with_bound(values, shape.topology_vertices), rings))
}

/// Positions, normals, attributes, intersections and the clusters a file holds.
fn vertices(
    sections: &Sections,
    reader: &Reader,
    counts: &[u8],
    shape: &Shape,
    kinds: &[SectionKind],
    step: &(dyn Fn(SectionKind) + Sync),
) -> Result<Vertices, DecodeError> {
    let topology_positions = match sections.coded(SectionKind::TopologyPositionsCoded) {
        Some(coded) => reader.positions(coded)?,
        None => read_vec3s(
            SectionKind::TopologyPositions,
            sections.get(SectionKind::TopologyPositions),
        )?,
    };
    step(SectionKind::TopologyPositions);
    let render_normals = match sections.coded(SectionKind::RenderNormalsCoded) {
        Some(coded) => reader.normals(coded)?,
        None => read_vec3s(
            SectionKind::RenderNormals,
            sections.get(SectionKind::RenderNormals),
        )?,
    };
    step(SectionKind::RenderNormals);
    // The shape came from declared counts and lengths, and each decoder kept to its own.
    debug_assert_eq!(topology_positions.len(), shape.topology_vertices);
    debug_assert_eq!(render_normals.len(), shape.render_vertices);
    let render_positions = read_render_positions(
        sections.get(SectionKind::RenderPositions),
        counts,
        &topology_positions,
        render_normals.len(),
    )?;
    step(SectionKind::RenderPositions);
    let (edge_attributes, kind) = match sections.coded(SectionKind::EdgeAttributesCoded) {
        Some(coded) => (
            reader.words(SectionKind::EdgeAttributesCoded, coded)?,
            SectionKind::EdgeAttributesCoded,
        ),
        None => (
            read_u32s(
                SectionKind::EdgeAttributes,
                sections.get(SectionKind::EdgeAttributes),
            )?,
            SectionKind::EdgeAttributes,
        ),
    };
    validate_attributes(&edge_attributes, kind)?;
    step(SectionKind::EdgeAttributes);
    let intersection_segments = read_segments(sections.get(SectionKind::IntersectionSegments))?;
    let intersection_starts = read_u32s(
        SectionKind::IntersectionPolylines,
        sections.get(SectionKind::IntersectionPolylines),
    )?;
    validate_intersections(&intersection_segments, &intersection_starts)?;
    step(SectionKind::IntersectionSegments);
    // Format 5 may leave the clusters to the loader; earlier formats store them from version 3.
    let stored = sections.get(SectionKind::EdgeClusters);
    let clusters = match sections.coded(SectionKind::EdgeClustersCoded) {
        Some(coded) => Some(reader.clusters(coded, &edge_attributes)?),
        None if kinds.contains(&SectionKind::EdgeClusters)
            && (!stored.is_empty() || kinds.len() < SectionKind::ALL.len()) =>
        {
            Some(read_clusters(stored, edge_attributes.len())?)
        }
        None => None,
    };
    if clusters.is_some() {
        step(SectionKind::EdgeClusters);
    }
    Ok(Vertices {
        topology_positions,
        render_normals,
        render_positions,
        edge_attributes,
        intersection_segments,
        intersection_starts,
        clusters,
    })
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
