//! Known answers for the hidden-line pass, and a check of its exact splits against brute-force ray
//! casts.

use glam::camera::rh::{proj::directx, view::look_at_mat4};
use glam::{DVec3, Mat4, Vec3};

use super::*;
use crate::mesh::Mesh;
use crate::{BakeOptions, bake};

fn asset_of(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Asset {
    let mesh = Mesh {
        positions: positions.iter().map(|&p| Vec3::from(p)).collect(),
        triangles: triangles.to_vec(),
        ..Mesh::default()
    };
    bake(mesh, "test", &BakeOptions::DEFAULT.with_intersections(true))
        .expect("bakes")
        .asset
}

/// Looking down -Z from z = 5 at 100 px per unit, orthographic, 400 x 300 px.
fn top_view() -> Camera {
    Camera {
        model_view: look_at_mat4(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y),
        projection: directx::orthographic(-2.0, 2.0, -1.5, 1.5, 0.1, 10.0),
        viewport: [400, 300],
    }
}

/// A 2 x 0.5 strip at z = 0 under a 1 x 1 square at z = 1: the strip's long boundary edges pass
/// under the square for x in [-0.5, 0.5].
fn strip_under_square() -> Asset {
    asset_of(
        &[
            [-1.0, -0.25, 0.0],
            [1.0, -0.25, 0.0],
            [1.0, 0.25, 0.0],
            [-1.0, 0.25, 0.0],
            [-0.5, -0.5, 1.0],
            [0.5, -0.5, 1.0],
            [0.5, 0.5, 1.0],
            [-0.5, 0.5, 1.0],
        ],
        &[[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
    )
}

fn lines_of(drawing: &Drawing, class: LineClass, hidden: bool) -> &[Vec<[f32; 2]>] {
    drawing
        .lines
        .iter()
        .find(|s| s.class == class && s.hidden == hidden)
        .map_or(&[], |s| s.polylines.as_slice())
}

#[test]
fn an_edge_under_a_square_splits_exactly_where_the_square_begins_and_ends() {
    let drawing = hidden_lines(&strip_under_square(), &top_view(), &DrawOptions::DEFAULT);
    assert!((drawing.units_per_px - 0.01).abs() < 1e-7);
    let boundary = lines_of(&drawing, LineClass::Boundary, false);
    // The square's outline (one closed polyline) and, per long side of the strip, two pieces that
    // run from the square's sides (x = 150 and 250 px) to the strip's ends, chained with its short
    // sides: two polylines, each [150,y] -> [100,y] -> [100,y'] -> [150,y'] and the same at 250..300.
    let mut ends: Vec<[f32; 2]> = boundary
        .iter()
        .filter(|p| p.first() != p.last())
        .flat_map(|p| [p[0], p[p.len() - 1]])
        .collect();
    ends.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
    let expected = [
        [150.0, 125.0],
        [150.0, 175.0],
        [250.0, 125.0],
        [250.0, 175.0],
    ];
    assert_eq!(ends.len(), 4, "{boundary:?}");
    for (got, want) in ends.iter().zip(expected) {
        assert!(
            (got[0] - want[0]).abs() < 1e-3 && (got[1] - want[1]).abs() < 1e-3,
            "{got:?} vs {want:?}"
        );
    }
    assert!(
        boundary.iter().any(|p| p.len() == 5 && p[0] == p[4]),
        "the square is closed"
    );
    assert!(lines_of(&drawing, LineClass::Boundary, true).is_empty());

    let with_hidden = hidden_lines(
        &strip_under_square(),
        &top_view(),
        &DrawOptions::DEFAULT.with_hidden(true),
    );
    let hidden = lines_of(&with_hidden, LineClass::Boundary, true);
    assert_eq!(hidden.len(), 2, "{hidden:?}");
    for line in hidden {
        let xs = [line[0][0], line[1][0]];
        assert!(
            (xs[0] - xs[1]).abs() > 99.99
                && xs
                    .iter()
                    .all(|x| (x - 150.0).abs() < 1e-3 || (x - 250.0).abs() < 1e-3)
        );
    }
    assert_eq!(lines_of(&with_hidden, LineClass::Boundary, false), boundary);
}

#[test]
fn classes_can_be_left_out_and_lines_outside_the_frame_are_clipped() {
    let only_creases = DrawOptions::DEFAULT.with_classes(&[LineClass::Crease]);
    let drawing = hidden_lines(&strip_under_square(), &top_view(), &only_creases);
    assert_eq!(drawing.lines.len(), 1);
    assert!(drawing.lines[0].polylines.is_empty());
    // Zoomed in 4x: the strip's ends leave the frame, clipped at its sides.
    let mut view = top_view();
    view.projection = directx::orthographic(-0.5, 0.5, -0.375, 0.375, 0.1, 10.0);
    let drawing = hidden_lines(&strip_under_square(), &view, &DrawOptions::DEFAULT);
    for p in lines_of(&drawing, LineClass::Boundary, false)
        .iter()
        .flatten()
    {
        assert!(
            (0.0..=400.0).contains(&p[0]) && (0.0..=300.0).contains(&p[1]),
            "{p:?}"
        );
    }
}

/// The runtime's orbit camera, rebuilt from glam (the same formulas as `Camera::orbit`).
fn orbit(bounds: [[f32; 3]; 2], azimuth: f32, elevation: f32, viewport: [u32; 2]) -> Camera {
    let [lo, hi] = bounds.map(Vec3::from);
    let center = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    let aspect = viewport[0] as f32 / viewport[1] as f32;
    let (a, e) = (azimuth.to_radians(), elevation.to_radians());
    let towards = Vec3::new(e.cos() * a.sin(), e.sin(), e.cos() * a.cos());
    let fov = 35f32.to_radians();
    let fov_x = 2.0 * ((fov * 0.5).tan() * aspect).atan();
    let distance = radius / (fov.min(fov_x) * 0.5).sin() * 1.02;
    let view = look_at_mat4(center + towards * distance, center, Vec3::Y);
    let projection: Mat4 = directx::perspective(
        fov,
        aspect,
        (distance - radius * 1.5).max(distance * 1e-3),
        distance + radius * 1.5,
    );
    Camera {
        model_view: view,
        projection,
        viewport,
    }
}

/// True if the segment from the eye to `p` passes through the inside of a triangle whose plane
/// `p` lies more than `tolerance` behind (the drawing's definition of hidden), by Möller–Trumbore
/// in f64 against every triangle.
fn ray_blocked(eye: DVec3, p: DVec3, triangles: &[[DVec3; 3]], tolerance: f64) -> bool {
    let dir = p - eye;
    triangles.iter().any(|&[a, b, c]| {
        let (e1, e2) = (b - a, c - a);
        let h = dir.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-300 {
            return false;
        }
        let s = eye - a;
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let v = dir.dot(q) / det;
        let t = e2.dot(q) / det;
        let behind = e1.cross(e2).normalize().dot(p - a).abs();
        u > 0.0 && v > 0.0 && u + v < 1.0 && t > 0.0 && t < 1.0 && behind > tolerance
    })
}

#[test]
fn every_piece_agrees_with_a_brute_force_ray_cast_at_its_midpoint() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/meshes/fandisk.obj");
    let asset = crate::bake_file(&path, &BakeOptions::DEFAULT)
        .expect("fandisk")
        .asset;
    let bounds = [asset.header.bounds_min, asset.header.bounds_max];
    let view = orbit(bounds, 35.0, 25.0, [640, 480]);
    let scene = Scene::new(&asset, &view);
    let occluders = Occluders::new(render_triangles(&asset), &scene);
    let triangles: Vec<[DVec3; 3]> = occluders.triangles.clone();
    let eye = scene.eye.truncate();
    let lines = candidate_lines(&asset, &scene, &DrawOptions::DEFAULT);
    let (mut checked, mut disagree) = (0, Vec::new());
    for line in &lines {
        let Some(spans) = occluders.spans(&scene, line) else {
            continue;
        };
        for (from, to, hidden) in spans.parts(true) {
            // Only parts of at least a pixel: shorter ones end within rounding of an occluder's side.
            if to - from < spans.per_px {
                continue;
            }
            let [p0, p1] = line.ends;
            let mid = p0 + (p1 - p0) * (0.5 * (from + to));
            checked += 1;
            if ray_blocked(eye, mid, &triangles, scene.behind) != hidden {
                disagree.push((line.class, from, to, hidden));
            }
        }
    }
    assert!(checked > 500, "{checked}");
    assert!(
        disagree.is_empty(),
        "{} of {checked}: {:?}",
        disagree.len(),
        &disagree[..disagree.len().min(5)]
    );
}

#[test]
fn a_section_drawing_of_the_fandisk_outlines_its_cut_in_closed_loops_over_a_hatch() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/meshes/fandisk.obj");
    let asset = crate::bake_file(&path, &BakeOptions::DEFAULT)
        .expect("fandisk")
        .asset;
    let bounds = [asset.header.bounds_min, asset.header.bounds_max];
    let centre = (Vec3::from(bounds[0]) + Vec3::from(bounds[1])).as_dvec3() * 0.5;
    // From +z, looking at the cut face of a plane facing the eye: the cut is in front of all
    // that is kept, so none of it is hidden.
    let view = orbit(bounds, 0.0, 0.0, [640, 480]);
    let plane = Plane {
        normal: [0.0, 0.0, 1.0],
        offset: centre.z,
    };
    let options = DrawOptions::DEFAULT
        .with_hidden(true)
        .with_section(Some(plane));
    let drawing = hidden_lines(&asset, &view, &options);
    let cut = lines_of(&drawing, LineClass::Cut, false);
    assert!(!cut.is_empty());
    for outline in cut {
        assert!(
            outline.len() > 3 && outline.first() == outline.last(),
            "{outline:?}"
        );
    }
    assert!(lines_of(&drawing, LineClass::Cut, true).is_empty());
    assert!(!lines_of(&drawing, LineClass::Hatch, false).is_empty());
    // Hatches are never drawn hidden, and nothing is drawn from the half cut away.
    assert!(
        drawing
            .lines
            .iter()
            .all(|s| !(s.class == LineClass::Hatch && s.hidden))
    );
    let whole = hidden_lines(&asset, &view, &DrawOptions::DEFAULT.with_hidden(true));
    let count = |d: &Drawing| d.lines.iter().map(|s| s.polylines.len()).sum::<usize>();
    assert_ne!(count(&whole), 0);
    assert!(lines_of(&whole, LineClass::Cut, false).is_empty());
    // Seen from behind (the kept side), the same cut is hidden by what is kept where it is not
    // on the kept half's silhouette (about half of it, drawn and checked by eye), and its
    // hatch, facing away, is not drawn.
    let behind = orbit(bounds, 180.0, 0.0, [640, 480]);
    let drawing = hidden_lines(&asset, &behind, &options);
    let length = |lines: &[Vec<[f32; 2]>]| -> f64 {
        lines
            .iter()
            .flat_map(|l| l.windows(2))
            .map(|w| f64::from((w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])))
            .sum()
    };
    let (seen, hidden) = (
        length(lines_of(&drawing, LineClass::Cut, false)),
        length(lines_of(&drawing, LineClass::Cut, true)),
    );
    assert!(
        hidden > 0.3 * (seen + hidden) && seen > 0.3 * (seen + hidden),
        "{seen} seen, {hidden} hidden"
    );
    assert!(lines_of(&drawing, LineClass::Hatch, false).is_empty());
}
