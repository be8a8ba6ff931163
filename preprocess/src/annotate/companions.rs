//! The files an annotated glTF refers to. A `.gltf` (or a GLB's extra buffers and images) names
//! them by a `uri` relative to its own folder, so a copy written to another folder would name files
//! that are not there, and could not be read back (issue 23: 23 of 27 annotated Khronos samples).
//!
//! Each buffer and image file the input refers to is copied beside the output at the same
//! relative path: read under the loader's rules (inside the input's folder after following links,
//! a regular file, within the size limit), streamed, and written atomically. A file already there
//! with the same bytes is kept; one with other bytes belongs to something else (another model's
//! `buffer.bin`) and is never replaced: annotate fails before writing anything. Nothing is
//! copied when the output's folder is the input's. An image that is missing or not a file beside
//! the input is not copied, with a warning (the output refers to it just as the input does).

use std::fs::File;
use std::io::{self, Read};
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::Error;
use crate::load::files::{RefusedReference, folder_of, open_reference};
use crate::load::gltf::buffers::relative_path;
use crate::write::write_atomically;

/// One file to copy: where the input names it, and where it goes.
pub(super) struct Companion {
    relative: PathBuf,
    target: PathBuf,
}

/// The files `document` (read from `input`) refers to that must be copied for `output` to be read,
/// checked: refuses a buffer that cannot be read and a target that exists with other bytes or lies
/// outside the output's folder through a link. Images that cannot be copied are warnings.
pub(super) fn plan(
    input: &Path,
    output: &Path,
    document: &Value,
    limit: u64,
    warnings: &mut Vec<String>,
) -> Result<Vec<Companion>, Error> {
    let from = folder_of(input)
        .canonicalize()
        .map_err(|source| Error::Read {
            path: input.to_owned(),
            source,
        })?;
    let to = folder_of(output)
        .canonicalize()
        .map_err(|source| Error::Write {
            path: output.to_owned(),
            source,
        })?;
    if from == to {
        return Ok(Vec::new());
    }
    let mut planned: Vec<Companion> = Vec::new();
    for (kind, key) in [("buffer", "buffers"), ("image", "images")] {
        let items = document.get(key).and_then(Value::as_array);
        for (i, item) in items.into_iter().flatten().enumerate() {
            let Some(uri) = item.get("uri").and_then(Value::as_str) else {
                continue;
            };
            if uri.starts_with("data:") {
                continue;
            }
            let refused = |problem: String| Error::Reference {
                path: output.to_owned(),
                reference: format!("{kind} {i} uri '{uri}'"),
                problem,
            };
            let opened = relative_path(uri).and_then(|relative| {
                match open_reference(input, &relative, limit) {
                    Ok(_) => Ok(relative),
                    Err(RefusedReference::Missing) => {
                        Err("names a file that does not exist beside the input".into())
                    }
                    Err(RefusedReference::Refused(problem)) => Err(problem),
                }
            });
            let relative = match opened {
                Ok(relative) => relative,
                Err(problem) if kind == "image" => {
                    warnings.push(format!(
                        "image {i} uri '{uri}': {problem}: not copied beside the output"
                    ));
                    continue;
                }
                Err(problem) => return Err(refused(problem)),
            };
            if planned.iter().any(|c| c.relative == relative) {
                continue;
            }
            let target = to.join(&relative);
            if !inside(&to, &target) {
                return Err(refused(format!(
                    "{} would be written outside the output's folder (through a link)",
                    target.display()
                )));
            }
            let source = from.join(&relative);
            if target.symlink_metadata().is_ok() {
                let same_file = target.canonicalize().ok() == source.canonicalize().ok();
                if same_file || same_bytes(&source, &target).unwrap_or(false) {
                    continue;
                }
                return Err(refused(format!(
                    "{} already exists with other content and is left alone (write the output \
                     to another folder, or as .glb)",
                    target.display()
                )));
            }
            planned.push(Companion { relative, target });
        }
    }
    Ok(planned)
}

/// Copies the planned files (each atomically, folders created as needed); returns where they went.
pub(super) fn copy(
    input: &Path,
    companions: &[Companion],
    limit: u64,
) -> Result<Vec<PathBuf>, Error> {
    let mut copied = Vec::with_capacity(companions.len());
    for companion in companions {
        let (file, _) =
            open_reference(input, &companion.relative, limit).map_err(|e| Error::Reference {
                path: input.to_owned(),
                reference: companion.relative.display().to_string(),
                problem: match e {
                    RefusedReference::Missing => "vanished while annotating".into(),
                    RefusedReference::Refused(problem) => problem,
                },
            })?;
        if let Some(folder) = companion.target.parent() {
            std::fs::create_dir_all(folder).map_err(|source| Error::Write {
                path: folder.to_owned(),
                source,
            })?;
        }
        write_atomically(&companion.target, |out| {
            io::copy(&mut file.take(limit), out).map(|_| ())
        })?;
        copied.push(companion.target.clone());
    }
    Ok(copied)
}

/// Whether `target`, once its missing folders exist, lies inside `folder` (both canonical where
/// they exist): its nearest existing ancestor must resolve inside.
fn inside(folder: &Path, target: &Path) -> bool {
    let mut existing = target.parent();
    while let Some(path) = existing {
        if path.exists() {
            return path.canonicalize().is_ok_and(|p| p.starts_with(folder));
        }
        existing = path.parent();
    }
    false
}

/// Whether the regular file `b` holds the same bytes as `a` (compared in chunks; `b` is not
/// opened unless it is a regular file: a FIFO would block).
fn same_bytes(a: &Path, b: &Path) -> io::Result<bool> {
    let (meta_a, meta_b) = (std::fs::metadata(a)?, std::fs::metadata(b)?);
    if !meta_b.is_file() || meta_a.len() != meta_b.len() {
        return Ok(false);
    }
    let (mut a, mut b) = (File::open(a)?, File::open(b)?);
    let (mut x, mut y) = (vec![0u8; 1 << 16], vec![0u8; 1 << 16]);
    loop {
        let n = a.read(&mut x)?;
        if n == 0 {
            return Ok(true);
        }
        b.read_exact(&mut y[..n])?;
        if x[..n] != y[..n] {
            return Ok(false);
        }
    }
}
