//! Baking in Bevy's asset processor: a `.glb`, `.obj`, `.ply` (or `.ply.gz`, `.stl`, `.3mf`) in
//! the assets folder whose `.meta` names the [`ChamferBake`] processor is baked once into the
//! processed assets as a `.chamfer` file, with the bake options of its `.meta` ([`BakeSettings`],
//! `chamfer bake`'s flags and defaults). The processor bakes again when the file or its `.meta`
//! changes (at start-up, or while running with Bevy's `file_watcher` feature). Loading the path
//! then gives a [`ChamferAsset`](crate::ChamferAsset), and `path#mesh` its render mesh.
//!
//! The file is baked from its own bytes: files it refers to (an OBJ's `.mtl`, a `.gltf`'s external
//! buffers) are not read, since Bevy would not re-bake when they change. Use `.glb` for glTF.

use std::path::Path;
use std::sync::Arc;

use bevy::asset::AssetPath;
use bevy::asset::AsyncWriteExt;
use bevy::asset::io::{AssetReaderError, AssetWriterError, Writer};
use bevy::asset::processor::{AssetProcessor, Process, ProcessContext, ProcessError};
use bevy::reflect::TypePath;
use bevy::tasks::futures_lite::AsyncReadExt;
use chamfer_preprocess::schema::{BakeSettings, SettingsError};
use chamfer_preprocess::{Companions, bake_with_companions, compact};

use crate::asset::ChamferLoader;

/// The asset processor that bakes mesh files into `.chamfer` assets. In a `.meta` file:
///
/// ```ron
/// (
///     meta_format_version: "1.0",
///     asset: Process(
///         processor: "ChamferBake",
///         settings: (crease_deg: 40.0, radius_rel: Some(0.004), compact: true),
///     ),
/// )
/// ```
///
/// A file that fails to bake leaves no processed file behind (Bevy opens the processed file before
/// the processor runs, so it would be left empty): its processed file and `.meta` are removed, so
/// loading it is an error naming the path, never an empty asset.
#[derive(Default, TypePath)]
pub struct ChamferBake {
    /// The app's processor, whose processed sources the failed files are removed from.
    processor: Option<AssetProcessor>,
}

impl ChamferBake {
    /// The processor for an app whose asset processor (if it has one) is `processor`.
    pub fn new(processor: Option<AssetProcessor>) -> Self {
        Self { processor }
    }

    /// Removes what Bevy began writing for `path` (and its stale `.meta`).
    async fn leave_nothing(&self, path: &AssetPath<'static>) {
        let Some(processor) = &self.processor else {
            return;
        };
        let Ok(source) = processor.get_source(path.source().clone()) else {
            return;
        };
        let Ok(writer) = source.processed_writer() else {
            return;
        };
        // Either may be missing already; the failure itself is what Bevy reports.
        let _ = writer.remove(path.path()).await;
        let _ = writer.remove_meta(path.path()).await;
    }
}

/// Why a file was not baked; the message names the file.
#[derive(Debug, thiserror::Error)]
pub enum BakeError {
    /// The `.meta` settings are out of range.
    #[error("{path}: bake settings: {source}")]
    Settings {
        /// The asset path.
        path: String,
        /// What was refused.
        source: SettingsError,
    },
    /// The file could not be loaded or baked (the message names the file).
    #[error(transparent)]
    Bake(#[from] chamfer_preprocess::Error),
    /// The asset could not be encoded.
    #[error("{path}: cannot encode the asset: {source}")]
    Encode {
        /// The asset path.
        path: String,
        /// What the encoder said.
        source: std::io::Error,
    },
}

/// Bakes a mesh file's bytes into a `.chamfer` file's bytes, as `chamfer bake` would with
/// `settings`; `path` names the file (its extension picks the format) in errors.
pub fn bake_to_asset(
    path: &Path,
    bytes: &[u8],
    settings: &BakeSettings,
) -> Result<Vec<u8>, BakeError> {
    let named = || path.display().to_string();
    let (options, compact) = settings.options().map_err(|source| BakeError::Settings {
        path: named(),
        source,
    })?;
    let baked = bake_with_companions(path, bytes, Companions::Memory(&[]), &options)?;
    let mut asset = Vec::new();
    compact::encode(&baked.asset, compact.as_ref(), &mut asset).map_err(|source| {
        BakeError::Encode {
            path: named(),
            source,
        }
    })?;
    Ok(asset)
}

impl Process for ChamferBake {
    type Settings = BakeSettings;
    type OutputLoader = ChamferLoader;

    async fn process(
        &self,
        context: &mut ProcessContext<'_>,
        settings: &BakeSettings,
        writer: &mut Writer,
    ) -> Result<(), ProcessError> {
        let asset_path = context.path().clone();
        let result = bake_into(context, settings, writer).await;
        if result.is_err() {
            self.leave_nothing(&asset_path).await;
        }
        result
    }
}

/// Reads the file `context` processes, bakes it with `settings` and writes the asset to `writer`.
async fn bake_into(
    context: &mut ProcessContext<'_>,
    settings: &BakeSettings,
    writer: &mut Writer,
) -> Result<(), ProcessError> {
    let asset_path = context.path().clone();
    // One byte past the input limit is enough for the bake to refuse the file by name.
    let limit = settings.max_input_bytes.saturating_add(1);
    let mut bytes = Vec::new();
    AsyncReadExt::take(context.asset_reader(), limit)
        .read_to_end(&mut bytes)
        .await
        .map_err(|err| ProcessError::AssetReaderError {
            path: asset_path.clone(),
            err: AssetReaderError::Io(Arc::new(err)),
        })?;
    let asset = bake_to_asset(asset_path.path(), &bytes, settings)
        .map_err(|e| ProcessError::AssetTransformError(Box::new(e)))?;
    writer
        .write_all(&asset)
        .await
        .map_err(|err| ProcessError::AssetWriterError {
            path: asset_path,
            err: AssetWriterError::Io(err),
        })?;
    Ok(())
}
