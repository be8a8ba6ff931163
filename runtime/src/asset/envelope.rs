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
        .map_err(|e| DecodeError::BadHeader(describe(&e)))?;
    if used != bytes.len() {
        return Err(DecodeError::BadHeader(format!(
            "header is {} bytes but its length field says {}",
            used,
            bytes.len()
        )));
    }
    Ok(header)
}

/// bincode's own `Display` is its `Debug` text (`LimitExceeded`); say what it means instead.
fn describe(error: &bincode::error::DecodeError) -> String {
    use bincode::error::DecodeError as E;
    match error {
        E::UnexpectedEnd { additional } => {
            format!("the header ends {additional} bytes before its last field")
        }
        E::LimitExceeded => format!(
            "a length inside the header would take it past the {MAX_HEADER_BYTES}-byte header limit"
        ),
        E::Utf8 { .. } => "a text field of the header is not valid UTF-8".into(),
        E::OutsideUsizeRange(n) => format!("a length inside the header ({n}) is out of range"),
        E::InvalidBooleanValue(b) => format!("a yes/no field of the header holds {b}"),
        E::UnexpectedVariant {
            type_name, found, ..
        } => {
            format!("the header's {type_name} field holds an unknown value {found}")
        }
        E::ArrayLengthMismatch { required, found } => {
            format!("a fixed-size list of the header has {found} entries, not {required}")
        }
        _ => "the header's fields could not be read".into(),
    }
}
