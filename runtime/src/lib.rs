//! Chamfer's runtime crate: the `.chamfer` edge asset and, with the `render` feature, the wgpu renderer
//! that draws its edges inside the user's own frame.
//!
//! The asset module has no GPU dependency, so the offline baker (`chamfer-preprocess`) shares the exact
//! same format definition with `default-features = false`.
//!
//! ```
//! use chamfer_runtime::asset::Asset;
//! # fn load(bytes: &[u8]) -> Result<(), chamfer_runtime::asset::DecodeError> {
//! let asset = Asset::decode(bytes)?; // validates every index, count and float
//! println!("{} edges, {} triangles", asset.edge_count(), asset.triangle_count());
//! # Ok(()) }
//! ```

pub mod asset;
pub mod camera;
pub mod highlight;
#[cfg(feature = "render")]
pub mod render;
pub mod rig;
pub mod scene;
pub mod schema;
pub mod section;
