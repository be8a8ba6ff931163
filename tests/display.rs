//! Display modes (issue 42): the hidden edges the renderer draws against the exact hidden-line
//! drawing of `chamfer draw --hidden` (the same camera, rasterized here), a hidden style's
//! pattern, and the face modes.

use chamfer_preprocess::draw::{DrawOptions, LineClass, hidden_lines};
use chamfer_runtime::asset::Asset;
use chamfer_runtime::render::{
    Camera, Display, EdgeColors, EdgeStyle, FaceMode, GpuAsset, HiddenStyle, Image, Instance,
    LinePattern, MeshRenderer, MeshStyle, Orbit, SceneRenderer,
};
use chamfer_tests::{bake_fixture, gpu};
use glam::{Mat4, Vec3};

const WHITE: [f64; 4] = [1.0; 4];
const GREEN: [f32; 3] = [0.0, 1.0, 0.0];

/// Visible edges black, hidden ones solid green, both 2 px.
fn hidden_in_green(pattern: LinePattern) -> EdgeStyle {
    EdgeStyle {
        colors: EdgeColors::all([0.0, 0.0, 0.0, 1.0]),
        width_px: 2.0,
        classes: chamfer_runtime::render::EdgeClasses::CONTOUR
            | chamfer_runtime::render::EdgeClasses::BOUNDARY
            | chamfer_runtime::render::EdgeClasses::CREASE
            | chamfer_runtime::render::EdgeClasses::MARKED,
        display: Display {
            hidden: Some(HiddenStyle {
                color: Some(GREEN),
                opacity: 1.0,
                width_px: 2.0,
                pattern,
            }),
            fade: None,
        },
        ..EdgeStyle::default()
    }
}

/// One frame of `instances` with `faces` under `style`, on white.
fn picture(
    camera: &Camera,
    instances: &[Instance<'_>],
    faces: FaceMode,
    style: &EdgeStyle,
) -> Image {
    let gpu = gpu();
    let [width, height] = camera.viewport;
    let target = gpu.target(width, height, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let mut mesh = MeshRenderer::for_scenes(&pipelines).expect("mesh");
    let mesh_style = faces.mesh_style(MeshStyle::default(), [1.0; 4]);
    if let Some(mesh_style) = &mesh_style {
        mesh.prepare_scene(&gpu.queue, camera, instances, mesh_style);
    }
    let mut scene = SceneRenderer::new(&pipelines);
    let mut encoder = gpu.encoder();
    let prepared = scene
        .prepare(&gpu.queue, &mut encoder, camera, instances, style)
        .expect("prepare");
    {
        let mut pass = target.begin_pass(&mut encoder, WHITE);
        if mesh_style.is_some() {
            mesh.render(&mut pass);
        }
        prepared.render(&mut pass);
    }
    gpu.submit(encoder).expect("submit");
    let image = target.read(gpu).expect("read");
    if let Ok(dir) = std::env::var("CHAMFER_TEST_IMAGES") {
        let name = std::thread::current()
            .name()
            .unwrap_or("display")
            .replace("::", "-");
        chamfer_tests::save_png(
            &image,
            &std::path::Path::new(&dir).join(format!("{name}.png")),
        );
    }
    image
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Seen {
    Nothing,
    Visible,
    Hidden,
}

/// Each pixel of a picture drawn by [`hidden_in_green`] over hidden-line faces: white is nothing,
/// green a hidden edge, anything else a visible one.
fn classify(image: &Image) -> Vec<Seen> {
    image
        .rgba
        .chunks(4)
        .map(|p| match (p[0], p[1], p[2]) {
            (r, g, b) if r > 240 && g > 240 && b > 240 => Seen::Nothing,
            (r, g, b) if g > 150 && r < 110 && b < 110 => Seen::Hidden,
            _ => Seen::Visible,
        })
        .collect()
}

/// Pixels of a `[width, height]` frame whose centre lies within `reach` pixels of a segment of
/// `polylines`.
fn rasterize(polylines: &[&Vec<[f32; 2]>], reach: f32, [width, height]: [u32; 2]) -> Vec<bool> {
    let mut mask = vec![false; (width * height) as usize];
    for line in polylines {
        for pair in line.windows(2) {
            let (a, b) = (glam::Vec2::from(pair[0]), glam::Vec2::from(pair[1]));
            let lo = a.min(b) - reach;
            let hi = a.max(b) + reach;
            for y in (lo.y.floor().max(0.0) as u32)..(hi.y.ceil().min(height as f32) as u32) {
                for x in (lo.x.floor().max(0.0) as u32)..(hi.x.ceil().min(width as f32) as u32) {
                    let p = glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                    let ab = b - a;
                    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
                    if (a + ab * t).distance(p) <= reach {
                        mask[(y * width + x) as usize] = true;
                    }
                }
            }
        }
    }
    mask
}

/// Distance (Chebyshev, pixels) from pixel `i` to the nearest set pixel of `mask`, a frame `width`
/// pixels wide, up to `most`.
fn nearest(mask: &[bool], width: u32, i: usize, most: i32) -> Option<i32> {
    let height = (mask.len() / width as usize) as u32;
    let (x, y) = ((i as u32 % width) as i32, (i as u32 / width) as i32);
    (0..=most).find(|&r| {
        (-r..=r).any(|dy| {
            (-r..=r).any(|dx| {
                (dx.abs() == r || dy.abs() == r)
                    && (0..width as i32).contains(&(x + dx))
                    && (0..height as i32).contains(&(y + dy))
                    && mask[((y + dy) as u32 * width + (x + dx) as u32) as usize]
            })
        })
    })
}

/// How the picture's edge pixels agree with the exact drawing.
#[derive(Debug)]
struct Agreement {
    /// Rendered edge pixels with a drawn line within 2 px.
    matched: usize,
    /// ... whose visibility is the nearest drawn line's (either, at equal distance).
    agreeing: usize,
    /// Rendered hidden pixels.
    hidden_pixels: usize,
    /// Share of the drawing's hidden line pixels with a rendered hidden pixel within 2 px.
    hidden_found: f64,
}

impl Agreement {
    fn share(&self) -> f64 {
        self.agreeing as f64 / self.matched.max(1) as f64
    }
}

fn agreement(image: &Image, camera: &Camera, exact: &Asset) -> Agreement {
    let options = DrawOptions::DEFAULT.with_hidden(true).with_classes(&[
        LineClass::Contour,
        LineClass::Boundary,
        LineClass::Marked,
        LineClass::Crease,
    ]);
    let drawing = hidden_lines(exact, camera, &options);
    let lines = |hidden: bool| {
        drawing
            .lines
            .iter()
            .filter(|set| set.hidden == hidden)
            .flat_map(|set| set.polylines.iter())
            .collect::<Vec<_>>()
    };
    let width = image.width;
    let visible = rasterize(&lines(false), 1.0, camera.viewport);
    let hidden = rasterize(&lines(true), 1.0, camera.viewport);
    let seen = classify(image);
    let (mut matched, mut agreeing) = (0, 0);
    for (i, &s) in seen.iter().enumerate() {
        if s == Seen::Nothing {
            continue;
        }
        let (v, h) = (
            nearest(&visible, width, i, 2),
            nearest(&hidden, width, i, 2),
        );
        let expected = match (v, h) {
            (None, None) => continue,
            (Some(_), None) => [Seen::Visible; 2],
            (None, Some(_)) => [Seen::Hidden; 2],
            (Some(v), Some(h)) if v < h => [Seen::Visible; 2],
            (Some(v), Some(h)) if h < v => [Seen::Hidden; 2],
            _ => [Seen::Visible, Seen::Hidden],
        };
        matched += 1;
        agreeing += usize::from(expected.contains(&s));
    }
    let hidden_seen: Vec<bool> = seen.iter().map(|&s| s == Seen::Hidden).collect();
    let drawn_hidden: Vec<usize> = (0..hidden.len()).filter(|&i| hidden[i]).collect();
    let found = drawn_hidden
        .iter()
        .filter(|&&i| nearest(&hidden_seen, width, i, 2).is_some())
        .count();
    Agreement {
        matched,
        agreeing,
        hidden_pixels: hidden_seen.iter().filter(|&&h| h).count(),
        hidden_found: found as f64 / drawn_hidden.len().max(1) as f64,
    }
}

/// An OBJ of two unit cubes, the second at `offset`.
fn two_cubes(offset: Vec3) -> String {
    let mut obj = String::new();
    for (k, origin) in [Vec3::ZERO, offset].into_iter().enumerate() {
        for i in 0..8 {
            let corner = Vec3::new((i >> 2) as f32, ((i >> 1) & 1) as f32, (i & 1) as f32);
            let p = origin + corner;
            obj.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
        }
        for [a, b, c] in [
            [1, 2, 4],
            [1, 4, 3],
            [5, 7, 8],
            [5, 8, 6],
            [1, 5, 6],
            [1, 6, 2],
            [3, 4, 8],
            [3, 8, 7],
            [1, 3, 7],
            [1, 7, 5],
            [2, 6, 8],
            [2, 8, 4],
        ] {
            let o = 8 * k;
            obj.push_str(&format!("f {} {} {}\n", a + o, b + o, c + o));
        }
    }
    obj
}

fn bake_obj(text: &str) -> Asset {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("cubes.obj");
    std::fs::write(&path, text).expect("write");
    chamfer_preprocess::bake_file(&path, &chamfer_preprocess::BakeOptions::DEFAULT)
        .expect("bake")
        .asset
}

fn orbit_camera(bounds: [[f32; 3]; 2], azimuth: f32, elevation: f32, size: [u32; 2]) -> Camera {
    let orbit = Orbit {
        azimuth,
        elevation,
        ..Orbit::default()
    };
    Camera::orbit(bounds, &orbit, size)
}

/// The bound of the issue: at least 98 % of the rendered edge pixels near a drawn line (within
/// 2 px) take the visibility of the nearest one. Measured (lavapipe): fandisk 0.9973, from behind
/// 0.9920, cube_gears.3mf 0.9850 (at 1280 x 960), two boxes 0.9984.
const AGREE: f64 = 0.98;

/// And the drawing's hidden lines are drawn: the share of its hidden line pixels with a rendered
/// hidden pixel within 2 px. A hidden line that runs under a visible one within the visible line's
/// width is drawn over by it, which the gears' crowded teeth do most. Measured: fandisk 0.9923 and
/// 0.9894, cube_gears.3mf 0.9792, two boxes 0.9981.
const FOUND: f64 = 0.97;

fn check(name: &str, image: &Image, camera: &Camera, exact: &Asset) {
    let a = agreement(image, camera, exact);
    println!(
        "{name}: {} of {} edge pixels agree on visibility ({:.4}); {} hidden pixels drawn, {:.4} of the drawing's hidden line pixels found",
        a.agreeing,
        a.matched,
        a.share(),
        a.hidden_pixels,
        a.hidden_found
    );
    assert!(a.share() >= AGREE, "{name}: {a:?}");
    assert!(a.hidden_found >= FOUND, "{name}: {a:?}");
}

#[test]
fn hidden_edges_agree_with_the_exact_drawing() {
    // The gears' teeth are a few pixels apart at 480 x 360: they are drawn at 1280 x 960.
    for (name, fixture, azimuth, elevation, size) in [
        ("fandisk", "meshes/fandisk.obj", 35.0, 25.0, [480, 360]),
        (
            "fandisk from behind",
            "meshes/fandisk.obj",
            -140.0,
            30.0,
            [480, 360],
        ),
        (
            "cube_gears.3mf",
            "cad/cube_gears.3mf",
            35.0,
            25.0,
            [1280, 960],
        ),
    ] {
        let asset = bake_fixture(fixture);
        let uploaded = GpuAsset::new(&gpu().device, &asset).expect("upload");
        let camera = orbit_camera(uploaded.bounds(), azimuth, elevation, size);
        let instances = [Instance::new(&uploaded)];
        let style = hidden_in_green(LinePattern::Solid);
        let image = picture(&camera, &instances, FaceMode::HiddenLine, &style);
        check(name, &image, &camera, &asset);
    }
}

/// Two objects: the box in front hides part of the one behind, whose hidden edges the scene's
/// depth finds although they belong to another instance. The exact drawing is of one asset holding
/// both boxes.
#[test]
fn an_edge_hidden_by_another_object_is_hidden() {
    let offset = Vec3::new(0.6, 0.3, -1.6);
    let cube = bake_fixture("shapes/cube.obj");
    let both = bake_obj(&two_cubes(offset));
    let uploaded = GpuAsset::new(&gpu().device, &cube).expect("upload");
    let instances = [
        Instance::new(&uploaded),
        Instance::new(&uploaded).with_transform(Mat4::from_translation(offset)),
    ];
    let bounds = Instance::scene_bounds(&instances).expect("bounds");
    let camera = orbit_camera(bounds, 20.0, 15.0, [480, 360]);
    let style = hidden_in_green(LinePattern::Solid);
    let image = picture(&camera, &instances, FaceMode::HiddenLine, &style);
    check("two boxes", &image, &camera, &both);
    // Drawn alone, the box behind has no edge hidden by the other.
    let alone = picture(&camera, &instances[1..], FaceMode::HiddenLine, &style);
    let hidden = |image: &Image| {
        classify(image)
            .iter()
            .filter(|&&s| s == Seen::Hidden)
            .count()
    };
    assert!(
        hidden(&image) > hidden(&alone) + 200,
        "{} hidden pixels with the front box, {} without",
        hidden(&image),
        hidden(&alone)
    );
}

/// A ribbon along x of `segments` short quads: its long boundaries are polylines of short edges.
fn ribbon(segments: usize) -> String {
    let mut obj = String::new();
    for i in 0..=segments {
        let x = 4.0 * i as f32 / segments as f32;
        obj.push_str(&format!("v {x} 0 0\nv {x} 0.2 0\n"));
    }
    for i in 0..segments {
        let (a, b, c, d) = (2 * i + 1, 2 * i + 2, 2 * i + 3, 2 * i + 4);
        obj.push_str(&format!("f {a} {c} {d}\nf {a} {d} {b}\n"));
    }
    obj
}

/// The on and off runs of the hidden (green) pixels along the row of `image` with the most of
/// them in its lower half (the ribbon's lower boundary), ends left out: (first x, length, on).
fn dash_runs(image: &Image) -> Vec<(u32, u32, bool)> {
    let seen = classify(image);
    let w = image.width as usize;
    let row = (image.height as usize / 2..image.height as usize)
        .max_by_key(|&y| (0..w).filter(|&x| seen[y * w + x] == Seen::Hidden).count())
        .expect("rows");
    let hidden: Vec<bool> = (0..w).map(|x| seen[row * w + x] == Seen::Hidden).collect();
    let first = hidden.iter().position(|&h| h).expect("a hidden pixel");
    let last = hidden.iter().rposition(|&h| h).expect("a hidden pixel");
    let mut runs = Vec::new();
    let mut start = first;
    for x in first + 1..=last + 1 {
        if x > last || hidden[x] != hidden[start] {
            runs.push((start as u32, (x - start) as u32, hidden[start]));
            start = x;
        }
    }
    // The first and last dashes end where the line does.
    runs[1..runs.len().saturating_sub(1)].to_vec()
}

/// The pattern checks: a dashed hidden line keeps its phase across the joins of a chain of
/// short edges (each about 7.7 px here: a pattern restarting at every edge, the control without
/// joins, is not 6 on and 4 off), and moves by at most a pixel when the
/// camera turns by 0.1°.
#[test]
fn a_dashed_hidden_line_keeps_its_phase_along_a_chain_and_stands_still() {
    let strip = bake_obj(&ribbon(40));
    let cube = bake_fixture("shapes/cube.obj");
    let (strip, cube) = (
        GpuAsset::new(&gpu().device, &strip).expect("upload"),
        GpuAsset::new(&gpu().device, &cube).expect("upload"),
    );
    // A thin box in front hides the whole ribbon.
    let cover = Mat4::from_translation(Vec3::new(-1.0, -1.0, 1.0))
        * Mat4::from_scale(Vec3::new(6.0, 2.2, 0.1));
    let instances = [
        Instance::new(&strip),
        Instance::new(&cube).with_transform(cover),
    ];
    let bounds = Instance::scene_bounds(&instances).expect("bounds");
    let dashed = hidden_in_green(LinePattern::dashes(&[6.0, 4.0]).expect("valid"));
    let frame = |azimuth: f32, style: &EdgeStyle| {
        let camera = orbit_camera(bounds, azimuth, 0.0, [480, 360]);
        dash_runs(&picture(&camera, &instances, FaceMode::HiddenLine, style))
    };
    let runs = frame(0.0, &dashed);
    println!("runs along the chain: {runs:?}");
    // Every dash 6 px and every gap 4 px, within a pixel.
    let regular = |runs: &[(u32, u32, bool)]| {
        runs.len() >= 20
            && runs
                .iter()
                .all(|&(_, length, on)| length.abs_diff(if on { 6 } else { 4 }) <= 1)
    };
    assert!(regular(&runs), "{runs:?}");
    // Without joins each edge (about 7.7 px) starts the pattern again: not that pattern.
    let restarting = EdgeStyle {
        caps: chamfer_runtime::render::CapMethod::None,
        ..dashed
    };
    let control = frame(0.0, &restarting);
    assert!(!regular(&control), "the control passes: {control:?}");
    // A tenth of a degree later every dash begins within a pixel of where it began.
    let turned = frame(0.1, &dashed);
    for &(x, _, on) in &runs {
        let moved = turned
            .iter()
            .filter(|&&(_, _, o)| o == on)
            .map(|&(t, _, _)| t.abs_diff(x))
            .min()
            .expect("runs");
        assert!(moved <= 1, "a run at x = {x} moved {moved} px: {turned:?}");
    }
}
