//! Chamfer's offline bake: load a mesh, weld it, build its edge adjacency, classify the edges, split
//! normals at creases and write the compact `.chamfer` asset that `chamfer-runtime` draws.
//!
//! One module per step, each with one public entry and its contract:
//! [`load`] → [`weld`] → [`degenerate`] → [`adjacency`] → [`stitch`] → [`classify`] → [`radii`] → [`caps`] →
//! [`intersections`] (optional) → [`normals`] → the asset. [`draw`] makes hidden-line drawings (SVG) of
//! an asset.
//!
//! ```
//! use chamfer_preprocess::{BakeOptions, bake_bytes};
//! use chamfer_runtime::asset::{Asset, EdgeFlags};
//! // A unit cube as an OBJ (the path's extension names the format; `bake_file` reads a file).
//! let cube = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
//!     f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
//! let baked = bake_bytes("cube.obj".as_ref(), cube, &BakeOptions::DEFAULT)?;
//! // Its 12 sides are ridge creases; the 6 face diagonals are coplanar and dropped.
//! let asset = Asset::decode(&baked.asset.encode_to_vec())?;
//! let ridges = (0..asset.edge_count())
//!     .filter(|&e| asset.edge_flags(e).contains(EdgeFlags::RIDGE))
//!     .count();
//! assert_eq!((asset.edge_count(), ridges), (12, 12));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod adjacency;
pub mod annotate;
mod bake;
pub mod build;
mod bvh;
pub mod caps;
pub mod classify;
pub mod compact;
pub mod degenerate;
pub mod draw;
pub mod environment;
mod error;
pub mod input;
pub mod inspect;
pub mod intersections;
pub mod limits;
pub mod load;
pub mod mesh;
mod mesh_order;
pub mod motion;
pub mod normals;
mod options;
mod polylines;
pub mod radii;
pub mod scene;
pub mod schema;
pub mod stitch;
pub mod weld;
pub mod write;

pub use bake::{
    Baked, STITCH_BOUNDARY_BEFORE, Timings, bake, bake_bytes, bake_file, bake_with_companions,
};
pub use error::Error;
pub use limits::Limits;
pub use load::Companions;
pub use options::{BakeOptions, OptionsError, Radius, Stitch, WeldTolerance};
pub use schema::{BakeSettings, SettingsError};
