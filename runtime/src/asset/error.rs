//! Why an asset was rejected.

use super::SectionKind;

/// Everything [`Asset::decode`](super::Asset::decode) can reject; the message names what is wrong.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum DecodeError {
    /// The file does not start with [`MAGIC`](super::MAGIC).
    #[error("not a .chamfer asset (bad magic bytes)")]
    BadMagic,
    /// Written by a different format version.
    #[error(
        "asset format version {found} is not supported (this build reads versions 1 to {supported}); re-bake the source mesh"
    )]
    UnsupportedVersion {
        /// Version in the file.
        found: u32,
        /// The newest version this crate reads (it reads every version from 1 up).
        supported: u32,
    },
    /// The file ends before something it announces.
    #[error("truncated: {what} needs {needed} bytes but the file has {available}")]
    Truncated {
        /// What was being read.
        what: &'static str,
        /// Bytes required (from the start of the file).
        needed: u64,
        /// Bytes present.
        available: u64,
    },
    /// Bytes after the last section.
    #[error("{0} unexpected bytes after the last section")]
    TrailingBytes(u64),
    /// The header could not be decoded or is inconsistent.
    #[error("bad header: {0}")]
    BadHeader(String),
    /// The section table is malformed.
    #[error("bad section table: {0}")]
    BadSectionTable(String),
    /// A section's length does not fit its element size or its count.
    #[error("section {}: {reason}", kind.name())]
    BadSectionLength {
        /// The section.
        kind: SectionKind,
        /// What is wrong.
        reason: String,
    },
    /// A coded section (format 5) that does not decode.
    #[error("section {}: {reason}", kind.name())]
    BadCoding {
        /// The section.
        kind: SectionKind,
        /// What is wrong.
        reason: String,
    },
    /// An index points past the end of what it indexes.
    #[error(
        "section {}: element {position} is {value}, out of range (must be below {bound})", kind.name()
    )]
    IndexOutOfRange {
        /// The section.
        kind: SectionKind,
        /// Position of the bad index in the section.
        position: u64,
        /// The index.
        value: u32,
        /// The exclusive upper bound.
        bound: u64,
    },
    /// A NaN or infinity where a finite number is required.
    #[error("section {}: element {position} is not a finite number", kind.name())]
    NonFinite {
        /// The section.
        kind: SectionKind,
        /// Position of the bad float in the section.
        position: u64,
    },
    /// Structurally valid numbers that break a rule of the format (e.g. unknown flag bits).
    #[error("section {}: element {position}: {reason}", kind.name())]
    Invalid {
        /// The section.
        kind: SectionKind,
        /// Position of the bad element in the section.
        position: u64,
        /// The rule broken.
        reason: String,
    },
    /// More kept edges meet at one vertex than the runtime's join walk follows.
    #[error(
        "vertex {vertex} has {ends} kept edge ends, more than the {limit} the runtime's join walk follows"
    )]
    RingTooLong {
        /// The topology vertex.
        vertex: u32,
        /// Kept edge ends at it.
        ends: u64,
        /// [`MAX_RING`](super::MAX_RING).
        limit: u32,
    },
}
