//! Chamfer's offline bake: load a mesh, weld it, build its edge adjacency, classify the edges, split
//! normals at creases and write the compact `.chamfer` asset that `chamfer-runtime` draws.
//!
//! One module per step, each with one public entry and its contract:
//! [`load`] → [`weld`] → [`degenerate`] → [`adjacency`] → [`classify`] → [`radii`] → [`caps`] →
//! [`intersections`] (optional) → [`normals`] → the asset. [`draw`] makes hidden-line drawings (SVG) of
//! an asset.
//!
//! ```no_run
//! use chamfer_preprocess::{bake_file, BakeOptions};
//! let baked = bake_file("model.obj".as_ref(), &BakeOptions::DEFAULT)?;
//! std::fs::write("model.chamfer", baked.asset.encode_to_vec())?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod adjacency;
pub mod annotate;
mod bake;
pub mod build;
pub mod caps;
pub mod classify;
mod corners;
pub mod degenerate;
pub mod draw;
mod error;
pub mod intersections;
pub mod limits;
pub mod load;
pub mod mesh;
pub mod normals;
mod options;
mod polylines;
pub mod radii;
pub mod scene;
pub mod weld;
pub mod write;

pub use bake::{Baked, Timings, bake, bake_bytes, bake_file};
pub use error::Error;
pub use limits::Limits;
pub use options::{BakeOptions, OptionsError, Radius};
