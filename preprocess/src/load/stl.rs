//! STL, binary and ASCII: the triangle soup CAD tools export, read into a [`Mesh`] whose every
//! triangle has its own three vertices (the weld, and the stitch after it, give it its topology).
//!
//! Binary or ASCII is decided by the size rule, never by the first word: a file that is exactly
//! 84 + 50 × (its declared count) bytes long is binary, even when its 80-byte header begins with
//! `solid` (many exporters write that). Anything else that begins with `solid` is ASCII; anything
//! else is refused, saying what the size rule expected. The declared count is checked against the
//! file's size and [`Limits`] before anything is allocated.
//!
//! Facet normals are ignored (parsed and checked in ASCII, skipped in binary): the winding decides
//! which side is out, as in trimesh and meshoptimizer's tools, because exporters often write zero or
//! stale normals. The binary attribute byte count is ignored. ASCII files may hold several
//! `solid … endsolid` blocks (kept as one mesh) separated by any whitespace; any other token is an
//! error naming its line.

use std::path::Path;

use glam::Vec3;
use rayon::prelude::*;

use crate::limits::Limited;
use crate::mesh::{Mesh, first_non_finite};
use crate::{Error, Limits};

/// `limits` with the vertex limit at most `u32::MAX`: a soup numbers its corners in u32.
fn vertex_limit(limits: &Limits) -> Limits {
    limits.with_max_vertices(limits.max_vertices.min(u64::from(u32::MAX)))
}

/// Bytes before the first binary record: an 80-byte header and the u32 triangle count.
const HEADER_BYTES: usize = 84;
/// Bytes of one binary record: normal, three vertices (12 little-endian f32) and a u16 attribute.
const RECORD_BYTES: usize = 50;

pub(super) fn parse(
    path: &Path,
    bytes: &[u8],
    limits: &Limits,
    _warnings: &mut Vec<String>,
) -> Result<Mesh, Error> {
    let invalid = |message: String| Error::Parse {
        path: path.to_owned(),
        format: "STL",
        message,
    };
    if let Some(count) = binary_count(bytes) {
        limits.check(path, Limited::Triangles, count)?;
        vertex_limit(limits).check(path, Limited::Vertices, count.saturating_mul(3))?;
        return Ok(soup(read_binary(&bytes[HEADER_BYTES..])))
            .and_then(|mesh| refuse_non_finite(mesh, &invalid, |v| format!("triangle {}", v / 3)));
    }
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let declared = || {
        bytes.get(80..HEADER_BYTES).map(|count| {
            let count = u32::from_le_bytes([count[0], count[1], count[2], count[3]]);
            format!(
                "as binary its header declares {count} triangles, which take {} bytes, but the file has {}",
                (HEADER_BYTES as u64).saturating_add(u64::from(count) * RECORD_BYTES as u64),
                bytes.len()
            )
        })
    };
    if first_word(text) == Some(&b"solid"[..]) {
        // A NUL byte is no ASCII STL's: a binary file whose header begins with `solid` and whose
        // size breaks the rule (truncated, or a wrong count) is named as that, not as bad ASCII.
        if let Some(binary) = declared().filter(|_| bytes.contains(&0)) {
            return Err(invalid(format!(
                "it begins with `solid` but holds NUL bytes, so it is not ASCII; {binary}"
            )));
        }
        let (positions, lines) = read_ascii(text, limits, path, &invalid)?;
        return refuse_non_finite(soup(positions), &invalid, |v| format!("line {}", lines[v]));
    }
    Err(invalid(match declared() {
        None => format!(
            "{} bytes: too short for a binary STL (an 84-byte header) and not an ASCII one (it does not begin with `solid`)",
            bytes.len()
        ),
        Some(binary) => format!("not ASCII (it does not begin with `solid`), and {binary}"),
    }))
}

/// Checks a `.stl.gz` while it inflates (see [`read`](super::read)): once the header is in, a file
/// that does not begin with `solid` can only be binary, so its declared count is checked against
/// `limits` and inflating ends with an error as soon as it passes the length that count gives.
/// Returns `Ok(true)` when nothing more needs checking.
pub(super) fn check_stream_prefix(
    path: &Path,
    prefix: &[u8],
    limits: &Limits,
) -> Result<bool, Error> {
    let Some(count) = prefix.get(80..HEADER_BYTES) else {
        return Ok(false);
    };
    if first_word(prefix.strip_prefix(b"\xef\xbb\xbf").unwrap_or(prefix)) == Some(&b"solid"[..]) {
        return Ok(true);
    }
    let count = u64::from(u32::from_le_bytes([count[0], count[1], count[2], count[3]]));
    limits.check(path, Limited::Triangles, count)?;
    vertex_limit(limits).check(path, Limited::Vertices, count.saturating_mul(3))?;
    let expected = count * RECORD_BYTES as u64 + HEADER_BYTES as u64;
    if prefix.len() as u64 > expected {
        return Err(Error::Parse {
            path: path.to_owned(),
            format: "STL",
            message: format!(
                "not ASCII (it does not begin with `solid`), and as binary its header declares {count} triangles, \
                 which take {expected} bytes, but it inflates to more"
            ),
        });
    }
    Ok(false)
}

/// The declared triangle count when `bytes` are a binary STL by the size rule.
fn binary_count(bytes: &[u8]) -> Option<u64> {
    let count = bytes.get(80..HEADER_BYTES)?;
    let count = u64::from(u32::from_le_bytes([count[0], count[1], count[2], count[3]]));
    let expected = count
        .checked_mul(RECORD_BYTES as u64)?
        .checked_add(HEADER_BYTES as u64)?;
    (expected == bytes.len() as u64).then_some(count)
}

/// The three vertices of every record, in parallel (records are independent).
fn read_binary(records: &[u8]) -> Vec<Vec3> {
    /// Records per parallel block: large enough that rayon's bookkeeping is nothing beside it.
    const BLOCK: usize = 1 << 12;
    let mut positions = vec![Vec3::ZERO; records.len() / RECORD_BYTES * 3];
    positions
        .par_chunks_mut(3 * BLOCK)
        .zip(records.par_chunks(RECORD_BYTES * BLOCK))
        .for_each(|(corners, block)| {
            for (corners, record) in corners
                .chunks_exact_mut(3)
                .zip(block.chunks_exact(RECORD_BYTES))
            {
                // The nine little-endian f32 after the normal.
                let f = |i: usize| {
                    let at = 12 + 4 * i;
                    f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]])
                };
                corners[0] = Vec3::new(f(0), f(1), f(2));
                corners[1] = Vec3::new(f(3), f(4), f(5));
                corners[2] = Vec3::new(f(6), f(7), f(8));
            }
        });
    positions
}

/// A soup: triangle `i` is vertices `3i, 3i + 1, 3i + 2`.
fn soup(positions: Vec<Vec3>) -> Mesh {
    let triangles = (0..positions.len() as u32 / 3)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Mesh {
        positions,
        triangles,
        ..Mesh::default()
    }
}

fn refuse_non_finite(
    mesh: Mesh,
    invalid: &dyn Fn(String) -> Error,
    locate: impl Fn(usize) -> String,
) -> Result<Mesh, Error> {
    match first_non_finite(&mesh.positions) {
        None => Ok(mesh),
        Some((vertex, axis, value)) => Err(invalid(format!(
            "{}: vertex {} has {} = {value}, which is not a finite number",
            locate(vertex),
            vertex % 3,
            ["x", "y", "z"][axis]
        ))),
    }
}

fn first_word(text: &[u8]) -> Option<&[u8]> {
    text.split(|b| b.is_ascii_whitespace())
        .find(|w| !w.is_empty())
}

/// Whitespace-separated words with the line each is on.
struct Words<'a> {
    text: &'a [u8],
    at: usize,
    line: usize,
}

impl<'a> Words<'a> {
    fn next(&mut self) -> Option<(&'a [u8], usize)> {
        while let Some(&b) = self.text.get(self.at) {
            if !b.is_ascii_whitespace() {
                break;
            }
            self.line += usize::from(b == b'\n');
            self.at += 1;
        }
        let start = self.at;
        while self
            .text
            .get(self.at)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.at += 1;
        }
        (self.at > start).then(|| (&self.text[start..self.at], self.line))
    }

    /// Skips to the end of the current line (a solid's name).
    fn skip_line(&mut self) {
        while self.text.get(self.at).is_some_and(|&b| b != b'\n') {
            self.at += 1;
        }
    }
}

/// Every facet's vertices, and the line each vertex is on.
fn read_ascii(
    text: &[u8],
    limits: &Limits,
    path: &Path,
    invalid: &dyn Fn(String) -> Error,
) -> Result<(Vec<Vec3>, Vec<u32>), Error> {
    let mut words = Words {
        text,
        at: 0,
        line: 1,
    };
    let mut positions = Vec::new();
    let mut lines = Vec::new();
    let show = |w: &[u8]| String::from_utf8_lossy(&w[..w.len().min(40)]).into_owned();
    let expect = |words: &mut Words<'_>, wanted: &str| match words.next() {
        Some((w, _)) if w == wanted.as_bytes() => Ok(()),
        Some((w, line)) => Err(invalid(format!(
            "line {line}: expected `{wanted}`, found `{}`",
            show(w)
        ))),
        None => Err(invalid(format!(
            "line {}: the file ends where `{wanted}` was expected",
            words.line
        ))),
    };
    let number = |words: &mut Words<'_>, what: &str| -> Result<f32, Error> {
        match words.next() {
            Some((w, line)) => std::str::from_utf8(w)
                .ok()
                .and_then(|s| s.parse::<f32>().ok())
                .ok_or_else(|| {
                    invalid(format!("line {line}: {what} `{}` is not a number", show(w)))
                }),
            None => Err(invalid(format!(
                "line {}: the file ends inside a {what}",
                words.line
            ))),
        }
    };
    let mut solids = 0usize;
    while let Some((word, line)) = words.next() {
        if word != b"solid" {
            return Err(invalid(format!(
                "line {line}: expected `solid`, found `{}`",
                show(word)
            )));
        }
        solids += 1;
        words.skip_line();
        loop {
            match words.next() {
                Some((w, _)) if w == b"endsolid" => {
                    words.skip_line();
                    break;
                }
                Some((w, _)) if w == b"facet" => {}
                Some((w, line)) => {
                    return Err(invalid(format!(
                        "line {line}: expected `facet` or `endsolid`, found `{}`",
                        show(w)
                    )));
                }
                None => {
                    return Err(invalid(format!(
                        "line {}: the file ends inside solid {solids} (no `endsolid`)",
                        words.line
                    )));
                }
            }
            let triangles = positions.len() as u64 / 3 + 1;
            limits.check(path, Limited::Triangles, triangles)?;
            vertex_limit(limits).check(path, Limited::Vertices, triangles.saturating_mul(3))?;
            expect(&mut words, "normal")?;
            for _ in 0..3 {
                number(&mut words, "facet normal")?;
            }
            expect(&mut words, "outer")?;
            expect(&mut words, "loop")?;
            for _ in 0..3 {
                expect(&mut words, "vertex")?;
                let line = words.line;
                let p = Vec3::new(
                    number(&mut words, "vertex coordinate")?,
                    number(&mut words, "vertex coordinate")?,
                    number(&mut words, "vertex coordinate")?,
                );
                positions.push(p);
                lines.push(u32::try_from(line).unwrap_or(u32::MAX));
            }
            expect(&mut words, "endloop")?;
            expect(&mut words, "endfacet")?;
        }
    }
    Ok((positions, lines))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binary(header: &[u8; 80], triangles: &[[f32; 9]]) -> Vec<u8> {
        let mut out = header.to_vec();
        out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
        for t in triangles {
            out.extend_from_slice(&[0u8; 12]);
            for c in t {
                out.extend_from_slice(&c.to_le_bytes());
            }
            out.extend_from_slice(&[0xab, 0xcd]); // attribute bytes: ignored
        }
        out
    }

    fn parse_ok(bytes: &[u8]) -> Mesh {
        parse(
            Path::new("part.stl"),
            bytes,
            &Limits::DEFAULT,
            &mut Vec::new(),
        )
        .expect("parses")
    }

    fn parse_err(bytes: &[u8], limits: &Limits) -> String {
        parse(Path::new("part.stl"), bytes, limits, &mut Vec::new())
            .expect_err("refused")
            .to_string()
    }

    const TRIANGLE: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

    #[test]
    fn a_binary_file_whose_header_begins_with_solid_is_read_as_binary() {
        let mut header = [b' '; 80];
        header[..11].copy_from_slice(b"solid part1");
        let mesh = parse_ok(&binary(&header, &[TRIANGLE, TRIANGLE]));
        assert_eq!(mesh.triangles, [[0, 1, 2], [3, 4, 5]]);
        assert_eq!(mesh.positions[1], Vec3::X);
    }

    #[test]
    fn ascii_with_two_solids_and_odd_whitespace_reads_every_facet() {
        let text = "solid a name with words\n facet normal 0 0 1\n\touter loop\n vertex 0 0 0\n vertex 1 0 0\r\n vertex 0 1 0\n endloop endfacet\nendsolid a\n\
                    solid b\nfacet normal 0 0 0 outer loop vertex 0 0 1 vertex 1 0 1 vertex 0 1 1e0 endloop endfacet endsolid\n";
        let mesh = parse_ok(text.as_bytes());
        assert_eq!(mesh.triangles.len(), 2);
        assert_eq!(mesh.positions[5], Vec3::new(0.0, 1.0, 1.0));
    }

    #[test]
    fn a_declared_count_larger_than_the_file_is_refused_naming_both_sizes() {
        let mut bytes = binary(&[0; 80], &[TRIANGLE]);
        bytes[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
        let message = parse_err(&bytes, &Limits::DEFAULT);
        assert!(
            message.contains("declares 4294967295 triangles"),
            "{message}"
        );
        assert!(message.contains("but the file has 134"), "{message}");
    }

    #[test]
    fn a_count_over_the_triangle_limit_is_refused_before_reading() {
        let bytes = binary(&[0; 80], &[TRIANGLE, TRIANGLE, TRIANGLE]);
        let message = parse_err(&bytes, &Limits::DEFAULT.with_max_triangles(2));
        assert!(message.contains("--max-triangles"), "{message}");
    }

    #[test]
    fn ascii_errors_name_the_line_and_the_problem() {
        let cases = [
            (
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n",
                "line 4: vertex 0 has z = NaN",
            ),
            (
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\nendloop",
                "line 5: vertex coordinate `endloop` is not a number",
            ),
            (
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n",
                "the file ends where `vertex` was expected",
            ),
            (
                "solid x\nfacet normal 0 0 1\n",
                "the file ends where `outer` was expected",
            ),
            ("solid x\n", "no `endsolid`"),
            (
                "solid x\nendsolid\ngarbage",
                "line 3: expected `solid`, found `garbage`",
            ),
            (
                "solid x\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 vertex 1 1 0",
                "expected `endloop`, found `vertex`",
            ),
        ];
        for (text, expected) in cases {
            let message = parse_err(text.as_bytes(), &Limits::DEFAULT);
            assert!(message.contains(expected), "{text:?}: {message}");
            assert!(message.starts_with("part.stl: invalid STL"), "{message}");
        }
    }

    #[test]
    fn a_binary_nan_names_its_triangle() {
        let mut bad = TRIANGLE;
        bad[4] = f32::INFINITY;
        let message = parse_err(&binary(&[0; 80], &[TRIANGLE, bad]), &Limits::DEFAULT);
        assert!(
            message.contains("triangle 1: vertex 1 has y = inf"),
            "{message}"
        );
    }

    #[test]
    fn neither_binary_nor_ascii_says_what_the_size_rule_expected() {
        let mut bytes = binary(&[0; 80], &[TRIANGLE]);
        bytes.push(0);
        let message = parse_err(&bytes, &Limits::DEFAULT);
        assert!(
            message.contains("declares 1 triangles, which take 134 bytes, but the file has 135"),
            "{message}"
        );
        assert!(parse_err(b"abc", &Limits::DEFAULT).contains("too short"));
    }

    #[test]
    fn ascii_counts_are_checked_against_the_limits_as_they_grow() {
        let facet = "facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet\n";
        let text = format!("solid x\n{}endsolid\n", facet.repeat(3));
        let message = parse_err(text.as_bytes(), &Limits::DEFAULT.with_max_triangles(2));
        assert!(message.contains("--max-triangles"), "{message}");
    }
}
