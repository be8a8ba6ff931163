//! The cut of a section plane through an asset (issue 43), exact in f64: the plane ∩ mesh
//! segments chained into outlines, which outlines close around material (caps), the caps as
//! triangles (they hide what lies behind the cut face) and the triangles of the kept half.
//!
//! Corners are one vertex when their positions are bit-equal, so crease splits do not break the
//! outlines. A vertex exactly on the plane counts as on the cut-away side (a symbolic shift that
//! gives every triangle either no crossing or exactly two, on two of its edges), and the point on
//! an edge is computed from its two ends in one order, so the triangles on either side of an
//! edge give the same point bit for bit and outlines chain. An outline is capped only when every
//! triangle it crosses belongs to a closed piece of surface (each of its edges has two
//! triangles): an open sheet or a tube is cut without a false cap.

use std::collections::HashMap;

use chamfer_runtime::asset::Asset;
use chamfer_runtime::section::Plane;
use glam::{DVec2, DVec3};

/// One outline of the cut, in model space.
#[derive(Clone, Debug, PartialEq)]
pub struct Outline {
    /// The points in order; a closed outline repeats its first point at the end.
    pub points: Vec<DVec3>,
    /// Closed around material: the region inside is a cut face.
    pub capped: bool,
}

/// What a plane cuts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cut {
    /// The outlines: loops, and open chains where an open surface is cut.
    pub outlines: Vec<Outline>,
    /// The cut faces as triangles in the plane (the capped outlines' inside, holes left out).
    pub caps: Vec<[DVec3; 3]>,
    /// The render triangles clipped to the kept half (a triangle the plane crosses gives one or
    /// two).
    pub kept: Vec<[DVec3; 3]>,
    /// An orthonormal basis of the plane (`u`, `v`), for 2D work in it.
    pub basis: [DVec3; 2],
}

/// The plane of a section drawing: `section` checked, and refused (naming the entry) when it
/// is a box or more than one plane, which a drawing cannot take; `None` when nothing is cut.
pub fn drawing_plane(
    section: &chamfer_runtime::section::Section,
) -> Result<Option<Plane>, chamfer_runtime::schema::SchemaError> {
    use chamfer_runtime::schema::SchemaError;
    section.check()?;
    if section.section_box.is_some() {
        return Err(SchemaError::Invalid {
            name: "section_box",
            reason: "cannot be drawn: a drawing takes one section plane, not a box".into(),
        });
    }
    let planes = section.planes()?;
    if planes.len() > 1 {
        return Err(SchemaError::Invalid {
            name: "section",
            reason: format!(
                "must be one section plane in a drawing, not {}",
                planes.len()
            ),
        });
    }
    Ok(planes.first().copied())
}

/// Cuts `asset` by `plane`.
pub fn cut(asset: &Asset, plane: &Plane) -> Cut {
    let normal = DVec3::from(plane.normal);
    // Weld render vertices by position.
    let mut ids: HashMap<[u32; 3], u32> = HashMap::with_capacity(asset.render_positions.len());
    let mut points: Vec<DVec3> = Vec::new();
    let vertex_of: Vec<u32> = asset
        .render_positions
        .iter()
        .map(|p| {
            *ids.entry(p.map(f32::to_bits)).or_insert_with(|| {
                points.push(glam::Vec3::from(*p).as_dvec3());
                (points.len() - 1) as u32
            })
        })
        .collect();
    let distance: Vec<f64> = points
        .iter()
        .map(|p| plane.distance(p.to_array()))
        .collect();
    let cut_away = |v: u32| distance[v as usize] >= 0.0;
    let triangles: Vec<[u32; 3]> = (0..asset.triangle_count())
        .map(|t| std::array::from_fn(|k| vertex_of[asset.mesh_indices.get(3 * t + k) as usize]))
        .collect();

    let closed = closed_pieces(&triangles);
    // Crossing points, one per cut edge, keyed by the edge's ends (smaller first).
    let mut crossing: HashMap<(u32, u32), u32> = HashMap::new();
    let mut crossing_points: Vec<DVec3> = Vec::new();
    let mut crossing_capped: Vec<bool> = Vec::new();
    let mut segments: Vec<[u32; 2]> = Vec::new();
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        if a == b || b == c || c == a {
            continue;
        }
        let sides = [a, b, c].map(cut_away);
        let away = sides.iter().filter(|&&s| s).count();
        if away == 0 || away == 3 {
            continue;
        }
        // The vertex alone on its side, and the two edges from it.
        let lone = (0..3)
            .find(|&k| sides[k] != sides[(k + 1) % 3] && sides[k] != sides[(k + 2) % 3])
            .unwrap_or(0);
        let corners = [a, b, c];
        let ends = [1, 2].map(|step| {
            let (u, v) = (corners[lone], corners[(lone + step) % 3]);
            let key = (u.min(v), u.max(v));
            *crossing.entry(key).or_insert_with(|| {
                let (kept, away) = if cut_away(u) { (v, u) } else { (u, v) };
                crossing_points.push(edge_point(&points, &distance, kept, away));
                crossing_capped.push(true);
                (crossing_points.len() - 1) as u32
            })
        });
        if !closed[t] {
            for end in ends {
                crossing_capped[end as usize] = false;
            }
        }
        segments.push([ends[0].min(ends[1]), ends[0].max(ends[1])]);
    }
    segments.sort_unstable();
    segments.dedup();

    let outlines: Vec<Outline> = crate::polylines::chain(crossing_points.len(), &segments)
        .into_iter()
        .map(|chain| {
            let capped = chain.closed && chain.points.iter().all(|&p| crossing_capped[p as usize]);
            let mut points: Vec<DVec3> = chain
                .points
                .iter()
                .map(|&p| crossing_points[p as usize])
                .collect();
            points.dedup();
            Outline { points, capped }
        })
        // A vertex touching the plane with all its neighbours kept chains to a point: no outline.
        .filter(|outline| outline.points.len() >= 2)
        .map(|mut outline| {
            // A closed chain of fewer than three distinct points encloses nothing.
            if outline.capped && outline.points.len() < 4 {
                outline.capped = false;
            }
            outline
        })
        .collect();

    let basis = plane_basis(normal);
    let caps = triangulate_caps(&outlines, basis);
    let kept = kept_triangles(asset, plane);
    Cut {
        outlines,
        caps,
        kept,
        basis,
    }
}

/// The point where the edge from `kept` (strictly on the kept side) to `away` meets the plane;
/// `away` itself when it lies on the plane.
fn edge_point(points: &[DVec3], distance: &[f64], kept: u32, away: u32) -> DVec3 {
    let (p, q) = (points[kept as usize], points[away as usize]);
    let (dp, dq) = (distance[kept as usize], distance[away as usize]);
    if dq == 0.0 {
        return q;
    }
    p + (q - p) * (dp / (dp - dq))
}

/// Per triangle: whether its connected piece of surface is closed (every edge of the piece has
/// exactly two triangles).
fn closed_pieces(triangles: &[[u32; 3]]) -> Vec<bool> {
    let mut edges: HashMap<(u32, u32), (u32, u32)> =
        HashMap::with_capacity(3 * triangles.len() / 2);
    let mut parent: Vec<u32> = (0..triangles.len() as u32).collect();
    fn root(parent: &mut [u32], mut t: u32) -> u32 {
        while parent[t as usize] != t {
            let up = parent[parent[t as usize] as usize];
            parent[t as usize] = up;
            t = up;
        }
        t
    }
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        for (u, v) in [(a, b), (b, c), (c, a)] {
            if u == v {
                continue;
            }
            let entry = edges.entry((u.min(v), u.max(v))).or_insert((t as u32, 0));
            entry.1 += 1;
            let (x, y) = (root(&mut parent, entry.0), root(&mut parent, t as u32));
            parent[x as usize] = y;
        }
    }
    let mut open = vec![false; triangles.len()];
    for &(first, uses) in edges.values() {
        if uses != 2 {
            let r = root(&mut parent, first);
            open[r as usize] = true;
        }
    }
    (0..triangles.len() as u32)
        .map(|t| !open[root(&mut parent, t) as usize])
        .collect()
}

/// Two unit vectors spanning the plane with normal `n`, right-handed with it (`u × v = n`).
pub fn plane_basis(n: DVec3) -> [DVec3; 2] {
    let helper = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let u = helper.cross(n).normalize();
    [u, n.cross(u)]
}

/// Whether `point` lies inside the closed 2D polygon `ring` (even-odd).
fn inside(ring: &[DVec2], point: DVec2) -> bool {
    let mut odd = false;
    for pair in ring.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if (a.y > point.y) != (b.y > point.y) {
            let x = a.x + (point.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if point.x < x {
                odd = !odd;
            }
        }
    }
    odd
}

/// A point strictly inside the closed 2D polygon `ring`, next to the middle of its longest side:
/// unlike a vertex, it is not on the boundary of a neighbouring ring that shares a vertex or a
/// side with this one, so it tells nesting from touching.
fn inner_point(ring: &[DVec2]) -> DVec2 {
    let Some(pair) = ring.windows(2).max_by(|a, b| {
        a[0].distance_squared(a[1])
            .total_cmp(&b[0].distance_squared(b[1]))
    }) else {
        return ring.first().copied().unwrap_or_default();
    };
    let (a, b) = (pair[0], pair[1]);
    let middle = (a + b) * 0.5;
    let across = (b - a).perp() * 1e-6;
    if inside(ring, middle + across) {
        middle + across
    } else {
        middle - across
    }
}

/// The capped outlines' inside as triangles: each outline nested an even number of times is an
/// outer boundary, and the outlines directly inside it are its holes (even-odd, as the hatch).
/// Nesting is tested with a point just inside each outline ([`inner_point`]), against the outlines
/// whose bounding box holds it. Outlines that cross each other (parts that overlap) are not
/// resolved: the overlap counts twice, and even-odd leaves it out of both the cap and the hatch.
fn triangulate_caps(outlines: &[Outline], [u, v]: [DVec3; 2]) -> Vec<[DVec3; 3]> {
    let rings: Vec<(&Outline, Vec<DVec2>)> = outlines
        .iter()
        .filter(|o| o.capped && o.points.len() >= 4)
        .map(|o| {
            (
                o,
                o.points
                    .iter()
                    .map(|p| DVec2::new(p.dot(u), p.dot(v)))
                    .collect(),
            )
        })
        .collect();
    let boxes: Vec<(DVec2, DVec2)> = rings
        .iter()
        .map(|(_, ring)| {
            ring.iter()
                .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| {
                    (lo.min(p), hi.max(p))
                })
        })
        .collect();
    // Nesting: which rings contain a point inside each ring.
    let containers: Vec<Vec<usize>> = rings
        .iter()
        .enumerate()
        .map(|(i, (_, ring))| {
            let probe = inner_point(ring);
            (0..rings.len())
                .filter(|&j| {
                    let (lo, hi) = boxes[j];
                    j != i
                        && probe.cmpge(lo).all()
                        && probe.cmple(hi).all()
                        && inside(&rings[j].1, probe)
                })
                .collect()
        })
        .collect();
    let mut earcut = earcut::Earcut::new();
    let mut triangles = Vec::new();
    let mut indices: Vec<u32> = Vec::new();
    for (i, (outer, ring)) in rings.iter().enumerate() {
        if containers[i].len() % 2 == 1 {
            continue; // a hole
        }
        let depth = containers[i].len();
        let holes: Vec<usize> = (0..rings.len())
            .filter(|&j| containers[j].len() == depth + 1 && containers[j].contains(&i))
            .collect();
        let mut points3: Vec<DVec3> = outer.points[..outer.points.len() - 1].to_vec();
        let mut points2: Vec<[f64; 2]> = ring[..ring.len() - 1]
            .iter()
            .map(|p| p.to_array())
            .collect();
        let mut starts: Vec<u32> = Vec::new();
        for &h in &holes {
            starts.push(points2.len() as u32);
            let (hole, hole2) = (&rings[h].0.points, &rings[h].1);
            points3.extend_from_slice(&hole[..hole.len() - 1]);
            points2.extend(hole2[..hole2.len() - 1].iter().map(|p| p.to_array()));
        }
        earcut.earcut(points2.iter().copied(), &starts, &mut indices);
        triangles.extend(
            indices
                .chunks_exact(3)
                .map(|t| [0, 1, 2].map(|k| points3[t[k] as usize])),
        );
    }
    triangles
}

/// The render triangles clipped to the kept half, with the cut's convention (a point on the plane
/// is cut away: a triangle lying in the plane is dropped, one touching it is kept) and its edge
/// points, so clipped triangles meet the outline bit for bit.
fn kept_triangles(asset: &Asset, plane: &Plane) -> Vec<[DVec3; 3]> {
    let mut kept = Vec::with_capacity(asset.triangle_count());
    for t in 0..asset.triangle_count() {
        let corners: [DVec3; 3] = std::array::from_fn(|k| {
            glam::Vec3::from(asset.render_positions[asset.mesh_indices.get(3 * t + k) as usize])
                .as_dvec3()
        });
        let d = corners.map(|p| plane.distance(p.to_array()));
        let away = d.map(|x| x >= 0.0);
        match away.iter().filter(|&&a| a).count() {
            0 => {
                kept.push(corners);
                continue;
            }
            3 => continue,
            _ => {}
        }
        // Sutherland–Hodgman against one plane: at most four corners.
        let mut polygon: Vec<DVec3> = Vec::with_capacity(4);
        for k in 0..3 {
            let next = (k + 1) % 3;
            if !away[k] {
                polygon.push(corners[k]);
            }
            if away[k] != away[next] {
                let (inside, outside) = if away[k] { (next, k) } else { (k, next) };
                polygon.push(edge_point(&corners, &d, inside as u32, outside as u32));
            }
        }
        for k in 1..polygon.len().saturating_sub(1) {
            kept.push([polygon[0], polygon[k], polygon[k + 1]]);
        }
    }
    kept
}

/// Hatch lines over the capped outlines, in frame pixels: parallel lines `spacing_px` apart at
/// `angle_deg` (counter-clockwise from the frame's x axis, y up as on paper), clipped to the
/// outlines' inside (even-odd). `project` gives an outline point's pixel, `None` behind the eye.
/// Returns pixel segments; an outline that reaches behind the eye is not hatched.
pub fn hatch(
    outlines: &[Outline],
    spacing_px: f64,
    angle_deg: f64,
    project: impl Fn(DVec3) -> Option<DVec2>,
) -> Vec<[DVec2; 2]> {
    if !(spacing_px.is_finite() && spacing_px > 0.0) {
        return Vec::new();
    }
    // Rotate the frame so hatch lines are rows of constant y'. Frame y points down; paper
    // angles turn counter-clockwise with y up.
    let (sin, cos) = (-angle_deg.to_radians()).sin_cos();
    let to_rows = |p: DVec2| DVec2::new(p.x * cos + p.y * sin, -p.x * sin + p.y * cos);
    let from_rows = |q: DVec2| DVec2::new(q.x * cos - q.y * sin, q.x * sin + q.y * cos);
    let rings: Vec<Vec<DVec2>> = outlines
        .iter()
        .filter(|o| o.capped && o.points.len() >= 4)
        .filter_map(|o| {
            o.points
                .iter()
                .map(|&p| project(p).map(to_rows))
                .collect::<Option<Vec<DVec2>>>()
        })
        .collect();
    let (lo, hi) = rings
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    if lo > hi {
        return Vec::new();
    }
    // Rows on a grid through the frame's origin, so the hatch does not move with the outline.
    let first = (lo / spacing_px).ceil() as i64;
    let last = (hi / spacing_px).floor() as i64;
    let mut segments = Vec::new();
    // At most 2^20 rows: the style's least spacing keeps a hatch far below that on any frame.
    for row in first..=last.min(first.saturating_add(1 << 20)) {
        let y = row as f64 * spacing_px;
        let mut xs: Vec<f64> = Vec::new();
        for ring in &rings {
            for pair in ring.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                if (a.y > y) != (b.y > y) {
                    xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
                }
            }
        }
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            if pair[1] > pair[0] {
                segments.push([
                    from_rows(DVec2::new(pair[0], y)),
                    from_rows(DVec2::new(pair[1], y)),
                ]);
            }
        }
    }
    segments
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::{BakeOptions, bake};

    fn asset_of(positions: Vec<[f32; 3]>, triangles: Vec<[u32; 3]>) -> Asset {
        let mesh = Mesh {
            positions: positions.into_iter().map(glam::Vec3::from).collect(),
            triangles,
            ..Mesh::default()
        };
        bake(mesh, "test", &BakeOptions::DEFAULT)
            .expect("bakes")
            .asset
    }

    fn plane(normal: [f64; 3], offset: f64) -> Plane {
        let length = DVec3::from(normal).length();
        Plane {
            normal: normal.map(|c| c / length),
            offset: offset / length,
        }
    }

    fn unit_cube() -> Asset {
        let (positions, triangles) = crate::classify::tests::cube();
        asset_of(
            positions.iter().map(glam::Vec3::to_array).collect(),
            triangles,
        )
    }

    /// A torus around +Z: `major` the radius of its centre circle, `minor` of its tube.
    fn torus(major: f32, minor: f32, around: u32, tube: u32) -> Asset {
        let mut positions = Vec::new();
        for i in 0..around {
            let u = i as f32 / around as f32 * std::f32::consts::TAU;
            for j in 0..tube {
                let v = j as f32 / tube as f32 * std::f32::consts::TAU;
                let r = major + minor * v.cos();
                positions.push([r * u.cos(), r * u.sin(), minor * v.sin()]);
            }
        }
        let id = |i: u32, j: u32| (i % around) * tube + j % tube;
        let mut triangles = Vec::new();
        for i in 0..around {
            for j in 0..tube {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        asset_of(positions, triangles)
    }

    fn area(triangles: &[[DVec3; 3]]) -> f64 {
        triangles
            .iter()
            .map(|[a, b, c]| 0.5 * (*b - *a).cross(*c - *a).length())
            .sum()
    }

    #[test]
    fn a_cube_cut_through_its_middle_has_one_square_outline_capped() {
        let cut = cut(&unit_cube(), &plane([1.0, 0.0, 0.0], 0.5));
        assert_eq!(cut.outlines.len(), 1);
        let outline = &cut.outlines[0];
        assert!(outline.capped);
        assert_eq!(outline.points.first(), outline.points.last());
        assert!(outline.points.iter().all(|p| p.x == 0.5));
        // The square's four corners are on it, and nothing but its sides.
        for corner in [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]] {
            let corner = DVec3::new(0.5, corner[0], corner[1]);
            assert!(outline.points.contains(&corner), "{corner}");
        }
        assert!(
            outline
                .points
                .iter()
                .all(|p| p.y == 0.0 || p.y == 1.0 || p.z == 0.0 || p.z == 1.0)
        );
        assert!((area(&cut.caps) - 1.0).abs() < 1e-12);
        // The kept half: the x = 0 face and half of each of four sides.
        assert!((area(&cut.kept) - 3.0).abs() < 1e-12);
        assert!(cut.kept.iter().flatten().all(|p| p.x <= 0.5));
    }

    #[test]
    fn a_torus_cut_through_its_hole_gives_two_discs_and_across_its_axis_a_ring() {
        let (major, minor) = (1.0, 0.3);
        let shape = torus(major, minor, 64, 32);
        // Through the axis: two tube sections, each a disc of the tube's radius.
        let through = cut(&shape, &plane([0.0, 1.0, 0.0], 0.0));
        assert_eq!(through.outlines.len(), 2);
        assert!(through.outlines.iter().all(|o| o.capped));
        let disc = std::f64::consts::PI * f64::from(minor).powi(2);
        let capped = area(&through.caps);
        // The 32-gon's area is 0.6 % under the circle's.
        assert!((capped / (2.0 * disc) - 1.0).abs() < 0.01, "{capped}");
        // Across the axis: an annulus, its inner outline a hole.
        let across = cut(&shape, &plane([0.0, 0.0, 1.0], 0.0));
        assert_eq!(across.outlines.len(), 2);
        let ring = std::f64::consts::PI
            * (f64::from(major + minor).powi(2) - f64::from(major - minor).powi(2));
        let capped = area(&across.caps);
        assert!((capped / ring - 1.0).abs() < 0.01, "{capped} vs {ring}");
    }

    #[test]
    fn an_open_sheet_is_cut_without_a_cap() {
        let n = 4u32;
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| [i as f32, j as f32, 0.0]))
            .collect();
        let id = |i: u32, j: u32| j * (n + 1) + i;
        let triangles = (0..n)
            .flat_map(|j| {
                (0..n).flat_map(move |i| {
                    [
                        [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                        [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                    ]
                })
            })
            .collect();
        let sheet = asset_of(positions, triangles);
        let cut = cut(&sheet, &plane([1.0, 0.0, 0.0], 1.3));
        assert_eq!(cut.outlines.len(), 1);
        assert!(!cut.outlines[0].capped);
        assert_ne!(
            cut.outlines[0].points.first(),
            cut.outlines[0].points.last()
        );
        assert!(cut.caps.is_empty());
        // A closed tube (a cylinder without ends) is open too: its circle is not capped.
        let tube = asset_of(
            (0..16)
                .flat_map(|i| {
                    let a = i as f32 / 16.0 * std::f32::consts::TAU;
                    [[a.cos(), a.sin(), 0.0], [a.cos(), a.sin(), 2.0]]
                })
                .collect(),
            (0..16u32)
                .flat_map(|i| {
                    let (a, b, c, d) =
                        (2 * i, 2 * ((i + 1) % 16), 2 * ((i + 1) % 16) + 1, 2 * i + 1);
                    [[a, b, c], [a, c, d]]
                })
                .collect(),
        );
        let cut = super::cut(&tube, &plane([0.0, 0.0, 1.0], 1.0));
        assert_eq!(cut.outlines.len(), 1);
        assert!(!cut.outlines[0].capped, "a tube has no material inside");
        assert_eq!(
            cut.outlines[0].points.first(),
            cut.outlines[0].points.last()
        );
        assert!(cut.caps.is_empty());
    }

    #[test]
    fn the_outlines_are_the_plane_triangle_intersections_of_an_f64_reference() {
        let fandisk = crate::bake_file(
            std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/fandisk.obj")),
            &BakeOptions::DEFAULT,
        )
        .expect("fandisk")
        .asset;
        let lo = glam::Vec3::from(fandisk.header.bounds_min).as_dvec3();
        let hi = glam::Vec3::from(fandisk.header.bounds_max).as_dvec3();
        let size = (hi - lo).length();
        for (normal, at) in [
            ([1.0, 0.0, 0.0], 0.37),
            ([0.3, 1.0, -0.2], 0.52),
            ([0.0, 0.0, 1.0], 0.61),
        ] {
            let n = DVec3::from(normal).normalize();
            let centre = lo + (hi - lo) * at;
            let plane = Plane {
                normal: n.to_array(),
                offset: n.dot(centre),
            };
            // The reference: each triangle's segment, by the textbook formula.
            let mut reference: Vec<[DVec3; 2]> = Vec::new();
            for t in 0..fandisk.triangle_count() {
                let p: [DVec3; 3] = std::array::from_fn(|k| {
                    glam::Vec3::from(
                        fandisk.render_positions[fandisk.mesh_indices.get(3 * t + k) as usize],
                    )
                    .as_dvec3()
                });
                let d = p.map(|q| n.dot(q) - plane.offset);
                let mut ends = Vec::new();
                for k in 0..3 {
                    let (a, b) = (k, (k + 1) % 3);
                    if (d[a] < 0.0) != (d[b] < 0.0) {
                        ends.push(p[a] + (p[b] - p[a]) * (d[a] / (d[a] - d[b])));
                    }
                }
                if let [a, b] = ends[..] {
                    reference.push([a, b]);
                }
            }
            let cut = cut(&fandisk, &plane);
            let segments: Vec<[DVec3; 2]> = cut
                .outlines
                .iter()
                .flat_map(|o| o.points.windows(2).map(|w| [w[0], w[1]]))
                .collect();
            assert_eq!(segments.len(), reference.len(), "{normal:?}");
            let tolerance = 1e-6 * size;
            let near = |x: &[DVec3; 2], y: &[DVec3; 2]| {
                (x[0].distance(y[0]) < tolerance && x[1].distance(y[1]) < tolerance)
                    || (x[0].distance(y[1]) < tolerance && x[1].distance(y[0]) < tolerance)
            };
            for s in &segments {
                assert!(reference.iter().any(|r| near(s, r)), "{normal:?}: {s:?}");
            }
            for r in &reference {
                assert!(segments.iter().any(|s| near(s, r)), "{normal:?}: {r:?}");
            }
            // The fandisk is closed: every outline is a capped loop.
            assert!(cut.outlines.iter().all(|o| o.capped), "{normal:?}");
        }
    }

    #[test]
    fn outlines_touching_at_a_vertex_are_two_caps_and_a_ring_inside_another_a_hole() {
        let square = |lo: [f64; 2], size: f64, start: usize| {
            let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
            let mut points: Vec<DVec3> = (0..4)
                .map(|k| {
                    let [x, y] = corners[(k + start) % 4];
                    DVec3::new(lo[0] + size * x, lo[1] + size * y, 0.0)
                })
                .collect();
            points.push(points[0]);
            Outline {
                points,
                capped: true,
            }
        };
        let basis = plane_basis(DVec3::Z);
        // Each starts at the shared corner (1, 1), where a test of the first point is ambiguous.
        let touching = [square([0.0, 0.0], 1.0, 2), square([1.0, 1.0], 1.0, 0)];
        assert!((area(&triangulate_caps(&touching, basis)) - 2.0).abs() < 1e-12);
        let nested = [square([0.0, 0.0], 3.0, 0), square([1.0, 1.0], 1.0, 0)];
        assert!((area(&triangulate_caps(&nested, basis)) - 8.0).abs() < 1e-12);
        let three = [
            square([0.0, 0.0], 5.0, 0),
            square([1.0, 1.0], 3.0, 1),
            square([2.0, 2.0], 1.0, 3),
        ];
        assert!((area(&triangulate_caps(&three, basis)) - (25.0 - 9.0 + 1.0)).abs() < 1e-12);
    }

    #[test]
    fn hatch_lines_are_spaced_and_inside_the_cut_face() {
        let cut = cut(&unit_cube(), &plane([1.0, 0.0, 0.0], 0.5));
        // Looking along -x at the cut face: frame x = model -z... any map that is a similarity.
        let project = |p: DVec3| Some(DVec2::new(100.0 * p.y + 10.0, 100.0 * p.z + 20.0));
        let lines = hatch(&cut.outlines, 7.0, 45.0, project);
        assert!(!lines.is_empty());
        let direction = DVec2::new(1.0, -1.0).normalize();
        let across = DVec2::new(direction.y, -direction.x);
        let mut offsets: Vec<f64> = Vec::new();
        for [a, b] in &lines {
            for p in [a, b] {
                assert!(
                    (9.999..=110.001).contains(&p.x) && (19.999..=120.001).contains(&p.y),
                    "{p}"
                );
            }
            assert!(((*b - *a).normalize().dot(direction)).abs() > 1.0 - 1e-9);
            offsets.push(a.dot(across));
        }
        offsets.sort_by(f64::total_cmp);
        for pair in offsets.windows(2) {
            assert!((pair[1] - pair[0] - 7.0).abs() < 1e-9, "{pair:?}");
        }
        // The square's diagonal across the lines, 100 sqrt 2, holds 20 of them.
        assert_eq!(lines.len(), 20);
        assert!(hatch(&cut.outlines, 0.0, 45.0, project).is_empty());
    }
}
