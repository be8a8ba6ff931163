//! Hidden-line drawings: the visible (and optionally the hidden) parts of an asset's contours,
//! boundaries, marked edges, creases and intersection edges from one camera, as 2D polylines
//! ready for a vector file ([`svg`]). The edge classes and the contour test are the thesis' (§2.2
//! types, §6.1 tests: a contour has one face towards the eye and one away), evaluated exactly as the
//! runtime's classify pass does, so a drawing matches `chamfer render` of the same camera.
//!
//! Visibility is exact, not per pixel: every edge is clipped to the view frustum, and each triangle
//! that may lie in front of it (an obvhs BVH2 over the triangles' screen-space boxes with their
//! depth, queried with the edge's box) hides the interval of the edge that lies inside the wedge of
//! planes through the eye and the triangle's sides *and* behind the triangle's plane. The union of
//! those intervals is hidden, the rest visible, so each edge is split exactly where occluders begin
//! and end. A point counts as behind a triangle only when it is more than 1e-5 of the model's radius
//! behind its plane, so an edge is never hidden by the faces it lies on (or by neighbours that
//! share one of its vertices) through rounding; intervals closer than 1e-3 px are merged, and pieces
//! shorter than 1e-2 px dropped.

#[cfg(feature = "vector-drawings")]
pub mod dxf;
pub mod paper;
#[cfg(feature = "vector-drawings")]
pub mod pdf;
pub mod section;
pub mod style;
pub mod svg;

use glam::{DMat4, DVec3, DVec4, Vec3};
use obvhs::aabb::Aabb;
use rayon::prelude::*;

use chamfer_runtime::asset::{Asset, EdgeFlags};
use chamfer_runtime::section::Plane;

use crate::polylines;

/// The camera of a drawing: the runtime's own (`chamfer render` of the same camera draws the same
/// lines), its viewport the drawing's frame in pixels, y down.
pub use chamfer_runtime::camera::Camera;

/// What a line is; drawn in this order, and a mesh edge in several classes takes the first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LineClass {
    /// Edges with one face towards the eye and one away (per camera).
    Contour,
    /// Edges with one face, or more than two.
    Boundary,
    /// Edges marked in the source file, and material seams.
    Marked,
    /// Ridge and valley creases.
    Crease,
    /// Where surfaces cut through each other (baked with `--intersections`).
    Intersection,
    /// The outline of a section plane's cut (only with a section).
    Cut,
    /// The hatch of the cut faces (only with a section; never hidden).
    Hatch,
}

impl LineClass {
    /// Every class, in drawing order.
    pub const ALL: [Self; 7] = [
        Self::Contour,
        Self::Boundary,
        Self::Marked,
        Self::Crease,
        Self::Intersection,
        Self::Cut,
        Self::Hatch,
    ];

    /// The name used as the SVG `class` attribute and on the command line.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Contour => "contour",
            Self::Boundary => "boundary",
            Self::Marked => "marked",
            Self::Crease => "crease",
            Self::Intersection => "intersection",
            Self::Cut => "cut",
            Self::Hatch => "hatch",
        }
    }

    const fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// What to draw. Start from [`DrawOptions::DEFAULT`] and change it with the `with_*` setters.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct DrawOptions {
    /// The classes drawn, one bit per [`LineClass`]. Default: all.
    pub classes: u8,
    /// Also give the hidden parts of the lines, as their own line sets. Default false.
    pub hidden: bool,
    /// A section plane: the half it keeps is drawn, with the cut's outline and hatch. Default
    /// none.
    pub section: Option<Plane>,
    /// The hatch of the cut faces.
    pub hatch: Hatch,
}

/// Parallel hatch lines over cut faces, laid out in the frame (as drafting standards lay
/// hatches out on paper), so they keep their spacing whatever the plane's slant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hatch {
    /// Distance between lines, frame pixels; 0: no hatch.
    pub spacing_px: f64,
    /// Direction, degrees counter-clockwise from the frame's x axis.
    pub angle_deg: f64,
}

impl DrawOptions {
    /// Every class, visible parts only.
    pub const DEFAULT: Self = Self {
        classes: (1 << LineClass::ALL.len()) - 1,
        hidden: false,
        section: None,
        hatch: Hatch {
            spacing_px: 8.0,
            angle_deg: 45.0,
        },
    };

    /// Sets [`classes`](Self::classes) to exactly these.
    pub fn with_classes(self, classes: &[LineClass]) -> Self {
        Self {
            classes: classes.iter().fold(0, |bits, c| bits | c.bit()),
            ..self
        }
    }

    /// Sets [`hidden`](Self::hidden).
    pub fn with_hidden(self, hidden: bool) -> Self {
        Self { hidden, ..self }
    }

    /// Sets [`section`](Self::section).
    pub fn with_section(self, section: Option<Plane>) -> Self {
        Self { section, ..self }
    }

    /// Sets [`hatch`](Self::hatch).
    pub fn with_hatch(self, hatch: Hatch) -> Self {
        Self { hatch, ..self }
    }

    fn draws(&self, class: LineClass) -> bool {
        self.classes & class.bit() != 0
    }
}

impl Default for DrawOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The lines of one class, visible or hidden.
#[derive(Clone, Debug, PartialEq)]
pub struct LineSet {
    /// What the lines are.
    pub class: LineClass,
    /// True for the hidden parts.
    pub hidden: bool,
    /// Polylines in frame pixels (x right, y down), chained end to end where lines meet.
    pub polylines: Vec<Vec<[f32; 2]>>,
}

/// A hidden-line drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    /// The frame, in pixels.
    pub viewport: [u32; 2],
    /// Model units per pixel in the plane through the model's centre facing the camera (the
    /// drawing's scale there; the same everywhere for an orthographic camera).
    pub units_per_px: f64,
    /// One set per drawn class (in [`LineClass::ALL`] order), then, if asked for, one hidden set per
    /// drawn class.
    pub lines: Vec<LineSet>,
    /// Counts, for reports.
    pub stats: DrawStats,
}

/// What the hidden-line pass did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawStats {
    /// Lines (mesh edges and intersection segments) of a drawn class.
    pub lines: u64,
    /// Triangle–line occlusion tests.
    pub occlusion_tests: u64,
    /// Visible pieces before chaining.
    pub visible_pieces: u64,
    /// Hidden pieces before chaining (0 unless hidden lines were asked for).
    pub hidden_pieces: u64,
}

/// Draws `asset` from `view`; see the module documentation. Deterministic for any thread count.
pub fn hidden_lines(asset: &Asset, view: &Camera, options: &DrawOptions) -> Drawing {
    let scene = Scene::new(asset, view);
    let mut candidates = candidate_lines(asset, &scene, options);
    let occluders = match &options.section {
        None => Occluders::new(render_triangles(asset), &scene),
        Some(plane) => {
            let cut = section::cut(asset, plane);
            candidates = candidates
                .into_iter()
                .filter_map(|line| line.kept_part(plane))
                .collect();
            candidates.extend(section_lines(&cut, &scene, options));
            let mut occluding = cut.kept;
            occluding.extend(cut.caps);
            Occluders::new(occluding, &scene)
        }
    };
    let pieces: Vec<(Vec<Piece>, u64)> = candidates
        .par_iter()
        .map(|line| {
            occluders
                .spans(&scene, line)
                .map_or((Vec::new(), 0), |spans| {
                    (pieces_of(&scene, line, &spans, options.hidden), spans.tests)
                })
        })
        .collect();
    let mut stats = DrawStats::default();
    let mut by_set: Vec<Vec<[[f32; 2]; 2]>> = vec![Vec::new(); 2 * LineClass::ALL.len()];
    for ((line_pieces, tests), line) in pieces.iter().zip(&candidates) {
        stats.lines += 1;
        stats.occlusion_tests += tests;
        for piece in line_pieces {
            if piece.hidden {
                stats.hidden_pieces += 1;
            } else {
                stats.visible_pieces += 1;
            }
            if piece.hidden && line.class == LineClass::Hatch {
                continue; // a hatch behind something is not drawn
            }
            let set = line.class as usize + usize::from(piece.hidden) * LineClass::ALL.len();
            by_set[set].push(piece.ends);
        }
    }
    let mut lines = Vec::new();
    for hidden in [false, true] {
        if hidden && !options.hidden {
            break;
        }
        for class in LineClass::ALL {
            let sectioned = matches!(class, LineClass::Cut | LineClass::Hatch);
            if hidden && class == LineClass::Hatch {
                continue;
            }
            if options.draws(class) && (!sectioned || options.section.is_some()) {
                let set = class as usize + usize::from(hidden) * LineClass::ALL.len();
                lines.push(LineSet {
                    class,
                    hidden,
                    polylines: chain_pieces(&by_set[set]),
                });
            }
        }
    }
    Drawing {
        viewport: view.viewport,
        units_per_px: scene.units_per_px,
        lines,
        stats,
    }
}

/// Model units per pixel of `view`'s frame in the plane through the model's centre facing the
/// camera: [`Drawing::units_per_px`], known before drawing (to lay a hatch out in millimetres).
pub fn units_per_px(asset: &Asset, view: &Camera) -> f64 {
    Scene::new(asset, view).units_per_px
}

/// The camera in the forms the tests need, and the model's scale.
struct Scene {
    /// Model space to clip space, in f64.
    clip: DMat4,
    /// Its inverse.
    unclip: DMat4,
    /// The eye in model space, homogeneous: a point (w = 1) or, orthographic, the direction towards
    /// the viewer (w = 0).
    eye: DVec4,
    /// Model space to view depth (distance in front of the eye along the view axis).
    depth: DVec4,
    viewport: [f64; 2],
    /// Behind a plane by more than this counts as behind (model units).
    behind: f64,
    units_per_px: f64,
}

impl Scene {
    fn new(asset: &Asset, view: &Camera) -> Self {
        let model_view = view.model_view.as_dmat4();
        let clip = (view.projection * view.model_view).as_dmat4();
        let towards_viewer = if view.is_orthographic() {
            DVec4::Z
        } else {
            DVec4::W
        };
        let eye = model_view.inverse() * towards_viewer;
        // Row 2 of the view matrix gives view z; depth is its negation.
        let depth = -model_view.row(2);
        let lo = Vec3::from(asset.header.bounds_min).as_dvec3();
        let hi = Vec3::from(asset.header.bounds_max).as_dvec3();
        let centre_depth = depth.dot((lo + hi).extend(2.0) * 0.5);
        let [width, height] = view.viewport.map(|v| f64::from(v.max(1)));
        let per_px_at_unit_depth = 2.0 / (f64::from(view.projection.y_axis.y).abs() * height);
        let units_per_px = if view.is_orthographic() {
            per_px_at_unit_depth
        } else {
            per_px_at_unit_depth * centre_depth.abs()
        };
        Self {
            clip,
            unclip: clip.inverse(),
            eye,
            depth,
            viewport: [width, height],
            // A few f32 ulps of the largest coordinate: the rounding of stored positions (an
            // intersection segment's ends are rounded off its two triangles' planes).
            behind: 8.0 * f64::from(f32::EPSILON) * lo.abs().max(hi.abs()).max_element().max(1e-30),
            units_per_px,
        }
    }

    fn to_clip(&self, p: DVec3) -> DVec4 {
        self.clip * p.extend(1.0)
    }

    /// Frame pixels of a clip-space point in front of the eye (the runtime's `to_pixels`).
    fn to_pixels(&self, c: DVec4) -> [f32; 2] {
        let (x, y) = (c.x / c.w, c.y / c.w);
        [
            ((x + 1.0) * 0.5 * self.viewport[0]) as f32,
            ((1.0 - y) * 0.5 * self.viewport[1]) as f32,
        ]
    }

    /// Frame pixels of a model point, `None` when it is not in front of the eye.
    fn pixel_of(&self, p: DVec3) -> Option<glam::DVec2> {
        let c = self.to_clip(p);
        (c.w > 1e-12 * c.z.abs().max(1.0)).then(|| {
            glam::DVec2::new(
                (c.x / c.w + 1.0) * 0.5 * self.viewport[0],
                (1.0 - c.y / c.w) * 0.5 * self.viewport[1],
            )
        })
    }

    /// The model point on `plane` that the frame pixel `px` shows (the sight line through it meets
    /// the plane there), `None` when the sight line runs along the plane.
    fn on_plane(&self, px: glam::DVec2, plane: &Plane) -> Option<DVec3> {
        let ndc_x = 2.0 * px.x / self.viewport[0] - 1.0;
        let ndc_y = 1.0 - 2.0 * px.y / self.viewport[1];
        let near = self.unclip * DVec4::new(ndc_x, ndc_y, 0.0, 1.0);
        let far = self.unclip * DVec4::new(ndc_x, ndc_y, 1.0, 1.0);
        let h = DVec3::from(plane.normal).extend(-plane.offset);
        let (h0, h1) = (h.dot(near), h.dot(far));
        if h0 == h1 {
            return None;
        }
        let point = near + (far - near) * (h0 / (h0 - h1));
        (point.w.abs() > 1e-300).then(|| point.truncate() / point.w)
    }

    /// Which side of the plane `(normal, d)` the eye is on (> 0: in front).
    fn eye_side(&self, plane: DVec4) -> f64 {
        plane.dot(self.eye)
    }
}

/// A 3D line to draw.
struct Line {
    class: LineClass,
    ends: [DVec3; 2],
}

/// The drawn lines of a class the options ask for: mesh edges classified as the runtime does, then
/// the intersection segments.
fn candidate_lines(asset: &Asset, scene: &Scene, options: &DrawOptions) -> Vec<Line> {
    let position = |v: u32| Vec3::from(asset.topology_positions[v as usize]).as_dvec3();
    let mut lines: Vec<Line> = (0..asset.edge_count())
        .into_par_iter()
        .filter_map(|e| {
            let [v0, v1, v2, v3] = asset.edge(e).map(position);
            let flags = asset.edge_flags(e);
            let single = flags.intersects(EdgeFlags::BOUNDARY | EdgeFlags::NON_MANIFOLD);
            // Face planes as the runtime's face_planes pass builds them.
            let a = plane((v1 - v0).cross(v2 - v0), v0);
            let mut b = a;
            if !single {
                b = plane((v0 - v1).cross(v3 - v1), v1);
                if flags.contains(EdgeFlags::FLIPPED) {
                    b = -b;
                }
            }
            let contour = !single && (scene.eye_side(a) > 0.0) != (scene.eye_side(b) > 0.0);
            let class = if contour {
                LineClass::Contour
            } else if single {
                LineClass::Boundary
            } else if flags.intersects(EdgeFlags::MARKED | EdgeFlags::MATERIAL) {
                LineClass::Marked
            } else if flags.intersects(EdgeFlags::CREASE) {
                LineClass::Crease
            } else {
                return None;
            };
            options.draws(class).then_some(Line {
                class,
                ends: [v0, v1],
            })
        })
        .collect();
    if options.draws(LineClass::Intersection) {
        lines.extend(asset.intersection_segments.iter().map(|s| Line {
            class: LineClass::Intersection,
            ends: s.map(|p| Vec3::from(p).as_dvec3()),
        }));
    }
    lines
}

/// The asset's triangles in model space.
fn render_triangles(asset: &Asset) -> Vec<[DVec3; 3]> {
    (0..asset.triangle_count())
        .into_par_iter()
        .map(|t| {
            std::array::from_fn(|k| {
                let v = asset.mesh_indices.get(3 * t + k) as usize;
                Vec3::from(asset.render_positions[v]).as_dvec3()
            })
        })
        .collect()
}

/// The cut's outline segments and its hatch, lifted from the frame onto the plane, as lines.
fn section_lines(cut: &section::Cut, scene: &Scene, options: &DrawOptions) -> Vec<Line> {
    let mut lines = Vec::new();
    if options.draws(LineClass::Cut) {
        for outline in &cut.outlines {
            lines.extend(outline.points.windows(2).map(|pair| Line {
                class: LineClass::Cut,
                ends: [pair[0], pair[1]],
            }));
        }
    }
    if let (true, Some(plane)) = (options.draws(LineClass::Hatch), &options.section) {
        let hatch = section::hatch(
            &cut.outlines,
            options.hatch.spacing_px,
            options.hatch.angle_deg,
            |p| scene.pixel_of(p),
        );
        lines.extend(hatch.into_iter().filter_map(|[a, b]| {
            Some(Line {
                class: LineClass::Hatch,
                ends: [scene.on_plane(a, plane)?, scene.on_plane(b, plane)?],
            })
        }));
    }
    lines
}

fn plane(normal: DVec3, p: DVec3) -> DVec4 {
    normal.extend(-normal.dot(p))
}

/// A visible or hidden piece of a line, in frame pixels.
struct Piece {
    ends: [[f32; 2]; 2],
    hidden: bool,
}

/// The triangles that can hide lines, and a BVH over their screen boxes.
struct Occluders {
    /// Per triangle: its corners in model space.
    triangles: Vec<[DVec3; 3]>,
    /// The triangles with a bounded screen box (NDC x, y and view depth), and the tree over those
    /// boxes (`None` when there are none).
    bounded: Vec<(u32, Aabb)>,
    bvh: Option<obvhs::bvh2::Bvh2>,
    /// Triangles reaching behind the eye, whose screen box is unbounded: tested against every line.
    everywhere: Vec<u32>,
}

impl Occluders {
    fn new(triangles: Vec<[DVec3; 3]>, scene: &Scene) -> Self {
        let screen: Vec<Option<Aabb>> =
            triangles.par_iter().map(|t| screen_box(scene, t)).collect();
        let everywhere = (0..triangles.len() as u32)
            .filter(|&t| screen[t as usize].is_none())
            .collect();
        let bounded: Vec<(u32, Aabb)> = screen
            .into_iter()
            .enumerate()
            .filter_map(|(t, b)| Some((t as u32, b?)))
            .collect();
        let boxes: Vec<Aabb> = bounded.iter().map(|&(_, b)| b).collect();
        let bvh = (!boxes.is_empty()).then(|| crate::bvh::build(&boxes));
        Self {
            triangles,
            bounded,
            bvh,
            everywhere,
        }
    }

    /// Where `line` is inside the frame and which parts of that are hidden; `None` if it is
    /// outside the frame.
    fn spans(&self, scene: &Scene, line: &Line) -> Option<Spans> {
        let [p0, p1] = line.ends;
        let (c0, c1) = (scene.to_clip(p0), scene.to_clip(p1));
        // The part inside the view frustum: -w <= x, y <= w and 0 <= z <= w, each linear in t.
        let mut inside = (0.0f64, 1.0f64);
        let frustum: [fn(DVec4) -> f64; 6] = [
            |c: DVec4| c.w + c.x,
            |c: DVec4| c.w - c.x,
            |c: DVec4| c.w + c.y,
            |c: DVec4| c.w - c.y,
            |c: DVec4| c.z,
            |c: DVec4| c.w - c.z,
        ];
        for f in frustum {
            inside = clip_interval(inside, f(c0), f(c1));
        }
        let (t0, t1) = inside;
        if t1 <= t0 {
            return None;
        }
        let (a, b) = (line.clip_at(scene, t0), line.clip_at(scene, t1));
        let [ax, ay] = [a.x / a.w, a.y / a.w];
        let [bx, by] = [b.x / b.w, b.y / b.w];
        let (d0, d1) = (
            scene.depth.dot(p0.extend(1.0)),
            scene.depth.dot(p1.extend(1.0)),
        );
        let query = Aabb::new(
            glam::Vec3A::new(ax.min(bx) as f32, ay.min(by) as f32, f32::MIN),
            glam::Vec3A::new(ax.max(bx) as f32, ay.max(by) as f32, d0.max(d1) as f32),
        );
        let mut covered: Vec<(f64, f64)> = Vec::new();
        let mut tests = 0u64;
        let mut test = |t: u32| {
            tests += 1;
            let triangle = &self.triangles[t as usize];
            if let Some(interval) = hidden_interval(scene, triangle, p0, p1) {
                let clipped = (interval.0.max(t0), interval.1.min(t1));
                if clipped.1 > clipped.0 {
                    covered.push(clipped);
                }
            }
        };
        if let Some(bvh) = &self.bvh {
            bvh.aabb_traverse(query, |bvh, node| {
                let node = &bvh.nodes[node as usize];
                for slot in node.first_index..node.first_index + node.prim_count {
                    let (t, screen) = self.bounded[bvh.primitive_indices[slot as usize] as usize];
                    if screen.intersect_aabb(&query) {
                        test(t);
                    }
                }
                true
            });
        }
        for &t in &self.everywhere {
            test(t);
        }
        let (pa, pb) = (scene.to_pixels(a), scene.to_pixels(b));
        let length_px = f64::from((pb[0] - pa[0]).hypot(pb[1] - pa[1])).max(1e-9);
        let per_px = (t1 - t0) / length_px;
        Some(Spans {
            inside,
            hidden: union(covered, 1e-3 * per_px),
            per_px,
            tests,
        })
    }
}

/// The parameters (0 at a line's first end, 1 at its second) of what is in the frame and hidden.
struct Spans {
    /// The part in the frame.
    inside: (f64, f64),
    /// Hidden parts, sorted, disjoint, within `inside`.
    hidden: Vec<(f64, f64)>,
    /// Parameter length of one pixel along the line.
    per_px: f64,
    /// Triangles tested.
    tests: u64,
}

impl Spans {
    /// The visible parts, then (if `hidden`) the hidden ones, as `(from, to, hidden)`; parts
    /// shorter than 1e-2 px are left out.
    fn parts(&self, hidden: bool) -> Vec<(f64, f64, bool)> {
        let mut parts = Vec::new();
        let min = 1e-2 * self.per_px;
        let mut cursor = self.inside.0;
        for &(from, to) in &self.hidden {
            if from - cursor > min {
                parts.push((cursor, from, false));
            }
            if hidden && to - from > min {
                parts.push((from, to, true));
            }
            cursor = to;
        }
        if self.inside.1 - cursor > min {
            parts.push((cursor, self.inside.1, false));
        }
        parts
    }
}

impl Line {
    /// The part of the line on the kept side of `plane`, `None` when none is.
    fn kept_part(self, plane: &Plane) -> Option<Self> {
        let [p0, p1] = self.ends;
        let (d0, d1) = (plane.distance(p0.to_array()), plane.distance(p1.to_array()));
        let (t0, t1) = clip_interval((0.0, 1.0), -d0, -d1);
        if t1 <= t0 || (d0 >= 0.0 && d1 >= 0.0) {
            return None;
        }
        let at = |t: f64| match t {
            0.0 => p0,
            1.0 => p1,
            _ => p0 + (p1 - p0) * t,
        };
        Some(Self {
            class: self.class,
            ends: [at(t0), at(t1)],
        })
    }

    /// Clip coordinates of the point at `t`; the ends themselves exactly.
    fn clip_at(&self, scene: &Scene, t: f64) -> DVec4 {
        let [p0, p1] = self.ends;
        let p = match t {
            0.0 => p0,
            1.0 => p1,
            _ => p0 + (p1 - p0) * t,
        };
        scene.to_clip(p)
    }
}

/// The pieces of `line` in frame pixels.
fn pieces_of(scene: &Scene, line: &Line, spans: &Spans, hidden: bool) -> Vec<Piece> {
    // Ends at the line's own vertices are projected from them, so lines that share a vertex share
    // the end point bit for bit and chain.
    let point = |t: f64| scene.to_pixels(line.clip_at(scene, t));
    spans
        .parts(hidden)
        .into_iter()
        .map(|(from, to, hidden)| Piece {
            ends: [point(from), point(to)],
            hidden,
        })
        .collect()
}

/// The screen box of a triangle (NDC x, y and view depth), or `None` if it reaches to or behind
/// the eye plane of a perspective camera.
fn screen_box(scene: &Scene, t: &[DVec3; 3]) -> Option<Aabb> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &p in t {
        let c = scene.to_clip(p);
        if c.w <= 1e-12 * c.z.abs().max(1.0) {
            return None;
        }
        let q = [c.x / c.w, c.y / c.w, scene.depth.dot(p.extend(1.0))];
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    // Widened by a hair so f32 rounding never drops a touching box.
    let widen = |v: f64, s: f64| (v + s * (v.abs() * 1e-6 + 1e-9)) as f32;
    Some(Aabb::new(
        glam::Vec3A::new(widen(lo[0], -1.0), widen(lo[1], -1.0), widen(lo[2], -1.0)),
        glam::Vec3A::new(widen(hi[0], 1.0), widen(hi[1], 1.0), widen(hi[2], 1.0)),
    ))
}

/// Narrows `(t0, t1)` to where the linear function with values `f0` at 0 and `f1` at 1 is >= 0.
fn clip_interval((t0, t1): (f64, f64), f0: f64, f1: f64) -> (f64, f64) {
    if f0 >= 0.0 && f1 >= 0.0 {
        return (t0, t1);
    }
    if f0 < 0.0 && f1 < 0.0 {
        return (1.0, 0.0);
    }
    let t = f0 / (f0 - f1);
    if f0 < 0.0 {
        (t0.max(t), t1)
    } else {
        (t0, t1.min(t))
    }
}

/// The parameters of segment `p0 p1` that triangle `t` hides: inside the wedge through the eye and
/// the triangle's sides, and behind its plane.
fn hidden_interval(scene: &Scene, t: &[DVec3; 3], p0: DVec3, p1: DVec3) -> Option<(f64, f64)> {
    let [a, b, c] = *t;
    let normal = (b - a).cross(c - a);
    let length = normal.length();
    if length == 0.0 {
        return None;
    }
    let face = plane(normal, a);
    let eye_side = scene.eye_side(face);
    if eye_side == 0.0 {
        return None; // seen edge-on: hides nothing
    }
    // Behind: on the far side from the eye by more than the tolerance.
    let behind = |p: DVec3| -eye_side.signum() * face.dot(p.extend(1.0)) - scene.behind * length;
    let mut interval = clip_interval((0.0, 1.0), behind(p0), behind(p1));
    let eye = scene.eye;
    for (u, v, w) in [(a, b, c), (b, c, a), (c, a, b)] {
        if interval.1 <= interval.0 {
            return None;
        }
        // The plane through u, v and the eye (a point, or a direction at infinity).
        let m = (v - u).cross(eye.truncate() - u * eye.w);
        let side = plane(m, u);
        let inward = side.dot(w.extend(1.0)).signum();
        let f = |p: DVec3| inward * side.dot(p.extend(1.0));
        interval = clip_interval(interval, f(p0), f(p1));
    }
    (interval.1 > interval.0).then_some(interval)
}

/// The union of intervals, merging those less than `gap` apart, sorted.
fn union(mut intervals: Vec<(f64, f64)>, gap: f64) -> Vec<(f64, f64)> {
    intervals.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(intervals.len());
    for (from, to) in intervals {
        match merged.last_mut() {
            Some(last) if from <= last.1 + gap => last.1 = last.1.max(to),
            _ => merged.push((from, to)),
        }
    }
    merged
}

/// Chains pieces that meet end to end (bitwise equal points) into polylines.
fn chain_pieces(pieces: &[[[f32; 2]; 2]]) -> Vec<Vec<[f32; 2]>> {
    // -0.0 and 0.0 are one point.
    let pieces: Vec<[[f32; 2]; 2]> = pieces
        .iter()
        .map(|piece| piece.map(|p| p.map(|x| x + 0.0)))
        .collect();
    let key = |p: [f32; 2]| p.map(f32::to_bits);
    let mut points: Vec<[f32; 2]> = pieces.iter().flatten().copied().collect();
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup_by_key(|p| key(*p));
    let id = |p: [f32; 2]| {
        points
            .binary_search_by(|q| q[0].total_cmp(&p[0]).then(q[1].total_cmp(&p[1])))
            .map_or(0, |i| i as u32)
    };
    let mut segments: Vec<[u32; 2]> = pieces
        .iter()
        .map(|&[a, b]| {
            let (a, b) = (id(a), id(b));
            [a.min(b), a.max(b)]
        })
        .filter(|[a, b]| a != b)
        .collect();
    segments.sort_unstable();
    segments.dedup();
    polylines::chain(points.len(), &segments)
        .into_iter()
        .map(|chain| chain.points.iter().map(|&i| points[i as usize]).collect())
        .collect()
}

#[cfg(test)]
mod tests;
