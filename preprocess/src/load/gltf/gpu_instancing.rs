//! `EXT_mesh_gpu_instancing` (Khronos extension registry, `extensions/2.0/Vendor/EXT_mesh_gpu_instancing`):
//! a node draws its mesh once per element of its `TRANSLATION`, `ROTATION` and `SCALE`
//! accessors (all of one count; a missing one is the identity), each instance's transform applied
//! before the node's own (`world = node_world * T * R * S`).
//!
//! [`count`] reads only the JSON, so the node graph's instances are counted against
//! [`Limits::max_instances`](crate::Limits::max_instances) before any accessor is read;
//! [`transforms`] reads the accessors once the buffers are loaded.

use glam::{Mat4, Quat, Vec3, Vec4};
use gltf::json;
use serde_json::Value;

use super::accessor::Accessors;

/// The extension's name in `extensionsUsed` and on nodes.
pub(super) const NAME: &str = "EXT_mesh_gpu_instancing";

const ATTRIBUTES: [&str; 3] = ["TRANSLATION", "ROTATION", "SCALE"];

/// The accessor of each attribute (`TRANSLATION`, `ROTATION`, `SCALE`) that `node` names, or `None`
/// when the node does not use the extension (or has no mesh, which it instances).
fn attributes(node: &json::scene::Node) -> Result<Option<[Option<usize>; 3]>, String> {
    let Some(extension) = node
        .extensions
        .as_ref()
        .and_then(|e| e.others.get(NAME))
        .filter(|_| node.mesh.is_some())
    else {
        return Ok(None);
    };
    let Some(attributes) = extension.get("attributes").and_then(Value::as_object) else {
        return Err(format!("{NAME} has no attributes object"));
    };
    let mut found = [None; 3];
    for (slot, name) in found.iter_mut().zip(ATTRIBUTES) {
        if let Some(index) = attributes.get(name) {
            let index = index
                .as_u64()
                .and_then(|i| usize::try_from(i).ok())
                .ok_or_else(|| format!("{NAME} attribute {name} is not an accessor index"))?;
            *slot = Some(index);
        }
    }
    Ok(Some(found))
}

/// How many instances `node` draws of its mesh: `None` without the extension (once, as usual),
/// else the attributes' common element count. Refuses attributes that name no accessor or
/// disagree on the count.
pub(super) fn count(root: &json::Root, node: &json::scene::Node) -> Result<Option<u64>, String> {
    let Some(attributes) = attributes(node)? else {
        return Ok(None);
    };
    let mut count: Option<(u64, &str)> = None;
    for (index, name) in attributes.iter().zip(ATTRIBUTES) {
        let Some(index) = *index else { continue };
        let accessor = root.accessors.get(index).ok_or_else(|| {
            format!("{NAME} attribute {name} names accessor {index}, which does not exist")
        })?;
        let n = accessor.count.0;
        match count {
            Some((first, first_name)) if first != n => {
                return Err(format!(
                    "{NAME} attributes disagree: {first_name} has {first} elements, {name} {n}"
                ));
            }
            _ => count = Some((n, name)),
        }
    }
    // An extension without attributes draws the mesh once, untransformed.
    Ok(Some(count.map_or(1, |(n, _)| n)))
}

/// Each instance's transform in the node's space (`T * R * S`), `count` of them (as [`count`]
/// found them). Rotations are normalized; the accessors are read with their checks (bounds, NaN).
pub(super) fn transforms(
    accessors: &Accessors,
    node: &json::scene::Node,
    count: u64,
) -> Result<Vec<Mat4>, String> {
    let Some([translation, rotation, scale]) = attributes(node)? else {
        return Ok(vec![Mat4::IDENTITY]);
    };
    let vectors = |index: Option<usize>| index.map(|i| accessors.read_vectors::<3>(i)).transpose();
    let translations = vectors(translation)?;
    let scales = vectors(scale)?;
    let rotations = rotation
        .map(|i| accessors.read_vectors::<4>(i))
        .transpose()?;
    let count = usize::try_from(count).map_err(|_| format!("{count} instances"))?;
    let lengths = [
        translations.as_ref().map(Vec::len),
        rotations.as_ref().map(Vec::len),
        scales.as_ref().map(Vec::len),
    ];
    if lengths.iter().flatten().any(|&n| n != count) {
        return Err(format!(
            "{NAME} attributes do not all have {count} elements"
        ));
    }
    (0..count)
        .map(|i| {
            let t = translations
                .as_ref()
                .map_or(Vec3::ZERO, |t| Vec3::from(t[i]));
            let r = match &rotations {
                None => Quat::IDENTITY,
                Some(r) => Vec4::from_array(r[i])
                    .try_normalize()
                    .map(Quat::from_vec4)
                    .ok_or_else(|| format!("{NAME} ROTATION {i} is {:?}, not a rotation", r[i]))?,
            };
            let s = scales.as_ref().map_or(Vec3::ONE, |s| Vec3::from(s[i]));
            Ok(Mat4::from_scale_rotation_translation(s, r, t))
        })
        .collect()
}
