//! What the loader does with each extension a glTF lists in `extensionsUsed` or
//! `extensionsRequired` (Khronos glTF extension registry): compressed geometry it cannot decode
//! is refused; extensions it reads, and those that never change geometry (materials, textures,
//! lights, metadata), pass silently; every other one — those known to change the geometry drawn,
//! and those it does not know — is named in a warning, so a bake never differs from the file
//! without a word.

use std::path::Path;

use gltf::json;

use super::gpu_instancing;
use crate::Error;

/// Compression schemes whose data this loader cannot decode.
pub(super) const COMPRESSION: [&str; 3] = [
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
];

/// Extensions the loader reads.
const READ: [&str; 4] = [
    "KHR_mesh_quantization",
    gpu_instancing::NAME,
    "CESIUM_primitive_outline",
    "EXT_mesh_primitive_edge_visibility",
];

/// Extensions that change the geometry a file draws and are not applied, with what is baked instead.
const NOT_APPLIED: [(&str, &str); 5] = [
    (
        "MSFT_lod",
        "only the full-detail meshes are read, not the other levels of detail",
    ),
    (
        "KHR_node_visibility",
        "nodes it hides are baked as if they were visible",
    ),
    (
        "KHR_gaussian_splatting",
        "its splats are not triangles and are not baked",
    ),
    (
        "EXT_meshopt_compression",
        "compressed buffer views are read from their uncompressed fallback buffers",
    ),
    (
        "KHR_meshopt_compression",
        "compressed buffer views are read from their uncompressed fallback buffers",
    ),
];

/// Extensions (by name prefix) that never change geometry.
const NOT_GEOMETRY: [&str; 22] = [
    "KHR_materials_",
    "KHR_texture_",
    "EXT_texture_",
    "MSFT_texture_",
    "MSFT_packing_",
    "ADOBE_materials_",
    "KHR_lights_",
    "EXT_lights_",
    "KHR_xmp",
    "KHR_animation_pointer",
    "KHR_techniques_webgl",
    "KHR_interactivity",
    "KHR_audio",
    "KHR_physics_",
    "KHR_implicit_shapes",
    "KHR_node_selectability",
    "KHR_node_hoverability",
    "EXT_mesh_features",
    "EXT_structural_metadata",
    "EXT_instance_features",
    "EXT_mesh_manifold",
    "FB_geometry_metadata",
];

/// Refuses required compression; warns for each listed extension that is neither read nor known
/// to leave geometry alone (once per name).
pub(super) fn check(
    path: &Path,
    root: &json::Root,
    warnings: &mut Vec<String>,
) -> Result<(), Error> {
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| COMPRESSION.contains(&e.as_str()))
    {
        return Err(Error::Unsupported {
            path: path.to_owned(),
            what: format!(
                "{ext} compressed geometry (decompress it first, e.g. `gltf-transform copy`)"
            ),
        });
    }
    let mut seen: Vec<&str> = Vec::new();
    let listed = root.extensions_required.iter().chain(&root.extensions_used);
    for ext in listed.map(String::as_str) {
        let required = root.extensions_required.iter().any(|e| e == ext);
        if seen.contains(&ext)
            || READ.contains(&ext)
            || NOT_GEOMETRY.iter().any(|prefix| ext.starts_with(prefix))
            // Used, not required: a compressed primitive is refused where it is read.
            || ext == COMPRESSION[0]
        {
            continue;
        }
        seen.push(ext);
        let kind = if required {
            "required extension"
        } else {
            "extension"
        };
        warnings.push(match NOT_APPLIED.iter().find(|(name, _)| *name == ext) {
            Some((_, instead)) => format!("{kind} {ext} changes geometry and is not applied: {instead}"),
            None => format!(
                "{kind} {ext} is not supported and is ignored (if it changes geometry, the bake does not show it)"
            ),
        });
    }
    Ok(())
}
