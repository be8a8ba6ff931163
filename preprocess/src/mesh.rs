//! The in-memory mesh every loader produces and the bake consumes.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// An edge marked in the source file, by two vertex indices of [`Mesh::positions`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mark {
    /// The edge's two vertices (order is irrelevant).
    pub vertices: [u32; 2],
    /// The chamfer radius in mesh units, if the file gives one.
    pub radius: Option<f32>,
}

/// A triangle mesh as loaded: render vertices (seams split, as the file has them), triangles,
/// a material id per triangle, and marked edges.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// One position per render vertex.
    pub positions: Vec<Vec3>,
    /// Per-vertex normals, if the file has them (the bake computes its own split normals).
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates, if the file has them.
    pub uvs: Option<Vec<Vec2>>,
    /// Triangles as indices into `positions`, in the file's winding.
    pub triangles: Vec<[u32; 3]>,
    /// Material (or glTF primitive material) of each triangle: one per triangle, or empty when the
    /// whole mesh has one material.
    pub materials: Vec<u32>,
    /// Edges marked in the file.
    pub marks: Vec<Mark>,
}

/// The bounding box of `positions`: (min, max) corners; (+inf, -inf) when there are none.
pub(crate) fn bounds(positions: &[Vec3]) -> (Vec3, Vec3) {
    positions
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        })
}

/// The index of the first item for which `pred` holds, in parallel over blocks: rayon's
/// `position_first` per item costs ~10 ns an item in its bookkeeping (a third of loading a binary
/// STL, BENCHMARKS.md "STL and 3MF"), a block scan almost nothing.
pub(crate) fn first_where<T: Sync>(items: &[T], pred: impl Fn(&T) -> bool + Sync) -> Option<usize> {
    const BLOCK: usize = 1 << 14;
    let block = items
        .par_chunks(BLOCK)
        .position_first(|b| b.iter().any(&pred))?;
    let within = items[block * BLOCK..].iter().position(pred)?;
    Some(block * BLOCK + within)
}

/// The first position with a coordinate that is not a finite number: (vertex, axis 0-2, value).
/// The loaders name it in the file's own terms (a PLY property, an OBJ line).
pub(crate) fn first_non_finite(positions: &[Vec3]) -> Option<(usize, usize, f32)> {
    let vertex = first_where(positions, |p| !p.is_finite())?;
    let position = positions[vertex].to_array();
    let axis = position.iter().position(|c| !c.is_finite())?;
    Some((vertex, axis, position[axis]))
}

/// What makes a mesh unusable; the loaders add the file name.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum MeshError {
    /// No triangles at all.
    #[error("the mesh has no triangles")]
    Empty,
    /// Every triangle repeats a vertex or has zero area.
    #[error("all {count} triangles are degenerate (repeated vertices or zero area)")]
    AllDegenerate {
        /// How many triangles there were.
        count: usize,
    },
    /// A position with a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite position {position:?}")]
    NonFinitePosition {
        /// The vertex.
        vertex: usize,
        /// Its coordinates.
        position: [f32; 3],
    },
    /// A triangle refers to a vertex that does not exist.
    #[error(
        "triangle {triangle} refers to vertex {index}, but there are only {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The bad index.
        index: u32,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A marked edge refers to a vertex that does not exist.
    #[error(
        "marked edge {mark} refers to vertex {index}, but there are only {vertex_count} vertices"
    )]
    MarkOutOfRange {
        /// The mark.
        mark: usize,
        /// The bad index.
        index: u32,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A marked edge's radius is negative, NaN or infinite.
    #[error("marked edge {mark} has radius {radius}, which is not a finite non-negative number")]
    BadRadius {
        /// The mark.
        mark: usize,
        /// The radius.
        radius: f32,
    },
    /// Attribute arrays of different lengths.
    #[error("{what} has {found} entries but the mesh has {expected}")]
    LengthMismatch {
        /// The attribute.
        what: &'static str,
        /// Its length.
        found: usize,
        /// The length it must have.
        expected: usize,
    },
    /// More kept edges meet at one vertex than the runtime's join walk follows
    /// ([`MAX_RING`](chamfer_runtime::asset::MAX_RING)); the asset would not decode.
    #[error(
        "welded vertex {vertex} at ({}, {}, {}) has {ends} kept edge ends, more than the {limit} the runtime's join walk follows",
        position[0], position[1], position[2]
    )]
    RingTooLong {
        /// The welded vertex.
        vertex: u32,
        /// Its position.
        position: [f32; 3],
        /// Kept edge ends at it.
        ends: u64,
        /// The bound.
        limit: u32,
    },
    /// More vertices or triangles than 32-bit indices can address.
    #[error("{what} count {count} exceeds the limit of {limit}")]
    TooLarge {
        /// What overflowed.
        what: &'static str,
        /// How many there are.
        count: usize,
        /// The most allowed.
        limit: usize,
    },
}

/// The most vertices or triangles a mesh may have: corners are numbered in 31 bits.
pub const MAX_ELEMENTS: usize = (1 << 31) / 3;

impl Mesh {
    /// Checks everything the bake relies on: finite positions, indices in range, matching lengths.
    pub fn validate(&self) -> Result<(), MeshError> {
        let vertex_count = self.positions.len();
        for (what, count) in [("vertex", vertex_count), ("triangle", self.triangles.len())] {
            if count > MAX_ELEMENTS {
                return Err(MeshError::TooLarge {
                    what,
                    count,
                    limit: MAX_ELEMENTS,
                });
            }
        }
        if self.triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(vertex) = first_where(&self.positions, |p| !p.is_finite()) {
            let position = self.positions[vertex].to_array();
            return Err(MeshError::NonFinitePosition { vertex, position });
        }
        let out_of_range = |t: &[u32; 3]| t.iter().any(|&i| i as usize >= vertex_count);
        if let Some(triangle) = first_where(&self.triangles, out_of_range) {
            let t = self.triangles[triangle];
            if let Some(&index) = t.iter().find(|&&i| i as usize >= vertex_count) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertex_count,
                });
            }
        }
        for (mark, m) in self.marks.iter().enumerate() {
            if let Some(&index) = m.vertices.iter().find(|&&i| i as usize >= vertex_count) {
                return Err(MeshError::MarkOutOfRange {
                    mark,
                    index,
                    vertex_count,
                });
            }
            if let Some(radius) = m.radius.filter(|r| !r.is_finite() || *r < 0.0) {
                return Err(MeshError::BadRadius { mark, radius });
            }
        }
        let lengths = [
            (
                "materials",
                match self.materials.len() {
                    0 => self.triangles.len(),
                    n => n,
                },
                self.triangles.len(),
            ),
            (
                "normals",
                self.normals.as_ref().map_or(vertex_count, Vec::len),
                vertex_count,
            ),
            (
                "uvs",
                self.uvs.as_ref().map_or(vertex_count, Vec::len),
                vertex_count,
            ),
        ];
        for (what, found, expected) in lengths {
            if found != expected {
                return Err(MeshError::LengthMismatch {
                    what,
                    found,
                    expected,
                });
            }
        }
        Ok(())
    }

    /// Bytes the mesh occupies in memory (its arrays, not their spare capacity).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(self.positions.as_slice())
            + self.normals.as_deref().map_or(0, size_of_val)
            + self.uvs.as_deref().map_or(0, size_of_val)
            + size_of_val(self.triangles.as_slice())
            + size_of_val(self.materials.as_slice())
            + size_of_val(self.marks.as_slice())
    }

    /// Appends another mesh, offsetting its indices.
    pub fn append(&mut self, other: Mesh) {
        let base = self.positions.len() as u32;
        let (self_len, other_len) = (self.positions.len(), other.positions.len());
        merge_optional(
            &mut self.normals,
            other.normals,
            self_len,
            other_len,
            Vec3::ZERO,
        );
        merge_optional(&mut self.uvs, other.uvs, self_len, other_len, Vec2::ZERO);
        self.positions.extend(other.positions);
        // An empty material list means "all material 0": expand it only when the other side has one.
        if self.materials.is_empty() != other.materials.is_empty() {
            self.materials.resize(self.triangles.len(), 0);
        }
        if !self.materials.is_empty() && other.materials.is_empty() {
            self.materials
                .resize(self.triangles.len() + other.triangles.len(), 0);
        } else {
            self.materials.extend(other.materials);
        }
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
        self.marks.extend(other.marks.into_iter().map(|m| Mark {
            vertices: m.vertices.map(|i| i + base),
            ..m
        }));
    }
}

/// Concatenates optional per-vertex attributes, filling the side that lacks them.
fn merge_optional<T: Copy>(
    ours: &mut Option<Vec<T>>,
    theirs: Option<Vec<T>>,
    ours_len: usize,
    theirs_len: usize,
    fill: T,
) {
    match (ours.as_mut(), theirs) {
        (None, None) => {}
        (Some(a), Some(b)) => a.extend(b),
        (Some(a), None) => a.resize(ours_len + theirs_len, fill),
        (None, Some(b)) => {
            let mut a = vec![fill; ours_len];
            a.extend(b);
            *ours = Some(a);
        }
    }
}
