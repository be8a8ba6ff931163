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
}
