//! The header envelope: the one place that knows the header (and the rig section) is bincode.
//!
//! bincode is pinned to the 2.x line (3.x is a deliberate compile error); swapping the envelope means
//! changing only this file and bumping [`FORMAT_VERSION`](super::FORMAT_VERSION).

use super::{DecodeError, Header, MAX_HEADER_BYTES, SectionKind};
use crate::rig::Rig;

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
        .map_err(|e| DecodeError::BadHeader(describe(&e, "header", MAX_HEADER_BYTES as usize)))?;
    if used != bytes.len() {
        return Err(DecodeError::BadHeader(format!(
            "header is {} bytes but its length field says {}",
            used,
            bytes.len()
        )));
    }
    Ok(header)
}

/// The rig section can outgrow the header (long animations); a file's own length bounds it, and
/// serde allocates containers as their elements arrive, so this only stops absurd declared lengths.
const MAX_RIG_BYTES: usize = 1 << 31;

fn rig_config() -> impl bincode::config::Config {
    bincode::config::standard()
        .with_little_endian()
        .with_fixed_int_encoding()
        .with_limit::<MAX_RIG_BYTES>()
}

/// Serializes a rig section; empty for an empty rig.
pub(super) fn encode_rig(rig: &Rig) -> std::io::Result<Vec<u8>> {
    if *rig == Rig::default() {
        return Ok(Vec::new());
    }
    bincode::serde::encode_to_vec(rig, rig_config())
        .map_err(|e| std::io::Error::other(format!("asset rig cannot be encoded: {e}")))
}

/// Deserializes a rig section that must fill `bytes` exactly; an empty section is an empty rig.
/// Its rules are checked by the caller ([`Rig::validate`]).
pub(super) fn decode_rig(bytes: &[u8]) -> Result<Rig, DecodeError> {
    if bytes.is_empty() {
        return Ok(Rig::default());
    }
    let invalid = |reason: String| DecodeError::Invalid {
        kind: SectionKind::Rig,
        position: 0,
        reason,
    };
    let (rig, used): (Rig, usize) = bincode::serde::decode_from_slice(bytes, rig_config())
        .map_err(|e| invalid(describe(&e, "rig", MAX_RIG_BYTES)))?;
    if used != bytes.len() {
        return Err(invalid(format!(
            "the rig is {used} bytes but its section {}",
            bytes.len()
        )));
    }
    Ok(rig)
}

/// bincode's own `Display` is its `Debug` text (`LimitExceeded`); say what it means instead.
fn describe(error: &bincode::error::DecodeError, what: &str, limit: usize) -> String {
    use bincode::error::DecodeError as E;
    match error {
        E::UnexpectedEnd { additional } => {
            format!("the {what} ends {additional} bytes before its last field")
        }
        E::LimitExceeded => {
            format!("a length inside the {what} would take it past the {limit}-byte {what} limit")
        }
        E::Utf8 { .. } => format!("a text field of the {what} is not valid UTF-8"),
        E::OutsideUsizeRange(n) => format!("a length inside the {what} ({n}) is out of range"),
        E::InvalidBooleanValue(b) => format!("a yes/no field of the {what} holds {b}"),
        E::UnexpectedVariant {
            type_name, found, ..
        } => {
            format!("the {what}'s {type_name} field holds an unknown value {found}")
        }
        E::ArrayLengthMismatch { required, found } => {
            format!("a fixed-size list of the {what} has {found} entries, not {required}")
        }
        _ => format!("the {what}'s fields could not be read"),
    }
}
