//! OBJ via tobj: every object and group, polygons fanned into triangles, normals and uvs optional.
//! Each `usemtl` material (from the `mtllib` files beside the OBJ) is a material id.
//!
//! Material libraries are optional, so one rule covers every library that is not read — missing,
//! outside the OBJ's folder (absolute or `..`, after following links), not a regular file, over
//! the size limit or unreadable: a warning names it, its line and why, and the faces of its
//! materials get the default material. Nothing outside the folder is opened.
//!
//! A leading UTF-8 byte-order mark is skipped; errors name the line they are on and say what is
//! wrong with it (a position that is not three numbers, a corner that is not `v/vt/vn`, a
//! non-finite position in the PLY loader's words).

use std::cell::{Cell, RefCell};
use std::io::{BufRead, Read};
use std::path::Path;

use glam::{Vec2, Vec3};

use super::files::{Companions, RefusedReference, read_reference};
use crate::limits::Limited;
use crate::mesh::{Mesh, first_non_finite};
use crate::{Error, Limits};

pub(super) fn parse(
    path: &Path,
    bytes: &[u8],
    companions: Companions<'_>,
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
    let skipped = RefCell::new(Vec::new());
    let load_mtl = |mtl: &Path| {
        let problem = match read_reference(path, mtl, limits.max_input_bytes, companions) {
            Ok(text) => return tobj::load_mtl_buf(&mut text.as_slice()),
            Err(RefusedReference::Missing) => "does not exist".to_owned(),
            Err(RefusedReference::Refused(problem)) => problem,
        };
        skipped.borrow_mut().push(format!(
            "material library '{}' on line {} {problem}: not read, its faces get the default material",
            mtl.display(),
            line_at(bytes, consumed.get())
        ));
        Ok(Default::default())
    };
    let mut reader = Counted {
        bytes,
        consumed: &consumed,
    };
    let parsed = tobj::load_obj_buf(&mut reader, &options, load_mtl);
    let (models, _materials) = parsed.map_err(|e| {
        let located = match e {
            // Found when an object is finished, not on the face's own line: look for it.
            tobj::LoadError::FaceVertexOutOfBounds
            | tobj::LoadError::FaceTexCoordOutOfBounds
            | tobj::LoadError::FaceNormalOutOfBounds => first_face_out_of_bounds(bytes),
            _ => Some(line_at(bytes, consumed.get())),
        };
        invalid(match located {
            Some(line) => format!(
                "line {line}: {} ({})",
                explain(&e, line_text(bytes, line)),
                quote_line(bytes, line)
            ),
            None => e.to_string(),
        })
    })?;
    warnings.extend(skipped.into_inner());

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
    if first_non_finite(&mesh.positions).is_some() {
        if let Some((line, axis, value)) = first_non_finite_line(bytes) {
            return Err(invalid(format!(
                "line {line}: non-finite position: {} is {value} ({})",
                ["x", "y", "z"][axis],
                quote_line(bytes, line)
            )));
        }
    }
    Ok(mesh)
}

/// What is wrong with the line tobj refused, in words: tobj's own names ("color parse error")
/// often point elsewhere.
fn explain(error: &tobj::LoadError, line: &str) -> String {
    use tobj::LoadError;
    let values: Vec<&str> = line.split_whitespace().skip(1).collect();
    let not_a_number = values.iter().find(|v| v.parse::<f32>().is_err());
    let numbers = |what: &str| match not_a_number {
        Some(v) => format!("'{v}' is not a number ({what})"),
        None => format!("{what}, not {} numbers", values.len()),
    };
    match error {
        LoadError::PositionParseError | LoadError::ColorParseError => {
            numbers("a position is `v x y z`, optionally followed by w or by r g b")
        }
        LoadError::NormalParseError => numbers("a normal is `vn x y z`"),
        LoadError::TexcoordParseError => numbers("a texture coordinate is `vt u v`"),
        LoadError::ScalingByZeroError => "a position's w is 0 (x y z are divided by it)".into(),
        LoadError::FaceParseError => {
            let corner = |c: &&&str| {
                let parts: Vec<&str> = c.split('/').collect();
                parts.len() > 3
                    || parts
                        .iter()
                        .any(|p| !p.is_empty() && p.parse::<i64>().is_err())
                    || parts[0].is_empty()
            };
            match values.iter().find(corner) {
                Some(c) => {
                    format!("'{c}' is not a face corner (v, v/vt, v//vn or v/vt/vn, whole numbers)")
                }
                None => error.to_string(),
            }
        }
        _ => error.to_string(),
    }
}

/// The first `v` line with a coordinate that is not a finite number once read as tobj reads it
/// (as f32, divided by w when there is one): (1-based line, axis, value).
fn first_non_finite_line(bytes: &[u8]) -> Option<(usize, usize, f32)> {
    bytes
        .split(|&b| b == b'\n')
        .enumerate()
        .find_map(|(number, line)| {
            let line = String::from_utf8_lossy(line);
            let mut words = line.split_whitespace();
            (words.next() == Some("v")).then_some(())?;
            let values: Vec<f32> = words.filter_map(|w| w.parse().ok()).collect();
            let w = if values.len() == 4 { values[3] } else { 1.0 };
            let position = values.get(..3)?.iter().map(|&c| c / w);
            let (axis, value) = position.enumerate().find(|(_, c)| !c.is_finite())?;
            Some((number + 1, axis, value))
        })
}

/// Line `line` (1-based) as text.
fn line_text(bytes: &[u8], line: usize) -> &str {
    let text = bytes
        .split(|&b| b == b'\n')
        .nth(line.saturating_sub(1))
        .unwrap_or_default();
    std::str::from_utf8(text).unwrap_or_default()
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
