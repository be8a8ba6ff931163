//! OBJ via tobj: every object and group, polygons fanned into triangles, normals and uvs optional.
//! Each `usemtl` material (from the `mtllib` files beside the OBJ) is a material id; a missing
//! `.mtl` leaves one material, one outside the OBJ's folder or not a regular file is an error.
//! A leading UTF-8 byte-order mark is skipped; errors name the line they are on.

use std::cell::{Cell, RefCell};
use std::io::{BufRead, Read};
use std::path::Path;

use glam::{Vec2, Vec3};

use super::files::{RefusedReference, read_reference};
use crate::limits::Limited;
use crate::mesh::Mesh;
use crate::{Error, Limits};

pub(super) fn parse(
    path: &Path,
    bytes: &[u8],
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Result<Mesh, Error> {
    // Editors on Windows start files with a byte-order mark; it is not part of the first line.
    let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let invalid = |message: String| Error::Parse {
        path: path.to_owned(),
        format: "OBJ",
        message,
    };
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let consumed = Cell::new(0);
    let missing = RefCell::new(Vec::new());
    let refused = RefCell::new(None);
    let load_mtl = |mtl: &Path| match read_reference(path, mtl, limits.max_input_bytes) {
        Ok(text) => tobj::load_mtl_buf(&mut text.as_slice()),
        Err(RefusedReference::Missing) => {
            missing.borrow_mut().push(mtl.display().to_string());
            Ok(Default::default())
        }
        Err(RefusedReference::Refused(problem)) => {
            refused.borrow_mut().get_or_insert(Error::Reference {
                path: path.to_owned(),
                reference: format!(
                    "material library '{}' on line {}",
                    mtl.display(),
                    line_at(bytes, consumed.get())
                ),
                problem,
            });
            Ok(Default::default())
        }
    };
    let mut reader = Counted {
        bytes,
        consumed: &consumed,
    };
    let parsed = tobj::load_obj_buf(&mut reader, &options, load_mtl);
    if let Some(error) = refused.into_inner() {
        return Err(error);
    }
    let (models, _materials) = parsed.map_err(|e| {
        let located = match e {
            // Found when an object is finished, not on the face's own line: look for it.
            tobj::LoadError::FaceVertexOutOfBounds
            | tobj::LoadError::FaceTexCoordOutOfBounds
            | tobj::LoadError::FaceNormalOutOfBounds => first_face_out_of_bounds(bytes),
            _ => Some(line_at(bytes, consumed.get())),
        };
        invalid(match located {
            Some(line) => format!("line {line}: {e} ({})", quote_line(bytes, line)),
            None => e.to_string(),
        })
    })?;

    for mtl in missing.into_inner() {
        warnings.push(format!(
            "material library {mtl} not found: all faces get one material"
        ));
    }
    let vertices: u64 = models
        .iter()
        .map(|m| m.mesh.positions.len() as u64 / 3)
        .sum();
    let triangles: u64 = models.iter().map(|m| m.mesh.indices.len() as u64 / 3).sum();
    limits.check(path, Limited::Vertices, vertices)?;
    limits.check(path, Limited::Triangles, triangles)?;
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

/// The OBJ text as tobj reads it, remembering how far it got so errors can name the line.
struct Counted<'a> {
    bytes: &'a [u8],
    consumed: &'a Cell<usize>,
}

impl Read for Counted<'_> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let n = self.fill_buf()?.len().min(out.len());
        out[..n].copy_from_slice(&self.bytes[self.consumed.get()..][..n]);
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for Counted<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        Ok(&self.bytes[self.consumed.get()..])
    }
    fn consume(&mut self, amount: usize) {
        self.consumed
            .set((self.consumed.get() + amount).min(self.bytes.len()));
    }
}

/// The 1-based number of the line that the first `consumed` bytes end in.
fn line_at(bytes: &[u8], consumed: usize) -> usize {
    let read = &bytes[..consumed.min(bytes.len())];
    let newlines = read.iter().filter(|&&b| b == b'\n').count();
    if read.last().is_none_or(|&b| b == b'\n') {
        newlines.max(1)
    } else {
        newlines + 1
    }
}

/// Line `line` (1-based), shortened, for an error message.
fn quote_line(bytes: &[u8], line: usize) -> String {
    let text = bytes
        .split(|&b| b == b'\n')
        .nth(line.saturating_sub(1))
        .unwrap_or_default();
    let text = String::from_utf8_lossy(text);
    let text = text.trim();
    match text.char_indices().nth(60) {
        Some((cut, _)) => format!("`{}...`", &text[..cut]),
        None => format!("`{text}`"),
    }
}

/// The line of the first face that refers to a position, uv or normal the file does not have.
fn first_face_out_of_bounds(bytes: &[u8]) -> Option<usize> {
    let lines = || bytes.split(|&b| b == b'\n').map(String::from_utf8_lossy);
    let mut totals = [0i64; 3];
    for line in lines() {
        match line.split_whitespace().next() {
            Some("v") => totals[0] += 1,
            Some("vt") => totals[1] += 1,
            Some("vn") => totals[2] += 1,
            _ => {}
        }
    }
    let mut seen = [0i64; 3];
    for (number, line) in lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => seen[0] += 1,
            Some("vt") => seen[1] += 1,
            Some("vn") => seen[2] += 1,
            Some("f") => {
                for corner in words {
                    for (k, index) in corner.split('/').take(3).enumerate() {
                        let Ok(index) = index.parse::<i64>() else {
                            continue; // empty (`1//3`) or unparsable: tobj reports those itself
                        };
                        let absolute = if index < 0 {
                            seen[k].saturating_add(index).saturating_add(1)
                        } else {
                            index
                        };
                        if absolute < 1 || absolute > totals[k] {
                            return Some(number + 1);
                        }
                    }
                }
            }
            _ => {}
        }
    }
    None
}
