//! 3MF (3MF Consortium core specification 1.3): a zip package whose model part holds objects —
//! meshes, or components placing other objects — and the build items that place objects in the
//! scene. [`parse`] flattens every build item into one [`Mesh`], in millimetres (the format's
//! default unit; files in other units are converted); [`parse_scene`] keeps each mesh object in its
//! own space and lists its instances, for `bake --scene`.
//!
//! One object placed twice is read once. Components are resolved before anything is expanded:
//! references to missing objects, cycles and chains deeper than [`MAX_COMPONENT_DEPTH`] are
//! refused, and the instances, triangles and vertices the build would make are counted against
//! [`Limits`] first. A transform whose determinant is negative mirrors: its triangles' winding is
//! reversed so their outside stays out. Objects of type `other` (not meant to be drawn, §4.1) are
//! left out with a warning; materials and colours (the materials extension) are not read.

mod model;
mod package;

use std::collections::HashMap;
use std::path::Path;

use glam::Mat4;

use super::SceneMeshes;
use crate::limits::Limited;
use crate::mesh::Mesh;
use crate::{Error, Limits};
use model::{Model, Placement, Shape};

/// The deepest chain of components (object in object in ...) read.
pub const MAX_COMPONENT_DEPTH: usize = 64;

pub(super) fn parse(
    path: &Path,
    bytes: &[u8],
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Result<Mesh, Error> {
    let (model, instances) = read(path, bytes, limits, warnings)?;
    let mut mesh = Mesh::default();
    for (object, transform) in instances {
        let Shape::Mesh {
            positions,
            triangles,
        } = &model.objects[object].shape
        else {
            continue;
        };
        // At most u32::MAX vertices in all (checked in `read`), so neither this nor `v + base` wraps.
        let base = mesh.positions.len() as u32;
        mesh.positions
            .extend(positions.iter().map(|&p| transform.transform_point3(p)));
        let mirrored = transform.determinant() < 0.0;
        mesh.triangles.extend(triangles.iter().map(|t| {
            let [a, b, c] = t.map(|v| v + base);
            if mirrored { [a, c, b] } else { [a, b, c] }
        }));
    }
    Ok(mesh)
}

/// Every mesh object the build places, each in its own space, and its instances.
pub(crate) fn parse_scene(
    path: &Path,
    bytes: &[u8],
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Result<SceneMeshes, Error> {
    let (model, instances) = read(path, bytes, limits, warnings)?;
    let mut slot = HashMap::new();
    let mut meshes = Vec::new();
    let mut placed = Vec::with_capacity(instances.len());
    for (object, transform) in instances {
        let k = *slot.entry(object).or_insert_with(|| {
            let mesh = match &model.objects[object].shape {
                Shape::Mesh {
                    positions,
                    triangles,
                } => Mesh {
                    positions: positions.clone(),
                    triangles: triangles.clone(),
                    ..Mesh::default()
                },
                Shape::Components(_) => Mesh::default(),
            };
            meshes.push((model.objects[object].id as usize, mesh, None));
            meshes.len() - 1
        });
        placed.push((k, transform));
    }
    Ok(SceneMeshes {
        meshes,
        instances: placed,
    })
}

fn invalid(path: &Path, message: String) -> Error {
    Error::Parse {
        path: path.to_owned(),
        format: "3MF",
        message,
    }
}

/// Millimetres per unit (§3.4.1's units).
fn millimetres_per(unit: &str) -> Option<f32> {
    Some(match unit {
        "micron" => 0.001,
        "millimeter" => 1.0,
        "centimeter" => 10.0,
        "inch" => 25.4,
        "foot" => 304.8,
        "meter" => 1000.0,
        _ => return None,
    })
}

/// The parsed model and its mesh instances: (index into `model.objects`, transform to the build's
/// space in millimetres).
fn read(
    path: &Path,
    bytes: &[u8],
    limits: &Limits,
    warnings: &mut Vec<String>,
) -> Result<(Model, Vec<(usize, Mat4)>), Error> {
    let mut package = package::Package::open(path, bytes, limits)?;
    let (part, xml) = package.model(warnings)?;
    let model = model::parse(&xml, limits).map_err(|e| match e.limit {
        Some((what, count)) => Error::LimitExceeded {
            path: path.to_owned(),
            what,
            count,
            limit: match what {
                Limited::Vertices => limits.max_vertices,
                _ => limits.max_triangles,
            },
        },
        None => invalid(path, format!("{part}: line {}: {}", e.line, e.message)),
    })?;
    let scale = millimetres_per(&model.unit).ok_or_else(|| {
        invalid(
            path,
            format!(
                "{part}: unit `{}` is none of micron, millimeter, centimeter, inch, foot, meter",
                model.unit
            ),
        )
    })?;
    if model.build.is_empty() {
        return Err(invalid(path, format!("{part}: the build places no object")));
    }
    let graph = Graph::new(path, &model, warnings)?;
    // Count what the build would make, each object once, before expanding anything.
    let mut walk = Walk {
        totals: vec![None; model.objects.len()],
        on_path: vec![false; model.objects.len()],
    };
    let mut sum = Totals::default();
    for item in &model.build {
        let object = graph.index(path, item.object)?;
        sum = sum.plus(graph.totals(path, object, &mut walk, 0)?);
    }
    limits.check(path, Limited::Instances, sum.instances)?;
    limits.check(path, Limited::Triangles, sum.triangles)?;
    // Vertex numbers are u32 whatever the limit says.
    let vertex_cap = limits.max_vertices.min(u64::from(u32::MAX));
    limits
        .with_max_vertices(vertex_cap)
        .check(path, Limited::Vertices, sum.vertices)?;
    let to_millimetres = Mat4::from_scale(glam::Vec3::splat(scale));
    let mut instances = Vec::new();
    for item in &model.build {
        let object = graph.index(path, item.object)?;
        graph.expand(
            object,
            to_millimetres * item.transform,
            &walk,
            &mut instances,
        );
    }
    Ok((model, instances))
}

/// What an object expands into.
#[derive(Clone, Copy, Debug, Default)]
struct Totals {
    instances: u64,
    triangles: u64,
    vertices: u64,
}

impl Totals {
    fn plus(self, other: Self) -> Self {
        Self {
            instances: self.instances.saturating_add(other.instances),
            triangles: self.triangles.saturating_add(other.triangles),
            vertices: self.vertices.saturating_add(other.vertices),
        }
    }
}

/// The component walk's state: each object's totals once known, and the objects on the path.
struct Walk {
    totals: Vec<Option<Totals>>,
    on_path: Vec<bool>,
}

/// The objects by id, with those not drawn (`type="other"`) marked.
struct Graph<'m> {
    model: &'m Model,
    by_id: HashMap<u32, usize>,
    drawn: Vec<bool>,
}

impl<'m> Graph<'m> {
    fn new(path: &Path, model: &'m Model, warnings: &mut Vec<String>) -> Result<Self, Error> {
        let mut by_id = HashMap::with_capacity(model.objects.len());
        let mut drawn = Vec::with_capacity(model.objects.len());
        for (k, object) in model.objects.iter().enumerate() {
            if by_id.insert(object.id, k).is_some() {
                return Err(invalid(path, format!("two objects have id {}", object.id)));
            }
            let other = object.kind == "other";
            if other {
                warnings.push(format!(
                    "object {} is of type `other` (not drawn): left out",
                    object.id
                ));
            }
            drawn.push(!other);
        }
        Ok(Self {
            model,
            by_id,
            drawn,
        })
    }

    fn index(&self, path: &Path, id: u32) -> Result<usize, Error> {
        self.by_id
            .get(&id)
            .copied()
            .ok_or_else(|| invalid(path, format!("object {id} is placed but not defined")))
    }

    fn components(&self, object: usize) -> &'m [Placement] {
        match &self.model.objects[object].shape {
            Shape::Components(components) => components,
            Shape::Mesh { .. } => &[],
        }
    }

    /// The totals of `object`, memoized in `walk`; `depth` is how many components lead to it.
    /// Refuses a reference to a missing object, a cycle and a chain deeper than
    /// [`MAX_COMPONENT_DEPTH`], so [`expand`](Self::expand) after it is bounded.
    fn totals(
        &self,
        path: &Path,
        object: usize,
        walk: &mut Walk,
        depth: usize,
    ) -> Result<Totals, Error> {
        if let Some(known) = walk.totals[object] {
            return Ok(known);
        }
        let id = self.model.objects[object].id;
        if walk.on_path[object] {
            return Err(invalid(
                path,
                format!("components form a cycle through object {id}"),
            ));
        }
        if depth > MAX_COMPONENT_DEPTH {
            return Err(invalid(
                path,
                format!("components nest deeper than {MAX_COMPONENT_DEPTH} at object {id}"),
            ));
        }
        walk.on_path[object] = true;
        let mut sum = Totals::default();
        if self.drawn[object] {
            match &self.model.objects[object].shape {
                Shape::Mesh {
                    positions,
                    triangles,
                } => {
                    sum = Totals {
                        instances: 1,
                        triangles: triangles.len() as u64,
                        vertices: positions.len() as u64,
                    }
                }
                Shape::Components(components) => {
                    for component in components {
                        let child = self.index(path, component.object)?;
                        sum = sum.plus(self.totals(path, child, walk, depth + 1)?);
                    }
                }
            }
        }
        walk.on_path[object] = false;
        walk.totals[object] = Some(sum);
        Ok(sum)
    }

    /// Appends the mesh instances of `object` placed by `transform` (after [`totals`](Self::totals)
    /// accepted it: every reference resolves and the depth is bounded).
    /// Subtrees that draw nothing are not walked, so the walk is linear in the instances made.
    fn expand(&self, object: usize, transform: Mat4, walk: &Walk, out: &mut Vec<(usize, Mat4)>) {
        if walk.totals[object].is_none_or(|t| t.instances == 0) {
            return;
        }
        if matches!(self.model.objects[object].shape, Shape::Mesh { .. }) {
            out.push((object, transform));
            return;
        }
        for component in self.components(object) {
            if let Some(&child) = self.by_id.get(&component.object) {
                self.expand(child, transform * component.transform, walk, out);
            }
        }
    }
}
