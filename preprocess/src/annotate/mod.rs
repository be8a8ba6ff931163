//! Annotate: write a mesh back out with its marked and chamfer edges embedded, so artists and other
//! tools can read and edit them (`chamfer annotate`).
//!
//! The mesh is baked with the given options (file marks first, then the radius rule, then clamping),
//! and its edges are written:
//! - PLY: every element and property of the input is kept, byte for byte; an `edge` element
//!   (`vertex1 vertex2 radius class`) replaces any existing one and lists every marked or chamfer
//!   edge. `class` is the edge's [`EdgeFlags`] bits; `radius` 0 means marked without a chamfer.
//! - glTF / GLB, in the dialects [`GltfEdges`] picks:
//!   - `extras.chamfer` (default): each triangle primitive's `extras` gains `"chamfer": {"version":
//!     1, "edges": [[a, b, radius], ...]}`, the marked or chamfer edges in that primitive's vertex
//!     indices (other extras keys are kept);
//!   - `EXT_mesh_primitive_edge_visibility`: 2 bits per triangle edge: every edge the bake always
//!     draws ([`EdgeFlags::STATIC`]: creases, boundaries, marks, material seams, non-manifold) is
//!     hard (2 at its first occurrence in the primitive, 3 after), every kept smooth edge is a
//!     silhouette (1 once, then 0) with its two faces' normals in `silhouetteNormals` (normalized
//!     bytes), coplanar edges are hidden (0);
//!   - `CESIUM_primitive_outline`: the same hard edges as index pairs (TRIANGLES primitives only).
//!
//!   Occurrences are counted by welded position, so an edge split by a normal or UV seam is one edge.
//!   The rest of the JSON keeps its content and key order. Without the extensions buffers are not
//!   touched (a GLB's binary chunk is copied byte for byte); with them their data is appended: to a
//!   GLB's binary chunk (earlier bytes unchanged), or as a new embedded buffer of a `.gltf`. The
//!   buffer and image files the input names by `uri` are copied beside an output in another
//!   folder, so it reads back (a file there with other bytes is an error, never replaced).
//! - OBJ, STL and 3MF have nowhere to keep edges: they are written as a new PLY (vertices, triangles) or glTF /
//!   GLB (one primitive per material), chosen by the output's extension, then annotated as above.
//!
//! Reading the output back gives the same marks and radii (`extras.chamfer` wins over the
//! extensions when a primitive has both: `load/gltf/marks.rs`); the
//! extensions alone read back as marks on exactly the hard edges.

mod companions;
mod convert;
mod gltf;
mod ply;

use std::collections::HashMap;
use std::path::Path;

use chamfer_runtime::asset::{Asset, EdgeFlags};
use glam::Vec3;

use crate::load::files::Companions;
use crate::load::{self, Format, format_of};
use crate::write::ensure_not_an_input;
use crate::{BakeOptions, Error, bake};

/// What [`annotate`] wrote.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Annotated {
    /// Marked or chamfer edges written (PLY `edge` elements, glTF `extras.chamfer` entries).
    pub edges: usize,
    /// Hard edges written to `EXT_mesh_primitive_edge_visibility` or `CESIUM_primitive_outline`
    /// (once per primitive that has them).
    pub hard_edges: usize,
    /// Silhouette edges written to `EXT_mesh_primitive_edge_visibility` (once per primitive).
    pub silhouette_edges: usize,
    /// What the loader skipped, extensions that did not apply to a primitive, and images that
    /// could not be copied.
    pub warnings: Vec<String>,
    /// The buffer and image files the output refers to, copied beside it (a `.gltf` written to
    /// another folder than its input's; empty otherwise).
    pub copied: Vec<std::path::PathBuf>,
}

/// Which glTF dialects [`annotate_with`] writes. Start from [`GltfEdges::DEFAULT`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct GltfEdges {
    /// `extras.chamfer`: marks and radii, what Chamfer reads back. Default true.
    pub extras: bool,
    /// `EXT_mesh_primitive_edge_visibility`: hard and silhouette edges. Default false.
    pub edge_visibility: bool,
    /// `CESIUM_primitive_outline`: hard edges as index pairs. Default false.
    pub primitive_outline: bool,
}

impl GltfEdges {
    /// `extras.chamfer` only.
    pub const DEFAULT: Self = Self {
        extras: true,
        edge_visibility: false,
        primitive_outline: false,
    };

    /// Sets [`extras`](Self::extras).
    pub fn with_extras(self, extras: bool) -> Self {
        Self { extras, ..self }
    }

    /// Sets [`edge_visibility`](Self::edge_visibility).
    pub fn with_edge_visibility(self, edge_visibility: bool) -> Self {
        Self {
            edge_visibility,
            ..self
        }
    }

    /// Sets [`primitive_outline`](Self::primitive_outline).
    pub fn with_primitive_outline(self, primitive_outline: bool) -> Self {
        Self {
            primitive_outline,
            ..self
        }
    }

    fn extensions(self) -> bool {
        self.edge_visibility || self.primitive_outline
    }
}

impl Default for GltfEdges {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Writes `input` to `output` with its marked and chamfer edges embedded, in `extras.chamfer` for
/// glTF ([`annotate_with`] picks other dialects).
///
/// A PLY or glTF is written in its own format; an OBJ, STL or 3MF as a PLY, glTF or GLB, as
/// `output` is named.
/// The output is written to a temporary file and renamed; `input` is never modified, and naming it
/// as the output is an error.
pub fn annotate(input: &Path, output: &Path, options: &BakeOptions) -> Result<Annotated, Error> {
    annotate_with(input, output, options, &GltfEdges::DEFAULT)
}

/// [`annotate`], writing the glTF dialects `dialects` names.
pub fn annotate_with(
    input: &Path,
    output: &Path,
    options: &BakeOptions,
    dialects: &GltfEdges,
) -> Result<Annotated, Error> {
    options.validate()?;
    let input_format = format_of(input).ok_or_else(|| Error::UnknownFormat {
        path: input.to_owned(),
    })?;
    let output_format = format_of(output);
    let usage = |what: String| Error::Unsupported {
        path: output.to_owned(),
        what,
    };
    let converted = !matches!(input_format, Format::Ply | Format::Gltf);
    let format = match (input_format, output_format) {
        (_, Some(out @ (Format::Ply | Format::Gltf))) if converted => out,
        _ if converted => {
            return Err(usage(format!(
                "{} has no place for edge data: name the output .ply, .glb or .gltf",
                input_format.name()
            )));
        }
        (format, Some(out))
            if out == format
                && (format != Format::Gltf || extension(input) == extension(output)) =>
        {
            format
        }
        _ => {
            return Err(usage(format!(
                "annotate writes the input's own format: name the output like {}",
                input.display()
            )));
        }
    };
    if format == Format::Ply && dialects.extensions() {
        return Err(usage(
            "EXT_mesh_primitive_edge_visibility and CESIUM_primitive_outline are glTF extensions; \
             a PLY keeps its edges in an edge element"
                .into(),
        ));
    }
    if format == Format::Gltf && !dialects.extras && !dialects.extensions() {
        return Err(usage(
            "no glTF edge dialect chosen: nothing to write".into(),
        ));
    }
    ensure_not_an_input(output, &[input])?;
    let mut warnings = Vec::new();
    let source = load::read(input, &options.limits)?;
    // An OBJ, STL or 3MF is first converted, in memory, to the output's format; the rest reads that.
    let bytes = if converted {
        let loaded = load::load_bytes(input, &source, &options.limits)?;
        warnings = loaded.warnings;
        let convert_error = |message: String| Error::Parse {
            path: input.to_owned(),
            format: input_format.name(),
            message,
        };
        match format {
            Format::Ply => convert::to_ply(&loaded.mesh).map_err(convert_error)?,
            _ => convert::to_gltf(&loaded.mesh, extension(output).as_deref() == Some("glb"))
                .map_err(convert_error)?,
        }
    } else {
        source
    };
    let mut spans = Vec::new();
    let mesh = match format {
        Format::Gltf => load::gltf::parse_with_spans(
            input,
            &bytes,
            Companions::Folder,
            &options.limits,
            &mut warnings,
            &mut spans,
        )?,
        _ => load::ply::parse(input, &bytes, &options.limits, &mut warnings)?,
    };
    mesh.validate().map_err(|source| Error::Mesh {
        path: input.to_owned(),
        source,
    })?;
    let name = input.file_name().map_or_else(
        || input.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let triangles = mesh.triangles.clone();
    let baked = bake(mesh, &name, options).map_err(|e| match e {
        Error::Mesh { source, .. } => Error::Mesh {
            path: input.to_owned(),
            source,
        },
        other => other,
    })?;
    let remap = &baked.input_vertex_map;
    let marked = MarkedEdges::of(&baked.asset, &baked.radii);
    let mut annotated = match format {
        Format::Ply => Annotated {
            edges: ply::write(input, &bytes, output, &marked, remap)?,
            ..Annotated::default()
        },
        _ => {
            let kinds = (dialects.extensions()).then(|| EdgeKinds::of(&baked.asset));
            let baked_edges = gltf::BakedEdges {
                marked: &marked,
                kinds: kinds.as_ref(),
                remap,
                triangles: &triangles,
                spans: &spans,
            };
            gltf::write(
                input,
                &bytes,
                output,
                &baked_edges,
                dialects,
                options.limits.max_input_bytes,
            )?
        }
    };
    warnings.append(&mut annotated.warnings);
    annotated.warnings = warnings;
    Ok(annotated)
}

fn extension(path: &Path) -> Option<String> {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

/// The asset's marked or chamfer edges by welded vertex pair.
struct MarkedEdges {
    by_pair: HashMap<(u32, u32), (EdgeFlags, f32)>,
    /// In asset order: (v0, v1, flags, radius).
    list: Vec<(u32, u32, EdgeFlags, f32)>,
}

impl MarkedEdges {
    /// `radii` are the exact radii per asset edge (or empty), so no f16 rounding reaches the file.
    fn of(asset: &Asset, radii: &[f32]) -> Self {
        let list: Vec<_> = (0..asset.edge_count())
            .filter(|&e| {
                asset
                    .edge_flags(e)
                    .intersects(EdgeFlags::MARKED | EdgeFlags::CHAMFER)
            })
            .map(|e| {
                let [v0, v1, ..] = asset.edge(e);
                (
                    v0,
                    v1,
                    asset.edge_flags(e),
                    radii.get(e).copied().unwrap_or(0.0),
                )
            })
            .collect();
        let by_pair = list
            .iter()
            .map(|&(a, b, f, r)| ((a.min(b), a.max(b)), (f, r)))
            .collect();
        Self { by_pair, list }
    }

    fn get(&self, a: u32, b: u32) -> Option<(EdgeFlags, f32)> {
        self.by_pair.get(&(a.min(b), a.max(b))).copied()
    }
}

/// What the glTF extensions say about a welded edge.
#[derive(Clone, Copy, Debug, PartialEq)]
enum EdgeKind {
    /// Drawn from every camera ([`EdgeFlags::STATIC`] or a chamfer).
    Hard,
    /// A kept smooth edge between two faces, drawn where it is a contour: the faces' unit normals.
    Silhouette([Vec3; 2]),
}

/// Every kept edge of the asset by welded vertex pair.
struct EdgeKinds(HashMap<(u32, u32), EdgeKind>);

impl EdgeKinds {
    fn of(asset: &Asset) -> Self {
        let position = |v: u32| Vec3::from(asset.topology_positions[v as usize]);
        let kinds = (0..asset.edge_count())
            .map(|e| {
                let v = asset.edge(e);
                let flags = asset.edge_flags(e);
                let kind =
                    if flags.intersects(EdgeFlags(EdgeFlags::STATIC.0 | EdgeFlags::CHAMFER.0)) {
                        EdgeKind::Hard
                    } else {
                        // Face a is (v0 v1 v2); face b holds v1 v0 v3, wound the other way unless FLIPPED.
                        let p = v.map(position);
                        let a = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
                        let b = (p[3] - p[0]).cross(p[1] - p[0]).normalize_or_zero();
                        let b = if flags.contains(EdgeFlags::FLIPPED) {
                            -b
                        } else {
                            b
                        };
                        EdgeKind::Silhouette([a, b])
                    };
                ((v[0].min(v[1]), v[0].max(v[1])), kind)
            })
            .collect();
        Self(kinds)
    }

    fn get(&self, a: u32, b: u32) -> Option<EdgeKind> {
        self.0.get(&(a.min(b), a.max(b))).copied()
    }
}
