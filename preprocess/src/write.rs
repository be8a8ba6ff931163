//! Writing outputs without ever leaving a half-written file or touching an input.
//!
//! An output is written to a temporary file beside it and renamed into place, so a failure leaves
//! the old file as it was. The new file gets the mode any new file would (0666 minus the umask);
//! replacing an existing file keeps that file's mode. Only regular files are replaced: a FIFO or a
//! device named as the output is refused and left as it is (renaming over `/dev/null` would replace
//! it). Errors name the output path, never the temporary file.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use crate::Error;
use crate::load::files::kind_of;

/// Writes `path` through a temporary file in the same directory, renamed into place only after
/// `fill` and the flush succeed; on any error the destination is left as it was.
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<&File>) -> std::io::Result<()>,
) -> Result<(), Error> {
    let write_error = |source| Error::Write {
        path: path.to_owned(),
        source,
    };
    let existing = ensure_replaceable(path)?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".chamfer-").suffix(".tmp");
    #[cfg(unix)]
    {
        // The mode a plain `File::create` would give (the umask applies); tempfile's own is 0600.
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let temp = builder
        .tempfile_in(dir)
        .map_err(|e| write_error(without_path(e)))?;
    if let Some(permissions) = existing {
        // The old file's read and write bits, not its set-user-id or sticky bits.
        #[cfg(unix)]
        let permissions = {
            use std::os::unix::fs::PermissionsExt;
            std::fs::Permissions::from_mode(permissions.mode() & 0o777)
        };
        temp.as_file()
            .set_permissions(permissions)
            .map_err(write_error)?;
    }
    {
        let mut out = BufWriter::with_capacity(1 << 20, temp.as_file());
        fill(&mut out).map_err(write_error)?;
        out.flush().map_err(write_error)?;
    }
    temp.persist(path)
        .map_err(|e| write_error(without_path(e.error)))?;
    Ok(())
}

/// Refuses an output path that exists and is not a regular file (a FIFO, a device, a folder);
/// returns the permissions of the regular file it would replace, if there is one.
pub fn ensure_replaceable(path: &Path) -> Result<Option<std::fs::Permissions>, Error> {
    match std::fs::metadata(path) {
        Ok(meta) if !meta.is_file() => Err(Error::NotAFile {
            path: path.to_owned(),
            kind: kind_of(&meta),
        }),
        Ok(meta) => Ok(Some(meta.permissions())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(Error::Write {
            path: path.to_owned(),
            source: e,
        }),
    }
}

/// tempfile appends ` at path "<the temporary file>"` to its errors (and hides the OS error
/// behind that wrapper); the user named another path, so only the reason is kept.
fn without_path(error: std::io::Error) -> std::io::Error {
    if let Some(code) = error.raw_os_error() {
        return std::io::Error::from_raw_os_error(code);
    }
    let text = error.to_string();
    match text.rfind(" at path ") {
        Some(end) => std::io::Error::new(error.kind(), &text[..end]),
        None => error,
    }
}

/// Refuses an output path that names one of the inputs (after resolving links and `..`).
pub fn ensure_not_an_input(output: &Path, inputs: &[&Path]) -> Result<(), Error> {
    let Ok(out) = output.canonicalize() else {
        return Ok(()); // does not exist yet, so it cannot be an input
    };
    if inputs
        .iter()
        .any(|i| i.canonicalize().is_ok_and(|i| i == out))
    {
        return Err(Error::OutputIsInput {
            path: output.to_owned(),
        });
    }
    Ok(())
}
