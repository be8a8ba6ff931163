//! glTF 2.0 via the `gltf` crate: `.gltf` (external or base64-embedded buffers) and `.glb`.
//!
//! The default scene (or the first, or every mesh when there is no scene) is flattened with its node
//! transforms; instances are counted through the node graph before anything is expanded, and
//! each primitive is read once however many nodes draw it. TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives are read; points and lines are
//! skipped with a warning. Accessors are read here, bounds-checked, with sparse substitution and
//! KHR_mesh_quantization's integer types; the crate's own validation is bypassed because it rejects
//! every required extension, quantization included. Each primitive's material is its material id.
//! `EXT_mesh_gpu_instancing` nodes draw their mesh once per instance (`gpu_instancing.rs`). Draco
//! and meshopt compressed files are refused with the extension's name; other extensions that
//! change geometry are named in a warning (`extensions.rs`). A file whose meshes hold only points or
//! lines is refused saying so.

mod accessor;
pub(crate) mod buffers;
mod extensions;
mod gpu_instancing;
mod instances;
pub mod marks;
mod motion;

use std::collections::HashMap;
use std::collections::hash_map::Entry;
use std::path::Path;

use glam::{Mat3, Mat4, Quat, Vec2, Vec3};
use gltf::json::{self, validation::Checked};

use self::accessor::Accessors;
use super::SceneMeshes;
use crate::limits::Limited;
use crate::load::files::Companions;
use crate::mesh::Mesh;
use crate::motion::InputMotion;
use crate::{Error, Limits};

/// Where one primitive's first drawn instance lies in the loaded mesh (for writing marks back).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PrimitiveSpan {
    /// Index in the document's `meshes`.
    pub mesh: usize,
    /// Index in that mesh's `primitives`.
    pub primitive: usize,
    /// Its first vertex in the loaded mesh; its vertex `i` is mesh vertex `first_vertex + i`.
    pub first_vertex: u32,
    /// Its first triangle in the loaded mesh.
    pub first_triangle: u32,
    /// How many triangles it has.
    pub triangle_count: u32,
    /// Its first instance mirrors it (negative determinant): the loaded triangles have their last
    /// two corners swapped against the file's.
    pub mirrored: bool,
}

/// One drawing of a mesh: the mesh, its world transform, the node that draws it (`None` when the
/// file has no scene) and whether that node draws it through `EXT_mesh_gpu_instancing`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Placed {
    pub mesh: usize,
    pub world: Mat4,
    pub node: Option<usize>,
    pub gpu_instanced: bool,
}

/// The file's drawn meshes flattened into one, and what moves them (skins, morph targets,
/// animations; `None` when nothing does).
pub(super) fn parse(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Result<(Mesh, Option<InputMotion>), Error> {
    parse_drawn(
        path,
        bytes,
        companions,
        limits,
        warnings,
        &mut Vec::new(),
        true,
    )
}

/// The flattened mesh alone, also listing each primitive's first instance.
pub(crate) fn parse_with_spans(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    limits: &Limits,
    warnings: &mut Vec<String>,
    spans: &mut Vec<PrimitiveSpan>,
) -> Result<Mesh, Error> {
    parse_drawn(path, bytes, companions, limits, warnings, spans, false).map(|(mesh, _)| mesh)
}

fn parse_drawn(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    limits: &Limits,
    warnings: &mut Vec<String>,
    spans: &mut Vec<PrimitiveSpan>,
    read_motion: bool,
) -> Result<(Mesh, Option<InputMotion>), Error> {
    with_document(
        path,
        bytes,
        companions,
        limits,
        warnings,
        |root, accessors, instances, warnings| {
            let invalid = |message: String| Error::Parse {
                path: path.to_owned(),
                format: "glTF",
                message,
            };
            // Each primitive is read once, however many nodes draw it; instances only transform it.
            let mut read: HashMap<(usize, usize), Option<Mesh>> = HashMap::new();
            let mut mesh = Mesh::default();
            let mut motion =
                read_motion.then(|| motion::MotionReader::new(root, accessors, limits.max_joints));
            for placed in instances {
                let Placed {
                    mesh: mesh_index,
                    world: transform,
                    ..
                } = placed;
                let Some(m) = root.meshes.get(mesh_index) else {
                    return Err(invalid(format!(
                        "a node refers to mesh {mesh_index}, which does not exist"
                    )));
                };
                for (p, primitive) in m.primitives.iter().enumerate() {
                    let (local, first) = match read.entry((mesh_index, p)) {
                        Entry::Occupied(entry) => (entry.into_mut(), false),
                        Entry::Vacant(entry) => {
                            let name = format!("mesh {mesh_index} primitive {p}");
                            let local = read_primitive(accessors, primitive, &name, warnings)
                                .map_err(|e| invalid(format!("{name}: {e}")))?;
                            (entry.insert(local), true)
                        }
                    };
                    let Some(local) = local else {
                        continue;
                    };
                    if first {
                        spans.push(PrimitiveSpan {
                            mesh: mesh_index,
                            primitive: p,
                            first_vertex: mesh.positions.len() as u32,
                            first_triangle: mesh.triangles.len() as u32,
                            triangle_count: local.triangles.len() as u32,
                            mirrored: transform.determinant() < 0.0,
                        });
                    }
                    if let Some(motion) = &mut motion {
                        motion
                            .add(&motion::Drawn {
                                mesh_index,
                                primitive,
                                node: placed.node,
                                world: transform,
                                gpu_instanced: placed.gpu_instanced,
                                first_vertex: mesh.positions.len() as u32,
                                vertices: local.positions.len(),
                            })
                            .map_err(|e| {
                                invalid(format!("mesh {mesh_index} primitive {p}: {e}"))
                            })?;
                    }
                    mesh.append(transformed(local, transform));
                }
            }
            let motion = match motion {
                Some(motion) => motion.finish(warnings).map_err(invalid)?,
                None => None,
            };
            if mesh.triangles.is_empty() {
                let drawn: Vec<usize> = read.keys().map(|&(m, _)| m).collect();
                if let Some(held) = non_triangle_modes(root, &drawn) {
                    return Err(Error::Unsupported {
                        path: path.to_owned(),
                        what: format!(
                            "nothing to bake: the meshes it draws hold only {held}, no triangles"
                        ),
                    });
                }
            }
            Ok((mesh, motion))
        },
    )
}

/// "points", "lines" or "points and lines": what the primitives of `meshes` hold when none of
/// them is made of triangles; `None` if one is (or there is no primitive at all).
pub(crate) fn non_triangle_modes(root: &json::Root, meshes: &[usize]) -> Option<&'static str> {
    use json::mesh::Mode;
    let (mut points, mut lines) = (false, false);
    for primitive in meshes
        .iter()
        .filter_map(|&m| root.meshes.get(m))
        .flat_map(|m| &m.primitives)
    {
        match primitive.mode {
            Checked::Valid(Mode::Points) => points = true,
            Checked::Valid(Mode::Lines | Mode::LineLoop | Mode::LineStrip) => lines = true,
            _ => return None,
        }
    }
    match (points, lines) {
        (true, true) => Some("points and lines"),
        (true, false) => Some("points"),
        (false, true) => Some("lines"),
        (false, false) => None,
    }
}

/// The document's scene kept as it is: each mesh the scene draws, once, with its primitives in its
/// own space (in document order), and every instance as (index into those meshes, world
/// transform).
pub(crate) fn parse_scene(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Result<SceneMeshes, Error> {
    with_document(
        path,
        bytes,
        companions,
        limits,
        warnings,
        |root, accessors, instances, warnings| {
            let invalid = |message: String| Error::Parse {
                path: path.to_owned(),
                format: "glTF",
                message,
            };
            let mut used: Vec<usize> = instances.iter().map(|p| p.mesh).collect();
            used.sort_unstable();
            used.dedup();
            let mut meshes = Vec::with_capacity(used.len());
            for &mesh_index in &used {
                let Some(m) = root.meshes.get(mesh_index) else {
                    return Err(invalid(format!(
                        "a node refers to mesh {mesh_index}, which does not exist"
                    )));
                };
                let mut mesh = Mesh::default();
                for (p, primitive) in m.primitives.iter().enumerate() {
                    let name = format!("mesh {mesh_index} primitive {p}");
                    if let Some(local) = read_primitive(accessors, primitive, &name, warnings)
                        .map_err(|e| invalid(format!("{name}: {e}")))?
                    {
                        mesh.append(local);
                    }
                }
                meshes.push((mesh_index, mesh, non_triangle_modes(root, &[mesh_index])));
            }
            let instances = instances
                .into_iter()
                .filter_map(|p| used.binary_search(&p.mesh).ok().map(|i| (i, p.world)))
                .collect();
            Ok(SceneMeshes { meshes, instances })
        },
    )
}

/// Checks the document, counts what it asks for against `limits`, loads its buffers, and hands the
/// node graph's instances to `read`.
fn with_document<R>(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
    limits: &Limits,
    warnings: &mut Vec<String>,
    read: impl FnOnce(&json::Root, &Accessors<'_>, Vec<Placed>, &mut Vec<String>) -> Result<R, Error>,
) -> Result<R, Error> {
    let invalid = |message: String| Error::Parse {
        path: path.to_owned(),
        format: "glTF",
        message,
    };
    check_glb_length(bytes).map_err(invalid)?;
    let gltf =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| invalid(e.to_string()))?;
    let root = gltf.document.as_json();
    extensions::check(path, root, warnings)?;
    // Everything the file asks for is counted before any of it is read or expanded.
    let node_meshes = instances::mesh_instances(path, root, limits)?;
    let (vertices, triangles) = node_meshes
        .iter()
        .filter_map(|n| Some((root.meshes.get(n.mesh)?, n.copies())))
        .flat_map(|(m, copies)| m.primitives.iter().map(move |p| (p, copies)))
        .map(|(p, copies)| {
            let (v, t) = primitive_size(root, p);
            (v.saturating_mul(copies), t.saturating_mul(copies))
        })
        .fold((0u64, 0u64), |(v, t), (pv, pt)| {
            (v.saturating_add(pv), t.saturating_add(pt))
        });
    limits.check(path, Limited::Vertices, vertices)?;
    limits.check(path, Limited::Triangles, triangles)?;
    // The joints of the skins the drawn nodes use, declared before any is read.
    let skins: std::collections::BTreeSet<usize> = node_meshes
        .iter()
        .filter_map(|n| root.nodes.get(n.node?)?.skin.map(|s| s.value()))
        .collect();
    let joints = skins
        .iter()
        .filter_map(|&s| root.skins.get(s))
        .fold(0u64, |n, skin| n.saturating_add(skin.joints.len() as u64));
    limits.check(path, Limited::Joints, joints)?;

    let buffers =
        buffers::load(root, gltf.blob.as_deref(), path, companions, limits).map_err(invalid)?;
    let accessors = Accessors {
        root,
        buffers: &buffers,
    };
    let mut instances = Vec::new();
    for n in node_meshes {
        match (
            n.gpu_instances,
            n.node.and_then(|i| Some((i, root.nodes.get(i)?))),
        ) {
            (Some(count), Some((index, node))) => {
                let local = gpu_instancing::transforms(&accessors, node, count)
                    .map_err(|e| invalid(format!("node {index}: {e}")))?;
                instances.extend(local.into_iter().map(|t| Placed {
                    mesh: n.mesh,
                    world: n.world * t,
                    node: Some(index),
                    gpu_instanced: true,
                }));
            }
            _ => instances.push(Placed {
                mesh: n.mesh,
                world: n.world,
                node: n.node,
                gpu_instanced: false,
            }),
        }
    }
    read(root, &accessors, instances, warnings)
}

/// A GLB's header states the file's length; a file longer or shorter than that is damaged (or
/// carries something that is not glTF).
fn check_glb_length(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(b"glTF") {
        return Ok(());
    }
    let Some(&[a, b, c, d]) = bytes.get(8..12) else {
        return Err(format!("GLB header is {} bytes, not 12", bytes.len()));
    };
    let declared = u32::from_le_bytes([a, b, c, d]);
    if u64::from(declared) != bytes.len() as u64 {
        return Err(format!(
            "GLB header says the file is {declared} bytes, but it is {}",
            bytes.len()
        ));
    }
    Ok(())
}

/// Vertices and triangles one instance of `primitive` adds, from its accessors' declared counts.
fn primitive_size(root: &json::Root, primitive: &json::mesh::Primitive) -> (u64, u64) {
    use json::mesh::{Mode, Semantic};
    let count = |index: usize| root.accessors.get(index).map_or(0, |a| a.count.0);
    let vertices = primitive
        .attributes
        .get(&Checked::Valid(Semantic::Positions))
        .map_or(0, |a| count(a.value()));
    let corners = primitive.indices.map_or(vertices, |a| count(a.value()));
    let triangles = match primitive.mode {
        Checked::Valid(Mode::Triangles) => corners / 3,
        Checked::Valid(Mode::TriangleStrip | Mode::TriangleFan) => corners.saturating_sub(2),
        _ => return (0, 0),
    };
    (vertices, triangles)
}

fn local_transform(node: &json::scene::Node) -> Mat4 {
    if let Some(m) = node.matrix {
        return Mat4::from_cols_array(&m);
    }
    let t = node.translation.map_or(Vec3::ZERO, Vec3::from);
    let r = node
        .rotation
        .map_or(Quat::IDENTITY, |q| Quat::from_array(q.0).normalize());
    let s = node.scale.map_or(Vec3::ONE, Vec3::from);
    Mat4::from_scale_rotation_translation(s, r, t)
}

/// One primitive as a mesh part in its own space; `None` if it is not made of triangles.
fn read_primitive(
    accessors: &Accessors,
    primitive: &json::mesh::Primitive,
    name: &str,
    warnings: &mut Vec<String>,
) -> Result<Option<Mesh>, String> {
    use json::mesh::{Mode, Semantic};
    let mode = match primitive.mode {
        Checked::Valid(mode) => mode,
        Checked::Invalid => return Err("invalid primitive mode".into()),
    };
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        warnings.push(format!(
            "{name}: {mode:?} primitive skipped (only triangles are baked)"
        ));
        return Ok(None);
    }
    if primitive
        .extensions
        .as_ref()
        .is_some_and(|e| e.others.contains_key(extensions::COMPRESSION[0]))
    {
        return Err(format!(
            "{} compressed primitive (decompress it first)",
            extensions::COMPRESSION[0]
        ));
    }
    let attribute = |semantic: Semantic| {
        primitive
            .attributes
            .get(&Checked::Valid(semantic))
            .map(|a| a.value())
    };
    let position = attribute(Semantic::Positions).ok_or("no POSITION attribute")?;
    let positions: Vec<Vec3> = accessors
        .read_vectors::<3>(position)?
        .into_iter()
        .map(Vec3::from)
        .collect();
    // Attributes of another length are ignored, so they are not read at all (a huge one would
    // only cost time).
    let matching = |a: &usize| accessors.count(*a) == Some(positions.len() as u64);
    let normals = attribute(Semantic::Normals)
        .filter(matching)
        .map(|a| accessors.read_vectors::<3>(a))
        .transpose()?
        .map(|n| n.into_iter().map(Vec3::from).collect::<Vec<_>>());
    let uvs = attribute(Semantic::TexCoords(0))
        .filter(matching)
        .map(|a| accessors.read_vectors::<2>(a))
        .transpose()?
        .map(|t| t.into_iter().map(Vec2::from).collect());
    let indices = match primitive.indices {
        Some(a) => accessors.read_indices(a.value())?,
        None => (0..positions.len() as u32).collect(),
    };
    let triangles = assemble_triangles(mode, &indices);
    // Edge visibility bits follow the file's triangle order and corner order: read before mirroring.
    let marks = marks::read(
        accessors,
        primitive,
        &triangles,
        positions.len(),
        warnings,
        name,
    )?;

    let material = primitive.material.map_or(0, |m| m.value() as u32 + 1);
    Ok(Some(Mesh {
        positions,
        normals,
        uvs,
        materials: vec![material; triangles.len()],
        triangles,
        marks,
    }))
}

/// A primitive placed in world space: positions by the matrix, normals by its inverse transpose;
/// a mirroring transform reverses the winding, so two corners swap to keep faces outward.
fn transformed(local: &Mesh, transform: Mat4) -> Mesh {
    let mirrored = transform.determinant() < 0.0;
    let normal_matrix = Mat3::from_mat4(transform).inverse().transpose();
    Mesh {
        positions: local
            .positions
            .iter()
            .map(|&p| transform.transform_point3(p))
            .collect(),
        normals: local.normals.as_ref().map(|n| {
            n.iter()
                .map(|&v| (normal_matrix * v).normalize_or_zero())
                .collect()
        }),
        uvs: local.uvs.clone(),
        triangles: local
            .triangles
            .iter()
            .map(|&[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect(),
        materials: local.materials.clone(),
        marks: local.marks.clone(),
    }
}

/// Triangles from a triangle list, strip or fan, numbered and with their corners in the order of the
/// glTF specification (§3.7.2.1).
fn assemble_triangles(mode: json::mesh::Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    use json::mesh::Mode;
    let n = indices.len();
    match mode {
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [indices[i], indices[i + 1], indices[i + 2]]
                } else {
                    [indices[i], indices[i + 2], indices[i + 1]]
                }
            })
            .collect(),
        // p_i = {v_i+1, v_i+2, v_0}: the corner order matters to EXT_mesh_primitive_edge_visibility.
        Mode::TriangleFan => (1..n.saturating_sub(1))
            .map(|i| [indices[i], indices[i + 1], indices[0]])
            .collect(),
        _ => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use json::mesh::Mode;

    #[test]
    fn strips_alternate_winding_and_fans_share_the_first_vertex() {
        assert_eq!(
            assemble_triangles(Mode::TriangleStrip, &[0, 1, 2, 3, 4]),
            [[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            assemble_triangles(Mode::TriangleFan, &[0, 1, 2, 3]),
            [[1, 2, 0], [2, 3, 0]]
        );
        assert_eq!(
            assemble_triangles(Mode::Triangles, &[0, 1, 2, 3]),
            [[0, 1, 2]]
        );
    }
}
