//! Annotate: write a mesh back out in its own format with its marked and chamfer edges embedded, so
//! artists and other tools can read and edit them (`chamfer annotate`).
//!
//! The mesh is baked with the given options (file marks first, then the radius rule, then clamping),
//! and every edge that ends up marked or chamfered is written:
//! - PLY: every element and property of the input is kept; an `edge` element
//!   (`vertex1 vertex2 radius class`) replaces any existing one. `class` is the edge's
//!   [`EdgeFlags`] bits; `radius` 0 means marked without a chamfer.
//! - glTF / GLB: each triangle primitive's `extras` gains `"chamfer": {"version": 1, "edges":
//!   [[a, b, radius], ...]}` in that primitive's vertex indices (other extras keys are kept); the rest
//!   of the JSON keeps its content and key order, and buffers are not touched (a GLB's binary chunk is
//!   copied byte for byte).
//!
//! Reading the output back gives the same marks and radii.

mod gltf;
mod ply;

use std::collections::HashMap;
use std::path::Path;

use chamfer_runtime::asset::{Asset, EdgeFlags};

use crate::load::{self, Format, format_of};
use crate::write::ensure_not_an_input;
use crate::{BakeOptions, Error, bake, weld};

/// What [`annotate`] wrote.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Annotated {
    /// Marked or chamfer edges written.
    pub edges: usize,
    /// What the loader skipped.
    pub warnings: Vec<String>,
}

/// Writes `input` to `output` (same format) with its marked and chamfer edges embedded.
///
/// The output is written to a temporary file and renamed; `input` is never modified, and naming it
/// as the output is an error.
pub fn annotate(input: &Path, output: &Path, options: &BakeOptions) -> Result<Annotated, Error> {
    options.validate()?;
    let format = format_of(input).ok_or_else(|| Error::UnknownFormat {
        path: input.to_owned(),
    })?;
    let same_format = format_of(output) == Some(format)
        && (format != Format::Gltf || extension(input) == extension(output));
    if !same_format {
        return Err(Error::Unsupported {
            path: output.to_owned(),
            what: format!(
                "annotate writes the input's own format: name the output like {}",
                input.display()
            ),
        });
    }
    ensure_not_an_input(output, &[input])?;
    let bytes = load::read(input, &options.limits)?;
    let mut warnings = Vec::new();
    let mut spans = Vec::new();
    let mesh = match format {
        Format::Gltf => {
            load::gltf::parse_with_spans(input, &bytes, &options.limits, &mut warnings, &mut spans)?
        }
        _ => {
            let loaded = load::load_bytes(input, &bytes, &options.limits)?;
            warnings = loaded.warnings;
            loaded.mesh
        }
    };
    mesh.validate().map_err(|source| Error::Mesh {
        path: input.to_owned(),
        source,
    })?;
    // The bake welds with the same function and options, so this remap is its vertex numbering.
    let remap = weld::weld(&mesh.positions, options.weld_epsilon).remap;
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
    let marked = MarkedEdges::of(&baked.asset, &baked.radii);
    let edges = match format {
        Format::Ply => ply::write(input, &bytes, output, &marked, &remap)?,
        Format::Gltf => gltf::write(input, &bytes, output, &marked, &remap, &triangles, &spans)?,
        Format::Obj => {
            return Err(Error::Unsupported {
                path: input.to_owned(),
                what: "OBJ has no place for edge data: convert to PLY or glTF to annotate".into(),
            });
        }
    };
    Ok(Annotated { edges, warnings })
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
