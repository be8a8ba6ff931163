//! How much work one input file may ask for: the bounds that keep a hostile file (a node graph that
//! lists each child twice, a PLY header claiming 2⁶⁴ elements, a small `.gz` that inflates to
//! gigabytes) from taking unbounded time or memory. Loaders check them against the counts a file
//! declares *before* allocating or looping over those counts.
//!
//! The defaults fit a 10-million-triangle model several times over; raise them for bigger inputs.

use std::path::Path;

use crate::Error;

/// Bounds on what a loader will read. Start from [`Limits::DEFAULT`] and change fields with the
/// `with_*` setters; [`BakeOptions::limits`](crate::BakeOptions::limits) carries them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Limits {
    /// Triangles after fanning polygons and expanding glTF instances. Default 2²⁶ (67,108,864).
    pub max_triangles: u64,
    /// Vertices as loaded (before welding), all glTF and 3MF instances counted. Default 2²⁶.
    pub max_vertices: u64,
    /// Mesh instances: each glTF primitive once per node that draws its mesh, each 3MF mesh object
    /// once per build item and component that places it, counted through the whole node graph or
    /// build before anything is expanded. Default 2²⁰ (1,048,576).
    pub max_instances: u64,
    /// Bytes of one input file after inflating `.gz`, and of each file it refers to (`.mtl`,
    /// glTF buffers). Default 2³¹ (2 GiB).
    pub max_input_bytes: u64,
    /// Joints of the skins a glTF's drawn meshes are bound to, all skins and every joint that
    /// moves a rigid part counted. Default 2¹² (4,096); an asset holds at most 2¹⁶.
    pub max_joints: u64,
}

impl Limits {
    /// 64 Mi triangles and vertices, 1 Mi instances, 2 GiB per file, 4 Ki joints.
    pub const DEFAULT: Self = Self {
        max_triangles: 1 << 26,
        max_vertices: 1 << 26,
        max_instances: 1 << 20,
        max_input_bytes: 1 << 31,
        max_joints: 1 << 12,
    };

    /// No bound at all: for inputs that are trusted and known to be large.
    pub const NONE: Self = Self {
        max_triangles: u64::MAX,
        max_vertices: u64::MAX,
        max_instances: u64::MAX,
        max_input_bytes: u64::MAX,
        max_joints: u64::MAX,
    };

    /// Sets [`max_triangles`](Self::max_triangles).
    pub fn with_max_triangles(self, max_triangles: u64) -> Self {
        Self {
            max_triangles,
            ..self
        }
    }

    /// Sets [`max_vertices`](Self::max_vertices).
    pub fn with_max_vertices(self, max_vertices: u64) -> Self {
        Self {
            max_vertices,
            ..self
        }
    }

    /// Sets [`max_instances`](Self::max_instances).
    pub fn with_max_instances(self, max_instances: u64) -> Self {
        Self {
            max_instances,
            ..self
        }
    }

    /// Sets [`max_input_bytes`](Self::max_input_bytes).
    pub fn with_max_input_bytes(self, max_input_bytes: u64) -> Self {
        Self {
            max_input_bytes,
            ..self
        }
    }

    /// Sets [`max_joints`](Self::max_joints).
    pub fn with_max_joints(self, max_joints: u64) -> Self {
        Self { max_joints, ..self }
    }

    /// [`Error::LimitExceeded`] naming `path` if `count` is over the bound on `what`.
    pub(crate) fn check(&self, path: &Path, what: Limited, count: u64) -> Result<(), Error> {
        let limit = match what {
            Limited::Triangles => self.max_triangles,
            Limited::Vertices => self.max_vertices,
            Limited::Instances => self.max_instances,
            Limited::InputBytes => self.max_input_bytes,
            Limited::Joints => self.max_joints,
        };
        if count > limit {
            Err(Error::LimitExceeded {
                path: path.to_owned(),
                what,
                count,
                limit,
            })
        } else {
            Ok(())
        }
    }
}

impl Default for Limits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Which of the [`Limits`] a file ran into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limited {
    /// [`Limits::max_triangles`].
    Triangles,
    /// [`Limits::max_vertices`].
    Vertices,
    /// [`Limits::max_instances`].
    Instances,
    /// [`Limits::max_input_bytes`].
    InputBytes,
    /// [`Limits::max_joints`].
    Joints,
}

impl Limited {
    /// What is counted, in words ("triangles").
    pub const fn noun(self) -> &'static str {
        match self {
            Self::Triangles => "triangles",
            Self::Vertices => "vertices",
            Self::Instances => "mesh instances",
            Self::InputBytes => "bytes",
            Self::Joints => "joints",
        }
    }

    /// The `chamfer` flag that raises it.
    pub const fn flag(self) -> &'static str {
        match self {
            Self::Triangles => "--max-triangles",
            Self::Vertices => "--max-vertices",
            Self::Instances => "--max-instances",
            Self::InputBytes => "--max-input-bytes",
            Self::Joints => "--max-joints",
        }
    }
}
