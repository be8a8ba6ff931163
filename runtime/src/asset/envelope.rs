//! The header envelope: the one place that knows the header is bincode.
//!
//! bincode is pinned to the 2.x line (3.x is a deliberate compile error); swapping the envelope means
//! changing only this file and bumping [`FORMAT_VERSION`](super::FORMAT_VERSION).

use super::{DecodeError, Header, MAX_HEADER_BYTES};

// Fixed-width integers keep the header's length independent of the section offsets it records,
// so the encoder can lay out sections before it knows them.
fn config() -> impl bincode::config::Config {
    bincode::config::standard()
        .with_little_endian()
        .with_fixed_int_encoding()
        .with_limit::<{ MAX_HEADER_BYTES as usize }>()
}

/// Serializes the header; fails only if it would exceed [`MAX_HEADER_BYTES`].
pub(super) fn encode_header(header: &Header) -> std::io::Result<Vec<u8>> {
    bincode::serde::encode_to_vec(header, config())
        .map_err(|e| std::io::Error::other(format!("asset header cannot be encoded: {e}")))
}

/// Deserializes a header that must fill `bytes` exactly.
pub(super) fn decode_header(bytes: &[u8]) -> Result<Header, DecodeError> {
    let (header, used): (Header, usize) = bincode::serde::decode_from_slice(bytes, config())
        .map_err(|e| DecodeError::BadHeader(e.to_string()))?;
    if used != bytes.len() {
        return Err(DecodeError::BadHeader(format!(
            "header is {} bytes but its length field says {}",
            used,
            bytes.len()
        )));
    }
    Ok(header)
}
