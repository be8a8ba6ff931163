//! Baking a glTF scene (or a 3MF build) with its structure kept: one asset per mesh the scene draws and a scene file
//! ([`chamfer_runtime::scene::SceneFile`]) of its instances, so a runtime can draw, move and hide
//! each instance (an exploded view, a door that opens), and reading such a scene back. The
//! flattened single asset stays what [`bake_file`](crate::bake_file) makes.

use std::path::{Path, PathBuf};

use chamfer_runtime::asset::Asset;
use chamfer_runtime::scene::{MAX_SCENE_BYTES, SceneFile, SceneInstance};
use glam::Mat4;

use crate::load::files::{Companions, RefusedReference, read_reference};
use crate::load::{self, Format};
use crate::write::write_atomically;
use crate::{BakeOptions, Baked, Error, Limits, bake};

/// A baked scene: its assets, named, and the scene file that draws them.
#[derive(Debug)]
pub struct BakedScene {
    /// Each asset's file name (`{stem}.mesh{N}.chamfer`, N the glTF mesh's index) and its bake.
    pub assets: Vec<(String, Baked)>,
    /// The instances, naming the assets above.
    pub scene: SceneFile,
    /// What the loader had to skip.
    pub warnings: Vec<String>,
}

/// Bakes every mesh a glTF/GLB file's scene draws (or every mesh object a 3MF build places), each
/// in its own space, and lists the instances. `stem` names the assets (`{stem}.mesh{N}.chamfer`, N
/// the glTF mesh index or the 3MF object id).
///
/// A mesh without triangles (only points or lines) is left out with a warning naming it, with its
/// instances. Fails, naming the file, for other formats (`--scene` keeps a glTF node graph or a 3MF
/// build; an OBJ, PLY or STL has none), for whatever [`bake_file`](crate::bake_file) fails on (a mesh that cannot be
/// baked is named: `file: mesh N: ...`), and for a scene with no mesh that has triangles.
pub fn bake_scene(path: &Path, stem: &str, options: &BakeOptions) -> Result<BakedScene, Error> {
    options.validate()?;
    let unsupported = || Error::Unsupported {
        path: path.to_owned(),
        what:
            "a scene from anything but glTF, GLB or 3MF (only they keep meshes and instances apart)"
                .into(),
    };
    if !matches!(load::format_of(path), Some(Format::Gltf | Format::ThreeMf)) {
        return Err(unsupported());
    }
    let bytes = load::read(path, &options.limits)?;
    let mut warnings = Vec::new();
    let parsed = load::parse_scene(
        path,
        &bytes,
        Companions::Folder,
        &options.limits,
        &mut warnings,
    )
    .ok_or_else(unsupported)??;
    if parsed.meshes.is_empty() {
        return Err(Error::Unsupported {
            path: path.to_owned(),
            what: "a scene that draws no mesh".into(),
        });
    }
    // A mesh without triangles (points, lines) has nothing to bake: it is left out, not fatal.
    let mut assets = Vec::with_capacity(parsed.meshes.len());
    let mut asset_of = vec![None; parsed.meshes.len()];
    for (k, (index, mesh, holds)) in parsed.meshes.into_iter().enumerate() {
        if mesh.triangles.is_empty() {
            let dropped = parsed.instances.iter().filter(|&&(m, _)| m == k).count();
            warnings.push(format!(
                "mesh {index} holds {} and no triangles: not baked, its {dropped} instance(s) left out of the scene",
                holds.unwrap_or("nothing to draw")
            ));
            continue;
        }
        let baked = bake(mesh, &format!("{} mesh {index}", path.display()), options).map_err(
            |e| match e {
                Error::Mesh { source, .. } => Error::SceneMesh {
                    path: path.to_owned(),
                    mesh: index,
                    source,
                },
                other => other,
            },
        )?;
        asset_of[k] = Some(assets.len() as u32);
        assets.push((format!("{stem}.mesh{index}.chamfer"), baked));
    }
    if assets.is_empty() {
        return Err(Error::Unsupported {
            path: path.to_owned(),
            what: "nothing to bake: no mesh the scene draws has triangles".into(),
        });
    }
    let instances = parsed
        .instances
        .into_iter()
        .filter_map(|(mesh, transform)| {
            Some(SceneInstance {
                asset: asset_of.get(mesh).copied().flatten()?,
                transform: transform.to_cols_array(),
                name: None,
            })
        })
        .collect();
    let scene = SceneFile::new(
        assets.iter().map(|(name, _)| name.clone()).collect(),
        instances,
    );
    Ok(BakedScene {
        assets,
        scene,
        warnings,
    })
}

/// Writes a baked scene into `folder` (each file atomically): the assets (compact with `compact`),
/// then `{stem}.scene.json`. Returns the scene file's path.
pub fn write_scene(
    baked: &BakedScene,
    folder: &Path,
    stem: &str,
    compact: Option<&chamfer_runtime::asset::CompactOptions>,
) -> Result<PathBuf, Error> {
    for (name, asset) in &baked.assets {
        write_atomically(&folder.join(name), |out| {
            crate::compact::encode(&asset.asset, compact, out)
        })?;
    }
    let scene_path = folder.join(format!("{stem}.scene.json"));
    let text = baked.scene.to_json();
    write_atomically(&scene_path, |out| {
        std::io::Write::write_all(out, text.as_bytes())
    })?;
    Ok(scene_path)
}

/// A scene file read back: its assets, decoded, and what draws them.
#[derive(Debug)]
pub struct LoadedScene {
    /// The assets, in the scene file's order.
    pub assets: Vec<Asset>,
    /// Each instance's asset (an index into `assets`) and model-to-world transform.
    pub instances: Vec<(usize, Mat4)>,
}

/// Reads a scene file (at most [`MAX_SCENE_BYTES`] and `limits.max_input_bytes`) and the assets it
/// names. Assets are read only from the scene's folder or below it (a link that leads out is
/// refused), each a regular file within `limits.max_input_bytes`, and decoded with the asset's
/// validation.
///
/// Fails, naming the file, for a scene that does not parse or validate
/// ([`SceneFile::parse`]), an asset that is missing, refused or does not decode.
pub fn read_scene(path: &Path, limits: &Limits) -> Result<LoadedScene, Error> {
    let limits = limits.with_max_input_bytes(limits.max_input_bytes.min(MAX_SCENE_BYTES));
    let bytes = load::read(path, &limits)?;
    let scene = SceneFile::parse(&bytes).map_err(|e| Error::Parse {
        path: path.to_owned(),
        format: "scene file",
        message: e.to_string(),
    })?;
    let assets = scene
        .assets
        .iter()
        .map(|name| {
            let refused = |problem: String| Error::Reference {
                path: path.to_owned(),
                reference: format!("asset {name:?}"),
                problem,
            };
            let bytes = read_reference(
                path,
                Path::new(name),
                limits.max_input_bytes,
                Companions::Folder,
            )
            .map_err(|e| match e {
                RefusedReference::Missing => refused("does not exist".into()),
                RefusedReference::Refused(problem) => refused(problem),
            })?;
            Asset::decode(&bytes).map_err(|e| Error::Parse {
                path: load::files::folder_of(path).join(name),
                format: "Chamfer asset",
                message: e.to_string(),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let instances = scene
        .instances
        .iter()
        .map(|i| (i.asset as usize, Mat4::from_cols_array(&i.transform)))
        .collect();
    Ok(LoadedScene { assets, instances })
}
