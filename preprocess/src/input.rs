//! What `chamfer draw` and `chamfer render` read: an asset (`.chamfer`) under the same rules as a
//! mesh (a regular file, never a FIFO or device, at most [`Limits::max_input_bytes`], decoded with
//! the asset's validation), or a mesh baked on the fly with the bake options — so every command
//! refuses a hostile input the way `bake` does, before allocating for it.
//!
//! [`Limits::max_input_bytes`]: crate::Limits::max_input_bytes

use std::path::Path;

use chamfer_runtime::asset::Asset;

use crate::{BakeOptions, Error, bake_file, load};

/// An asset to draw and what the loader skipped on the way (empty for a `.chamfer`).
#[derive(Debug)]
pub struct AssetInput {
    /// The asset.
    pub asset: Asset,
    /// The mesh loader's warnings, when a mesh was baked.
    pub warnings: Vec<String>,
}

/// Reads `path` as an asset if its name ends in `.chamfer` (any case), else bakes it as a mesh
/// with `options`. Errors name the file.
pub fn read_asset(path: &Path, options: &BakeOptions) -> Result<AssetInput, Error> {
    let is_asset = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("chamfer"));
    if !is_asset {
        let baked = bake_file(path, options)?;
        return Ok(AssetInput {
            asset: baked.asset,
            warnings: baked.warnings,
        });
    }
    options.validate()?;
    let bytes = load::read(path, &options.limits)?;
    let asset = Asset::decode(&bytes).map_err(|e| Error::Parse {
        path: path.to_owned(),
        format: "Chamfer asset",
        message: e.to_string(),
    })?;
    Ok(AssetInput {
        asset,
        warnings: Vec::new(),
    })
}
