//! PLY out: the input byte for byte — header lines, comments, encoding and every element's bytes —
//! with its `edge` element (if any) taken out and a new `edge` element (`vertex1 vertex2 radius
//! class`) added last, in the file's encoding.
//!
//! Nothing is decoded into values and nothing is held per element: the body is copied in the
//! element spans [`element_spans`] finds, so a header that claims 2⁶⁴ − 1 elements without
//! properties costs nothing (they occupy no bytes), and the memory is the input's bytes plus the
//! edge records.

use std::io::Write;
use std::ops::Range;
use std::path::Path;

use ply_rs_bw::ply::{Encoding, Header, PropertyType, ScalarType};

use super::MarkedEdges;
use crate::Error;
use crate::load::ply_header::{self, LineKind, scalar_size};
use crate::write::write_atomically;

/// The header lines of the element written, after its `element edge N` line.
const EDGE_PROPERTIES: &str =
    "property int vertex1\nproperty int vertex2\nproperty float radius\nproperty ushort class\n";

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
    let parsed = ply_header::parse(bytes, true)
        .map_err(invalid)?
        .ok_or_else(|| invalid("the header has no end_header line".into()))?;
    let header = &parsed.header;
    let edge = header.elements.get_index_of("edge");
    let body = &bytes[parsed.body_start..];
    let spans = element_spans(header, body).map_err(invalid)?;

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
    let mut records = Vec::new();
    for &(a, b, flags, radius) in &marked.list {
        let (a, b) = (to_index(a)?, to_index(b)?);
        match header.encoding {
            Encoding::Ascii => {
                records.extend(format!("{a} {b} {radius} {}\n", flags.0).into_bytes());
            }
            Encoding::BinaryLittleEndian => {
                records.extend(a.to_le_bytes());
                records.extend(b.to_le_bytes());
                records.extend(radius.to_le_bytes());
                records.extend(flags.0.to_le_bytes());
            }
            Encoding::BinaryBigEndian => {
                records.extend(a.to_be_bytes());
                records.extend(b.to_be_bytes());
                records.extend(radius.to_be_bytes());
                records.extend(flags.0.to_be_bytes());
            }
        }
    }

    let mut text = Vec::new();
    for (range, kind) in &parsed.lines {
        let line = &bytes[range.clone()];
        match *kind {
            LineKind::Element(i) | LineKind::Property(i) if Some(i) == edge => {}
            // The loader warned about these lines and read them as comments: so are they written.
            LineKind::Unknown => {
                text.extend_from_slice(b"comment ");
                text.extend_from_slice(line);
            }
            LineKind::End => {
                text.extend(
                    format!("element edge {}\n{EDGE_PROPERTIES}", marked.list.len()).into_bytes(),
                );
                text.extend_from_slice(line);
                if !line.ends_with(b"\n") {
                    text.push(b'\n');
                }
            }
            _ => text.extend_from_slice(line),
        }
    }

    let write_all = |out: &mut dyn Write| -> std::io::Result<()> {
        out.write_all(&text)?;
        for (i, span) in spans.iter().enumerate() {
            if Some(i) != edge {
                out.write_all(&body[span.clone()])?;
            }
        }
        out.write_all(&records)
    };
    let gzip = output
        .to_string_lossy()
        .to_ascii_lowercase()
        .ends_with(".gz");
    write_atomically(output, |out| {
        if gzip {
            let mut encoder = flate2::write::GzEncoder::new(out, flate2::Compression::default());
            write_all(&mut encoder)?;
            encoder.finish()?.flush()
        } else {
            write_all(out)
        }
    })?;
    Ok(marked.list.len())
}

/// Where each element of `header` lies in `body`, in header order, as the loader reads them: an
/// ASCII element is one line, a binary one its scalars' bytes and each list's count and items; an
/// element without properties takes no bytes, however many the header claims.
fn element_spans(header: &Header, body: &[u8]) -> Result<Vec<Range<usize>>, String> {
    let mut at = 0usize;
    let ends = || format!("the body ends inside its elements ({} bytes)", body.len());
    let mut spans = Vec::with_capacity(header.elements.len());
    for element in header.elements.values() {
        let start = at;
        let scalars: Option<usize> = element
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(s) => Some(scalar_size(s)),
                PropertyType::List(..) => None,
            })
            .sum();
        match (header.encoding, scalars) {
            (_, _) if element.properties.is_empty() => {}
            (Encoding::Ascii, _) => {
                for _ in 0..element.count {
                    let rest = body.get(at..).filter(|r| !r.is_empty()).ok_or_else(ends)?;
                    at += rest
                        .iter()
                        .position(|&b| b == b'\n')
                        .map_or(rest.len(), |n| n + 1);
                }
            }
            (_, Some(size)) => {
                at = element
                    .count
                    .checked_mul(size)
                    .and_then(|n| n.checked_add(at))
                    .filter(|&end| end <= body.len())
                    .ok_or_else(ends)?;
            }
            (encoding, None) => {
                let big_endian = encoding == Encoding::BinaryBigEndian;
                for _ in 0..element.count {
                    for property in element.properties.values() {
                        at = match &property.data_type {
                            PropertyType::Scalar(s) => at.checked_add(scalar_size(s)),
                            PropertyType::List(count, item) => {
                                let items =
                                    list_count(body, at, count, big_endian).ok_or_else(ends)?;
                                items
                                    .checked_mul(scalar_size(item))
                                    .and_then(|n| n.checked_add(at + scalar_size(count)))
                            }
                        }
                        .filter(|&end| end <= body.len())
                        .ok_or_else(ends)?;
                    }
                }
            }
        }
        spans.push(start..at);
    }
    Ok(spans)
}

/// A binary list's item count at `at` (negative counts are `None`, as the loader refuses them).
fn list_count(body: &[u8], at: usize, count: &ScalarType, big_endian: bool) -> Option<usize> {
    let bytes = body.get(at..at.checked_add(scalar_size(count))?)?;
    let word = |b: &[u8]| -> [u8; 4] {
        let mut w = [0u8; 4];
        if big_endian {
            w[4 - b.len()..].copy_from_slice(b);
            w.reverse();
        } else {
            w[..b.len()].copy_from_slice(b);
        }
        w
    };
    let unsigned = u32::from_le_bytes(word(bytes));
    let negative = match count {
        ScalarType::Char => bytes[0] & 0x80 != 0,
        ScalarType::Short => unsigned & 0x8000 != 0,
        ScalarType::Int => unsigned & 0x8000_0000 != 0,
        _ => false,
    };
    (!negative).then_some(unsigned as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_follow_ascii_lines_binary_lists_and_empty_elements() {
        let ascii = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nelement nothing 18446744073709551615\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0.5\n1\n3 0 1 1\n";
        let parsed = ply_header::parse(ascii.as_bytes(), true)
            .expect("parses")
            .expect("complete");
        let body = &ascii.as_bytes()[parsed.body_start..];
        assert_eq!(
            element_spans(&parsed.header, body).expect("spans"),
            [0..6, 6..6, 6..14]
        );
        for big_endian in [false, true] {
            let format = if big_endian { "big" } else { "little" };
            let text = format!(
                "ply\nformat binary_{format}_endian 1.0\nelement face 2\nproperty uchar flags\nproperty list ushort int vertex_indices\nelement tail 1\nproperty double w\nend_header\n"
            );
            let mut bytes = text.into_bytes();
            let start = bytes.len();
            let count = |n: u16| {
                if big_endian {
                    n.to_be_bytes()
                } else {
                    n.to_le_bytes()
                }
            };
            bytes.push(7);
            bytes.extend(count(3));
            bytes.extend([0u8; 12]);
            bytes.push(7);
            bytes.extend(count(1));
            bytes.extend([0u8; 4]);
            bytes.extend([0u8; 8]);
            let parsed = ply_header::parse(&bytes, true)
                .expect("parses")
                .expect("complete");
            assert_eq!(
                element_spans(&parsed.header, &bytes[start..]).expect("spans"),
                [0..22, 22..30]
            );
            assert!(element_spans(&parsed.header, &bytes[start..bytes.len() - 1]).is_err());
        }
    }
}
