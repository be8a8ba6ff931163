//! The PLY header (Bourke's PLY format description, "The header"): parsed here rather than by
//! ply-rs-bw so that every error names the header line and what is wrong with it, so that the counts a
//! header declares can be checked against [`Limits`] from the first bytes of a stream (a `.ply.gz`
//! is checked before it is inflated), and so that `annotate` can rewrite the header line by line.
//!
//! Accepted: everything ply-rs-bw's grammar accepts, plus blank lines and header lines that are not
//! PLY keywords (Blender 2.4x wrote an unprefixed "Created by Blender" line), which are read as
//! comments with a warning, as other readers do. Refused, naming the line: a missing `ply` line,
//! unknown formats, types and keywords' malformed arguments, an element or property declared twice
//! (ply-rs-bw's maps would silently merge them and read the body misaligned), a list whose count is
//! not an integer type, a property before any element and a header without `end_header`.

use std::ops::Range;
use std::path::Path;

use ply_rs_bw::ply::{
    Addable, ElementDef, Encoding, Header, PropertyDef, PropertyType, ScalarType, Version,
};

use crate::limits::Limited;
use crate::{Error, Limits};

/// A parsed header and where its parts lie in the file.
#[derive(Debug)]
pub(crate) struct ParsedHeader {
    /// The header as the element readers take it.
    pub header: Header,
    /// The first byte after the `end_header` line.
    pub body_start: usize,
    /// Every header line (with its line break), in order, and what it is.
    pub lines: Vec<(Range<usize>, LineKind)>,
    /// One per line read as a comment.
    pub warnings: Vec<String>,
}

/// What a header line is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LineKind {
    /// `ply`, `format`, `comment`, `obj_info`, or a blank line.
    Kept,
    /// Not a PLY keyword: read as a comment.
    Unknown,
    /// The `element` line of element `i` (in header order).
    Element(usize),
    /// A `property` line of element `i`.
    Property(usize),
    /// `end_header`.
    End,
}

/// Parses the header at the start of `bytes`. Returns `Ok(None)` when `bytes` ends before the
/// `end_header` line and `complete` is false (the rest of a stream has not been read yet; a line cut
/// short is not looked at); errors name the 1-based header line.
pub(crate) fn parse(bytes: &[u8], complete: bool) -> Result<Option<ParsedHeader>, String> {
    let mut header = Header::new();
    let mut format: Option<(Encoding, Version)> = None;
    let mut lines = Vec::new();
    let mut warnings = Vec::new();
    let mut element_lines: Vec<usize> = Vec::new();
    let mut at = 0;
    let mut number = 0;
    while at < bytes.len() {
        let end = bytes[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|n| at + n + 1);
        let end = match end {
            Some(end) => end,
            None if complete => bytes.len(),
            None => return Ok(None),
        };
        number += 1;
        let range = at..end;
        at = end;
        let text = String::from_utf8_lossy(&bytes[range.clone()]);
        let text = text.trim_end_matches(['\n', '\r']);
        let located =
            |problem: String| format!("header line {number} (`{}`): {problem}", quote(text));
        let mut words = text.split_ascii_whitespace();
        let keyword = words.next().unwrap_or("");
        if number == 1 {
            if keyword != "ply" || words.next().is_some() {
                return Err(located(
                    "not a PLY file: the first line must be `ply`".into(),
                ));
            }
            lines.push((range, LineKind::Kept));
            continue;
        }
        let kind = match keyword {
            "" | "comment" | "obj_info" => LineKind::Kept,
            "ply" => return Err(located("a second `ply` line".into())),
            "format" => {
                let parsed = parse_format(&mut words).map_err(located)?;
                if format.is_some_and(|f| f != parsed) {
                    return Err(located("contradicts the earlier format line".into()));
                }
                format = Some(parsed);
                LineKind::Kept
            }
            "element" => {
                let element = parse_element(&mut words).map_err(located)?;
                if let Some(first) = header.elements.get_index_of(&element.name) {
                    return Err(located(format!(
                        "element '{}' is already declared on header line {}",
                        element.name, element_lines[first]
                    )));
                }
                element_lines.push(number);
                header.elements.add(element);
                LineKind::Element(header.elements.len() - 1)
            }
            "property" => {
                let property = parse_property(&mut words).map_err(located)?;
                let index = header
                    .elements
                    .len()
                    .checked_sub(1)
                    .ok_or_else(|| located("a property before any element line".into()))?;
                let Some((name, element)) = header.elements.get_index_mut(index) else {
                    return Err(located("a property before any element line".into()));
                };
                if element.properties.contains_key(&property.name) {
                    return Err(located(format!(
                        "element '{name}' already has a property '{}'",
                        property.name
                    )));
                }
                element.properties.add(property);
                LineKind::Property(index)
            }
            "end_header" => {
                if let Some(extra) = words.next() {
                    return Err(located(format!("unexpected '{extra}' after end_header")));
                }
                lines.push((range, LineKind::End));
                let (encoding, version) =
                    format.ok_or("the header has no format line (e.g. `format ascii 1.0`)")?;
                header.encoding = encoding;
                header.version = version;
                return Ok(Some(ParsedHeader {
                    header,
                    body_start: at,
                    lines,
                    warnings,
                }));
            }
            _ => {
                warnings.push(format!(
                    "header line {:?} is not a PLY keyword; read as a comment",
                    text.trim()
                ));
                LineKind::Unknown
            }
        };
        if kind == LineKind::Kept && !matches!(keyword, "comment" | "obj_info") {
            // `format` and blank lines take no more words; comments take any.
            if let Some(extra) = words.next() {
                return Err(located(format!("unexpected '{extra}' at the end")));
            }
        }
        lines.push((range, kind));
    }
    if complete {
        Err(format!(
            "the header has no end_header line (the file ends after {number} lines)"
        ))
    } else {
        Ok(None)
    }
}

/// At most this many characters of a line are quoted in a message.
fn quote(text: &str) -> String {
    match text.char_indices().nth(60) {
        Some((cut, _)) => format!("{}...", &text[..cut]),
        None => text.to_owned(),
    }
}

fn parse_format<'a>(
    words: &mut impl Iterator<Item = &'a str>,
) -> Result<(Encoding, Version), String> {
    let encoding = match words.next() {
        Some("ascii") => Encoding::Ascii,
        Some("binary_little_endian") => Encoding::BinaryLittleEndian,
        Some("binary_big_endian") => Encoding::BinaryBigEndian,
        Some(other) => {
            return Err(format!(
                "unknown format '{other}' (ascii, binary_little_endian or binary_big_endian)"
            ));
        }
        None => return Err("the format line names no format".into()),
    };
    let version = words
        .next()
        .ok_or("the format line has no version (e.g. 1.0)")?;
    let parsed = version.split_once('.').and_then(|(major, minor)| {
        let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
        (digits(major) && digits(minor)).then_some(())?;
        Some(Version {
            major: major.parse().ok()?,
            minor: minor.parse().ok()?,
        })
    });
    let version =
        parsed.ok_or_else(|| format!("version '{version}' is not major.minor (e.g. 1.0)"))?;
    Ok((encoding, version))
}

fn parse_element<'a>(words: &mut impl Iterator<Item = &'a str>) -> Result<ElementDef, String> {
    let name = words
        .next()
        .ok_or("an element line needs a name and a count")?;
    check_name(name)?;
    let count = words
        .next()
        .ok_or_else(|| format!("element '{name}' has no count"))?;
    if !count.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!(
            "the count of element '{name}' is '{count}', not a whole number"
        ));
    }
    let count = count
        .parse::<u64>()
        .ok()
        .and_then(|c| usize::try_from(c).ok())
        .ok_or_else(|| format!("the count of element '{name}' is larger than 2^64 - 1"))?;
    if let Some(extra) = words.next() {
        return Err(format!("unexpected '{extra}' after the count"));
    }
    let mut element = ElementDef::new(name.to_owned());
    element.count = count;
    Ok(element)
}

fn parse_property<'a>(words: &mut impl Iterator<Item = &'a str>) -> Result<PropertyDef, String> {
    let first = words
        .next()
        .ok_or("a property line needs a type and a name")?;
    let data_type = if first == "list" {
        let count = scalar(words.next().ok_or("a list property needs a count type")?)?;
        if matches!(count, ScalarType::Float | ScalarType::Double) {
            return Err(format!(
                "a list's count type must be an integer type, not {}",
                scalar_name(&count)
            ));
        }
        let item = scalar(words.next().ok_or("a list property needs an item type")?)?;
        PropertyType::List(count, item)
    } else {
        PropertyType::Scalar(scalar(first)?)
    };
    let name = words.next().ok_or("the property has no name")?;
    check_name(name)?;
    if let Some(extra) = words.next() {
        return Err(format!("unexpected '{extra}' after the property name"));
    }
    Ok(PropertyDef::new(name.to_owned(), data_type))
}

/// Names as ply-rs-bw's grammar takes them: a letter or `_`, then letters, digits, `_` or `-`.
fn check_name(name: &str) -> Result<(), String> {
    let mut chars = name.chars();
    let starts_well = chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if starts_well && chars.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
        Ok(())
    } else {
        Err(format!(
            "'{name}' is not a name (a letter or _, then letters, digits, _ or -)"
        ))
    }
}

fn scalar(word: &str) -> Result<ScalarType, String> {
    Ok(match word {
        "char" | "int8" => ScalarType::Char,
        "uchar" | "uint8" => ScalarType::UChar,
        "short" | "int16" => ScalarType::Short,
        "ushort" | "uint16" => ScalarType::UShort,
        "int" | "int32" => ScalarType::Int,
        "uint" | "uint32" => ScalarType::UInt,
        "float" | "float32" => ScalarType::Float,
        "double" | "float64" => ScalarType::Double,
        _ => {
            return Err(format!(
                "unknown type '{word}' (char, uchar, short, ushort, int, uint, float, double, \
                 or int8 ... float64)"
            ));
        }
    })
}

/// The type's PLY name, for messages.
pub(crate) fn scalar_name(scalar: &ScalarType) -> &'static str {
    match scalar {
        ScalarType::Char => "char",
        ScalarType::UChar => "uchar",
        ScalarType::Short => "short",
        ScalarType::UShort => "ushort",
        ScalarType::Int => "int",
        ScalarType::UInt => "uint",
        ScalarType::Float => "float",
        ScalarType::Double => "double",
    }
}

/// A property's type as the header writes it (`float`, `list uchar int`), for messages.
pub(crate) fn type_name(data_type: &PropertyType) -> String {
    match data_type {
        PropertyType::Scalar(s) => scalar_name(s).to_owned(),
        PropertyType::List(count, item) => {
            format!("list {} {}", scalar_name(count), scalar_name(item))
        }
    }
}

/// Bytes one value of `scalar` takes in a binary body.
pub(crate) fn scalar_size(scalar: &ScalarType) -> usize {
    match scalar {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// The fewest bytes the body of `header` can take: each binary scalar its size, each list its count
/// (with no items); each ASCII value one character and a separator. Elements without properties
/// take nothing (there is nothing to read, however many the header claims). Saturates.
pub(crate) fn least_body_bytes(header: &Header) -> u64 {
    header.elements.values().fold(0u64, |total, element| {
        let per_element: u64 = element
            .properties
            .values()
            .map(|p| match (&header.encoding, &p.data_type) {
                (Encoding::Ascii, _) => 2,
                (_, PropertyType::Scalar(s) | PropertyType::List(s, _)) => scalar_size(s) as u64,
            })
            .sum();
        total.saturating_add(per_element.saturating_mul(element.count as u64))
    })
}

/// Checks what `header` declares against `limits` before any of it is read: the vertex count, and
/// the fewest bytes its elements need against [`Limits::max_input_bytes`] (so a compressed file
/// that claims more is refused from its first kilobytes, without inflating it).
pub(crate) fn check_declared(path: &Path, header: &Header, limits: &Limits) -> Result<(), Error> {
    if let Some(vertices) = header.elements.get("vertex") {
        limits.check(path, Limited::Vertices, vertices.count as u64)?;
    }
    limits.check(path, Limited::InputBytes, least_body_bytes(header))
}

/// Headers longer than this are not looked at while a stream is read (the loader still reads them).
pub(crate) const STREAM_CHECK_BYTES: usize = 1 << 20;

/// The check [`crate::load::read`] runs on the first bytes of a PLY while inflating it: `Ok(true)`
/// once the header has been checked (or is too long to wait for), `Ok(false)` while it is not yet
/// all there, and the loader's error for a header that is wrong or declares too much.
pub(crate) fn check_stream_prefix(
    path: &Path,
    prefix: &[u8],
    limits: &Limits,
) -> Result<bool, Error> {
    match parse(prefix, false) {
        Ok(Some(parsed)) => check_declared(path, &parsed.header, limits).map(|()| true),
        Ok(None) => Ok(prefix.len() > STREAM_CHECK_BYTES),
        Err(message) => Err(Error::Parse {
            path: path.to_owned(),
            format: "PLY",
            message,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        parse(text.as_bytes(), true).expect_err(text)
    }

    #[test]
    fn header_errors_name_the_line_and_the_problem() {
        let start = "ply\nformat ascii 1.0\nelement vertex 3\n";
        for (header, expected) in [
            ("plx\n", "header line 1 (`plx`): not a PLY file"),
            (
                "ply\nformat text 1.0\nend_header\n",
                "unknown format 'text'",
            ),
            ("ply\nformat ascii one\nend_header\n", "version 'one'"),
            (
                &format!("{start}property flot x\nend_header\n"),
                "header line 4 (`property flot x`): unknown type 'flot'",
            ),
            (
                &format!("{start}property list float int v\nend_header\n"),
                "count type must be an integer type, not float",
            ),
            (
                &format!("{start}property float x\nproperty float x\nend_header\n"),
                "header line 5 (`property float x`): element 'vertex' already has a property 'x'",
            ),
            (
                &format!("{start}element vertex 4\nend_header\n"),
                "element 'vertex' is already declared on header line 3",
            ),
            (
                "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
                "a property before any element",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n",
                "'-3', not a whole number",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 99999999999999999999\nend_header\n",
                "larger than 2^64 - 1",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex\nend_header\n",
                "element 'vertex' has no count",
            ),
            ("ply\nelement vertex 1\nend_header\n", "no format line"),
            (start, "no end_header line (the file ends after 3 lines)"),
        ] {
            let text = error(header);
            assert!(text.contains(expected), "{header:?}: {text}");
        }
    }

    #[test]
    fn unknown_lines_are_comments_and_a_stream_prefix_waits_for_the_whole_header() {
        let text = "ply\r\nformat binary_little_endian 1.0\nCreated by Blender\n\nelement vertex 3\nproperty float x\nend_header\nBODY";
        let parsed = parse(text.as_bytes(), true)
            .expect("parses")
            .expect("complete");
        assert_eq!(&text[parsed.body_start..], "BODY");
        assert_eq!(parsed.warnings.len(), 1);
        assert_eq!(parsed.lines[2].1, LineKind::Unknown);
        assert_eq!(parsed.lines[4].1, LineKind::Element(0));
        assert_eq!(parsed.lines[5].1, LineKind::Property(0));
        assert_eq!(parsed.header.elements["vertex"].count, 3);
        // A prefix that stops inside the header, even inside a line, is not yet an answer.
        for cut in [3, 20, text.len() - 10] {
            assert!(
                parse(&text.as_bytes()[..cut], false)
                    .expect("no error")
                    .is_none()
            );
        }
    }

    #[test]
    fn declared_counts_are_checked_from_the_header_alone() {
        let header = "ply\nformat binary_little_endian 1.0\nelement vertex 170000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        let path = Path::new("bomb.ply.gz");
        let error = check_stream_prefix(path, header.as_bytes(), &Limits::DEFAULT)
            .expect_err("over the vertex limit");
        assert!(error.to_string().contains("--max-vertices"), "{error}");
        let limits = Limits::DEFAULT
            .with_max_vertices(u64::MAX)
            .with_max_input_bytes(1 << 30);
        let error = check_stream_prefix(path, header.as_bytes(), &limits)
            .expect_err("12 bytes a vertex do not fit 1 GiB");
        assert!(error.to_string().contains("2040000000 bytes"), "{error}");
        assert!(
            check_stream_prefix(path, &header.as_bytes()[..40], &Limits::DEFAULT)
                .is_ok_and(|done| !done)
        );
    }
}
