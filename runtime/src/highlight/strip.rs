//! The light a rounded edge sends towards the viewer, integrated over a piece of its arc (seed 000 §3.1).
//!
//! A chamfered (filleted) edge of radius `r` between faces with unit normals `n1` and `n2` is a partial
//! cylinder whose normal `N(θ)` turns from `n1` to `n2`. A pixel sees the part of the arc whose projection
//! onto `across` (the screen direction perpendicular to the edge, `P` in the paper) falls inside it. The
//! mean Blinn intensity of that part, weighted by the projected length `cos σ dl` (eq. 3–4), is
//!
//! `∫ (R_d (N·L)₊ + R_s (N·H)₊ⁿ) (P·T) dθ / ∫ (P·T) dθ`,
//!
//! and each term is `|v⊥|^m [P_y (F(θb, m+1) − F(θa, m+1)) + P_x / (m+1) (cos^{m+1} θb − cos^{m+1} θa)]`
//! (eq. 5) in the frame whose x axis is the term's vector `v` (L, or H) projected on the arc's plane, with
//! the bounds clipped to the lobe where `N·v > 0` and to the half facing the viewer. `F(·, 2)` (the
//! diffuse term) has a closed form; the specular one reads a [`CosPowerRow`] for `m = n + 1`.
//!
//! [`arc_intensity`] is what the highlight shader computes; [`brute_force`] integrates the same
//! quantity by sampling the arc, for tests.

use glam::Vec3;

use super::table::CosPowerRow;

/// Blinn's material (seed 000, eq. 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Diffuse reflectance `R_d`.
    pub diffuse: f32,
    /// Specular reflectance `R_s`.
    pub specular: f32,
    /// Specular exponent `n`, 1 to 128.
    pub shininess: f32,
}

/// The geometry of one pixel's view of an edge, all unit vectors in one space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcView {
    /// Normal of the first face.
    pub n1: Vec3,
    /// Normal of the second face.
    pub n2: Vec3,
    /// Towards the light (at the edge).
    pub to_light: Vec3,
    /// Towards the viewer (at the edge).
    pub to_viewer: Vec3,
    /// The screen direction across the edge, perpendicular to the edge and to `to_viewer`.
    pub across: Vec3,
}

/// The part of the arc (angles from `n1` towards `n2`, radians) a pixel integrates.
pub type ArcRange = (f32, f32);

/// The frame of the arc: `ez` along `n1 × n2`, angles measured from `n1`.
pub(super) struct ArcFrame {
    pub(super) ex: Vec3,
    pub(super) ey: Vec3,
    pub(super) ez: Vec3,
    /// The angle from `n1` to `n2`.
    pub(super) span: f32,
}

impl ArcFrame {
    pub(super) fn new(n1: Vec3, n2: Vec3) -> Option<Self> {
        let ez = n1.cross(n2).try_normalize()?;
        Some(Self {
            ex: n1,
            ey: ez.cross(n1),
            ez,
            span: n1.dot(n2).clamp(-1.0, 1.0).acos(),
        })
    }

    /// Angle of `v` projected on the arc's plane, in (−π, π], and the projection's length.
    pub(super) fn angle_of(&self, v: Vec3) -> (f32, f32) {
        let (x, y) = (v.dot(self.ex), v.dot(self.ey));
        (y.atan2(x), x.hypot(y))
    }
}

/// Intersects `[a, b]` (inside [0, π)) with the half-turn lobe centred on angle `c`.
pub(super) fn clip_to_lobe((a, b): ArcRange, c: f32) -> Option<ArcRange> {
    use std::f32::consts::{FRAC_PI_2, TAU};
    // Of the lobe's copies, only one can meet an interval shorter than π inside [0, π).
    let c = if c < -FRAC_PI_2 { c + TAU } else { c };
    let (lo, hi) = (a.max(c - FRAC_PI_2), b.min(c + FRAC_PI_2));
    (lo < hi).then_some((lo, hi))
}

/// The visible part of the whole arc: where its normal faces the viewer.
pub fn visible_arc(view: &ArcView) -> Option<ArcRange> {
    let frame = ArcFrame::new(view.n1, view.n2)?;
    let (facing, _) = frame.angle_of(view.to_viewer);
    clip_to_lobe((0.0, frame.span), facing)
}

/// The mean intensity over `range` of the arc (relative to an incoming intensity of 1), and the
/// range's projected length on `across` per unit radius (what `range` covers on screen).
/// `specular_row` must be the row for exponent `shininess + 1`.
pub fn arc_intensity(
    view: &ArcView,
    range: ArcRange,
    material: &Material,
    specular_row: &CosPowerRow,
) -> (f32, f32) {
    let Some(frame) = ArcFrame::new(view.n1, view.n2) else {
        return (0.0, 0.0);
    };
    let normal = |theta: f32| frame.ex * theta.cos() + frame.ey * theta.sin();
    let projected = (normal(range.1) - normal(range.0)).dot(view.across);
    if projected.abs() < 1e-9 {
        return (0.0, 0.0);
    }
    let half = (view.to_light + view.to_viewer).normalize_or_zero();
    let diffuse = lobe_integral(&frame, view.across, view.to_light, range, 1.0, |phi| {
        0.5 * phi + 0.25 * (2.0 * phi).sin()
    });
    let specular = lobe_integral(
        &frame,
        view.across,
        half,
        range,
        material.shininess,
        |phi| specular_row.eval(phi),
    );
    let total = material.diffuse * diffuse + material.specular * specular;
    ((total / projected).max(0.0), projected.abs())
}

/// `∫ (N·v)₊^m (P·T) dθ` over `range`, with `f(φ) = F(φ, m + 1)`.
pub(super) fn lobe_integral(
    frame: &ArcFrame,
    across: Vec3,
    v: Vec3,
    range: ArcRange,
    m: f32,
    f: impl Fn(f32) -> f32,
) -> f32 {
    let (centre, length) = frame.angle_of(v);
    if length < 1e-6 {
        return 0.0;
    }
    let Some((a, b)) = clip_to_lobe(range, centre) else {
        return 0.0;
    };
    let centre = if centre < -std::f32::consts::FRAC_PI_2 {
        centre + std::f32::consts::TAU
    } else {
        centre
    };
    let (ua, ub) = (a - centre, b - centre);
    // The term's own frame: x along v's projection.
    let ex = frame.ex * centre.cos() + frame.ey * centre.sin();
    let ey = frame.ez.cross(ex);
    let (px, py) = (across.dot(ex), across.dot(ey));
    let power = |u: f32| u.cos().max(0.0).powf(m + 1.0);
    length.powf(m) * (py * (f(ub) - f(ua)) + px / (m + 1.0) * (power(ub) - power(ua)))
}

/// [`arc_intensity`] by sampling the arc at `samples` points (midpoint rule, f64): the reference.
pub fn brute_force(view: &ArcView, range: ArcRange, material: &Material, samples: usize) -> f64 {
    let d = |v: Vec3| v.as_dvec3();
    let (n1, n2) = (d(view.n1), d(view.n2));
    let ez = n1.cross(n2).normalize();
    let ey = ez.cross(n1);
    let half = (d(view.to_light) + d(view.to_viewer)).normalize();
    let (light, across) = (d(view.to_light), d(view.across));
    let (a, b) = (f64::from(range.0), f64::from(range.1));
    let step = (b - a) / samples as f64;
    let (mut light_sum, mut weight_sum) = (0.0, 0.0);
    for k in 0..samples {
        let theta = a + (k as f64 + 0.5) * step;
        let normal = n1 * theta.cos() + ey * theta.sin();
        let tangent = -n1 * theta.sin() + ey * theta.cos();
        let weight = across.dot(tangent);
        let shade = f64::from(material.diffuse) * normal.dot(light).max(0.0)
            + f64::from(material.specular)
                * normal
                    .dot(half)
                    .max(0.0)
                    .powf(f64::from(material.shininess));
        light_sum += shade * weight;
        weight_sum += weight;
    }
    (light_sum / weight_sum).max(0.0)
}

#[cfg(test)]
pub(super) mod tests_support {
    use super::*;
    /// A random edge seen from a random direction (from `random`), with its visible arc; `None`
    /// where the edge is seen end-on or its strip is out of sight.
    pub fn random_view(random: &mut impl FnMut() -> Vec3) -> Option<(ArcView, ArcRange)> {
        let n1 = random();
        let n2 = (n1 + random() * 1.2).normalize();
        let to_viewer = random();
        let across = n1.cross(n2).normalize().cross(to_viewer).try_normalize()?;
        let view = ArcView {
            n1,
            n2,
            to_light: random(),
            to_viewer,
            across,
        };
        Some((view, visible_arc(&view)?))
    }

    /// A deterministic stream of unit vectors.
    pub fn directions(seed: u64) -> impl FnMut() -> Vec3 {
        let mut state = seed;
        move || loop {
            let mut next = || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
            };
            let v = Vec3::new(next(), next(), next());
            if v.length_squared() > 0.05 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::tests_support::{directions, random_view};
    use super::*;

    #[test]
    fn the_closed_form_matches_sampling_the_arc() {
        let mut random = directions(7);
        let (mut checked, mut worst) = (0, 0.0f64);
        for case in 0..400 {
            let Some((view, visible)) = random_view(&mut random) else {
                continue;
            };
            let shininess = [1.0, 4.5, 32.0, 128.0][case % 4];
            let material = Material {
                diffuse: 0.6,
                specular: 0.4,
                shininess,
            };
            let row = CosPowerRow::new(shininess + 1.0);
            // The whole visible arc, and pieces of it (the pixels of a wide strip). A piece near the
            // cylinder's own silhouette covers almost nothing on screen, so each is judged by the light
            // it contributes (mean × projected length) against the whole arc's projection.
            let (_, whole) = arc_intensity(&view, visible, &material, &row);
            if whole < 0.05 {
                // Seen at grazing incidence (a silhouette edge): the strip is under 5 % of its radius wide
                // and f32 differences of nearly equal values dominate. Such edges are drawn as contours.
                continue;
            }
            let width = visible.1 - visible.0;
            for (from, to) in [(0.0, 1.0), (0.0, 0.2), (0.3, 0.55), (0.8, 1.0)] {
                let range = (visible.0 + from * width, visible.0 + to * width);
                let (closed, projected) = arc_intensity(&view, range, &material, &row);
                let sampled = brute_force(&view, range, &material, 20_000);
                let error = (f64::from(closed) - sampled).abs() * f64::from(projected);
                worst = worst.max(error / f64::from(whole));
                assert!(
                    error <= 1e-4 * f64::from(whole),
                    "case {case}: closed form {closed}, sampled {sampled}, n = {shininess}, range {range:?}"
                );
                checked += 1;
            }
        }
        assert!(checked > 800, "{checked}");
        eprintln!("worst error: {worst:.2e} of the arc's light");
    }

    #[test]
    fn a_flat_arc_is_lit_like_its_face() {
        // Faces almost coplanar: the strip is lit like its face (Blinn at n1).
        let n1 = Vec3::Z;
        let n2 = Vec3::new(0.0, 0.02, 1.0).normalize();
        let to_viewer = Vec3::new(0.0, 0.0, 1.0);
        let to_light = Vec3::new(0.3, 0.2, 1.0).normalize();
        let view = ArcView {
            n1,
            n2,
            to_light,
            to_viewer,
            across: Vec3::Y,
        };
        let material = Material {
            diffuse: 0.7,
            specular: 0.3,
            shininess: 16.0,
        };
        let (closed, _) = arc_intensity(&view, (0.0, 0.02), &material, &CosPowerRow::new(17.0));
        let half = (to_light + to_viewer).normalize();
        let face = 0.7 * n1.dot(to_light) + 0.3 * n1.dot(half).powf(16.0);
        assert!((closed - face).abs() < 0.01, "{closed} vs {face}");
    }
}
