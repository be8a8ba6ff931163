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
//! hash of the input's bytes, the options and this crate's version; when it matches, the bake is
//! skipped. A broken input fails the build with its path and what is wrong.

use std::path::{Path, PathBuf};

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
/// with the first broken input's error otherwise.
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
    let mut inputs = Vec::new();
    collect(dir, &mut inputs, cargo)?;
    let mut results = Vec::with_capacity(inputs.len());
    for input in inputs {
        cargo(format!("cargo:rerun-if-changed={}", input.display()));
        let relative = input.strip_prefix(dir).unwrap_or(&input);
        let output = out_dir.join(asset_name(relative));
        let key_path = output.with_extension("chamfer.key");
        let bytes = load::read(&input)?; // inflated if .gz
        let key = format!(
            "{:016x}\n",
            content_key(&bytes, &companions(&input)?, options)
        );
        let up_to_date =
            output.is_file() && std::fs::read_to_string(&key_path).is_ok_and(|k| k == key);
        if !up_to_date {
            let baked = bake_bytes(&input, &bytes, options)?;
            if let Some(parent) = output.parent() {
                std::fs::create_dir_all(parent).map_err(|source| Error::Write {
                    path: parent.to_owned(),
                    source,
                })?;
            }
            write_atomically(&output, |out| baked.asset.encode(out))?;
            write_atomically(&key_path, |out| {
                std::io::Write::write_all(out, key.as_bytes())
            })?;
        }
        results.push(BakedFile {
            input,
            output,
            baked: !up_to_date,
        });
    }
    Ok(results)
}

/// Every mesh file under `dir`, sorted; announces each folder to Cargo.
fn collect(
    dir: &Path,
    inputs: &mut Vec<PathBuf>,
    cargo: &mut dyn FnMut(String),
) -> Result<(), Error> {
    cargo(format!("cargo:rerun-if-changed={}", dir.display()));
    let read_error = |source| Error::Read {
        path: dir.to_owned(),
        source,
    };
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(read_error)?
        .map(|entry| entry.map(|e| e.path()))
        .collect::<Result<_, _>>()
        .map_err(read_error)?;
    entries.sort();
    for path in entries {
        if path.is_dir() {
            collect(&path, inputs, cargo)?;
        } else if format_of(&path).is_some() {
            inputs.push(path);
        }
    }
    Ok(())
}

/// `props/crate.glb` -> `props/crate.chamfer`; `scan.ply.gz` -> `scan.chamfer`.
fn asset_name(relative: &Path) -> PathBuf {
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

/// Files an OBJ or `.gltf` may refer to (`.mtl`, `.bin`, ...): every non-mesh file beside it, sorted.
/// Conservative: a change to any of them re-bakes the meshes of that folder.
fn companions(input: &Path) -> Result<Vec<Vec<u8>>, Error> {
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
    let mut siblings: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(read_error)?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && format_of(p).is_none())
        .collect();
    siblings.sort();
    siblings
        .iter()
        .map(|p| {
            std::fs::read(p).map_err(|source| Error::Read {
                path: p.clone(),
                source,
            })
        })
        .collect()
}

/// FNV-1a over the input, its companions, the options and this crate's version: stable across runs
/// and toolchains.
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
