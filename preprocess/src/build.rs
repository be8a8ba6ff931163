//! Baking from a `build.rs`: every mesh under a folder into `OUT_DIR`, re-baked only when its bytes or
//! the options change.
//!
//! ```no_run
//! // build.rs
//! fn main() -> Result<(), chamfer_preprocess::Error> {
//!     chamfer_preprocess::build::bake_dir("assets", &chamfer_preprocess::BakeOptions::DEFAULT)?;
//!     Ok(())
//! }
//! // main.rs: static CUBE: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/cube.chamfer"));
//! ```
//!
//! `assets/props/crate.glb` becomes `$OUT_DIR/props/crate.chamfer`. Cargo is told to re-run the
//! script when the folder or any input changes. Each output has a sidecar `.chamfer.key` holding a
//! hash of the input's bytes, the options, this crate's version and the format version; when it
//! matches, the bake is skipped ([`bake_if_changed`], which batch bakers such as the Python
//! package's Dask runner call per file). A broken input fails the build with its path and what is wrong.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use crate::load::files::{kind_of, open_regular};
use crate::load::format_of;
use crate::write::write_atomically;
use crate::{BakeOptions, Error, bake_bytes, load};

/// One input and the asset it produced.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BakedFile {
    /// The mesh file.
    pub input: PathBuf,
    /// The `.chamfer` asset in `OUT_DIR`.
    pub output: PathBuf,
    /// False when the asset was up to date and the bake was skipped.
    pub baked: bool,
}

/// Bakes every supported mesh under `dir` (recursively, in sorted order) into `OUT_DIR`.
///
/// Prints `cargo:rerun-if-changed` for `dir`, each sub-folder and each input. Fails with
/// [`Error::Read`] when `OUT_DIR` is not set (not running under Cargo) or `dir` cannot be read, and
/// with the first broken input's error otherwise. Inputs and the folders they are in must resolve,
/// after following links, inside `dir`; two inputs that would give the same asset
/// (`part.glb` and `part.ply`) fail with [`Error::OutputClash`] before anything is written.
pub fn bake_dir(dir: impl AsRef<Path>, options: &BakeOptions) -> Result<Vec<BakedFile>, Error> {
    let out_dir = std::env::var_os("OUT_DIR")
        .map(PathBuf::from)
        .ok_or_else(|| Error::Read {
            path: PathBuf::from("$OUT_DIR"),
            source: std::io::Error::new(
                std::io::ErrorKind::NotFound,
                "OUT_DIR is not set: call bake_dir from build.rs",
            ),
        })?;
    bake_dir_into(dir.as_ref(), &out_dir, options, &mut |line| {
        println!("{line}")
    })
}

/// [`bake_dir`] with an explicit output folder; `cargo` receives each `cargo:` line.
pub fn bake_dir_into(
    dir: &Path,
    out_dir: &Path,
    options: &BakeOptions,
    cargo: &mut dyn FnMut(String),
) -> Result<Vec<BakedFile>, Error> {
    options.validate()?;
    let jobs = plan_dir(dir, out_dir, cargo)?;
    let mut results = Vec::with_capacity(jobs.len());
    for (input, output) in jobs {
        cargo(format!("cargo:rerun-if-changed={}", input.display()));
        let baked = bake_if_changed(&input, &output, options)?;
        results.push(BakedFile {
            input,
            output,
            baked,
        });
    }
    Ok(results)
}

/// Bakes `input` into `output` unless `output` exists and its sidecar `.chamfer.key` (beside it)
/// holds the key of the input's bytes, its companion files, the options, this crate's version and
/// the asset format version. Returns true when it baked, false when the asset was up to date.
///
/// Both files are written atomically, the asset first: a process killed in between leaves an asset
/// whose key does not match its input, so the next call bakes it again, never a stale asset under a
/// fresh key. Parent folders of `output` are created. Errors name the input (or the output).
pub fn bake_if_changed(input: &Path, output: &Path, options: &BakeOptions) -> Result<bool, Error> {
    options.validate()?;
    let key_path = output.with_extension("chamfer.key");
    let bytes = load::read(input, &options.limits)?; // inflated if .gz
    let key = format!(
        "{:016x}\n",
        content_key(&bytes, &companions(input, options)?, options)
    );
    if output.is_file() && std::fs::read_to_string(&key_path).is_ok_and(|k| k == key) {
        return Ok(false);
    }
    let baked = bake_bytes(input, &bytes, options)?;
    if let Some(parent) = output.parent() {
        std::fs::create_dir_all(parent).map_err(|source| Error::Write {
            path: parent.to_owned(),
            source,
        })?;
    }
    write_atomically(output, |out| baked.asset.encode(out))?;
    write_atomically(&key_path, |out| {
        std::io::Write::write_all(out, key.as_bytes())
    })?;
    Ok(true)
}

/// Every mesh under `dir` paired with its asset under `out_dir` (`props/crate.glb` ->
/// `props/crate.chamfer`), sorted; refuses inputs outside `dir`, special files named like meshes,
/// and two inputs with one output. Announces each folder to Cargo.
pub fn plan_dir(
    dir: &Path,
    out_dir: &Path,
    cargo: &mut dyn FnMut(String),
) -> Result<Vec<(PathBuf, PathBuf)>, Error> {
    let read_error = |source| Error::Read {
        path: dir.to_owned(),
        source,
    };
    let root = dir.canonicalize().map_err(read_error)?;
    let mut inputs = Vec::new();
    collect(dir, &root, &mut HashSet::new(), &mut inputs, cargo)?;
    let mut jobs = Vec::with_capacity(inputs.len());
    let mut outputs: HashMap<PathBuf, PathBuf> = HashMap::new();
    for input in inputs {
        let relative = input.strip_prefix(dir).unwrap_or(&input);
        let output = out_dir.join(asset_name(relative));
        if let Some(first) = outputs.insert(output.clone(), input.clone()) {
            return Err(Error::OutputClash {
                first,
                second: input,
                output,
            });
        }
        jobs.push((input, output));
    }
    Ok(jobs)
}

/// Every mesh file under `dir`, sorted. Links are followed only when they resolve inside `root`
/// (the folder being baked), and each real folder is entered once, so a link loop ends.
fn collect(
    dir: &Path,
    root: &Path,
    entered: &mut HashSet<PathBuf>,
    inputs: &mut Vec<PathBuf>,
    cargo: &mut dyn FnMut(String),
) -> Result<(), Error> {
    let read_error = |path: &Path| {
        let path = path.to_owned();
        move |source| Error::Read { path, source }
    };
    let real = dir.canonicalize().map_err(read_error(dir))?;
    if !entered.insert(real) {
        return Ok(());
    }
    cargo(format!("cargo:rerun-if-changed={}", dir.display()));
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(read_error(dir))?
        .map(|entry| entry.map(|e| e.path()))
        .collect::<Result<_, _>>()
        .map_err(read_error(dir))?;
    entries.sort();
    for path in entries {
        let is_mesh = format_of(&path).is_some();
        let link = std::fs::symlink_metadata(&path)
            .map_err(read_error(&path))?
            .file_type()
            .is_symlink();
        if link {
            // A dangling link, or one that leaves the folder, is not an input.
            let Ok(target) = path.canonicalize() else {
                if is_mesh {
                    return Err(Error::Read {
                        path,
                        source: std::io::Error::new(
                            std::io::ErrorKind::NotFound,
                            "a link to nothing",
                        ),
                    });
                }
                continue;
            };
            if !target.starts_with(root) {
                if is_mesh || target.is_dir() {
                    return Err(Error::Reference {
                        path,
                        reference: format!("a link to {}", target.display()),
                        problem: format!("resolves outside {}", dir.display()),
                    });
                }
                continue;
            }
        }
        let meta = std::fs::metadata(&path).map_err(read_error(&path))?;
        if meta.is_dir() {
            collect(&path, root, entered, inputs, cargo)?;
        } else if is_mesh {
            if !meta.is_file() {
                return Err(Error::NotAFile {
                    path,
                    kind: kind_of(&meta),
                });
            }
            inputs.push(path);
        }
    }
    Ok(())
}

/// `props/crate.glb` -> `props/crate.chamfer`; `scan.ply.gz` -> `scan.chamfer`.
pub fn asset_name(relative: &Path) -> PathBuf {
    let name = relative
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = name.strip_suffix(".gz").unwrap_or(&name);
    let stem = Path::new(name)
        .file_stem()
        .map_or_else(|| name.to_owned(), |s| s.to_string_lossy().into_owned());
    relative.with_file_name(format!("{stem}.chamfer"))
}

/// What an OBJ or `.gltf` may refer to (`.mtl`, `.bin`, ...): every non-mesh regular file beside
/// it, sorted, by content. Conservative: a change to any of them re-bakes the meshes of that folder.
/// Links leaving the folder and special files are skipped (the loader would refuse them); a file
/// over the input-bytes limit is keyed by its length and modification time instead of read.
fn companions(input: &Path, options: &BakeOptions) -> Result<Vec<Vec<u8>>, Error> {
    let refers = input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("obj") || e.eq_ignore_ascii_case("gltf"));
    let Some(dir) = input.parent().filter(|_| refers) else {
        return Ok(Vec::new());
    };
    let read_error = |source| Error::Read {
        path: dir.to_owned(),
        source,
    };
    let folder = dir.canonicalize().map_err(read_error)?;
    let mut siblings: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(read_error)?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| format_of(p).is_none())
        .filter(|p| {
            p.canonicalize()
                .is_ok_and(|real| real.starts_with(&folder) && real.is_file())
        })
        .collect();
    siblings.sort();
    let limit = options.limits.max_input_bytes;
    siblings
        .iter()
        .map(|p| {
            let (file, length) = open_regular(p)?;
            if length > limit {
                let modified = file
                    .metadata()
                    .and_then(|m| m.modified())
                    .ok()
                    .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                    .map_or(0, |d| d.as_nanos());
                return Ok(format!("{length} bytes, modified {modified}").into_bytes());
            }
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut std::io::Read::take(file, limit), &mut bytes).map_err(
                |source| Error::Read {
                    path: p.clone(),
                    source,
                },
            )?;
            Ok(bytes)
        })
        .collect()
}

/// FNV-1a over the input, its companions, the options, this crate's version and the asset format
/// version and kinds (which change between releases while the crate's version may not): stable
/// across runs and toolchains.
fn content_key(bytes: &[u8], companions: &[Vec<u8>], options: &BakeOptions) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let mut feed = |data: &[u8]| {
        for &b in data {
            hash = (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    feed(bytes);
    for companion in companions {
        feed(&(companion.len() as u64).to_le_bytes());
        feed(companion);
    }
    feed(env!("CARGO_PKG_VERSION").as_bytes());
    feed(&chamfer_runtime::asset::FORMAT_VERSION.to_le_bytes());
    // The section kinds the format knows: they grow within a format version while it is developed.
    feed(&(chamfer_runtime::asset::SectionKind::ALL.len() as u64).to_le_bytes());
    for (name, value) in options.describe() {
        feed(name.as_bytes());
        feed(value.as_bytes());
    }
    hash
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixtures() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures")
    }

    #[test]
    fn bakes_a_folder_then_skips_what_did_not_change() {
        let assets = tempfile::tempdir().expect("tempdir");
        let out = tempfile::tempdir().expect("tempdir");
        std::fs::create_dir(assets.path().join("props")).expect("mkdir");
        std::fs::copy(
            fixtures().join("shapes/cube.obj"),
            assets.path().join("cube.obj"),
        )
        .expect("copy");
        std::fs::copy(
            fixtures().join("shapes/two-materials.glb"),
            assets.path().join("props/pair.glb"),
        )
        .expect("copy");
        std::fs::write(assets.path().join("notes.txt"), "not a mesh").expect("write");

        let mut lines = Vec::new();
        let first = bake_dir_into(assets.path(), out.path(), &BakeOptions::DEFAULT, &mut |l| {
            lines.push(l)
        })
        .expect("bakes");
        assert_eq!(first.len(), 2);
        assert!(first.iter().all(|f| f.baked && f.output.is_file()));
        assert!(out.path().join("props/pair.chamfer").is_file());
        assert!(lines.iter().any(|l| l.ends_with("cube.obj")), "{lines:?}");
        assert!(lines.iter().any(|l| l.ends_with("props")), "{lines:?}");

        let again = bake_dir_into(
            assets.path(),
            out.path(),
            &BakeOptions::DEFAULT,
            &mut |_| (),
        )
        .expect("bakes");
        assert!(again.iter().all(|f| !f.baked), "nothing changed: {again:?}");

        let other = BakeOptions::DEFAULT.with_crease_deg(45.0);
        let changed = bake_dir_into(assets.path(), out.path(), &other, &mut |_| ()).expect("bakes");
        assert!(
            changed.iter().all(|f| f.baked),
            "options changed: {changed:?}"
        );

        // A companion file beside an OBJ (its .mtl, say) counts as part of its input.
        std::fs::write(assets.path().join("notes.txt"), "edited").expect("write");
        let touched = bake_dir_into(assets.path(), out.path(), &other, &mut |_| ()).expect("bakes");
        assert_eq!(
            touched.iter().map(|f| f.baked).collect::<Vec<_>>(),
            vec![true, false]
        );

        std::fs::write(
            assets.path().join("cube.obj"),
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        )
        .expect("write");
        let edited = bake_dir_into(assets.path(), out.path(), &other, &mut |_| ()).expect("bakes");
        assert_eq!(
            edited.iter().map(|f| f.baked).collect::<Vec<_>>(),
            vec![true, false]
        );
    }

    #[test]
    fn a_broken_input_fails_with_its_path() {
        let assets = tempfile::tempdir().expect("tempdir");
        let out = tempfile::tempdir().expect("tempdir");
        std::fs::copy(
            fixtures().join("broken/nan-position.obj"),
            assets.path().join("bad.obj"),
        )
        .expect("copy");
        let error = bake_dir_into(
            assets.path(),
            out.path(),
            &BakeOptions::DEFAULT,
            &mut |_| (),
        )
        .expect_err("broken");
        assert!(error.to_string().contains("bad.obj"), "{error}");
    }
}
