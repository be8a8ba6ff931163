//! `chamfer._chamfer`, the extension module of the `chamfer` Python package (PyO3, abi3): bakes
//! (files, bytes, numpy arrays), assets with numpy views of their sections and the `chamfer
//! inspect` report, hidden-line SVG drawings, annotated meshes, and the per-file step of batch
//! bakes that `chamfer.dask` runs on a cluster. Python's side (`chamfer/`) adds trimesh input and
//! the Dask runner; the stubs are `chamfer/_chamfer.pyi`.
//!
//! Every function releases the interpreter while it reads, bakes, draws or writes, and every
//! failure is an exception of `chamfer.ChamferError`'s family naming the file (`errors.rs`).

mod arrays;
mod asset;
mod bake;
mod draw;
mod errors;
mod motion;
mod options;

use pyo3::prelude::*;

#[pymodule]
fn _chamfer(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    module.add("FORMAT_VERSION", chamfer_runtime::asset::FORMAT_VERSION)?;
    module.add("EDGE_FLAGS", asset::edge_flags())?;
    module.add("OPTIONS", options::table())?;
    module.add("BAKE_SCHEMA", options::schema(module.py())?)?;
    module.add("VIEW_SCHEMA", options::view_schema(module.py())?)?;
    module.add(
        "SECTION_SCHEMA",
        options::schema_of::<chamfer_runtime::section::Section>(module.py())?,
    )?;
    module.add(
        "DRAWING_STYLE_SCHEMA",
        options::schema_of::<chamfer_preprocess::draw::style::DrawingStyle>(module.py())?,
    )?;
    module.add(
        "ANIMATION_SCHEMA",
        options::schema_of::<chamfer_runtime::rig::AnimationSettings>(module.py())?,
    )?;
    module.add_class::<asset::PyAsset>()?;
    module.add_function(wrap_pyfunction!(motion::pose, module)?)?;
    module.add_function(wrap_pyfunction!(bake::bake, module)?)?;
    module.add_function(wrap_pyfunction!(bake::bake_arrays, module)?)?;
    module.add_function(wrap_pyfunction!(bake::settings, module)?)?;
    module.add_function(wrap_pyfunction!(bake::annotate, module)?)?;
    module.add_function(wrap_pyfunction!(bake::bake_if_changed, module)?)?;
    module.add_function(wrap_pyfunction!(bake::plan_folder, module)?)?;
    module.add_function(wrap_pyfunction!(asset::load, module)?)?;
    module.add_function(wrap_pyfunction!(asset::decode, module)?)?;
    module.add_function(wrap_pyfunction!(draw::draw_svg, module)?)?;
    module.add_function(wrap_pyfunction!(draw::draw_pdf, module)?)?;
    module.add_function(wrap_pyfunction!(draw::draw_dxf, module)?)?;
    errors::register(module)
}
