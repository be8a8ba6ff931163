//! OBJ via tobj: every object and group, polygons fanned into triangles, normals and uvs optional.
//! Each `usemtl` material (from the `.mtl` next to the file) is a material id; missing `.mtl`
//! files leave one material.

use std::io::BufReader;
use std::path::Path;

use glam::{Vec2, Vec3};

use crate::Error;
use crate::mesh::Mesh;

pub(super) fn parse(path: &Path, bytes: &[u8], warnings: &mut Vec<String>) -> Result<Mesh, Error> {
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let dir = path.parent().unwrap_or(Path::new("."));
    let missing = std::cell::RefCell::new(Vec::new());
    let load_mtl = |mtl: &Path| match std::fs::File::open(dir.join(mtl)) {
        Ok(file) => tobj::load_mtl_buf(&mut BufReader::new(file)),
        Err(_) => {
            missing.borrow_mut().push(mtl.display().to_string());
            Ok(Default::default())
        }
    };
    let (models, _materials) = tobj::load_obj_buf(&mut BufReader::new(bytes), &options, load_mtl)
        .map_err(|e| Error::Parse {
        path: path.to_owned(),
        format: "OBJ",
        message: e.to_string(),
    })?;

    for mtl in missing.into_inner() {
        warnings.push(format!(
            "material library {mtl} not found: all faces get one material"
        ));
    }
    let mut mesh = Mesh::default();
    for model in models {
        let m = model.mesh;
        let count = m.positions.len() / 3;
        let part = Mesh {
            positions: m.positions.chunks_exact(3).map(Vec3::from_slice).collect(),
            normals: (m.normals.len() == 3 * count)
                .then(|| m.normals.chunks_exact(3).map(Vec3::from_slice).collect()),
            uvs: (m.texcoords.len() == 2 * count)
                .then(|| m.texcoords.chunks_exact(2).map(Vec2::from_slice).collect()),
            triangles: m
                .indices
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect(),
            materials: vec![m.material_id.map_or(0, |id| id as u32 + 1); m.indices.len() / 3],
            marks: Vec::new(),
        };
        mesh.append(part);
    }
    Ok(mesh)
}
