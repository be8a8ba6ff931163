//! glTF 2.0 via the `gltf` crate: `.gltf` (external or base64-embedded buffers) and `.glb`.
//!
//! The default scene (or the first, or every mesh when there is no scene) is flattened with its node
//! transforms. TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives are read; points and lines are
//! skipped with a warning. Accessors are read here, bounds-checked, with sparse substitution and
//! KHR_mesh_quantization's integer types; the crate's own validation is bypassed because it rejects
//! every required extension, quantization included. Each primitive's material is its material id.
//! Draco and meshopt compressed files are refused with the extension's name.

mod accessor;
mod buffers;
pub mod marks;

use std::path::Path;

use glam::{Mat3, Mat4, Quat, Vec2, Vec3};
use gltf::json::{self, validation::Checked};

use self::accessor::Accessors;
use crate::Error;
use crate::mesh::Mesh;

/// Compression schemes whose data this loader cannot decode.
const COMPRESSION_EXTENSIONS: [&str; 3] = [
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
];
/// Required extensions that do not change how geometry is read.
const HARMLESS_EXTENSIONS: [&str; 1] = ["KHR_mesh_quantization"];

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
}

pub(super) fn parse(path: &Path, bytes: &[u8], warnings: &mut Vec<String>) -> Result<Mesh, Error> {
    parse_with_spans(path, bytes, warnings, &mut Vec::new())
}

/// [`parse`], also listing each primitive's first instance.
pub(crate) fn parse_with_spans(
    path: &Path,
    bytes: &[u8],
    warnings: &mut Vec<String>,
    spans: &mut Vec<PrimitiveSpan>,
) -> Result<Mesh, Error> {
    let invalid = |message: String| Error::Parse {
        path: path.to_owned(),
        format: "glTF",
        message,
    };
    let gltf =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| invalid(e.to_string()))?;
    let root = gltf.document.as_json();
    for ext in &root.extensions_required {
        if COMPRESSION_EXTENSIONS.contains(&ext.as_str()) {
            return Err(Error::Unsupported {
                path: path.to_owned(),
                what: format!(
                    "{ext} compressed geometry (decompress it first, e.g. `gltf-transform copy`)"
                ),
            });
        }
        if !HARMLESS_EXTENSIONS.contains(&ext.as_str()) {
            warnings.push(format!("required extension {ext} is ignored"));
        }
    }
    let buffers = buffers::load(root, gltf.blob.as_deref(), path).map_err(|e| match e {
        buffers::BufferError::Read(source) => Error::Read {
            path: path.to_owned(),
            source,
        },
        buffers::BufferError::Invalid(message) => invalid(message),
    })?;
    let accessors = Accessors {
        root,
        buffers: &buffers,
    };

    let mut mesh = Mesh::default();
    for (mesh_index, transform) in mesh_instances(root).map_err(invalid)? {
        let Some(m) = root.meshes.get(mesh_index) else {
            return Err(invalid(format!(
                "a node refers to mesh {mesh_index}, which does not exist"
            )));
        };
        for (p, primitive) in m.primitives.iter().enumerate() {
            let name = format!("mesh {mesh_index} primitive {p}");
            if let Some(part) = read_primitive(&accessors, primitive, transform, &name, warnings)
                .map_err(|e| invalid(format!("{name}: {e}")))?
            {
                if !spans
                    .iter()
                    .any(|s| (s.mesh, s.primitive) == (mesh_index, p))
                {
                    spans.push(PrimitiveSpan {
                        mesh: mesh_index,
                        primitive: p,
                        first_vertex: mesh.positions.len() as u32,
                        first_triangle: mesh.triangles.len() as u32,
                        triangle_count: part.triangles.len() as u32,
                    });
                }
                mesh.append(part);
            }
        }
    }
    Ok(mesh)
}

/// Every (mesh, world transform) the document draws: the default scene's node tree, or each mesh
/// once, untransformed, when the file has no scene.
fn mesh_instances(root: &json::Root) -> Result<Vec<(usize, Mat4)>, String> {
    let scene = root
        .scene
        .map(|s| s.value())
        .or((!root.scenes.is_empty()).then_some(0));
    let Some(scene) = scene else {
        return Ok((0..root.meshes.len())
            .map(|m| (m, Mat4::IDENTITY))
            .collect());
    };
    let scene = root
        .scenes
        .get(scene)
        .ok_or_else(|| format!("default scene {scene} does not exist"))?;
    let mut instances = Vec::new();
    let mut stack: Vec<(usize, Mat4, usize)> = scene
        .nodes
        .iter()
        .map(|n| (n.value(), Mat4::IDENTITY, 0))
        .collect();
    while let Some((index, parent, depth)) = stack.pop() {
        // A node tree is at most as deep as there are nodes; deeper means a cycle.
        if depth > root.nodes.len() {
            return Err(format!("node {index} is part of a cycle"));
        }
        let node = root
            .nodes
            .get(index)
            .ok_or_else(|| format!("node {index} does not exist"))?;
        let world = parent * local_transform(node);
        if let Some(m) = node.mesh {
            instances.push((m.value(), world));
        }
        for child in node.children.iter().flatten() {
            stack.push((child.value(), world, depth + 1));
        }
    }
    instances.reverse(); // depth-first in document order
    Ok(instances)
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

/// One primitive as a mesh part, transformed to world space; `None` if it is not made of triangles.
fn read_primitive(
    accessors: &Accessors,
    primitive: &json::mesh::Primitive,
    transform: Mat4,
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
        .is_some_and(|e| e.others.contains_key(COMPRESSION_EXTENSIONS[0]))
    {
        return Err(format!(
            "{} compressed primitive (decompress it first)",
            COMPRESSION_EXTENSIONS[0]
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
    let normals = attribute(Semantic::Normals)
        .map(|a| accessors.read_vectors::<3>(a))
        .transpose()?
        .filter(|n| n.len() == positions.len())
        .map(|n| n.into_iter().map(Vec3::from).collect::<Vec<_>>());
    let uvs = attribute(Semantic::TexCoords(0))
        .map(|a| accessors.read_vectors::<2>(a))
        .transpose()?
        .filter(|t| t.len() == positions.len())
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

    // World space: positions by the matrix, normals by its inverse transpose; a mirroring
    // transform reverses the winding, so swap two corners to keep faces outward.
    let mirrored = transform.determinant() < 0.0;
    let normal_matrix = Mat3::from_mat4(transform).inverse().transpose();
    let part = Mesh {
        positions: positions
            .iter()
            .map(|&p| transform.transform_point3(p))
            .collect(),
        normals: normals.map(|n| {
            n.iter()
                .map(|&v| (normal_matrix * v).normalize_or_zero())
                .collect()
        }),
        uvs,
        triangles: triangles
            .into_iter()
            .map(|[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect(),
        materials: Vec::new(),
        marks: Vec::new(),
    };

    let material = primitive.material.map_or(0, |m| m.value() as u32 + 1);
    Ok(Some(Mesh {
        materials: vec![material; part.triangles.len()],
        marks,
        ..part
    }))
}

/// Triangles from a triangle list, strip or fan, as the glTF specification numbers them.
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
        Mode::TriangleFan => (1..n.saturating_sub(1))
            .map(|i| [indices[0], indices[i], indices[i + 1]])
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
            [[0, 1, 2], [0, 2, 3]]
        );
        assert_eq!(
            assemble_triangles(Mode::Triangles, &[0, 1, 2, 3]),
            [[0, 1, 2]]
        );
    }
}
