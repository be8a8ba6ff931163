//! PLY via ply-rs-bw (the maintained fork of ply-rs, which is unmaintained since 2018; the fork reads
//! both binary encodings, caps preallocation from hostile element counts, and lets us parse into
//! typed structs instead of one hash map per vertex). The header (`ply_header`) and ASCII element
//! lines (`ply_ascii`) are read by this crate, so their errors name the line, property and value.
//!
//! Reads `vertex` (`x y z`, optional `nx ny nz`), `face` (`vertex_indices` or `vertex_index`, lists
//! of any integer type and length, fanned into triangles), `tristrips` (the same lists as triangle
//! strips with `-1` restarts, as Cyberware and Stanford scans store them) and `edge` (`vertex1
//! vertex2`, optional `radius`) as marked edges. Other elements and properties are skipped.
//!
//! Binary bodies of the common layout are read in bulk by `ply_bulk`, which leaves every other
//! file, and every file it finds wrong, to the per-element reader here.
//!
//! A position that is not a finite number is an error naming the vertex and the property, in the
//! OBJ loader's words ("non-finite position").

use std::io::BufRead;
use std::path::Path;

use glam::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{
    BeginList, ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult,
};

use crate::limits::Limited;
use crate::mesh::{Mark, Mesh, first_non_finite};
use crate::{Error, Limits};

pub(crate) fn parse(
    path: &Path,
    bytes: &[u8],
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Result<Mesh, Error> {
    parse_with(path, bytes, limits, warnings, true)
}

/// [`parse`], with the bulk reader of `ply_bulk` tried first when `bulk` (false in the tests
/// that compare the two readers).
pub(crate) fn parse_with(
    path: &Path,
    bytes: &[u8],
    limits: &Limits,
    warnings: &mut Vec<String>,
    bulk: bool,
) -> Result<Mesh, Error> {
    let parse_error = |message: String| Error::Parse {
        path: path.to_owned(),
        format: "PLY",
        message,
    };
    let parsed = super::ply_header::parse(bytes, true)
        .map_err(parse_error)?
        .ok_or_else(|| parse_error("the header has no end_header line".into()))?;
    warnings.extend(parsed.warnings);
    let header = parsed.header;
    let body = &bytes[parsed.body_start..];
    if bulk {
        if let Some(mesh) = super::ply_bulk::read(&header, body, limits) {
            return finite(mesh, &header).map_err(parse_error);
        }
    }
    let input = &mut &body[..];

    let mut mesh = Mesh::default();
    for (name, element) in header.elements.iter() {
        // Elements stream one at a time into the mesh: a million faces never exist as a million Vecs.
        let err = |(index, e): (usize, String)| {
            parse_error(format!(
                "element '{name}' number {index} of {}: {e}",
                element.count
            ))
        };
        // An element without properties occupies no bytes: there is nothing to read, however
        // many the header claims (2^64 - 1 of them would otherwise loop for ever).
        if element.properties.is_empty() {
            if name == "vertex" {
                return Err(parse_error(
                    "element 'vertex' has no x, y, z properties".into(),
                ));
            }
            continue;
        }
        // Every other element takes at least one byte (a binary value or an ASCII line), so a count
        // larger than the file is a lie: refuse it before looping over it.
        if element.count > bytes.len() {
            return Err(parse_error(format!(
                "element '{name}' claims {} elements but the whole file has {} bytes",
                element.count,
                bytes.len()
            )));
        }
        let plausible = element.count;
        match name.as_str() {
            "vertex" => {
                limits.check(path, Limited::Vertices, element.count as u64)?;
                let has_normals = ["nx", "ny", "nz"]
                    .iter()
                    .all(|p| element.properties.contains_key(*p));
                mesh.positions.reserve(plausible);
                for axis in ["x", "y", "z"] {
                    if !element.properties.contains_key(axis) {
                        return Err(parse_error(format!(
                            "element 'vertex' has no '{axis}' property"
                        )));
                    }
                }
                let mut normals = Vec::with_capacity(if has_normals { plausible } else { 0 });
                for_each_element(input, &header, element, |v: Vertex| {
                    mesh.positions.push(Vec3::from(v.position));
                    if has_normals {
                        normals.push(Vec3::from(v.normal));
                    }
                    Ok(())
                })
                .map_err(err)?;
                mesh.normals = has_normals.then_some(normals);
            }
            "face" => {
                mesh.triangles
                    .reserve(plausible.min(limits.max_triangles as usize));
                let mut over_limit = false;
                let faces = for_each_element(input, &header, element, |mut face: Face| {
                    // `int` lists arrive unconverted through the in-place fast path.
                    if !face.signed.is_empty() {
                        let signed = std::mem::take(&mut face.signed);
                        face.take(signed.into_iter().map(i64::from));
                    }
                    if let Some(v) = face.negative {
                        return Err(format!("negative vertex index {v}"));
                    }
                    super::fan(&face.indices, &mut mesh.triangles);
                    if mesh.triangles.len() as u64 > limits.max_triangles {
                        over_limit = true;
                        return Err(String::new());
                    }
                    Ok(())
                });
                if over_limit {
                    limits.check(path, Limited::Triangles, mesh.triangles.len() as u64)?;
                }
                faces.map_err(err)?;
            }
            "tristrips" => {
                let mut over_limit = false;
                let strips = for_each_element(input, &header, element, |strip: Strip| {
                    let values = strip.values();
                    // A strip of n indices holds at most n - 2 triangles: checked before any is added.
                    let most = mesh.triangles.len() as u64 + values.len().saturating_sub(2) as u64;
                    if most > limits.max_triangles {
                        over_limit = true;
                        return Err(String::new());
                    }
                    strip_triangles(&values, &mut mesh.triangles)
                });
                if over_limit {
                    limits.check(
                        path,
                        Limited::Triangles,
                        limits.max_triangles.saturating_add(1),
                    )?;
                }
                strips.map_err(err)?;
            }
            "edge" => {
                for_each_element(input, &header, element, |edge: Edge| {
                    if let Some(v) = edge.negative {
                        return Err(format!("negative vertex index {v}"));
                    }
                    mesh.marks.push(Mark {
                        vertices: edge.vertices,
                        radius: edge.radius,
                    });
                    Ok(())
                })
                .map_err(err)?;
            }
            _ => for_each_element(input, &header, element, |_: Skip| Ok(())).map_err(err)?,
        }
    }
    mesh.materials = vec![0; mesh.triangles.len()];
    finite(mesh, &header).map_err(parse_error)
}

/// The mesh, or which vertex property is not a finite number (the OBJ loader's words).
fn finite(mesh: Mesh, header: &Header) -> Result<Mesh, String> {
    match first_non_finite(&mesh.positions) {
        None => Ok(mesh),
        Some((vertex, axis, value)) => Err(format!(
            "element 'vertex' number {vertex} of {}: non-finite position: property '{}' is {value}",
            header.elements.get("vertex").map_or(0, |v| v.count),
            ["x", "y", "z"][axis],
        )),
    }
}

/// Triangles of a `tristrips` list: `-1` ends a strip; within a strip triangle `j` is
/// `(v_j, v_j+1, v_j+2)`, with the last two swapped when `j` is odd so every triangle keeps the
/// strip's winding. Triangles that repeat a vertex (the joins of stitched strips) are not added.
fn strip_triangles(indices: &[i64], out: &mut Vec<[u32; 3]>) -> Result<(), String> {
    for strip in indices.split(|&v| v == -1) {
        let strip: Vec<u32> = strip
            .iter()
            .map(|&v| {
                u32::try_from(v)
                    .map_err(|_| format!("negative vertex index {v} (only -1 restarts a strip)"))
            })
            .collect::<Result<_, _>>()?;
        for (j, w) in strip.windows(3).enumerate() {
            let triangle = if j % 2 == 0 {
                [w[0], w[1], w[2]]
            } else {
                [w[0], w[2], w[1]]
            };
            if w[0] != w[1] && w[1] != w[2] && w[0] != w[2] {
                out.push(triangle);
            }
        }
    }
    Ok(())
}

/// Reads `element.count` elements of type `E` in the file's encoding, handing each to `consume`.
/// Errors carry the element's index.
fn for_each_element<E: PropertyAccess>(
    input: &mut impl BufRead,
    header: &Header,
    element: &ElementDef,
    mut consume: impl FnMut(E) -> Result<(), String>,
) -> Result<(), (usize, String)> {
    let parser = Parser::<E>::new();
    let mut line = String::new();
    let binary_error = |e: ply_rs_bw::parser::ParseError| {
        let e = std::io::Error::from(e);
        match e.kind() {
            std::io::ErrorKind::UnexpectedEof => "the file ends inside it".to_owned(),
            _ => e.to_string(),
        }
    };
    for index in 0..element.count {
        let parsed = match header.encoding {
            Encoding::Ascii => {
                line.clear();
                match input.read_line(&mut line) {
                    Ok(0) => return Err((index, "the file ends before it".into())),
                    Ok(_) => super::ply_ascii::read_element(&line, element),
                    Err(e) => return Err((index, e.to_string())),
                }
            }
            Encoding::BinaryLittleEndian => parser
                .read_little_endian_element(input, element)
                .map_err(binary_error),
            Encoding::BinaryBigEndian => parser
                .read_big_endian_element(input, element)
                .map_err(binary_error),
        };
        let value = parsed.map_err(|e| (index, e))?;
        consume(value).map_err(|message| (index, message))?;
    }
    Ok(())
}

/// An element this loader does not use: parsed (to advance the reader) and dropped.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

#[derive(Default)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
}

impl Vertex {
    fn slot(&mut self, name: &str) -> Option<&mut f32> {
        match name {
            "x" => Some(&mut self.position[0]),
            "y" => Some(&mut self.position[1]),
            "z" => Some(&mut self.position[2]),
            "nx" => Some(&mut self.normal[0]),
            "ny" => Some(&mut self.normal[1]),
            "nz" => Some(&mut self.normal[2]),
            _ => None,
        }
    }

    fn store(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        match self.slot(name) {
            Some(slot) => {
                *slot = value;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::Ignored,
        }
    }
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Self::default()
    }
    fn set_float(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        self.store(name, value)
    }
    fn set_double(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        self.store(name, value as f32)
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        match property.to_f32_lossy() {
            Some(value) => self.store(name, value),
            None => PropertyAccessResult::Ignored,
        }
    }
}

#[derive(Default)]
struct Face {
    indices: Vec<u32>,
    signed: Vec<i32>,
    negative: Option<i64>,
}

impl Face {
    fn is_index_list(name: &str) -> bool {
        name == "vertex_indices" || name == "vertex_index"
    }

    fn take(&mut self, values: impl Iterator<Item = i64>) -> PropertyAccessResult {
        self.indices.clear();
        for v in values {
            match u32::try_from(v) {
                Ok(v) => self.indices.push(v),
                Err(_) => self.negative = self.negative.or(Some(v)),
            }
        }
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for Face {
    fn new() -> Self {
        Self::default()
    }
    fn begin_list_uint(&mut self, name: &str, _len: usize) -> BeginList<'_, u32> {
        if Self::is_index_list(name) {
            BeginList::Fill(&mut self.indices)
        } else {
            BeginList::UseSetter
        }
    }
    fn begin_list_int(&mut self, name: &str, _len: usize) -> BeginList<'_, i32> {
        if Self::is_index_list(name) {
            BeginList::Fill(&mut self.signed)
        } else {
            BeginList::UseSetter
        }
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if !Self::is_index_list(name) {
            return PropertyAccessResult::Ignored;
        }
        match property {
            Property::ListChar(v) => self.take(v.into_iter().map(i64::from)),
            Property::ListUChar(v) => self.take(v.into_iter().map(i64::from)),
            Property::ListShort(v) => self.take(v.into_iter().map(i64::from)),
            Property::ListUShort(v) => self.take(v.into_iter().map(i64::from)),
            Property::ListInt(v) => self.take(v.into_iter().map(i64::from)),
            Property::ListUInt(v) => self.take(v.into_iter().map(i64::from)),
            _ => PropertyAccessResult::UnsupportedType,
        }
    }
}

/// A `tristrips` element's index list as read, `-1` restarts included (an unsigned list's
/// all-ones value is its `-1`).
#[derive(Default)]
struct Strip {
    unsigned: Vec<u32>,
    signed: Vec<i32>,
    other: Vec<i64>,
}

impl Strip {
    fn values(self) -> Vec<i64> {
        if !self.signed.is_empty() {
            self.signed.into_iter().map(i64::from).collect()
        } else if !self.unsigned.is_empty() {
            let restart = |v: u32| if v == u32::MAX { -1 } else { i64::from(v) };
            self.unsigned.into_iter().map(restart).collect()
        } else {
            self.other
        }
    }
}

impl PropertyAccess for Strip {
    fn new() -> Self {
        Self::default()
    }
    fn begin_list_uint(&mut self, name: &str, _len: usize) -> BeginList<'_, u32> {
        if Face::is_index_list(name) {
            BeginList::Fill(&mut self.unsigned)
        } else {
            BeginList::UseSetter
        }
    }
    fn begin_list_int(&mut self, name: &str, _len: usize) -> BeginList<'_, i32> {
        if Face::is_index_list(name) {
            BeginList::Fill(&mut self.signed)
        } else {
            BeginList::UseSetter
        }
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if !Face::is_index_list(name) {
            return PropertyAccessResult::Ignored;
        }
        self.other = match property {
            Property::ListChar(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUChar(v) => v.into_iter().map(i64::from).collect(),
            Property::ListShort(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUShort(v) => v.into_iter().map(i64::from).collect(),
            _ => return PropertyAccessResult::UnsupportedType,
        };
        PropertyAccessResult::Set
    }
}

#[derive(Default)]
struct Edge {
    vertices: [u32; 2],
    radius: Option<f32>,
    negative: Option<i64>,
}

impl PropertyAccess for Edge {
    fn new() -> Self {
        Self::default()
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let slot = match name {
            "vertex1" => 0,
            "vertex2" => 1,
            "radius" => {
                self.radius = property.to_f32_lossy();
                return PropertyAccessResult::Set;
            }
            _ => return PropertyAccessResult::Ignored,
        };
        let value = match property {
            Property::Char(v) => i64::from(v),
            Property::UChar(v) => i64::from(v),
            Property::Short(v) => i64::from(v),
            Property::UShort(v) => i64::from(v),
            Property::Int(v) => i64::from(v),
            Property::UInt(v) => i64::from(v),
            _ => return PropertyAccessResult::UnsupportedType,
        };
        match u32::try_from(value) {
            Ok(v) => self.vertices[slot] = v,
            Err(_) => self.negative = self.negative.or(Some(value)),
        }
        PropertyAccessResult::Set
    }
}
