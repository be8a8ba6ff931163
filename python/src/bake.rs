//! Baking from Python: a file, a file's bytes, or vertex and face arrays, with the interpreter
//! released (other Python threads run while the bake does); and the per-file step of batch bakes.

use std::path::PathBuf;

use chamfer_preprocess::limits::Limited;
use chamfer_preprocess::mesh::Mesh;
use chamfer_preprocess::{Baked, Companions, Error, annotate as annotate_mesh, build};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::asset::PyAsset;
use crate::{arrays, errors, options};

fn asset_of(baked: Baked) -> PyAsset {
    PyAsset::new(baked.asset, None, baked.warnings)
}

/// Bakes a mesh file (.obj, .gltf, .glb, .ply, .stl, .3mf; .ply.gz, .stl.gz), or a file's bytes,
/// into an Asset.
///
/// `source` is a path (str or os.PathLike) or bytes; bytes need `name`, a file name whose
/// extension picks the format (`"part.glb"`; `.gz` bytes are inflated) and beside which files the
/// mesh refers to (an OBJ's .mtl, a .gltf's buffers) are looked for. The result is byte for byte
/// what `chamfer bake` writes with the same options (Asset.encode()).
///
/// Options (keywords, the `chamfer bake` flags with `_` for `-`; None leaves the default; from
/// chamfer.BAKE_SCHEMA, as chamfer.OPTIONS lists them):
/// {bake_keywords}
///
/// The interpreter is released while the file is read and baked. Raises ReadError, FormatError,
/// UnsupportedError, MeshError, LimitError or OptionsError (all ChamferError), each naming the
/// file and the problem.
#[pyfunction]
#[pyo3(signature = (source, *, name = None, **options))]
pub fn bake(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    name: Option<PathBuf>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyAsset> {
    let options = options::from_kwargs(options)?;
    let baked = if let Ok(bytes) = source.cast::<PyBytes>() {
        let name = name.ok_or_else(|| {
            errors::options(
                "bake(bytes) needs name=, a file name whose extension names the format".into(),
            )
        })?;
        let data = bytes.as_bytes();
        // Inflated first if `name` ends in `.gz`, within the input-bytes limit, as the file would be.
        py.detach(|| {
            chamfer_preprocess::bake_with_companions(&name, data, Companions::Folder, &options)
        })
    } else {
        let path: PathBuf = source.extract().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "bake() takes a path or bytes, not {}",
                source
                    .get_type()
                    .name()
                    .map_or_else(|_| "?".to_owned(), |n| n.to_string())
            ))
        })?;
        py.detach(|| chamfer_preprocess::bake_file(&path, &options))
    };
    baked.map(asset_of).map_err(errors::from_library)
}

/// Bakes a mesh given as arrays: `vertices` (N, 3) float32 or float64, `faces` (M, 3) integers
/// (any width; trimesh's int64 works as is). `name` names the mesh in the asset and in errors.
///
/// Gives the same edges as baking a file holding the same mesh. Options as for bake(); of the
/// limits, max_vertices and max_triangles apply. Raises ArrayError (wrong dtype or shape,
/// negative indices), MeshError (NaN positions, indices past the last vertex, no triangles),
/// LimitError or OptionsError. The interpreter is released while baking.
#[pyfunction]
#[pyo3(signature = (vertices, faces, *, name = "arrays", **options))]
pub fn bake_arrays(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    name: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyAsset> {
    let options = options::from_kwargs(options)?;
    let positions = arrays::positions(vertices, name)?;
    let triangles = arrays::triangles(faces, name)?;
    let limits = &options.limits;
    for (what, count, limit) in [
        (
            Limited::Vertices,
            positions.len() as u64,
            limits.max_vertices,
        ),
        (
            Limited::Triangles,
            triangles.len() as u64,
            limits.max_triangles,
        ),
    ] {
        if count > limit {
            return Err(errors::from_library(Error::LimitExceeded {
                path: name.into(),
                what,
                count,
                limit,
            }));
        }
    }
    let mesh = Mesh {
        positions,
        triangles,
        ..Mesh::default()
    };
    py.detach(|| chamfer_preprocess::bake(mesh, name, &options))
        .map(asset_of)
        .map_err(errors::from_library)
}

/// The bake settings the options give, as recorded in an asset (name -> value): checks the
/// options without baking anything (OptionsError if they are wrong). An asset's settings are
/// these plus what its bake recorded of its work: `stitch_boundary_before` (the boundary edges
/// stitching started from) when stitching is on.
#[pyfunction]
#[pyo3(signature = (**options))]
pub fn settings(options: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    Ok(options::from_kwargs(options)?.describe())
}

/// Writes the mesh `input` to `output` with its marked and chamfer edges embedded (what
/// `chamfer annotate` does): a PLY `edge` element, or glTF `extras.chamfer` per primitive and, as
/// `gltf_edges` asks, the EXT_mesh_primitive_edge_visibility ("edge-visibility") and
/// CESIUM_primitive_outline ("outline") extensions. An OBJ, STL or 3MF becomes the PLY, glTF or GLB `output`
/// names. Options as for bake(). Returns {"edges", "hard_edges", "silhouette_edges", "warnings"}.
/// Raises WriteError if `output` is `input`, and what bake() raises.
#[pyfunction]
#[pyo3(signature = (input, output, *, gltf_edges = vec!["extras".to_owned()], **options))]
pub fn annotate<'py>(
    py: Python<'py>,
    input: PathBuf,
    output: PathBuf,
    gltf_edges: Vec<String>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let options = options::from_kwargs(options)?;
    let mut dialects = annotate_mesh::GltfEdges::DEFAULT
        .with_extras(false)
        .with_edge_visibility(false)
        .with_primitive_outline(false);
    for dialect in &gltf_edges {
        dialects = match dialect.as_str() {
            "extras" => dialects.with_extras(true),
            "edge-visibility" | "EXT_mesh_primitive_edge_visibility" => {
                dialects.with_edge_visibility(true)
            }
            "outline" | "CESIUM_primitive_outline" => dialects.with_primitive_outline(true),
            other => {
                return Err(errors::options(format!(
                    "unknown glTF edge dialect {other:?} (extras, edge-visibility, outline)"
                )));
            }
        };
    }
    let annotated = py
        .detach(|| annotate_mesh::annotate_with(&input, &output, &options, &dialects))
        .map_err(|e| errors::from_library_writing(e, &output))?;
    let report = PyDict::new(py);
    report.set_item("edges", annotated.edges)?;
    report.set_item("hard_edges", annotated.hard_edges)?;
    report.set_item("silhouette_edges", annotated.silhouette_edges)?;
    report.set_item("warnings", annotated.warnings)?;
    Ok(report)
}

/// The per-file step of a batch bake: bakes `input` into `output` unless `output` and its
/// `.chamfer.key` sidecar show it is up to date for the input's bytes (and the files beside an
/// OBJ or .gltf), the options and the format version. Both files are written atomically. Returns
/// True when it baked, False when it skipped. Options as for bake(). The output is the same bytes
/// as `chamfer bake` writes.
#[pyfunction]
#[pyo3(signature = (input, output, **options))]
pub fn bake_if_changed(
    py: Python<'_>,
    input: PathBuf,
    output: PathBuf,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<bool> {
    let options = options::from_kwargs(options)?;
    py.detach(|| build::bake_if_changed(&input, &output, &options))
        .map_err(|e| errors::from_library_writing(e, &output))
}

/// Every mesh under the folder `src` paired with its asset under `dst`, sorted, as
/// `chamfer bake src/ -o dst/` names them (`props/crate.glb` -> `dst/props/crate.chamfer`,
/// `scan.ply.gz` -> `dst/scan.chamfer`). Raises ReadError (unreadable folder, a link leading out
/// of it, a FIFO named like a mesh) or WriteError (two inputs with one output).
#[pyfunction]
pub fn plan_folder(
    py: Python<'_>,
    src: PathBuf,
    dst: PathBuf,
) -> PyResult<Vec<(PathBuf, PathBuf)>> {
    py.detach(|| build::plan_dir(&src, &dst, &mut |_| ()))
        .map_err(errors::from_library)
}
