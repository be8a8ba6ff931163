//! `chamfer.Asset`: a baked or loaded `.chamfer` asset. Its sections are numpy views of the asset's
//! own memory (read-only, no copy), its `stats` the report `chamfer inspect --json` prints.

use std::path::PathBuf;

use chamfer_preprocess::Limits;
use chamfer_preprocess::write::write_atomically;
use chamfer_runtime::asset::{Asset, CompactOptions, EdgeFlags, Indices, Precision};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::arrays::{strided, view};
use crate::errors::{self, Failure};
use crate::options;

/// A baked edge asset: what `chamfer bake` writes and the runtime draws.
///
/// Get one from bake(), bake_arrays(), from_trimesh(), load() or decode(). It is immutable: the
/// section properties are read-only numpy views of its memory, valid as long as they are referenced
/// (they keep the asset alive). Index sections are uint16 when the counts allow, else uint32, as in
/// the file. save() writes it atomically; pickling encodes it, so assets travel between processes.
#[pyclass(frozen, module = "chamfer", name = "Asset")]
pub struct PyAsset {
    asset: Asset,
    /// The length of the file it was read from and the precision that file stores; `None` for an
    /// asset never written.
    file: Option<(u64, Precision)>,
    warnings: Vec<String>,
}

impl PyAsset {
    pub fn new(asset: Asset, file: Option<(u64, Precision)>, warnings: Vec<String>) -> Self {
        Self {
            asset,
            file,
            warnings,
        }
    }

    /// The asset decoded from a file's `bytes`.
    fn from_file(asset: Asset, bytes: &[u8]) -> Self {
        let precision = Asset::precision(bytes).unwrap_or(Precision::EXACT);
        Self::new(asset, Some((bytes.len() as u64, precision)), Vec::new())
    }

    /// The file's bytes: compact (format 5's coded sections) or not.
    fn file_bytes(&self, compact: Option<CompactOptions>) -> std::io::Result<Vec<u8>> {
        let mut bytes = Vec::new();
        chamfer_preprocess::compact::encode(&self.asset, compact.as_ref(), &mut bytes)?;
        Ok(bytes)
    }

    pub fn asset(&self) -> &Asset {
        &self.asset
    }
}

/// The sections of one index array, as its own width.
fn index_view<'py>(
    owner: &Bound<'py, PyAsset>,
    indices: &Indices,
    row: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = |len: usize| {
        if row == 1 {
            vec![len]
        } else {
            vec![len / row, row]
        }
    };
    match indices {
        Indices::U16(v) => view(owner.as_any(), v, &shape(v.len())),
        Indices::U32(v) => view(owner.as_any(), v, &shape(v.len())),
    }
}

fn vec3_view<'py>(owner: &Bound<'py, PyAsset>, data: &[[f32; 3]]) -> PyResult<Bound<'py, PyAny>> {
    view(
        owner.as_any(),
        bytemuck::cast_slice::<[f32; 3], f32>(data),
        &[data.len(), 3],
    )
}

#[pymethods]
impl PyAsset {
    /// The report `chamfer inspect --json` prints for this asset, as a dict with the same keys
    /// (vertices, welded_vertices, render_vertices, triangles, edges {...}, chamfer {...}, caps,
    /// intersections {...}, bounds, bytes {...}).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (total, precision) = match self.file {
            Some((bytes, precision)) => (bytes, Some(precision)),
            None => (self.asset.encoded_len(), None),
        };
        let report = chamfer_preprocess::inspect::summary(&self.asset, total, precision);
        // The report is JSON already (one source of truth with the CLI); Python's json module
        // turns it into dicts, lists and numbers.
        py.import("json")?
            .call_method1("loads", (report.to_string(),))
    }

    /// File name of the source mesh.
    #[getter]
    fn source(&self) -> &str {
        &self.asset.header.source
    }

    /// The program and version that baked the asset.
    #[getter]
    fn generator(&self) -> &str {
        &self.asset.header.generator
    }

    /// The bake settings recorded in the asset, name -> value.
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let settings = PyDict::new(py);
        for (name, value) in &self.asset.header.settings {
            settings.set_item(name, value)?;
        }
        Ok(settings)
    }

    /// The bounding box of the welded positions: ((x, y, z) minimum, (x, y, z) maximum).
    #[getter]
    fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        (self.asset.header.bounds_min, self.asset.header.bounds_max)
    }

    /// What the loader skipped or ignored (empty for a loaded asset).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// Number of edges.
    #[getter]
    fn edge_count(&self) -> usize {
        self.asset.edge_count()
    }

    /// Number of triangles of the render mesh.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.asset.triangle_count()
    }

    /// Render vertex positions, float32 (R, 3).
    #[getter]
    fn render_positions<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        vec3_view(slf, &slf.get().asset.render_positions)
    }

    /// Render vertex normals, unit length, split at creases: float32 (R, 3).
    #[getter]
    fn render_normals<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        vec3_view(slf, &slf.get().asset.render_normals)
    }

    /// Triangles as render vertex indices: uint16 or uint32 (T, 3).
    #[getter]
    fn mesh_indices<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        index_view(slf, &slf.get().asset.mesh_indices, 3)
    }

    /// Welded (topology) positions the edges refer to: float32 (V, 3).
    #[getter]
    fn topology_positions<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        vec3_view(slf, &slf.get().asset.topology_positions)
    }

    /// Per edge its four topology vertices v0 v1 v2 v3 (v0-v1 the edge, v2 and v3 the opposite
    /// corners of its faces; v3 == v0 on a boundary): uint16 or uint32 (E, 4).
    #[getter]
    fn edge_vertices<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        index_view(slf, &slf.get().asset.edge_vertices, 4)
    }

    /// Per edge its attribute word: flags in the low 16 bits, the radius as float16 in the high 16
    /// (of the asset's radius scale): uint32 (E,).
    #[getter]
    fn edge_attributes<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let attributes = &slf.get().asset.edge_attributes;
        view(slf.as_any(), attributes, &[attributes.len()])
    }

    /// Per edge its classes, EdgeFlags bits (BOUNDARY, RIDGE, ...): uint16 (E,), a strided view of
    /// the attribute words' low halves.
    #[getter]
    fn edge_flags<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let attributes = &slf.get().asset.edge_attributes;
        let halves = bytemuck::cast_slice::<u32, u16>(attributes);
        strided(slf.as_any(), halves, attributes.len(), 2)
    }

    /// Per edge its chamfer radius in mesh units, 0 where it has none: float32 (E,) (computed from
    /// the float16 in the attribute words, so a copy).
    #[getter]
    fn edge_radii<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f32>> {
        let radii = (0..self.asset.edge_count())
            .map(|e| self.asset.edge_radius(e))
            .collect::<Vec<f32>>();
        PyArray1::from_vec(py, radii)
    }

    /// The next-index rings: per edge end (2 * edge + end) the next edge end around the same
    /// vertex: uint16 or uint32 (2E,), empty if not baked.
    #[getter]
    fn next_ends<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        index_view(slf, &slf.get().asset.next_ends, 1)
    }

    /// Per capped vertex one edge end at it, the start of its ring: uint16 or uint32 (C,).
    #[getter]
    fn cap_heads<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        index_view(slf, &slf.get().asset.cap_heads, 1)
    }

    /// Intersection edges as segments, polyline after polyline: float32 (S, 2, 3).
    #[getter]
    fn intersection_segments<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let segments = &slf.get().asset.intersection_segments;
        view(
            slf.as_any(),
            bytemuck::cast_slice::<[[f32; 3]; 2], f32>(segments),
            &[segments.len(), 2, 3],
        )
    }

    /// Index of each intersection polyline's first segment: uint32 (P,).
    #[getter]
    fn intersection_starts<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let starts = &slf.get().asset.intersection_starts;
        view(slf.as_any(), starts, &[starts.len()])
    }

    /// Per topology vertex the four joints it follows (indices into the rig's joints): uint16
    /// (V, 4); empty (0, 4) when nothing is skinned.
    #[getter]
    fn joints<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let joints = &slf.get().asset.motion.joints;
        view(slf.as_any(), joints.as_flattened(), &[joints.len(), 4])
    }

    /// Per topology vertex how much it follows each of its joints (summing to 1, or all 0 for a
    /// vertex no joint moves): float32 (V, 4); empty (0, 4) when nothing is skinned.
    #[getter]
    fn weights<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let weights = &slf.get().asset.motion.weights;
        view(slf.as_any(), weights.as_flattened(), &[weights.len(), 4])
    }

    /// The morph targets, sparse: each target's first entry in morph_vertices/morph_deltas:
    /// uint32 (M,).
    #[getter]
    fn morph_starts<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let starts = &slf.get().asset.motion.morph_starts;
        view(slf.as_any(), starts, &[starts.len()])
    }

    /// The topology vertex of each morph entry: uint32 (D,).
    #[getter]
    fn morph_vertices<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let vertices = &slf.get().asset.motion.morph_vertices;
        view(slf.as_any(), vertices, &[vertices.len()])
    }

    /// How far each morph entry moves its vertex at weight 1: float32 (D, 3).
    #[getter]
    fn morph_deltas<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        vec3_view(slf, &slf.get().asset.motion.morph_deltas)
    }

    /// The rig: {"joints": J, "nodes": [names], "morph_targets": [names], "morph_weights": [rest
    /// weights], "animations": [{"name", "duration", "channels"}]}; all empty for a still asset.
    #[getter]
    fn rig<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rig = &self.asset.motion.rig;
        let summary = serde_json::json!({
            "joints": rig.joints.len(),
            "nodes": rig.nodes.iter().map(|n| n.name.as_str()).collect::<Vec<_>>(),
            "morph_targets": rig.morph_names,
            "morph_weights": rig.morph_weights,
            "animations": rig.animations.iter().map(|a| serde_json::json!({
                "name": a.name,
                "duration": a.duration(),
                "channels": a.channels.len(),
            })).collect::<Vec<_>>(),
        });
        py.import("json")?
            .call_method1("loads", (summary.to_string(),))
    }

    /// The asset as the bytes of a `.chamfer` file (what save() writes). Its keywords are the bake
    /// schema's "encoding" group (chamfer.BAKE_SCHEMA), as `chamfer bake`'s flags of the same
    /// names: `compact` writes the compact format for shipping (positions on a grid, normals as
    /// octahedral codes, each within the error bound `chamfer inspect` states).
    #[pyo3(signature = (**options))]
    fn encode<'py>(
        &self,
        py: Python<'py>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let options = options::encoding_from_kwargs(options)?;
        let bytes = py
            .detach(|| self.file_bytes(options))
            .map_err(|e| errors::internal(e.to_string()))?;
        Ok(PyBytes::new(py, &bytes))
    }

    /// Writes the asset to `path` through a temporary file renamed into place: a failure leaves
    /// an existing file as it was; a FIFO or device is never replaced. The keywords as for
    /// encode().
    #[pyo3(signature = (path, **options))]
    fn save(
        &self,
        py: Python<'_>,
        path: PathBuf,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<()> {
        let options = options::encoding_from_kwargs(options)?;
        py.detach(|| {
            write_atomically(&path, |out| {
                chamfer_preprocess::compact::encode(&self.asset, options.as_ref(), out)
            })
        })
        .map_err(|e| errors::from_library_writing(e, &path))
    }

    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let decode = py.import("chamfer._chamfer")?.getattr("decode")?;
        let bytes = py.detach(|| self.asset.encode_to_vec());
        Ok((decode, (PyBytes::new(py, &bytes),)))
    }

    fn __repr__(&self) -> String {
        format!(
            "<chamfer.Asset {:?}: {} triangles, {} edges, {} intersection segments>",
            self.asset.header.source,
            self.asset.triangle_count(),
            self.asset.edge_count(),
            self.asset.intersection_segments.len()
        )
    }
}

/// Reads a `.chamfer` file. Raises ReadError (missing, not a regular file), LimitError (over
/// 2 GiB) or AssetError (not a valid asset), each naming the file.
#[pyfunction]
pub fn load(py: Python<'_>, path: PathBuf) -> PyResult<PyAsset> {
    let asset = py.detach(|| -> Result<_, Failure> {
        let bytes = chamfer_preprocess::load::read(&path, &Limits::DEFAULT)?;
        let asset = Asset::decode(&bytes).map_err(|e| Failure::Decode(path.clone(), e))?;
        Ok(PyAsset::from_file(asset, &bytes))
    })?;
    Ok(asset)
}

/// Decodes the bytes of a `.chamfer` file (what Asset.encode() returns); `name` names them in
/// errors. Raises AssetError when they are not a valid asset.
#[pyfunction]
#[pyo3(signature = (data, name = "<bytes>"))]
pub fn decode(py: Python<'_>, data: &[u8], name: &str) -> PyResult<PyAsset> {
    let asset = py
        .detach(|| Asset::decode(data))
        .map_err(|e| errors::from_decode(name.as_ref(), e))?;
    Ok(PyAsset::from_file(asset, data))
}

/// The edge flag names and bits, for `chamfer.EdgeFlags`.
pub fn edge_flags() -> Vec<(&'static str, u16)> {
    vec![
        ("BOUNDARY", EdgeFlags::BOUNDARY.0),
        ("NON_MANIFOLD", EdgeFlags::NON_MANIFOLD.0),
        ("RIDGE", EdgeFlags::RIDGE.0),
        ("VALLEY", EdgeFlags::VALLEY.0),
        ("MARKED", EdgeFlags::MARKED.0),
        ("MATERIAL", EdgeFlags::MATERIAL.0),
        ("FLIPPED", EdgeFlags::FLIPPED.0),
        ("CHAMFER", EdgeFlags::CHAMFER.0),
    ]
}
