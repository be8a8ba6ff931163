//! What can go wrong between an asset and a picture.

use std::path::PathBuf;

/// An error from the renderer or the offscreen helper.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No GPU adapter (hardware or software) could be opened.
    #[error(
        "no GPU adapter: {0} (on Debian, `apt-get install mesa-vulkan-drivers` gives a software one)"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("could not open the GPU device: {0}")]
    Device(String),
    /// The asset file could not be read.
    #[error("{}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The asset file is not a valid asset.
    #[error("{}: {source}", path.display())]
    Decode {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        source: crate::asset::DecodeError,
    },
    /// A buffer the asset needs is larger than the device allows in one binding.
    #[error("the {what} buffer needs {bytes} bytes; this device binds at most {limit}")]
    TooLarge {
        /// Which buffer.
        what: &'static str,
        /// Its size.
        bytes: u64,
        /// The device's limit.
        limit: u64,
    },
    /// Reading the rendered image back failed.
    #[error("reading the image back from the GPU failed: {0}")]
    Readback(String),
    /// The render target cannot be drawn into correctly.
    #[error("the renderer cannot draw into a target with {0}")]
    Target(String),
    /// The device refused to create a resource or pipeline, or to run a command.
    #[error("the GPU refused {what}: {message}")]
    Gpu {
        /// What was being created or run.
        what: String,
        /// The device's message.
        message: String,
    },
    /// A technique needs something of the render target that it lacks.
    #[error("{technique} needs {needs} in the render target")]
    TargetLacks {
        /// The technique's name.
        technique: &'static str,
        /// What it needs.
        needs: &'static str,
    },
    /// A technique needs per-asset data that the asset was uploaded without.
    #[error(
        "{technique} needs the asset uploaded with {needs} (GpuAsset::with_extras or GpuAsset::for_techniques)"
    )]
    MissingAssetData {
        /// The technique's name.
        technique: &'static str,
        /// What the upload left out.
        needs: &'static str,
    },
    /// A bug in the renderer: two of its parts disagree. Please report it with the message.
    #[error("internal error in the renderer (please report it): {0}")]
    Internal(String),
    /// A pose that does not fit its asset's rig (another number of joints or morph targets, a
    /// number that is not finite).
    #[error("the pose does not fit the asset: {0}")]
    BadPose(String),
    /// The asset cannot be drawn by this technique.
    #[error("{technique} cannot draw this asset: {why}")]
    Unsupported {
        /// The technique's name.
        technique: &'static str,
        /// Why not.
        why: String,
    },
}
