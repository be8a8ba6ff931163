//! Loaders: OBJ (tobj), glTF 2.0 / GLB (gltf), PLY (ply-rs-bw), STL (our own bulk reader) and 3MF
//! (zip + quick-xml) into one [`Mesh`].
//!
//! Every loader reads the whole file, checks what it reads, and reports problems as
//! [`Error`]s naming the file. Loaders never modify their input, read only regular files, read
//! files an input refers to only inside the input's folder (`files.rs`), and check the counts a file
//! declares against [`Limits`] before allocating or looping over them.

pub(crate) mod files;

pub use files::Companions;
pub(crate) mod gltf;
mod obj;
pub(crate) mod ply;
mod ply_ascii;
mod ply_bulk;
pub(crate) mod ply_header;
mod stl;
mod threemf;

use std::path::Path;

use glam::Mat4;

use crate::mesh::Mesh;
use crate::motion::InputMotion;
use crate::{Error, Limits};

/// The mesh formats this crate reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// glTF 2.0, JSON (`.gltf`) or binary (`.glb`).
    Gltf,
    /// Stanford PLY, ASCII or binary (`.ply`, or gzip-compressed `.ply.gz`).
    Ply,
    /// STL, binary or ASCII (`.stl`, or gzip-compressed `.stl.gz`): a triangle soup.
    Stl,
    /// 3MF (`.3mf`): a zip package of objects, components and build items.
    ThreeMf,
}

impl Format {
    /// The format's name in messages ("OBJ", "glTF", ...).
    pub const fn name(self) -> &'static str {
        match self {
            Self::Obj => "OBJ",
            Self::Gltf => "glTF",
            Self::Ply => "PLY",
            Self::Stl => "STL",
            Self::ThreeMf => "3MF",
        }
    }
}

/// The format a path's extension names, if any (case-insensitive).
pub fn format_of(path: &Path) -> Option<Format> {
    let name = path.file_name()?.to_string_lossy().to_ascii_lowercase();
    let name = name.strip_suffix(".gz").unwrap_or(&name);
    match Path::new(name).extension()?.to_str()? {
        "obj" => Some(Format::Obj),
        "gltf" | "glb" => Some(Format::Gltf),
        "ply" => Some(Format::Ply),
        "stl" => Some(Format::Stl),
        "3mf" => Some(Format::ThreeMf),
        _ => None,
    }
}

/// A loaded mesh and what the loader had to skip or ignore.
#[derive(Clone, Debug, Default)]
pub struct Loaded {
    /// The mesh, validated.
    pub mesh: Mesh,
    /// Things the file holds that were skipped (line primitives, unknown required extensions, ...).
    pub warnings: Vec<String>,
    /// What moves the mesh (a glTF's skins, morph targets and animations); `None` for a still one.
    pub motion: Option<InputMotion>,
}

/// Loads a mesh file, choosing the loader by extension, and validates it.
pub fn load(path: &Path, limits: &Limits) -> Result<Loaded, Error> {
    format_of(path).ok_or_else(|| Error::UnknownFormat {
        path: path.to_owned(),
    })?;
    load_bytes(path, &read(path, limits)?, limits)
}

/// Parses a mesh already in memory; `path` picks the format and resolves files it refers to
/// (an OBJ's `.mtl`, a `.gltf`'s buffers). `bytes` must already be inflated if the name ends in `.gz`.
pub fn load_bytes(path: &Path, bytes: &[u8], limits: &Limits) -> Result<Loaded, Error> {
    load_bytes_with(path, bytes, Companions::Folder, limits)
}

/// [`load_bytes`], reading the files the mesh refers to from `companions`.
pub fn load_bytes_with(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    limits: &Limits,
) -> Result<Loaded, Error> {
    let format = format_of(path).ok_or_else(|| Error::UnknownFormat {
        path: path.to_owned(),
    })?;
    let mut warnings = Vec::new();
    let mut motion = None;
    let mesh = match format {
        Format::Obj => obj::parse(path, bytes, companions, limits, &mut warnings)?,
        Format::Gltf => {
            let (mesh, moves) = gltf::parse(path, bytes, companions, limits, &mut warnings)?;
            motion = moves;
            mesh
        }
        Format::Ply => ply::parse(path, bytes, limits, &mut warnings)?,
        Format::Stl => stl::parse(path, bytes, limits, &mut warnings)?,
        Format::ThreeMf => threemf::parse(path, bytes, limits, &mut warnings)?,
    };
    mesh.validate().map_err(|source| Error::Mesh {
        path: path.to_owned(),
        source,
    })?;
    Ok(Loaded {
        mesh,
        warnings,
        motion,
    })
}

/// The meshes of a file that keeps them apart (a glTF node graph, a 3MF build), each in its own
/// space, and their instances: what `bake --scene` bakes.
#[derive(Debug)]
pub(crate) struct SceneMeshes {
    /// (the mesh's number in the file (a glTF mesh index, a 3MF object id), the mesh in its own
    /// space, what it holds when it has no triangles: "points", "lines" or "points and lines").
    pub(crate) meshes: Vec<(usize, Mesh, Option<&'static str>)>,
    /// (index into `meshes`, world transform).
    pub(crate) instances: Vec<(usize, Mat4)>,
}

/// Parses the meshes and instances of a glTF/GLB or 3MF file in memory; `None` for other formats.
pub(crate) fn parse_scene(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Option<Result<SceneMeshes, Error>> {
    match format_of(path)? {
        Format::Gltf => Some(gltf::parse_scene(path, bytes, companions, limits, warnings)),
        Format::ThreeMf => Some(threemf::parse_scene(path, bytes, limits, warnings)),
        _ => None,
    }
}

/// Reads an input file (a mesh, or an asset): only a regular file, never a FIFO or device, at most
/// `limits.max_input_bytes`, inflated as a stream if its name ends in `.gz`. A PLY's declared counts
/// are checked against `limits` as soon as its header has been inflated; a binary STL's count too,
/// and its inflating stops as soon as it passes the length that count gives.
pub fn read(path: &Path, limits: &Limits) -> Result<Vec<u8>, Error> {
    files::read_input(path, limits, &|prefix| check_header(path, prefix, limits))
}

/// [`read`] for a file already in memory, named `path`: the same limits and checks, inflated if
/// the name ends in `.gz` (other files are borrowed, not copied).
pub fn read_bytes<'a>(
    path: &Path,
    bytes: &'a [u8],
    limits: &Limits,
) -> Result<std::borrow::Cow<'a, [u8]>, Error> {
    files::input_bytes(path, bytes, limits, &|prefix| {
        check_header(path, prefix, limits)
    })
}

/// Checks the counts a header declares from the first inflated bytes of a `.gz`: `Ok(true)` once
/// it has seen enough.
fn check_header(path: &Path, prefix: &[u8], limits: &Limits) -> Result<bool, Error> {
    match format_of(path) {
        Some(Format::Ply) => ply_header::check_stream_prefix(path, prefix, limits),
        Some(Format::Stl) => stl::check_stream_prefix(path, prefix, limits),
        _ => Ok(true),
    }
}

/// Splits a polygon into a triangle fan, the convention of OBJ and PLY readers (trimesh, tobj).
pub(crate) fn fan(polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    for i in 2..polygon.len() {
        out.push([polygon[0], polygon[i - 1], polygon[i]]);
    }
}
