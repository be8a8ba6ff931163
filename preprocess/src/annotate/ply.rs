//! PLY out: the input's elements and properties as read, plus an `edge` element.

use std::io::Write;
use std::path::Path;

use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, ElementDef, Property, PropertyDef, PropertyType, ScalarType};
use ply_rs_bw::writer::Writer;

use super::MarkedEdges;
use crate::Error;
use crate::write::write_atomically;

pub(super) fn write(
    input: &Path,
    bytes: &[u8],
    output: &Path,
    marked: &MarkedEdges,
    remap: &[u32],
) -> Result<usize, Error> {
    let invalid = |message: String| Error::Parse {
        path: input.to_owned(),
        format: "PLY",
        message,
    };
    // The loader already warned about header lines it reads as comments; they are written as such.
    let mut ply = Parser::<DefaultElement>::new()
        .read_ply(&mut crate::load::ply::lenient_header(
            bytes,
            &mut Vec::new(),
        ))
        .map_err(|e| invalid(e.to_string()))?;
    // Each welded vertex is written as its first input vertex.
    let mut first = vec![u32::MAX; remap.len()];
    for (i, &t) in remap.iter().enumerate() {
        if first[t as usize] == u32::MAX {
            first[t as usize] = i as u32;
        }
    }
    let to_index = |v: u32| {
        i32::try_from(first[v as usize])
            .map_err(|_| invalid(format!("vertex {v} does not fit a PLY int")))
    };
    let mut edges = Vec::with_capacity(marked.list.len());
    for &(a, b, flags, radius) in &marked.list {
        let mut element = DefaultElement::new();
        element.insert("vertex1".into(), Property::Int(to_index(a)?));
        element.insert("vertex2".into(), Property::Int(to_index(b)?));
        element.insert("radius".into(), Property::Float(radius));
        element.insert("class".into(), Property::UShort(flags.0));
        edges.push(element);
    }
    let mut definition = ElementDef::new("edge".into());
    for (name, scalar) in [
        ("vertex1", ScalarType::Int),
        ("vertex2", ScalarType::Int),
        ("radius", ScalarType::Float),
        ("class", ScalarType::UShort),
    ] {
        definition.properties.insert(
            name.into(),
            PropertyDef::new(name.into(), PropertyType::Scalar(scalar)),
        );
    }
    ply.header.elements.shift_remove("edge");
    ply.payload.shift_remove("edge");
    ply.header.elements.insert("edge".into(), definition);
    ply.payload.insert("edge".into(), edges);
    let count = marked.list.len();

    let gzip = output
        .to_string_lossy()
        .to_ascii_lowercase()
        .ends_with(".gz");
    write_atomically(output, |out| {
        let to_io = |e: std::io::Error| e;
        if gzip {
            let mut encoder = flate2::write::GzEncoder::new(out, flate2::Compression::default());
            Writer::<DefaultElement>::new()
                .write_ply(&mut encoder, &mut ply)
                .map_err(to_io)?;
            encoder.finish()?.flush()
        } else {
            Writer::<DefaultElement>::new()
                .write_ply(out, &mut ply)
                .map(|_| ())
                .map_err(to_io)
        }
    })?;
    Ok(count)
}
