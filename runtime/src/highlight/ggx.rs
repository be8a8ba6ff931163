//! The chamfer highlight under physically based shading (issue 29): the light a rounded edge sends to
//! the viewer when its surface follows glTF's metallic-roughness model (GGX distribution,
//! height-correlated Smith visibility, Schlick Fresnel, Lambert diffuse), integrated over a piece of
//! its arc as seed 000 §3.1 integrates Blinn's model.
//!
//! Light and viewer directions are constants of a pixel (taken at the edge's middle, as the seed
//! does), so `V·H` and with it Fresnel are too, and a pixel's mean radiance over its slice of the arc is
//!
//! `[(1 − F) c_diff / π · I_d + F · I_s] / ∫ (P·T) dθ`, with
//! `I_d = ∫ (N·L)₊ (P·T) dθ` (the seed's closed form for exponent 1) and
//! `I_s = ∫ D(N·H) Vis(N·L, N·V) (N·L)₊ (P·T) dθ`.
//!
//! **The specular integral in closed form plus a short rule.** Measure `u` from H's projection on the
//! arc's plane: `N·H = h cos u`, and `D = α² / (π (1 − k cos² u)²)` with `k = h² (1 − α²)`. The
//! substitution `tan u = a tan w`, `a² = 1 − k = (H·axis)² + h² α²` (no cancellation), turns the sharp
//! lobe into a smooth weight: `D du = α² / (π a³) · (cos² w + a² sin² w) dw`. What is left, `Vis · (N·L)₊
//! · (P·T)`, is smooth once the range is clipped to where `N·L > 0`, and a 16-point Gauss–Legendre rule in
//! `w` integrates it to within 1.4e-4 of the arc's light for roughness 0.045 to 1 in f32 (`tests` below:
//! 1e-3 asserted, against sampling the arc in f64). So where the seed needs a table row per exponent, this
//! needs none: the rule's 8 node pairs are the only constants ([`NODES`], shared with the shader).
//!
//! [`arc_radiance`] is what `shaders/highlight.wgsl` computes; [`radiance`] is one normal's shading (the
//! mesh pass's, `shaders/brdf.wgsl`); [`brute_force`] samples the arc, for tests.

use glam::Vec3;

use super::strip::{ArcFrame, ArcRange, ArcView, clip_to_lobe, lobe_integral};

/// The smallest roughness shaded (Filament's floor, which keeps `α⁴` representable): a smoother
/// surface's lobe is narrower than any pixel's slice of the arc anyway.
pub const MIN_ROUGHNESS: f32 = 0.045;

/// glTF's metallic-roughness material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PbrMaterial {
    /// Base colour, linear RGB.
    pub base_color: [f32; 3],
    /// 0 for a dielectric (F0 = 0.04), 1 for a metal (F0 = base colour).
    pub metallic: f32,
    /// Perceptual roughness, [`MIN_ROUGHNESS`] to 1; `α = roughness²`.
    pub roughness: f32,
}

impl Default for PbrMaterial {
    fn default() -> Self {
        Self {
            base_color: [0.8; 3],
            metallic: 0.0,
            roughness: 0.5,
        }
    }
}

impl PbrMaterial {
    /// GGX's `α`.
    pub fn alpha(&self) -> f32 {
        let r = if self.roughness.is_finite() {
            self.roughness
        } else {
            1.0
        };
        let r = r.clamp(MIN_ROUGHNESS, 1.0);
        r * r
    }

    /// Metallic within [0, 1] (0 if not finite).
    pub fn clamped_metallic(&self) -> f32 {
        if self.metallic.is_finite() {
            self.metallic.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The base colour within [0, 1] (0 where not finite).
    pub fn clamped_base(&self) -> Vec3 {
        Vec3::from(self.base_color.map(|c| if c.is_finite() { c } else { 0.0 }))
            .clamp(Vec3::ZERO, Vec3::ONE)
    }

    /// Reflectance at normal incidence.
    pub fn f0(&self) -> Vec3 {
        Vec3::splat(0.04).lerp(self.clamped_base(), self.clamped_metallic())
    }

    /// The diffuse albedo `c_diff` (metals have none).
    pub fn diffuse_color(&self) -> Vec3 {
        self.clamped_base() * (1.0 - self.clamped_metallic())
    }

    /// Schlick's Fresnel at `v_dot_h`.
    pub fn fresnel(&self, v_dot_h: f32) -> Vec3 {
        let f0 = self.f0();
        f0 + (Vec3::ONE - f0) * (1.0 - v_dot_h.clamp(0.0, 1.0)).powi(5)
    }
}

/// Positive nodes of the 16-point Gauss–Legendre rule on [−1, 1] and their weights (the rule is
/// symmetric). The shader receives them from here.
pub const NODES: [(f32, f32); 8] = [
    (0.095_012_51, 0.189_450_6),
    (0.281_603_55, 0.182_603_42),
    (0.458_016_78, 0.169_156_52),
    (0.617_876_24, 0.149_595_99),
    (0.755_404_4, 0.124_628_97),
    (0.865_631_2, 0.095_158_51),
    (0.944_575, 0.062_253_52),
    (0.989_400_9, 0.027_152_46),
];

/// Height-correlated Smith visibility `G / (4 N·L N·V)`.
pub fn visibility(n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let (l, v) = (n_dot_l.max(0.0), n_dot_v.max(0.0));
    let denominator = l * (v * v * (1.0 - a2) + a2).sqrt() + v * (l * l * (1.0 - a2) + a2).sqrt();
    0.5 / denominator.max(1e-12)
}

/// GGX's normal distribution at `n_dot_h`.
pub fn distribution(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let c = n_dot_h.max(0.0);
    let d = c * c * (a2 - 1.0) + 1.0;
    a2 / (std::f32::consts::PI * d * d)
}

/// The radiance a surface of normal `n` sends towards `to_viewer` under a light of radiance 1 arriving
/// from `to_light`: `[(1 − F) c_diff / π + F D Vis] (N·L)₊`.
pub fn radiance(n: Vec3, to_light: Vec3, to_viewer: Vec3, material: &PbrMaterial) -> Vec3 {
    let n_dot_l = n.dot(to_light);
    if n_dot_l <= 0.0 {
        return Vec3::ZERO;
    }
    let half = (to_light + to_viewer).normalize_or_zero();
    let alpha = material.alpha();
    let fresnel = material.fresnel(to_viewer.dot(half));
    let specular = distribution(n.dot(half), alpha) * visibility(n_dot_l, n.dot(to_viewer), alpha);
    ((Vec3::ONE - fresnel) * material.diffuse_color() / std::f32::consts::PI + fresnel * specular)
        * n_dot_l
}

/// `I_s = ∫ D(N·H) Vis(N·L, N·V) (N·L)₊ (P·T) dθ` over `range` (see the module's text).
pub fn specular_integral(view: &ArcView, range: ArcRange, alpha: f32) -> f32 {
    let Some(frame) = ArcFrame::new(view.n1, view.n2) else {
        return 0.0;
    };
    let half = (view.to_light + view.to_viewer).normalize_or_zero();
    let (centre, h) = frame.angle_of(half);
    if h < 1e-6 {
        return 0.0;
    }
    let Some(range) = clip_to_lobe(range, centre) else {
        return 0.0;
    };
    let Some((a, b)) = clip_to_lobe(range, frame.angle_of(view.to_light).0) else {
        return 0.0;
    };
    let centre = if centre < -std::f32::consts::FRAC_PI_2 {
        centre + std::f32::consts::TAU
    } else {
        centre
    };
    let axial = half.dot(frame.ez);
    let a2 = axial * axial + h * h * alpha * alpha;
    let scale = a2.sqrt();
    // w = atan(tan u / a), robust at u = ±π/2.
    let to_w = |u: f32| u.sin().atan2(scale * u.cos().max(0.0));
    let (wa, wb) = (to_w(a - centre), to_w(b - centre));
    let (mid, half_width) = (0.5 * (wa + wb), 0.5 * (wb - wa));
    let remainder = |w: f32| {
        let u = (scale * w.sin()).atan2(w.cos());
        let theta = centre + u;
        let (sin, cos) = theta.sin_cos();
        let normal = frame.ex * cos + frame.ey * sin;
        let tangent = frame.ey * cos - frame.ex * sin;
        let n_dot_l = normal.dot(view.to_light).max(0.0);
        let weight = w.cos().powi(2) + a2 * w.sin().powi(2);
        weight
            * visibility(n_dot_l, normal.dot(view.to_viewer), alpha)
            * n_dot_l
            * tangent.dot(view.across)
    };
    let sum: f32 = NODES
        .iter()
        .map(|&(x, weight)| {
            weight * (remainder(mid - half_width * x) + remainder(mid + half_width * x))
        })
        .sum();
    alpha * alpha / (std::f32::consts::PI * a2 * scale) * half_width * sum
}

/// The mean radiance over `range` of the arc under a light of radiance 1 (RGB), and the range's
/// projected length on `across` per unit radius (what `range` covers on screen).
pub fn arc_radiance(view: &ArcView, range: ArcRange, material: &PbrMaterial) -> (Vec3, f32) {
    let Some(frame) = ArcFrame::new(view.n1, view.n2) else {
        return (Vec3::ZERO, 0.0);
    };
    let normal = |theta: f32| frame.ex * theta.cos() + frame.ey * theta.sin();
    let projected = (normal(range.1) - normal(range.0)).dot(view.across);
    if projected.abs() < 1e-9 {
        return (Vec3::ZERO, 0.0);
    }
    let diffuse = lobe_integral(&frame, view.across, view.to_light, range, 1.0, |phi| {
        0.5 * phi + 0.25 * (2.0 * phi).sin()
    });
    let specular = specular_integral(view, range, material.alpha());
    let half = (view.to_light + view.to_viewer).normalize_or_zero();
    let fresnel = material.fresnel(view.to_viewer.dot(half));
    let total = (Vec3::ONE - fresnel) * material.diffuse_color() / std::f32::consts::PI * diffuse
        + fresnel * specular;
    ((total / projected).max(Vec3::ZERO), projected.abs())
}

/// [`arc_radiance`] by sampling the arc at `samples` points (midpoint rule, f64): the reference.
pub fn brute_force(
    view: &ArcView,
    range: ArcRange,
    material: &PbrMaterial,
    samples: usize,
) -> [f64; 3] {
    let d = |v: Vec3| v.as_dvec3();
    let (n1, n2) = (d(view.n1), d(view.n2));
    let ey = n1.cross(n2).normalize().cross(n1);
    let (light, viewer, across) = (d(view.to_light), d(view.to_viewer), d(view.across));
    let half = (light + viewer).normalize();
    let alpha = f64::from(material.alpha());
    let a2 = alpha * alpha;
    let f0 = d(material.f0());
    let fresnel = f0 + (glam::DVec3::ONE - f0) * (1.0 - viewer.dot(half)).powi(5);
    let diffuse = (glam::DVec3::ONE - fresnel) * d(material.diffuse_color()) / std::f64::consts::PI;
    let (a, b) = (f64::from(range.0), f64::from(range.1));
    let step = (b - a) / samples as f64;
    let (mut sum, mut weights) = (glam::DVec3::ZERO, 0.0);
    for k in 0..samples {
        let theta = a + (k as f64 + 0.5) * step;
        let normal = n1 * theta.cos() + ey * theta.sin();
        let weight = across.dot(-n1 * theta.sin() + ey * theta.cos());
        weights += weight;
        let (nl, nv, nh) = (normal.dot(light), normal.dot(viewer), normal.dot(half));
        if nl <= 0.0 || nv <= 0.0 {
            continue;
        }
        let dd = nh.max(0.0).powi(2) * (a2 - 1.0) + 1.0;
        let distribution = a2 / (std::f64::consts::PI * dd * dd);
        let visibility = 0.5
            / (nl * (nv * nv * (1.0 - a2) + a2).sqrt() + nv * (nl * nl * (1.0 - a2) + a2).sqrt());
        sum += (diffuse + fresnel * distribution * visibility) * nl * weight;
    }
    (sum / weights).max(glam::DVec3::ZERO).to_array()
}

#[cfg(test)]
mod tests {
    use super::super::strip::tests_support::{directions, random_view};
    use super::*;

    #[test]
    fn the_rule_matches_sampling_the_arc_over_roughness_and_angles() {
        let mut random = directions(29);
        let roughnesses = [MIN_ROUGHNESS, 0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 1.0];
        let (mut checked, mut worst, mut worst_at) = (0, 0.0f64, (0.0, 0));
        for case in 0..640 {
            let Some((view, visible)) = random_view(&mut random) else {
                continue;
            };
            let roughness = roughnesses[case % roughnesses.len()];
            let material = PbrMaterial {
                base_color: [0.9, 0.5, 0.2],
                metallic: [0.0, 1.0, 0.3][case % 3],
                roughness,
            };
            let (_, whole) = arc_radiance(&view, visible, &material);
            if whole < 0.05 {
                // Grazing: drawn as a contour (as for Blinn, strip.rs).
                continue;
            }
            let whole_light = brute_force(&view, visible, &material, 400_000);
            let scale = whole_light.iter().copied().fold(0.0, f64::max) * f64::from(whole);
            if scale < 1e-6 {
                continue;
            }
            let width = visible.1 - visible.0;
            for (from, to) in [
                (0.0, 1.0),
                (0.0, 0.2),
                (0.3, 0.55),
                (0.8, 1.0),
                (0.45, 0.47),
            ] {
                let range = (visible.0 + from * width, visible.0 + to * width);
                let (ours, projected) = arc_radiance(&view, range, &material);
                let sampled = brute_force(&view, range, &material, 400_000);
                for channel in 0..3 {
                    // Light contributed (mean × projected length) against the whole arc's.
                    let error = (f64::from(ours[channel]) - sampled[channel]).abs()
                        * f64::from(projected)
                        / scale;
                    if error > worst {
                        worst = error;
                        worst_at = (roughness, case);
                    }
                    assert!(
                        error <= 1e-3,
                        "case {case}: ours {ours}, sampled {sampled:?}, roughness {roughness}, range {range:?}"
                    );
                }
                checked += 1;
            }
        }
        assert!(checked > 1000, "{checked}");
        eprintln!(
            "GGX arc rule: worst error {worst:.2e} of the arc's light at {worst_at:?}, {checked} ranges"
        );
    }

    #[test]
    fn a_flat_arc_is_shaded_like_its_face() {
        let n1 = Vec3::Z;
        let n2 = Vec3::new(0.0, 0.01, 1.0).normalize();
        let (to_viewer, to_light) = (Vec3::Z, Vec3::new(0.3, 0.2, 1.0).normalize());
        let view = ArcView {
            n1,
            n2,
            to_light,
            to_viewer,
            across: Vec3::Y,
        };
        for roughness in [0.3, 0.6, 1.0] {
            let material = PbrMaterial {
                roughness,
                ..PbrMaterial::default()
            };
            let (ours, _) = arc_radiance(&view, (0.0, 0.01), &material);
            let face = radiance(n1, to_light, to_viewer, &material);
            assert!(
                (ours - face).abs().max_element() < 0.01 * face.max_element(),
                "{ours} vs {face}"
            );
        }
    }
}
