//! The library's one error type: every variant names the file and what is wrong with it.

use std::path::PathBuf;

use crate::limits::Limited;
use crate::mesh::MeshError;
use crate::options::OptionsError;

/// Why a load, bake or write failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The output could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The output file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not valid in its format.
    #[error("{}: invalid {format}: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// "OBJ", "glTF" or "PLY".
        format: &'static str,
        /// What the parser found.
        message: String,
    },
    /// The file is valid but uses something this loader does not support.
    #[error("{}: unsupported: {what}", path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// What is unsupported.
        what: String,
    },
    /// The file's extension is not a mesh format this crate reads.
    #[error("{}: unknown mesh format (expected .obj, .gltf, .glb, .ply, .stl or .3mf; .ply.gz and .stl.gz are inflated)", path.display())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// The mesh loaded but cannot be baked.
    #[error("{}: {source}", path.display())]
    Mesh {
        /// The file (or the name given to [`bake`](crate::bake)).
        path: PathBuf,
        /// What is wrong with the mesh.
        source: MeshError,
    },
    /// One mesh of a glTF scene (`bake --scene`) cannot be baked.
    #[error("{}: mesh {mesh}: {source}", path.display())]
    SceneMesh {
        /// The file.
        path: PathBuf,
        /// The glTF mesh's index.
        mesh: usize,
        /// What is wrong with that mesh.
        source: MeshError,
    },
    /// The bake options are out of range.
    #[error(transparent)]
    Options(#[from] OptionsError),
    /// Writing would replace one of the inputs.
    #[error("{}: output would overwrite an input file", path.display())]
    OutputIsInput {
        /// The path given as both.
        path: PathBuf,
    },
    /// The file asks for more than [`Limits`](crate::Limits) allow; nothing was allocated for it.
    #[error(
        "{}: needs at least {count} {}, more than the limit of {limit} (raise it with {} or Limits)",
        path.display(),
        what.noun(),
        what.flag()
    )]
    LimitExceeded {
        /// The file.
        path: PathBuf,
        /// Which limit.
        what: Limited,
        /// How many the file declares (or at least how many).
        count: u64,
        /// The limit.
        limit: u64,
    },
    /// A path names a FIFO, device, socket or directory where a regular file is needed; it was
    /// neither opened nor replaced.
    #[error("{}: is {kind}, not a regular file (left alone)", path.display())]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is ("a FIFO", "a character device", ...).
        kind: &'static str,
    },
    /// A file that the input refers to (an OBJ's `mtllib`, a glTF buffer `uri`) was refused.
    #[error("{}: {reference}: {problem}", path.display())]
    Reference {
        /// The input file.
        path: PathBuf,
        /// What it refers to and where ("material library '../a.mtl' on line 3").
        reference: String,
        /// Why it was not read ("resolves outside the file's folder", ...).
        problem: String,
    },
    /// Two inputs would be written to the same output.
    #[error("{} and {} would both be written to {}", first.display(), second.display(), output.display())]
    OutputClash {
        /// The first input.
        first: PathBuf,
        /// The second input.
        second: PathBuf,
        /// Their common output.
        output: PathBuf,
    },
}
