//! `.chamfer` files as Bevy assets: decoded and validated by `chamfer-runtime`, with the render
//! mesh (split crease normals) as a labeled [`Mesh`] sub-asset that Bevy draws with its own
//! materials, lights and shadows.

use std::sync::Arc;

use bevy::asset::io::Reader;
use bevy::asset::{AssetLoader, LoadContext, RenderAssetUsages};
use bevy::mesh::{Indices, Mesh, PrimitiveTopology};
use bevy::prelude::*;
use chamfer_runtime::asset::{self as format, Asset as EdgeAsset};

/// A baked edge asset: the decoded `.chamfer` file and its render mesh.
#[derive(Asset, TypePath, Clone, Debug)]
pub struct ChamferAsset {
    /// The decoded asset (edges, caps, next indices, render vertices).
    pub asset: Arc<EdgeAsset>,
    /// The render mesh, the sub-asset labeled [`ChamferAsset::MESH_LABEL`].
    pub mesh: Handle<Mesh>,
}

impl ChamferAsset {
    /// The label of the render mesh: `asset_server.load("part.chamfer#mesh")`.
    pub const MESH_LABEL: &'static str = "mesh";
}

/// Why a `.chamfer` file did not load; the message names the file.
#[derive(Debug, thiserror::Error)]
pub enum ChamferLoadError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The asset path.
        path: String,
        /// What the reader said.
        source: std::io::Error,
    },
    /// The bytes are not a valid asset.
    #[error("{path}: not a valid .chamfer asset: {source}")]
    Decode {
        /// The asset path.
        path: String,
        /// What the decoder found.
        source: format::DecodeError,
    },
}

/// Loads `.chamfer` files into [`ChamferAsset`]s.
#[derive(Default, TypePath)]
pub struct ChamferLoader;

impl AssetLoader for ChamferLoader {
    type Asset = ChamferAsset;
    type Settings = ();
    type Error = ChamferLoadError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        load_context: &mut LoadContext<'_>,
    ) -> Result<ChamferAsset, ChamferLoadError> {
        let path = load_context.path().to_string();
        let mut bytes = Vec::new();
        reader
            .read_to_end(&mut bytes)
            .await
            .map_err(|source| ChamferLoadError::Read {
                path: path.clone(),
                source,
            })?;
        let asset = EdgeAsset::decode(&bytes).map_err(|source| ChamferLoadError::Decode {
            path: path.clone(),
            source,
        })?;
        let mesh = load_context.add_labeled_asset(ChamferAsset::MESH_LABEL, render_mesh(&asset));
        Ok(ChamferAsset {
            asset: Arc::new(asset),
            mesh,
        })
    }

    fn extensions(&self) -> &[&str] {
        &["chamfer"]
    }
}

/// The asset's render vertices and triangles as a Bevy mesh.
pub fn render_mesh(asset: &EdgeAsset) -> Mesh {
    let indices = match &asset.mesh_indices {
        format::Indices::U16(i) => Indices::U16(i.clone()),
        format::Indices::U32(i) => Indices::U32(i.clone()),
    };
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, asset.render_positions.clone())
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, asset.render_normals.clone())
    .with_inserted_indices(indices)
}
