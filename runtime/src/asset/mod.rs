//! The `.chamfer` edge asset: what the bake writes and the runtime uploads.
//!
//! # Layout (format version 6)
//!
//! All numbers are little-endian.
//!
//! | bytes | content |
//! |---|---|
//! | 0..8 | magic `b"CHAMFER\0"` |
//! | 8..12 | format version (`u32`) |
//! | 12..16 | header length `H` (`u32`, at most [`MAX_HEADER_BYTES`]) |
//! | 16..16+H | [`Header`], bincode 2 (fixed-width integers), see `envelope.rs` |
//! | … | sections, each starting on a 16-byte boundary, zero padding between |
//!
//! The header lists every section as (kind, offset, length). Sections are raw arrays that go to the GPU
//! unchanged: no per-element decoding, only validation.
//!
//! | section | element | count |
//! |---|---|---|
//! | [`SectionKind::RenderPositions`] | `[f32; 3]` | R render vertices, or empty (see below) |
//! | [`SectionKind::RenderNormals`] | `[f32; 3]` | R (crease-split, unit length) |
//! | [`SectionKind::MeshIndices`] | index < R | 3 × T triangles |
//! | [`SectionKind::TopologyPositions`] | `[f32; 3]` | V welded vertices |
//! | [`SectionKind::EdgeVertices`] | index < V | 4 × E: `v0 v1 v2 v3` (thesis §8.1) |
//! | [`SectionKind::EdgeAttributes`] | `u32` | E: low 16 bits [`EdgeFlags`], high 16 bits radius (f16) |
//! | [`SectionKind::NextEnds`] | edge end < 2E | 2 × E, or empty |
//! | [`SectionKind::CapHeads`] | edge end < 2E | one per capped vertex, or empty (always empty without `NextEnds`) |
//! | [`SectionKind::IntersectionSegments`] | `[[f32; 3]; 2]` | S segments, or empty (since version 2) |
//! | [`SectionKind::IntersectionPolylines`] | `u32` segment index < S | P polylines, or empty (since version 2) |
//! | [`SectionKind::EdgeClusters`] | [`EdgeCluster`] (48 bytes) | ⌈E / 64⌉ (since version 3) |
//! | [`SectionKind::RenderVertexCounts`] | `u8` | V, or empty (since version 4) |
//! | the coded twins of the sections above ([`compact`]) | coded bytes | empty, or in place of their raw twin (since version 5) |
//! | skin joints and weights, morph targets, the rig ([`motion`]) | see there | empty for a still asset (since version 6) |
//!
//! An *index* section is `u16` when its values are bounded by 65 536 and `u32` otherwise
//! ([`IndexWidth::for_bound`]); the width is implied by the counts, so it is never stored.
//! An *edge end* is `2 * edge + end`, where end 0 is `v0` and end 1 is `v1`.
//!
//! For a boundary edge `v3 == v0` (thesis §6.2); [`EdgeFlags::BOUNDARY`] says the same explicitly.
//!
//! *Intersection edges* (thesis §2.2: where surfaces cut through each other, not along any mesh edge)
//! are stored apart from the mesh edges, as positions rather than indices: each segment is its two
//! end points, and the segments of one polyline follow each other, the end of one bit-identical to the
//! start of the next. [`SectionKind::IntersectionPolylines`] holds the index of each polyline's first
//! segment (strictly increasing from 0); a polyline whose last end equals its first start is closed.
//! Both sections are empty when the bake did not look for intersections or found none.
//!
//! *Render vertices* copy the position of a topology vertex: the split normals give a vertex one
//! render vertex per fan of faces between creases. The bake numbers them topology vertex by
//! topology vertex, so the file need not store their positions: [`SectionKind::RenderVertexCounts`]
//! says how many render vertices each topology vertex has (0 to 255), and the render positions are
//! those of the topology vertices, each repeated that many times, in order. The encoder writes the
//! counts whenever they reproduce the render positions exactly, and the positions themselves
//! otherwise (then the counts section is empty); a file never holds both.
//!
//! *Edge clusters* (see [`clusters`]) bound each run of 64 edges in the file's order, so that a
//! renderer can skip whole runs that cannot be drawn from a camera. The bake orders the edges so
//! that runs are spatially coherent. A wrong cluster can only make a renderer skip edges it should
//! draw: the decoder checks the section's length and numbers, not the bounds themselves.
//!
//! A *compact* file ([`Asset::encode_compact`]) stores sections coded instead of raw: quantized and
//! through meshoptimizer's codecs, edges relative to the mesh's corners, rings as each vertex's
//! order ([`compact`] has the table). [`Asset::decode`] turns them back into the same raw arrays, so a
//! renderer never sees the difference; a file holds each section raw or coded, never both.
//!
//! # Compatibility
//!
//! The version is bumped on any change to the header or to a section's meaning. Version 2 added the
//! two intersection sections, version 3 the edge clusters, version 4 the render vertex counts, version
//! 5 the coded sections of compact files (the header is unchanged), version 6 the sections of
//! animated assets. A reader of version 6 also reads versions 1 to 5: a version-1 file has no
//! intersection edges, the clusters of a version-1 or 2 file are computed when it is decoded (over
//! its edge order, which was not made for them: they cull less), and files before version 4 store
//! every render position. Any other version is reported as
//! [`DecodeError::UnsupportedVersion`]: re-bake the source mesh (bakes are deterministic, so this is
//! cheap to automate in `build.rs`).

// Sections are written and uploaded as they lie in memory.
#[cfg(target_endian = "big")]
compile_error!(
    "the .chamfer format is little-endian and this crate maps it directly: big-endian hosts are not supported"
);

pub mod clusters;
pub mod compact;
pub mod corners;
mod decode;
mod encode;
mod envelope;
mod error;
mod join;
pub mod motion;

pub use clusters::{CLUSTER_EDGES, EdgeCluster};
pub use compact::{Codecs, CompactOptions, Precision};
pub use error::DecodeError;
pub use motion::Motion;

use serde::{Deserialize, Serialize};

/// The eight bytes every asset starts with.
pub const MAGIC: [u8; 8] = *b"CHAMFER\0";
/// The format version this crate writes (and the newest it reads).
pub const FORMAT_VERSION: u32 = 6;
/// The oldest format version this crate still reads.
pub const OLDEST_READ_VERSION: u32 = 1;
/// The largest header accepted; real headers are a few hundred bytes.
pub const MAX_HEADER_BYTES: u32 = 1 << 20;
/// Every section starts at a multiple of this many bytes.
pub const SECTION_ALIGN: usize = 16;
/// The largest number of kept edge ends at one vertex that the runtime's join walk follows
/// (`MAX_RING` in `shaders/joins.wgsl`): a longer ring would get incomplete joins, so
/// [`Asset::decode`] refuses it and the bake refuses to write it.
pub const MAX_RING: u32 = 4096;

/// What a pipeline classified an edge as; several bits can be set at once.
///
/// An edge with none of these bits is a *smooth* edge: it is kept only because it can become a contour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct EdgeFlags(pub u16);

impl EdgeFlags {
    /// Only one face: `v3 == v0`.
    pub const BOUNDARY: Self = Self(1 << 0);
    /// More than two faces; `v2` and `v3` are the opposite vertices of the first two.
    pub const NON_MANIFOLD: Self = Self(1 << 1);
    /// Crease whose faces fold away from each other (convex, thesis §6.1).
    pub const RIDGE: Self = Self(1 << 2);
    /// Crease whose faces fold towards each other (concave).
    pub const VALLEY: Self = Self(1 << 3);
    /// Marked in the source file.
    pub const MARKED: Self = Self(1 << 4);
    /// The faces have different materials (or glTF primitives of different materials).
    pub const MATERIAL: Self = Self(1 << 5);
    /// The second face winds the edge the same way as the first: negate its normal.
    pub const FLIPPED: Self = Self(1 << 6);
    /// The edge carries a chamfer radius.
    pub const CHAMFER: Self = Self(1 << 7);
    /// Every bit that has a meaning in this format version.
    pub const ALL: Self = Self((1 << 8) - 1);
    /// Either crease direction.
    pub const CREASE: Self = Self(Self::RIDGE.0 | Self::VALLEY.0);
    /// Classes that are drawable from every camera (the thesis' "pre-calculated" edges).
    pub const STATIC: Self = Self(
        Self::BOUNDARY.0
            | Self::NON_MANIFOLD.0
            | Self::CREASE.0
            | Self::MARKED.0
            | Self::MATERIAL.0,
    );

    /// True if any bit of `other` is set in `self`.
    pub const fn intersects(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }

    /// True if every bit of `other` is set in `self`.
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }
}

impl std::ops::BitOr for EdgeFlags {
    type Output = Self;
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

impl std::ops::BitOrAssign for EdgeFlags {
    fn bitor_assign(&mut self, rhs: Self) {
        self.0 |= rhs.0;
    }
}

/// Packs an edge's flags and radius into its attribute word.
///
/// The radius is stored as an f16 of `radius / radius_scale` (relative precision about 5e-4);
/// `radius_scale` is the asset's [`Header::radius_scale`].
pub fn pack_attributes(flags: EdgeFlags, radius: f32, radius_scale: f32) -> u32 {
    let scaled = if radius_scale > 0.0 {
        radius / radius_scale
    } else {
        0.0
    };
    let half = half::f16::from_f32(scaled).to_bits();
    u32::from(flags.0) | (u32::from(half) << 16)
}

/// The flags of an attribute word.
pub fn attribute_flags(word: u32) -> EdgeFlags {
    EdgeFlags((word & 0xffff) as u16)
}

/// The radius of an attribute word, in mesh units.
pub fn attribute_radius(word: u32, radius_scale: f32) -> f32 {
    half::f16::from_bits((word >> 16) as u16).to_f32() * radius_scale
}

/// How wide the values of an index section are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndexWidth {
    /// Two bytes per index.
    U16,
    /// Four bytes per index.
    U32,
}

impl IndexWidth {
    /// The narrowest width that holds every value below `bound`.
    pub const fn for_bound(bound: usize) -> Self {
        if bound <= 1 << 16 {
            Self::U16
        } else {
            Self::U32
        }
    }

    /// Bytes per index.
    pub const fn bytes(self) -> usize {
        match self {
            Self::U16 => 2,
            Self::U32 => 4,
        }
    }
}

/// An index array stored as narrow as its bound allows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Indices {
    /// Values below 65 536.
    U16(Vec<u16>),
    /// Any `u32` values.
    U32(Vec<u32>),
}

impl Default for Indices {
    fn default() -> Self {
        Self::U16(Vec::new())
    }
}

impl Indices {
    /// Stores `values` as `u16` if `bound <= 65536`, else as `u32`.
    ///
    /// Every value must be below `bound` (checked in debug builds).
    pub fn with_bound(values: Vec<u32>, bound: usize) -> Self {
        debug_assert!(values.iter().all(|&v| (v as usize) < bound));
        match IndexWidth::for_bound(bound) {
            IndexWidth::U16 => Self::U16(values.iter().map(|&v| v as u16).collect()),
            IndexWidth::U32 => Self::U32(values),
        }
    }

    /// Number of indices.
    pub fn len(&self) -> usize {
        match self {
            Self::U16(v) => v.len(),
            Self::U32(v) => v.len(),
        }
    }

    /// True if there are no indices.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The width of each index.
    pub fn width(&self) -> IndexWidth {
        match self {
            Self::U16(_) => IndexWidth::U16,
            Self::U32(_) => IndexWidth::U32,
        }
    }

    /// The index at `i` (panics if out of range, like slice indexing).
    pub fn get(&self, i: usize) -> u32 {
        match self {
            Self::U16(v) => u32::from(v[i]),
            Self::U32(v) => v[i],
        }
    }

    /// All indices, widened to `u32`.
    pub fn iter(&self) -> IndicesIter<'_> {
        match self {
            Self::U16(v) => IndicesIter::U16(v.iter()),
            Self::U32(v) => IndicesIter::U32(v.iter()),
        }
    }

    /// All indices, widened to `u32`, in a new vector.
    pub fn to_u32_vec(&self) -> Vec<u32> {
        self.iter().collect()
    }

    /// The raw little-endian bytes, ready for a GPU buffer.
    pub fn as_bytes(&self) -> &[u8] {
        match self {
            Self::U16(v) => bytemuck::cast_slice(v),
            Self::U32(v) => bytemuck::cast_slice(v),
        }
    }
}

/// Iterator over [`Indices`], widening each to `u32`.
#[derive(Clone, Debug)]
pub enum IndicesIter<'a> {
    /// Over `u16` indices.
    U16(std::slice::Iter<'a, u16>),
    /// Over `u32` indices.
    U32(std::slice::Iter<'a, u32>),
}

impl Iterator for IndicesIter<'_> {
    type Item = u32;
    fn next(&mut self) -> Option<u32> {
        match self {
            Self::U16(it) => it.next().map(|&v| u32::from(v)),
            Self::U32(it) => it.next().copied(),
        }
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        match self {
            Self::U16(it) => it.size_hint(),
            Self::U32(it) => it.size_hint(),
        }
    }
}

impl ExactSizeIterator for IndicesIter<'_> {}

/// What a section holds; the numbers are part of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u32)]
pub enum SectionKind {
    /// `[f32; 3]` per render vertex.
    RenderPositions = 1,
    /// `[f32; 3]` unit normal per render vertex, split at creases and marked edges.
    RenderNormals = 2,
    /// Three render-vertex indices per triangle.
    MeshIndices = 3,
    /// `[f32; 3]` per welded (topology) vertex.
    TopologyPositions = 4,
    /// Four topology-vertex indices per edge: `v0 v1 v2 v3`.
    EdgeVertices = 5,
    /// One `u32` per edge: flags and radius, see [`pack_attributes`].
    EdgeAttributes = 6,
    /// Per edge end, the next edge end around the same vertex (thesis §13).
    NextEnds = 7,
    /// Per capped vertex, one edge end at that vertex: the start of its ring (thesis §10.5).
    CapHeads = 8,
    /// Intersection edges: two `[f32; 3]` end points per segment, polylines in order (version 2).
    IntersectionSegments = 9,
    /// Index of the first segment of each intersection polyline (version 2).
    IntersectionPolylines = 10,
    /// One [`EdgeCluster`] per 64 edges (version 3).
    EdgeClusters = 11,
    /// One `u8` per topology vertex: how many render vertices copy its position, in order; or
    /// empty (version 4). When present, [`RenderPositions`](Self::RenderPositions) is empty.
    RenderVertexCounts = 12,
    /// [`MeshIndices`](Self::MeshIndices), coded (version 5, [`compact`]).
    MeshIndicesCoded = 13,
    /// [`TopologyPositions`](Self::TopologyPositions) on a grid or lossless, coded (version 5).
    TopologyPositionsCoded = 14,
    /// [`RenderNormals`](Self::RenderNormals) octahedral or lossless, coded (version 5).
    RenderNormalsCoded = 15,
    /// [`EdgeVertices`](Self::EdgeVertices) as one bit per mesh corner (version 5).
    EdgeCorners = 16,
    /// [`EdgeAttributes`](Self::EdgeAttributes), coded (version 5).
    EdgeAttributesCoded = 17,
    /// [`NextEnds`](Self::NextEnds) and [`CapHeads`](Self::CapHeads) as each vertex's ring order
    /// (version 5).
    RingOrders = 18,
    /// [`RenderVertexCounts`](Self::RenderVertexCounts), coded (version 5).
    RenderVertexCountsCoded = 19,
    /// [`EdgeClusters`](Self::EdgeClusters), quantized and coded (version 5).
    EdgeClustersCoded = 20,
    /// Four joint indices (`u16`) per topology vertex, or empty ([`motion`], version 6).
    SkinJoints = 21,
    /// Four joint weights (`f32`) per topology vertex, or empty (version 6).
    SkinWeights = 22,
    /// The first entry of each morph target (`u32`, version 6).
    MorphStarts = 23,
    /// The topology vertex of each morph entry (`u32`, version 6).
    MorphVertices = 24,
    /// The position delta of each morph entry (`[f32; 3]`, version 6).
    MorphDeltas = 25,
    /// The [`Rig`](crate::rig::Rig): nodes, joints, morph weights, animations (bincode, version 6).
    Rig = 26,
}

impl SectionKind {
    /// Every kind, in the order sections are written.
    pub const ALL: [Self; 26] = [
        Self::RenderPositions,
        Self::RenderNormals,
        Self::MeshIndices,
        Self::TopologyPositions,
        Self::EdgeVertices,
        Self::EdgeAttributes,
        Self::NextEnds,
        Self::CapHeads,
        Self::IntersectionSegments,
        Self::IntersectionPolylines,
        Self::EdgeClusters,
        Self::RenderVertexCounts,
        Self::MeshIndicesCoded,
        Self::TopologyPositionsCoded,
        Self::RenderNormalsCoded,
        Self::EdgeCorners,
        Self::EdgeAttributesCoded,
        Self::RingOrders,
        Self::RenderVertexCountsCoded,
        Self::EdgeClustersCoded,
        Self::SkinJoints,
        Self::SkinWeights,
        Self::MorphStarts,
        Self::MorphVertices,
        Self::MorphDeltas,
        Self::Rig,
    ];

    /// Whether a decoded asset holds this kind as an array for the GPU: the raw kinds but the render
    /// vertex counts, which only say how to rebuild the render positions, and the rig, which the
    /// CPU samples.
    pub const fn is_gpu_ready(self) -> bool {
        (self as u32) < Self::RenderVertexCounts as u32
            || (self as u32 >= Self::SkinJoints as u32 && self as u32 <= Self::MorphDeltas as u32)
    }

    /// The coded kind that replaces this raw one in a compact file, and back; `None` for the kinds
    /// that have no other form.
    pub const fn twin(self) -> Option<Self> {
        Some(match self {
            Self::MeshIndices => Self::MeshIndicesCoded,
            Self::TopologyPositions => Self::TopologyPositionsCoded,
            Self::RenderNormals => Self::RenderNormalsCoded,
            Self::EdgeVertices => Self::EdgeCorners,
            Self::EdgeAttributes => Self::EdgeAttributesCoded,
            Self::NextEnds | Self::CapHeads => Self::RingOrders,
            Self::RenderVertexCounts => Self::RenderVertexCountsCoded,
            Self::EdgeClusters => Self::EdgeClustersCoded,
            Self::MeshIndicesCoded => Self::MeshIndices,
            Self::TopologyPositionsCoded => Self::TopologyPositions,
            Self::RenderNormalsCoded => Self::RenderNormals,
            Self::EdgeCorners => Self::EdgeVertices,
            Self::EdgeAttributesCoded => Self::EdgeAttributes,
            Self::RingOrders => Self::NextEnds,
            Self::RenderVertexCountsCoded => Self::RenderVertexCounts,
            Self::EdgeClustersCoded => Self::EdgeClusters,
            _ => return None,
        })
    }

    /// The kinds a file of format `version` holds (every one of them, possibly empty), or `None`
    /// for a version this crate does not read.
    pub fn of_version(version: u32) -> Option<&'static [Self]> {
        match version {
            1 => Some(&Self::ALL[..8]),
            2 => Some(&Self::ALL[..10]),
            3 => Some(&Self::ALL[..11]),
            4 => Some(&Self::ALL[..12]),
            5 => Some(&Self::ALL[..20]),
            6 => Some(&Self::ALL),
            _ => None,
        }
    }

    /// The kind with this number, if it is one of the newest version's.
    pub fn from_u32(value: u32) -> Option<Self> {
        Self::ALL.into_iter().find(|k| *k as u32 == value)
    }

    /// The name used in reports (`inspect --json`).
    pub const fn name(self) -> &'static str {
        match self {
            Self::RenderPositions => "render_positions",
            Self::RenderNormals => "render_normals",
            Self::MeshIndices => "mesh_indices",
            Self::TopologyPositions => "topology_positions",
            Self::EdgeVertices => "edge_vertices",
            Self::EdgeAttributes => "edge_attributes",
            Self::NextEnds => "next_ends",
            Self::CapHeads => "cap_heads",
            Self::IntersectionSegments => "intersection_segments",
            Self::IntersectionPolylines => "intersection_polylines",
            Self::EdgeClusters => "edge_clusters",
            Self::RenderVertexCounts => "render_vertex_counts",
            Self::MeshIndicesCoded => "mesh_indices_coded",
            Self::TopologyPositionsCoded => "topology_positions_coded",
            Self::RenderNormalsCoded => "render_normals_coded",
            Self::EdgeCorners => "edge_corners",
            Self::EdgeAttributesCoded => "edge_attributes_coded",
            Self::RingOrders => "ring_orders",
            Self::RenderVertexCountsCoded => "render_vertex_counts_coded",
            Self::EdgeClustersCoded => "edge_clusters_coded",
            Self::SkinJoints => "skin_joints",
            Self::SkinWeights => "skin_weights",
            Self::MorphStarts => "morph_starts",
            Self::MorphVertices => "morph_vertices",
            Self::MorphDeltas => "morph_deltas",
            Self::Rig => "rig",
        }
    }
}

/// Where one section lies in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SectionEntry {
    /// [`SectionKind`] as a number.
    pub kind: u32,
    /// Byte offset from the start of the file, a multiple of [`SECTION_ALIGN`].
    pub offset: u64,
    /// Length in bytes.
    pub length: u64,
}

/// Counts of the edge classes found by the bake (an edge can be in several classes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct EdgeStats {
    /// Unique undirected edges of the welded mesh, before coplanar edges were dropped.
    pub total: u64,
    /// Edges written to the asset.
    pub kept: u64,
    /// Edges with one face.
    pub boundary: u64,
    /// Edges with more than two faces.
    pub non_manifold: u64,
    /// Ridge and valley creases together.
    pub crease: u64,
    /// Convex creases.
    pub ridge: u64,
    /// Concave creases.
    pub valley: u64,
    /// Edges marked in the source file.
    pub marked: u64,
    /// Edges between faces of different materials.
    pub material: u64,
    /// Kept edges of no static class: drawn only when they are contours.
    pub smooth: u64,
    /// Edges between (nearly) coplanar faces that were dropped (thesis §6.2, Lander).
    pub coplanar_dropped: u64,
    /// Manifold edges whose two faces wind it the same way (inconsistent orientation).
    pub flipped: u64,
    /// Marks in the source that are not an edge of any face.
    pub marks_unmatched: u64,
}

/// The chamfer edges: those with a radius (seed 000 §3.2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ChamferStats {
    /// Edges with a radius (flag [`EdgeFlags::CHAMFER`]).
    pub edges: u64,
    /// Edges whose radius was reduced so the rounded strip stays on its two faces.
    pub clamped: u64,
    /// Smallest radius after clamping (0 when there is none).
    pub radius_min: f32,
    /// Largest radius after clamping (0 when there is none).
    pub radius_max: f32,
}

/// What the bake saw and produced; shown by `chamfer inspect`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Vertices in the source mesh (render vertices as loaded, seams split).
    pub input_vertices: u64,
    /// Vertices after welding positions: the topology vertices.
    pub welded_vertices: u64,
    /// Triangles in the source mesh after triangulating polygons.
    pub input_triangles: u64,
    /// Triangles skipped because they repeat a vertex or have zero area.
    pub degenerate_triangles: u64,
    /// Edge classes.
    pub edges: EdgeStats,
    /// Chamfer radii.
    pub chamfer: ChamferStats,
}

/// The asset's header: provenance, bounds, statistics and the section table.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// File name of the source mesh.
    pub source: String,
    /// The program and version that baked the asset.
    pub generator: String,
    /// The bake settings, as `(name, value)` pairs, for provenance.
    pub settings: Vec<(String, String)>,
    /// Minimum corner of the bounding box of the topology positions.
    pub bounds_min: [f32; 3],
    /// Maximum corner of the bounding box of the topology positions.
    pub bounds_max: [f32; 3],
    /// Radii in [`SectionKind::EdgeAttributes`] are multiples of this (the largest radius, or 0).
    pub radius_scale: f32,
    /// What the bake counted.
    pub stats: Stats,
    /// Where each section lies; filled in by [`Asset::encode`].
    pub sections: Vec<SectionEntry>,
}

/// A decoded, validated edge asset.
///
/// Build one in a baker and [`encode`](Asset::encode) it, or [`decode`](Asset::decode) a file's bytes.
/// Every section is a plain array ready for `queue.write_buffer` (see the `*_bytes` methods).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Asset {
    /// Provenance and statistics; its section table is rewritten on encode.
    pub header: Header,
    /// Render vertex positions.
    pub render_positions: Vec<[f32; 3]>,
    /// Render vertex normals, unit length, split at creases.
    pub render_normals: Vec<[f32; 3]>,
    /// Triangles as render vertex indices, three per triangle.
    pub mesh_indices: Indices,
    /// Welded positions the edges refer to.
    pub topology_positions: Vec<[f32; 3]>,
    /// `v0 v1 v2 v3` per edge, topology vertex indices.
    pub edge_vertices: Indices,
    /// Flags and radius per edge.
    pub edge_attributes: Vec<u32>,
    /// Next edge end around the vertex, per edge end; empty if not baked.
    pub next_ends: Indices,
    /// First edge end of each capped vertex's ring; empty if not baked.
    pub cap_heads: Indices,
    /// Intersection edges as segments (two end points each), polyline after polyline; empty if not
    /// baked or none were found. Read them through [`intersection_polylines`](Self::intersection_polylines).
    pub intersection_segments: Vec<[[f32; 3]; 2]>,
    /// Index into [`intersection_segments`](Self::intersection_segments) of each polyline's first segment.
    pub intersection_starts: Vec<u32>,
    /// One cluster per 64 edges, in edge order ([`clusters::edge_clusters`]). [`decode`](Self::decode)
    /// fills it; an asset built in code may leave it empty, and [`encode`](Self::encode) and the
    /// renderer then compute it (see [`clusters`](Self::clusters)).
    pub edge_clusters: Vec<EdgeCluster>,
    /// Skinning, morph targets and animations; empty for a still asset.
    pub motion: Motion,
}

impl Asset {
    /// Number of triangles in the render mesh.
    pub fn triangle_count(&self) -> usize {
        self.mesh_indices.len() / 3
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.edge_attributes.len()
    }

    /// The four topology vertices of edge `e`: `[v0, v1, v2, v3]`.
    pub fn edge(&self, e: usize) -> [u32; 4] {
        std::array::from_fn(|k| self.edge_vertices.get(4 * e + k))
    }

    /// The flags of edge `e`.
    pub fn edge_flags(&self, e: usize) -> EdgeFlags {
        attribute_flags(self.edge_attributes[e])
    }

    /// True if the mesh is closed: no edge is a boundary (every edge has two faces or more), so a
    /// section's cut faces can be filled. A non-manifold edge (CAD exports have a few slivers with
    /// three faces) still counts as closed: a cap's parity is then wrong only where the extra face
    /// is seen edge-on. One pass over the edges.
    pub fn is_closed(&self) -> bool {
        (0..self.edge_count()).all(|e| !self.edge_flags(e).contains(EdgeFlags::BOUNDARY))
    }

    /// The chamfer radius of edge `e`, in mesh units (0 if it has none).
    pub fn edge_radius(&self, e: usize) -> f32 {
        attribute_radius(self.edge_attributes[e], self.header.radius_scale)
    }

    /// The topology vertex at edge end `end` (`2 * edge + 0` is `v0`, `+ 1` is `v1`).
    pub fn end_vertex(&self, end: u32) -> u32 {
        self.edge_vertices
            .get(2 * end as usize - (end as usize & 1))
    }

    /// The intersection edges, one slice of chained segments per polyline (`s[k][1] == s[k + 1][0]`).
    ///
    /// They are view-independent like creases: a renderer can draw
    /// [`intersection_segments`](Self::intersection_segments) as one flat list of line segments
    /// (depth tested), using the polylines only where it joins consecutive segments.
    pub fn intersection_polylines(&self) -> impl ExactSizeIterator<Item = &[[[f32; 3]; 2]]> + '_ {
        let segments = &self.intersection_segments;
        let starts = &self.intersection_starts;
        (0..starts.len()).map(move |p| {
            let end = starts.get(p + 1).map_or(segments.len(), |&s| s as usize);
            &segments[starts[p] as usize..end]
        })
    }

    /// Total length of the intersection edges, in mesh units.
    pub fn intersection_length(&self) -> f64 {
        self.intersection_segments
            .iter()
            .map(|[a, b]| {
                let d: [f64; 3] = std::array::from_fn(|k| f64::from(b[k]) - f64::from(a[k]));
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
            })
            .sum::<f64>()
            + 0.0 // an empty sum is -0.0
    }

    /// The edge clusters: [`edge_clusters`](Self::edge_clusters) if it has one per 64 edges,
    /// otherwise computed from the edges.
    pub fn clusters(&self) -> std::borrow::Cow<'_, [EdgeCluster]> {
        if self.edge_clusters.len() == clusters::cluster_count(self.edge_count()) {
            std::borrow::Cow::Borrowed(&self.edge_clusters)
        } else {
            std::borrow::Cow::Owned(clusters::edge_clusters(self))
        }
    }

    /// The raw bytes of one section as held in memory (the clusters as stored, which
    /// [`encode`](Self::encode) replaces by [`clusters`](Self::clusters); the render positions, which
    /// it may replace by [`SectionKind::RenderVertexCounts`]). [`encoded_sections`](Self::encoded_sections)
    /// gives what the file holds.
    pub fn section_bytes(&self, kind: SectionKind) -> &[u8] {
        match kind {
            SectionKind::RenderPositions => bytemuck::cast_slice(&self.render_positions),
            SectionKind::RenderNormals => bytemuck::cast_slice(&self.render_normals),
            SectionKind::MeshIndices => self.mesh_indices.as_bytes(),
            SectionKind::TopologyPositions => bytemuck::cast_slice(&self.topology_positions),
            SectionKind::EdgeVertices => self.edge_vertices.as_bytes(),
            SectionKind::EdgeAttributes => bytemuck::cast_slice(&self.edge_attributes),
            SectionKind::NextEnds => self.next_ends.as_bytes(),
            SectionKind::CapHeads => self.cap_heads.as_bytes(),
            SectionKind::IntersectionSegments => bytemuck::cast_slice(&self.intersection_segments),
            SectionKind::IntersectionPolylines => bytemuck::cast_slice(&self.intersection_starts),
            SectionKind::EdgeClusters => bytemuck::cast_slice(&self.edge_clusters),
            SectionKind::SkinJoints
            | SectionKind::SkinWeights
            | SectionKind::MorphStarts
            | SectionKind::MorphVertices
            | SectionKind::MorphDeltas => self.motion.section_bytes(kind),
            // Derived when encoding, never held.
            SectionKind::RenderVertexCounts
            | SectionKind::MeshIndicesCoded
            | SectionKind::TopologyPositionsCoded
            | SectionKind::RenderNormalsCoded
            | SectionKind::EdgeCorners
            | SectionKind::EdgeAttributesCoded
            | SectionKind::RingOrders
            | SectionKind::RenderVertexCountsCoded
            | SectionKind::EdgeClustersCoded
            | SectionKind::Rig => &[],
        }
    }
}

#[cfg(test)]
mod tests;
