//! Opening what a loader reads, safely for anyone's pipeline: only regular files (a FIFO would hang
//! the read, `/dev/zero` would never end), never more than [`Limits::max_input_bytes`], and files an
//! input refers to (an OBJ's `mtllib`, a glTF buffer `uri`) only when they resolve, after following
//! symbolic links, inside the input's own folder.

use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::Path;

use crate::limits::Limited;
use crate::{Error, Limits};

/// Reads the input file `path`, inflating it if its name ends in `.gz`; refuses anything but a
/// regular file and more than `limits.max_input_bytes` (compressed or inflated).
pub(crate) fn read_input(path: &Path, limits: &Limits) -> Result<Vec<u8>, Error> {
    let read_error = |source| Error::Read {
        path: path.to_owned(),
        source,
    };
    let (file, length) = open_regular(path)?;
    limits.check(path, Limited::InputBytes, length)?;
    let compressed = path.to_string_lossy().to_ascii_lowercase().ends_with(".gz");
    let bytes = if compressed {
        read_capped(
            flate2::read::GzDecoder::new(io::BufReader::new(file)),
            0,
            limits.max_input_bytes,
        )
    } else {
        read_capped(file, length, limits.max_input_bytes)
    };
    match bytes.map_err(read_error)? {
        Some(bytes) => Ok(bytes),
        None => Err(Error::LimitExceeded {
            path: path.to_owned(),
            what: Limited::InputBytes,
            count: limits.max_input_bytes.saturating_add(1),
            limit: limits.max_input_bytes,
        }),
    }
}

/// Why a file an input refers to was not read.
#[derive(Debug)]
pub(crate) enum RefusedReference {
    /// It does not exist (loaders may carry on without it).
    Missing,
    /// Any other reason, in words.
    Refused(String),
}

/// Reads `reference` (relative to the folder of `input`, as the input names it) if it resolves
/// inside that folder and is a regular file of at most `limit` bytes.
pub(crate) fn read_reference(
    input: &Path,
    reference: &Path,
    limit: u64,
) -> Result<Vec<u8>, RefusedReference> {
    let folder = folder_of(input);
    let refused = |e: io::Error| match e.kind() {
        io::ErrorKind::NotFound => RefusedReference::Missing,
        _ => RefusedReference::Refused(format!("cannot be read: {e}")),
    };
    let base = folder.canonicalize().map_err(refused)?;
    let target = folder.join(reference).canonicalize().map_err(refused)?;
    if !target.starts_with(&base) {
        return Err(RefusedReference::Refused(
            "resolves outside the file's folder (only files beside it or below it are read)".into(),
        ));
    }
    let (file, length) = open_regular(&target).map_err(|e| match e {
        Error::NotAFile { kind, .. } => {
            RefusedReference::Refused(format!("is {kind}, not a regular file"))
        }
        Error::Read { source, .. } => refused(source),
        other => RefusedReference::Refused(other.to_string()),
    })?;
    let too_large = || {
        RefusedReference::Refused(format!(
            "is larger than the limit of {limit} bytes (raise it with --max-input-bytes or Limits)"
        ))
    };
    if length > limit {
        return Err(too_large());
    }
    read_capped(file, length, limit)
        .map_err(refused)?
        .ok_or_else(too_large)
}

/// The folder an input's references are relative to (`.` for a bare file name).
pub(crate) fn folder_of(input: &Path) -> &Path {
    match input.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder,
        _ => Path::new("."),
    }
}

/// Opens `path` for reading only if it is a regular file; returns it and its length.
///
/// The type is checked before opening (opening some devices has effects) and again on the open
/// file (the name may have been swapped in between); the open never blocks on a FIFO.
pub(crate) fn open_regular(path: &Path) -> Result<(File, u64), Error> {
    let read_error = |source| Error::Read {
        path: path.to_owned(),
        source,
    };
    let not_a_file = |meta: &Metadata| Error::NotAFile {
        path: path.to_owned(),
        kind: kind_of(meta),
    };
    let before = std::fs::metadata(path).map_err(read_error)?;
    if !before.is_file() {
        return Err(not_a_file(&before));
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(read_error)?;
    let after = file.metadata().map_err(read_error)?;
    if !after.is_file() {
        return Err(not_a_file(&after));
    }
    Ok((file, after.len()))
}

/// Reads everything, or `None` if there is more than `limit` bytes. `expected` sizes the buffer.
fn read_capped(source: impl Read, expected: u64, limit: u64) -> io::Result<Option<Vec<u8>>> {
    let mut bytes = Vec::with_capacity(usize::try_from(expected.min(limit)).unwrap_or(0));
    source
        .take(limit.saturating_add(1))
        .read_to_end(&mut bytes)?;
    Ok((bytes.len() as u64 <= limit).then_some(bytes))
}

/// "a FIFO", "a directory", ... for messages.
pub(crate) fn kind_of(meta: &Metadata) -> &'static str {
    let file_type = meta.file_type();
    if file_type.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO";
        }
        if file_type.is_char_device() {
            return "a character device";
        }
        if file_type.is_block_device() {
            return "a block device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    "a special file"
}
