//! Reading an environment for image-based light (issue 29): an equirectangular Radiance `.hdr` (RGBE)
//! file, decoded by the `image` crate into a [`chamfer_runtime::highlight::environment::Environment`].
//!
//! Bounded like every loader: the file is read through the same capped reader (regular files only, at
//! most [`Limits::max_input_bytes`], `.hdr.gz` inflated as a stream), and the header's declared size is
//! checked against [`MAX_TEXELS`] before any pixel is decoded, so a header that declares a huge image
//! is refused from its first line, not after allocating for it.

use std::path::Path;

use chamfer_runtime::highlight::environment::Environment;
use image::ImageDecoder;

use crate::{Error, Limits};

/// The most texels an environment may declare (8192 × 4096: 400 MB of f32 RGB). Prefiltering reduces
/// any environment to 128 × 64 first, so larger ones buy nothing.
pub const MAX_TEXELS: u64 = 8192 * 4096;

/// Reads the Radiance HDR environment at `path`.
pub fn read_environment(path: &Path, limits: &Limits) -> Result<Environment, Error> {
    let bytes = crate::load::files::read_input(path, limits, &|_| Ok(true))?;
    environment_from_bytes(path, &bytes)
}

/// Decodes a Radiance HDR environment from its bytes; `path` names it in errors.
pub fn environment_from_bytes(path: &Path, bytes: &[u8]) -> Result<Environment, Error> {
    let invalid = |message: String| Error::Parse {
        path: path.to_owned(),
        format: "Radiance HDR",
        message,
    };
    let decoder = image::codecs::hdr::HdrDecoder::new(std::io::Cursor::new(bytes))
        .map_err(|e| invalid(e.to_string()))?;
    let (width, height) = decoder.dimensions();
    let texels = u64::from(width) * u64::from(height);
    if texels == 0 || texels > MAX_TEXELS {
        return Err(invalid(format!(
            "declares {width}x{height} texels; an environment has 1 to {MAX_TEXELS}"
        )));
    }
    let mut buffer = vec![0u8; decoder.total_bytes() as usize];
    decoder
        .read_image(&mut buffer)
        .map_err(|e| invalid(e.to_string()))?;
    let texels: Vec<[f32; 3]> = buffer
        .chunks_exact(12)
        .map(|c| {
            let f = |i: usize| f32::from_ne_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
            [f(0), f(4), f(8)]
        })
        .collect();
    Environment::new(width, height, texels).map_err(|e| invalid(e.to_string()))
}
