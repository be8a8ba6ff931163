//! Opening what a loader reads, safely for anyone's pipeline: only regular files (a FIFO would hang
//! the read, `/dev/zero` would never end), never more than [`Limits::max_input_bytes`], and files an
//! input refers to (an OBJ's `mtllib`, a glTF buffer `uri`) only when they resolve, after following
//! symbolic links, inside the input's own folder.

use std::borrow::Cow;
use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::{Component, Path};

use crate::limits::Limited;
use crate::{Error, Limits};

/// Reads the input file `path`, inflating it if its name ends in `.gz`; refuses anything but a
/// regular file and more than `limits.max_input_bytes` (compressed or inflated).
///
/// While a `.gz` is inflated, `check_prefix` sees the bytes inflated so far after each chunk until
/// it returns `Ok(true)`; its error ends the read (a header that declares too much is refused from
/// its first kilobytes, not after gigabytes of inflating). Running out of memory while inflating is
/// an error that says how far it got and what the limit is.
pub(crate) fn read_input(
    path: &Path,
    limits: &Limits,
    check_prefix: &dyn Fn(&[u8]) -> Result<bool, Error>,
) -> Result<Vec<u8>, Error> {
    let read_error = |source| Error::Read {
        path: path.to_owned(),
        source,
    };
    let (file, length) = open_regular(path)?;
    limits.check(path, Limited::InputBytes, length)?;
    if !is_gzip(path) {
        return read_capped(file, length, limits.max_input_bytes)
            .map_err(read_error)?
            .ok_or_else(|| over_limit(path, limits));
    }
    inflate(path, io::BufReader::new(file), limits, check_prefix)
}

/// [`read_input`] for a file already in memory (a browser's dropped file): the same limits, the
/// same inflating of a `.gz` with `check_prefix` seeing what has been inflated so far; other files
/// are borrowed as they are.
pub(crate) fn input_bytes<'a>(
    path: &Path,
    bytes: &'a [u8],
    limits: &Limits,
    check_prefix: &dyn Fn(&[u8]) -> Result<bool, Error>,
) -> Result<Cow<'a, [u8]>, Error> {
    limits.check(path, Limited::InputBytes, bytes.len() as u64)?;
    if is_gzip(path) {
        inflate(path, bytes, limits, check_prefix).map(Cow::Owned)
    } else {
        Ok(Cow::Borrowed(bytes))
    }
}

/// True if the name ends in `.gz` (any case): the file is inflated as it is read.
fn is_gzip(path: &Path) -> bool {
    path.to_string_lossy().to_ascii_lowercase().ends_with(".gz")
}

fn over_limit(path: &Path, limits: &Limits) -> Error {
    Error::LimitExceeded {
        path: path.to_owned(),
        what: Limited::InputBytes,
        count: limits.max_input_bytes.saturating_add(1),
        limit: limits.max_input_bytes,
    }
}

/// Inflates the gzip stream `compressed`, at most `limits.max_input_bytes` of it (see [`read_input`]).
fn inflate(
    path: &Path,
    compressed: impl io::BufRead,
    limits: &Limits,
    check_prefix: &dyn Fn(&[u8]) -> Result<bool, Error>,
) -> Result<Vec<u8>, Error> {
    let read_error = |source| Error::Read {
        path: path.to_owned(),
        source,
    };
    let mut inflated = Vec::new();
    let mut checked = false;
    let mut chunk = vec![0u8; INFLATE_CHUNK];
    let mut source = flate2::bufread::GzDecoder::new(compressed);
    loop {
        let n = match source.read(&mut chunk) {
            Ok(0) => return Ok(inflated),
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(read_error(e)),
        };
        if inflated.len() as u64 + n as u64 > limits.max_input_bytes {
            return Err(over_limit(path, limits));
        }
        reserve(&mut inflated, n, limits.max_input_bytes).map_err(read_error)?;
        inflated.extend_from_slice(&chunk[..n]);
        if !checked {
            checked = check_prefix(&inflated)?;
        }
    }
}

/// Bytes inflated per read.
const INFLATE_CHUNK: usize = 1 << 16;

/// Makes room for `more` bytes in `bytes`, doubling as `Vec` does but never past `limit`, and
/// reports a failed allocation as an error naming the sizes instead of aborting.
fn reserve(bytes: &mut Vec<u8>, more: usize, limit: u64) -> io::Result<()> {
    let needed = bytes.len() + more;
    if needed <= bytes.capacity() {
        return Ok(());
    }
    let cap = usize::try_from(limit).unwrap_or(usize::MAX);
    let target = needed
        .max(bytes.capacity().saturating_mul(2))
        .min(cap.max(needed));
    bytes.try_reserve_exact(target - bytes.len()).map_err(|_| {
        io::Error::new(
            io::ErrorKind::OutOfMemory,
            format!(
                "out of memory while inflating: {} bytes inflated, {target} could not be allocated \
                 (the input limit is {limit} bytes, --max-input-bytes)",
                bytes.len()
            ),
        )
    })
}

/// Why a file an input refers to was not read.
#[derive(Debug)]
pub(crate) enum RefusedReference {
    /// It does not exist (loaders may carry on without it).
    Missing,
    /// Any other reason, in words.
    Refused(String),
}

/// Where the files an input refers to (an OBJ's `mtllib`, a glTF buffer `uri`) are read from.
#[derive(Clone, Copy, Debug, Default)]
pub enum Companions<'a> {
    /// Beside the input on disk: inside its folder, regular files only.
    #[default]
    Folder,
    /// Files in memory, as (name, bytes): what a web page is given when files are dropped on it.
    /// A reference is looked up by its path relative to the input's folder (`textures/a.bin`),
    /// then by its file name alone (a drop keeps no folders) when exactly one file has it. A
    /// reference that climbs out of the folder (`..`) or is absolute is refused, as on disk.
    Memory(&'a [(String, Vec<u8>)]),
}

/// Reads `reference` (relative to the folder of `input`, as the input names it) from `companions`:
/// on disk if it resolves inside that folder and is a regular file, in memory as
/// [`Companions::Memory`] says; at most `limit` bytes.
pub(crate) fn read_reference(
    input: &Path,
    reference: &Path,
    limit: u64,
    companions: Companions<'_>,
) -> Result<Vec<u8>, RefusedReference> {
    let Companions::Memory(files) = companions else {
        let (file, length) = open_reference(input, reference, limit)?;
        return read_capped(file, length, limit)
            .map_err(refused_by)?
            .ok_or_else(|| too_large(limit));
    };
    let bytes = find_in_memory(reference, files)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(limit));
    }
    Ok(bytes.to_vec())
}

/// The bytes `reference` names among `files` (see [`Companions::Memory`]).
fn find_in_memory<'a>(
    reference: &Path,
    files: &'a [(String, Vec<u8>)],
) -> Result<&'a [u8], RefusedReference> {
    let parts = |path: &Path| -> Option<Vec<String>> {
        path.components()
            .filter(|c| !matches!(c, Component::CurDir))
            .map(|c| match c {
                Component::Normal(part) => Some(part.to_string_lossy().into_owned()),
                _ => None,
            })
            .collect()
    };
    let wanted = parts(reference).filter(|p| !p.is_empty()).ok_or_else(|| {
        RefusedReference::Refused(
            "resolves outside the file's folder (only files beside it or below it are read)".into(),
        )
    })?;
    let named = |name: &str| parts(Path::new(&name.replace('\\', "/")));
    if let Some((_, bytes)) = files
        .iter()
        .find(|(name, _)| named(name).as_ref() == Some(&wanted))
    {
        return Ok(bytes);
    }
    let file_name = wanted.last();
    let mut same_name = files
        .iter()
        .filter(|(name, _)| named(name).and_then(|p| p.last().cloned()).as_ref() == file_name);
    match (same_name.next(), same_name.next()) {
        (Some((_, bytes)), None) => Ok(bytes),
        (None, _) => Err(RefusedReference::Missing),
        (Some(_), Some(_)) => Err(RefusedReference::Refused(
            "matches more than one of the given files by name: give it in its folder".into(),
        )),
    }
}

/// Opens `reference` as [`read_reference`] would read it: inside the folder of `input` after
/// following links, a regular file, at most `limit` bytes. Returns it and its length.
pub(crate) fn open_reference(
    input: &Path,
    reference: &Path,
    limit: u64,
) -> Result<(File, u64), RefusedReference> {
    let folder = folder_of(input);
    let base = folder.canonicalize().map_err(refused_by)?;
    let target = folder.join(reference).canonicalize().map_err(refused_by)?;
    if !target.starts_with(&base) {
        return Err(RefusedReference::Refused(
            "resolves outside the file's folder (only files beside it or below it are read)".into(),
        ));
    }
    let (file, length) = open_regular(&target).map_err(|e| match e {
        Error::NotAFile { kind, .. } => {
            RefusedReference::Refused(format!("is {kind}, not a regular file"))
        }
        Error::Read { source, .. } => refused_by(source),
        other => RefusedReference::Refused(other.to_string()),
    })?;
    if length > limit {
        return Err(too_large(limit));
    }
    Ok((file, length))
}

fn refused_by(e: io::Error) -> RefusedReference {
    match e.kind() {
        io::ErrorKind::NotFound => RefusedReference::Missing,
        _ => RefusedReference::Refused(format!("cannot be read: {e}")),
    }
}

fn too_large(limit: u64) -> RefusedReference {
    RefusedReference::Refused(format!(
        "is larger than the limit of {limit} bytes (raise it with --max-input-bytes or Limits)"
    ))
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
pub(crate) fn read_capped(
    source: impl Read,
    expected: u64,
    limit: u64,
) -> io::Result<Option<Vec<u8>>> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_allocation_that_fails_while_inflating_names_the_sizes_and_the_limit() {
        let mut bytes = vec![0u8; 10];
        let error = reserve(&mut bytes, usize::MAX / 2, u64::MAX).expect_err("cannot allocate");
        let text = error.to_string();
        assert_eq!(error.kind(), io::ErrorKind::OutOfMemory);
        assert!(
            text.contains("10 bytes inflated") && text.contains("--max-input-bytes"),
            "{text}"
        );
        // Growth doubles, but never past the limit.
        let mut bytes = vec![0u8; 600];
        assert_eq!(bytes.capacity(), 600);
        reserve(&mut bytes, 100, 1000).expect("fits");
        assert_eq!(bytes.capacity(), 1000);
    }
}
