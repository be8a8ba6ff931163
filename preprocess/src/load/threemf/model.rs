//! The 3D model part of a 3MF package, parsed (3MF core specification §3-§4): the `unit`, every
//! `<object>` with its `<mesh>` (vertices and triangles) or its `<components>` (other objects, each
//! with a transform), and the `<build>` items that place objects in the scene. Elements of
//! extensions (materials, production, beam lattice, slices) are skipped; a production `p:path`
//! (a component in another part) is refused.
//!
//! Bounded: no DOCTYPE (so no entity expansion), elements nested at most [`MAX_DEPTH`] deep, and
//! vertices and triangles counted against [`Limits`] as they are read, before they are stored.

use glam::{Mat4, Vec3};
use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use crate::Limits;
use crate::limits::Limited;

/// The deepest element nesting read; the core schema needs 6 (`model/resources/object/mesh/vertices/vertex`).
pub(super) const MAX_DEPTH: usize = 32;

/// The model part.
#[derive(Debug, Default)]
pub(super) struct Model {
    /// The `unit` attribute (`millimeter` when absent).
    pub unit: String,
    /// The objects, in document order.
    pub objects: Vec<Object>,
    /// The build items, in document order.
    pub build: Vec<Placement>,
}

/// An `<object>`.
#[derive(Debug)]
pub(super) struct Object {
    pub id: u32,
    /// The `type` attribute (`model` when absent).
    pub kind: String,
    pub shape: Shape,
}

/// What an object is made of.
#[derive(Debug)]
pub(super) enum Shape {
    Mesh {
        positions: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
    },
    Components(Vec<Placement>),
}

/// A `<component>` or a build `<item>`: an object and the transform that places it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Placement {
    pub object: u32,
    pub transform: Mat4,
}

/// What went wrong, and where (a 1-based line of the part).
pub(super) struct ModelError {
    pub line: usize,
    pub message: String,
    /// Set when a limit, not the syntax, refused the part.
    pub limit: Option<(Limited, u64)>,
}

/// Parses the model part `xml` within `limits` (vertices and triangles over all objects).
pub(super) fn parse(xml: &[u8], limits: &Limits) -> Result<Model, ModelError> {
    let line_of = |at: u64| {
        let at = usize::try_from(at).unwrap_or(usize::MAX).min(xml.len());
        1 + xml[..at].iter().filter(|&&b| b == b'\n').count()
    };
    let mut reader = Reader::from_reader(xml);
    let mut parser = Parser {
        limits,
        model: Model {
            unit: "millimeter".into(),
            ..Model::default()
        },
        depth: 0,
        object: None,
        in_build: false,
        vertices: 0,
        triangles: 0,
    };
    loop {
        let at = reader.buffer_position();
        let event = reader.read_event().map_err(|e| ModelError {
            line: line_of(reader.error_position()),
            message: e.to_string(),
            limit: None,
        })?;
        let fail = |(message, limit): (String, Option<(Limited, u64)>)| ModelError {
            line: line_of(at),
            message,
            limit,
        };
        match event {
            Event::Start(e) => {
                parser.depth += 1;
                if parser.depth > MAX_DEPTH {
                    return Err(fail((
                        format!("elements nested deeper than {MAX_DEPTH}"),
                        None,
                    )));
                }
                parser.open(&e, false).map_err(fail)?;
            }
            Event::Empty(e) => parser.open(&e, true).map_err(fail)?,
            Event::End(e) => {
                parser.depth = parser.depth.saturating_sub(1);
                parser.close(e.local_name().as_ref()).map_err(fail)?;
            }
            Event::DocType(_) => {
                return Err(fail((
                    "a DOCTYPE (refused: no entity expansion)".into(),
                    None,
                )));
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if parser.object.is_some() {
        return Err(ModelError {
            line: line_of(xml.len() as u64),
            message: "the part ends inside an <object>".into(),
            limit: None,
        });
    }
    Ok(parser.model)
}

type Failure = (String, Option<(Limited, u64)>);

struct Parser<'a> {
    limits: &'a Limits,
    model: Model,
    depth: usize,
    /// The object being read.
    object: Option<Object>,
    in_build: bool,
    /// Read so far, over all objects.
    vertices: u64,
    triangles: u64,
}

fn attribute<'e>(e: &'e BytesStart, key: &str) -> Option<std::borrow::Cow<'e, str>> {
    e.attributes()
        .with_checks(false)
        .flatten()
        .find(|a| a.key.local_name().as_ref() == key && a.key.prefix().is_none())
        .map(|a| a.value)
}

fn required<T: std::str::FromStr>(e: &BytesStart, element: &str, key: &str) -> Result<T, Failure> {
    let value = attribute(e, key).ok_or_else(|| (format!("<{element}> without `{key}`"), None))?;
    value.trim().parse().map_err(|_| {
        (
            format!("<{element}> `{key}` is `{value}`, not a valid number"),
            None,
        )
    })
}

/// A 3MF transform: 12 numbers, a 4 × 3 matrix applied to row vectors (`p' = [x y z 1] · M`), its
/// last row the translation; absent, the identity.
fn transform(e: &BytesStart, element: &str) -> Result<Mat4, Failure> {
    let Some(text) = attribute(e, "transform") else {
        return Ok(Mat4::IDENTITY);
    };
    let numbers: Vec<f32> = text
        .split_ascii_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| {
            (
                format!("<{element}> transform `{text}` holds something that is not a number"),
                None,
            )
        })?;
    let [m00, m01, m02, m10, m11, m12, m20, m21, m22, m30, m31, m32] = numbers[..] else {
        return Err((
            format!(
                "<{element}> transform has {} numbers, not 12",
                numbers.len()
            ),
            None,
        ));
    };
    if numbers.iter().any(|n| !n.is_finite()) {
        return Err((
            format!("<{element}> transform `{text}` is not finite"),
            None,
        ));
    }
    // The row-vector matrix, transposed into glam's column vectors.
    Ok(Mat4::from_cols_array(&[
        m00, m01, m02, 0.0, m10, m11, m12, 0.0, m20, m21, m22, 0.0, m30, m31, m32, 1.0,
    ]))
}

impl Parser<'_> {
    fn count(&mut self, what: Limited) -> Result<(), Failure> {
        let (counter, limit) = match what {
            Limited::Vertices => (&mut self.vertices, self.limits.max_vertices),
            _ => (&mut self.triangles, self.limits.max_triangles),
        };
        *counter += 1;
        if *counter > limit {
            return Err((
                format!("more than {limit} {}", what.noun()),
                Some((what, *counter)),
            ));
        }
        Ok(())
    }

    fn open(&mut self, e: &BytesStart, empty: bool) -> Result<(), Failure> {
        let name = e.local_name();
        let name = name.as_ref();
        match (name, &mut self.object) {
            ("model", None) => {
                if let Some(unit) = attribute(e, "unit") {
                    self.model.unit = unit.into_owned();
                }
            }
            ("object", None) => {
                let object = Object {
                    id: required(e, "object", "id")?,
                    kind: attribute(e, "type").map_or_else(|| "model".into(), |t| t.into_owned()),
                    shape: Shape::Components(Vec::new()),
                };
                if empty {
                    return Err((
                        format!("<object> {} holds neither a mesh nor components", object.id),
                        None,
                    ));
                }
                self.object = Some(object);
            }
            ("mesh", Some(object)) => {
                object.shape = Shape::Mesh {
                    positions: Vec::new(),
                    triangles: Vec::new(),
                };
            }
            ("vertex", Some(_)) => {
                let vertex = Vec3::new(
                    required(e, "vertex", "x")?,
                    required(e, "vertex", "y")?,
                    required(e, "vertex", "z")?,
                );
                if !vertex.is_finite() {
                    return Err((format!("<vertex> {vertex} is not finite"), None));
                }
                self.count(Limited::Vertices)?;
                if let Some(Object {
                    shape: Shape::Mesh { positions, .. },
                    ..
                }) = &mut self.object
                {
                    positions.push(vertex);
                }
            }
            ("triangle", Some(_)) => {
                let triangle = [
                    required(e, "triangle", "v1")?,
                    required(e, "triangle", "v2")?,
                    required(e, "triangle", "v3")?,
                ];
                self.count(Limited::Triangles)?;
                if let Some(Object {
                    shape: Shape::Mesh { triangles, .. },
                    ..
                }) = &mut self.object
                {
                    triangles.push(triangle);
                }
            }
            ("component", Some(object)) => {
                if e.attributes()
                    .with_checks(false)
                    .flatten()
                    .any(|a| a.key.local_name().as_ref() == "path")
                {
                    return Err((
                        format!(
                            "object {}: a component in another part (the production extension's `path`) is not supported",
                            object.id
                        ),
                        None,
                    ));
                }
                let placement = Placement {
                    object: required(e, "component", "objectid")?,
                    transform: transform(e, "component")?,
                };
                if let Shape::Components(components) = &mut object.shape {
                    components.push(placement);
                }
            }
            ("build", None) => self.in_build = !empty,
            ("item", None) if self.in_build => self.model.build.push(Placement {
                object: required(e, "item", "objectid")?,
                transform: transform(e, "item")?,
            }),
            _ => {}
        }
        Ok(())
    }

    fn close(&mut self, name: &str) -> Result<(), Failure> {
        match name {
            "object" => {
                if let Some(object) = self.object.take() {
                    if let Shape::Mesh {
                        positions,
                        triangles,
                    } = &object.shape
                    {
                        let outside = triangles.iter().enumerate().find_map(|(t, tri)| {
                            tri.iter()
                                .find(|&&v| v as usize >= positions.len())
                                .map(|&v| (t, v))
                        });
                        if let Some((t, v)) = outside {
                            return Err((
                                format!(
                                    "object {}: triangle {t} names vertex {v}, but the mesh has {}",
                                    object.id,
                                    positions.len()
                                ),
                                None,
                            ));
                        }
                    }
                    self.model.objects.push(object);
                }
            }
            "build" => self.in_build = false,
            _ => {}
        }
        Ok(())
    }
}
