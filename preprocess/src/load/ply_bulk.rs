//! Bulk read of binary PLY bodies: the vertex and face blocks are read straight from the file's
//! bytes, with no parser call and no allocation per element (issue 15; a third of a 1 M-triangle
//! bake went to the per-element reader).
//!
//! It takes the common layout only: a binary encoding; a `vertex` element whose properties are all
//! scalars, with `float` `x y z` (and `nx ny nz` when all three are there); a `face` element whose
//! properties are scalars and one integer index list (`vertex_indices` or `vertex_index`, any
//! count type); other elements of scalars alone, skipped by their fixed size. Anything else, and any
//! file this reader finds wrong (cut short, a negative index or count, over a limit), is left to
//! the general reader in `ply.rs`, which reads the same values and names the problem, so the two
//! readers give the same mesh or the same error for every file.

use glam::Vec3;
use ply_rs_bw::ply::{ElementDef, Encoding, Header, PropertyType, ScalarType};

use crate::Limits;
use crate::mesh::Mesh;

/// The mesh in `body` (the bytes after the header's `end_header` line), or `None` when the file
/// is not one this reader takes or is wrong (see the module's notes).
pub(crate) fn read(header: &Header, body: &[u8], limits: &Limits) -> Option<Mesh> {
    let big_endian = match header.encoding {
        Encoding::BinaryLittleEndian => false,
        Encoding::BinaryBigEndian => true,
        Encoding::Ascii => return None,
    };
    let mut mesh = Mesh::default();
    let mut rest = body;
    for (name, element) in header.elements.iter() {
        rest = match name.as_str() {
            "vertex" => read_vertices(element, rest, big_endian, limits, &mut mesh)?,
            "face" => read_faces(element, rest, big_endian, limits, &mut mesh.triangles)?,
            // Their meaning is the general reader's to apply.
            "tristrips" | "edge" => return None,
            _ => {
                let size = fixed_size(element)?;
                rest.get(element.count.checked_mul(size)?..)?
            }
        };
    }
    if !header.elements.contains_key("vertex") {
        return None;
    }
    mesh.materials = vec![0; mesh.triangles.len()];
    Some(mesh)
}

/// Bytes per element when every property is a scalar.
fn fixed_size(element: &ElementDef) -> Option<usize> {
    element
        .properties
        .values()
        .map(|p| match &p.data_type {
            PropertyType::Scalar(scalar) => Some(scalar_size(scalar)),
            PropertyType::List(..) => None,
        })
        .sum()
}

fn scalar_size(scalar: &ScalarType) -> usize {
    match scalar {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Reads `element.count` vertices; returns the bytes after them.
fn read_vertices<'a>(
    element: &ElementDef,
    body: &'a [u8],
    big_endian: bool,
    limits: &Limits,
    mesh: &mut Mesh,
) -> Option<&'a [u8]> {
    if element.count as u64 > limits.max_vertices {
        return None;
    }
    let stride = fixed_size(element)?;
    // The byte offset of a `float` property.
    let offset_of = |name: &str| {
        let (index, _, property) = element.properties.get_full(name)?;
        if property.data_type != PropertyType::Scalar(ScalarType::Float) {
            return None;
        }
        let before = element.properties.values().take(index);
        Some(before.map(|p| fixed_size_of(&p.data_type)).sum::<usize>())
    };
    let position = [offset_of("x")?, offset_of("y")?, offset_of("z")?];
    let normal = ["nx", "ny", "nz"].map(|n| element.properties.contains_key(n));
    let normal = match normal {
        [true, true, true] => Some([offset_of("nx")?, offset_of("ny")?, offset_of("nz")?]),
        _ => None,
    };
    let block = body.get(..element.count.checked_mul(stride)?)?;
    let float = |record: &[u8], at: usize| {
        let bytes = [record[at], record[at + 1], record[at + 2], record[at + 3]];
        if big_endian {
            f32::from_be_bytes(bytes)
        } else {
            f32::from_le_bytes(bytes)
        }
    };
    let vector = |record: &[u8], at: [usize; 3]| Vec3::from(at.map(|a| float(record, a)));
    // A stride of 0 cannot happen: x y z take 12 bytes.
    mesh.positions = block
        .chunks_exact(stride)
        .map(|r| vector(r, position))
        .collect();
    mesh.normals = normal.map(|at| block.chunks_exact(stride).map(|r| vector(r, at)).collect());
    body.get(block.len()..)
}

fn fixed_size_of(data_type: &PropertyType) -> usize {
    match data_type {
        PropertyType::Scalar(scalar) => scalar_size(scalar),
        // Not reached: callers check `fixed_size` first.
        PropertyType::List(..) => 0,
    }
}

/// Reads `element.count` faces, fanned into triangles as the general reader does; returns the
/// bytes after them.
fn read_faces<'a>(
    element: &ElementDef,
    body: &'a [u8],
    big_endian: bool,
    limits: &Limits,
    triangles: &mut Vec<[u32; 3]>,
) -> Option<&'a [u8]> {
    // (bytes of scalars before the list, the list's count and index types, bytes after it)
    let mut before = 0usize;
    let mut list = None;
    let mut after = 0usize;
    for (name, property) in element.properties.iter() {
        match &property.data_type {
            PropertyType::Scalar(scalar) if list.is_none() => before += scalar_size(scalar),
            PropertyType::Scalar(scalar) => after += scalar_size(scalar),
            PropertyType::List(count, index)
                if list.is_none() && (name == "vertex_indices" || name == "vertex_index") =>
            {
                list = Some((count, index));
            }
            PropertyType::List(..) => return None,
        }
    }
    let (count_type, index_type) = list?;
    let integer = |scalar: &ScalarType| !matches!(scalar, ScalarType::Float | ScalarType::Double);
    if !integer(count_type) || !integer(index_type) {
        return None;
    }
    let count_size = scalar_size(count_type);
    let index_size = scalar_size(index_type);
    // Every face takes at least its count's bytes: a larger count is a lie the general reader names.
    if element.count > body.len() {
        return None;
    }
    triangles.reserve(element.count.min(limits.max_triangles as usize));
    let mut at = 0usize;
    let mut polygon: [u32; 3] = [0; 3];
    for _ in 0..element.count {
        at = at.checked_add(before)?;
        let count = integer_at(body, at, count_type, big_endian)?;
        let count = usize::try_from(count).ok()?;
        at += count_size;
        let indices = body.get(at..at.checked_add(count.checked_mul(index_size)?)?)?;
        // The fan (v0, v[k-1], v[k]) of `load::fan`, without collecting the polygon first.
        for (k, index) in indices.chunks_exact(index_size).enumerate() {
            let index = u32::try_from(integer_at(index, 0, index_type, big_endian)?).ok()?;
            match k {
                0 | 1 => polygon[k] = index,
                _ => {
                    polygon[2] = index;
                    triangles.push(polygon);
                    polygon[1] = index;
                }
            }
        }
        if triangles.len() as u64 > limits.max_triangles {
            return None;
        }
        at += indices.len() + after;
    }
    body.get(at..)
}

/// The integer of type `scalar` at `at`, widened.
fn integer_at(bytes: &[u8], at: usize, scalar: &ScalarType, big_endian: bool) -> Option<i64> {
    macro_rules! read {
        ($t:ty) => {{
            let size = std::mem::size_of::<$t>();
            let raw = bytes.get(at..at.checked_add(size)?)?.try_into().ok()?;
            i64::from(if big_endian {
                <$t>::from_be_bytes(raw)
            } else {
                <$t>::from_le_bytes(raw)
            })
        }};
    }
    Some(match scalar {
        ScalarType::Char => read!(i8),
        ScalarType::UChar => read!(u8),
        ScalarType::Short => read!(i16),
        ScalarType::UShort => read!(u16),
        ScalarType::Int => read!(i32),
        ScalarType::UInt => read!(u32),
        ScalarType::Float | ScalarType::Double => return None,
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::load::ply::parse_with;

    /// A binary PLY: the header lines, then the body built by `body` in the given byte order.
    fn ply(big_endian: bool, header: &str, body: impl FnOnce(&mut Body)) -> Vec<u8> {
        let format = if big_endian { "big" } else { "little" };
        let mut bytes =
            format!("ply\nformat binary_{format}_endian 1.0\n{header}end_header\n").into_bytes();
        let mut b = Body {
            bytes: Vec::new(),
            big_endian,
        };
        body(&mut b);
        bytes.extend(b.bytes);
        bytes
    }

    struct Body {
        bytes: Vec<u8>,
        big_endian: bool,
    }

    impl Body {
        /// `VERTICES` as `float x y z`, then `faces` as `uchar int` lists.
        fn plain_mesh(&mut self, faces: &[&[i32]]) {
            for v in VERTICES {
                for &c in v.iter() {
                    self.f32(c);
                }
            }
            for f in faces {
                self.u8(f.len() as u8);
                for &i in f.iter() {
                    self.i32(i);
                }
            }
        }

        fn put<const N: usize>(&mut self, le: [u8; N], be: [u8; N]) -> &mut Self {
            self.bytes
                .extend_from_slice(if self.big_endian { &be } else { &le });
            self
        }
        fn f32(&mut self, v: f32) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn f64(&mut self, v: f64) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn i32(&mut self, v: i32) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn u16(&mut self, v: u16) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn u8(&mut self, v: u8) -> &mut Self {
            self.bytes.push(v);
            self
        }
    }

    /// Parses with and without the bulk reader: the same mesh or the same error. Returns whether
    /// the bulk reader took the file.
    fn same_as_general(bytes: &[u8], limits: &Limits) -> bool {
        let path = Path::new("test.ply");
        let bulk = parse_with(path, bytes, limits, &mut Vec::new(), true);
        let general = parse_with(path, bytes, limits, &mut Vec::new(), false);
        match (&bulk, &general) {
            (Ok(a), Ok(b)) => assert_eq!(a, b),
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
            _ => panic!("bulk {bulk:?}, general {general:?}"),
        }
        let header = Parser::<Skip>::new()
            .read_header(&mut Reader::new(bytes))
            .expect("header");
        let start = bytes
            .windows(11)
            .position(|w| w == b"end_header\n")
            .expect("end")
            + 11;
        read(&header, &bytes[start..], limits).is_some()
    }

    use ply_rs_bw::parser::{Parser, Reader};
    struct Skip;
    impl ply_rs_bw::ply::PropertyAccess for Skip {
        fn new() -> Self {
            Skip
        }
    }

    const VERTICES: [[f32; 3]; 5] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, -0.0],
        [0.5, 0.5, 2.0],
    ];

    /// A triangle, a quad and a pentagon (fanned), then a face of two indices (no triangle).
    const FACES: [&[i32]; 4] = [&[0, 1, 4], &[0, 1, 2, 3], &[4, 3, 2, 1, 0], &[1, 2]];

    #[test]
    fn common_layouts_read_in_bulk_give_the_general_readers_mesh() {
        for big_endian in [false, true] {
            let plain = ply(
                big_endian,
                "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
                 element face 4\nproperty list uchar int vertex_indices\n",
                |b| b.plain_mesh(&FACES),
            );
            assert!(
                same_as_general(&plain, &Limits::DEFAULT),
                "plain, big {big_endian}"
            );

            // Other scalars around the ones read, normals, a skipped element first, a face with
            // scalars on both sides of a `ushort`-counted `uint` list, and trailing bytes.
            let busy = ply(
                big_endian,
                "element material 2\nproperty uchar red\nproperty double shine\n\
                 element vertex 5\nproperty double w\nproperty float x\nproperty float y\n\
                 property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
                 property uchar alpha\n\
                 element face 4\nproperty uchar flags\nproperty list ushort uint vertex_index\n\
                 property float quality\n",
                |b| {
                    for m in 0..2 {
                        b.u8(m).f64(0.5);
                    }
                    for v in VERTICES {
                        b.f64(9.0);
                        for &c in v.iter() {
                            b.f32(c);
                        }
                        for &c in v.iter() {
                            b.f32(-c);
                        }
                        b.u8(7);
                    }
                    for f in FACES {
                        b.u8(1).u16(f.len() as u16);
                        for &i in f.iter() {
                            b.i32(i);
                        }
                        b.f32(0.25);
                    }
                    b.u8(0xee);
                },
            );
            assert!(
                same_as_general(&busy, &Limits::DEFAULT),
                "busy, big {big_endian}"
            );
        }
    }

    #[test]
    fn files_the_bulk_reader_finds_wrong_get_the_general_readers_error() {
        let header = "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
                      element face 4\nproperty list uchar int vertex_indices\n";
        let with_faces = |faces: &[&[i32]]| ply(false, header, |b| b.plain_mesh(faces));
        let negative = with_faces(&[&[0, 1, 2], &[0, -1, 2], &[1, 2, 3], &[1, 2, 4]]);
        assert!(!same_as_general(&negative, &Limits::DEFAULT));
        let full = with_faces(&FACES);
        for cut in [1, 5, 13, 40] {
            let short = &full[..full.len() - cut];
            assert!(!same_as_general(short, &Limits::DEFAULT), "cut {cut}");
        }
        // Six triangles against a limit of five.
        assert!(!same_as_general(
            &full,
            &Limits::DEFAULT.with_max_triangles(5)
        ));
        assert!(!same_as_general(
            &full,
            &Limits::DEFAULT.with_max_vertices(4)
        ));
        // Double positions and ASCII bodies are the general reader's alone.
        let double = ply(
            false,
            "element vertex 1\nproperty double x\nproperty double y\nproperty double z\n",
            |b| {
                b.f64(1.0).f64(2.0).f64(3.0);
            },
        );
        assert!(!same_as_general(&double, &Limits::DEFAULT));
    }
}
