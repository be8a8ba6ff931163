//! `F(φ, m) = ∫₀^φ cos^m θ dθ` for the highlight integral (seed 000 §3.1).
//!
//! The paper stores a 1024 × 128 table over φ ∈ [0, π/2] and integer exponents, read with bilinear
//! interpolation (512 KiB, error ≤ 2.0e-6). Here a material's exponent is a constant of its draw, so the
//! runtime generates one row per exponent in use, for any real exponent: `SAMPLES + 1` values of `F` on
//! a uniform grid, read by cubic Hermite interpolation whose slopes, `cos^m φ`, are computed exactly
//! rather than stored. The interpolation error is at most `h⁴/384 · max|F⁽⁴⁾|`; for m ≤ 129,
//! `max|F⁽⁴⁾| = max|(cos^m)'''| < 2.1e3`, so with h = (π/2)/128 it is below 1.3e-7, and f32 storage adds
//! about 1e-7: the test asserts 2e-6 over φ ∈ [0, π/2] and m ∈ [1, 129] against f64 quadrature, with
//! 516 bytes per exponent (the paper's table is 1016 times larger).

use std::f64::consts::FRAC_PI_2;

/// Grid intervals over [0, π/2].
pub const SAMPLES: usize = 128;

/// `F(·, m)` for one exponent `m`.
#[derive(Clone, Debug, PartialEq)]
pub struct CosPowerRow {
    exponent: f32,
    values: Vec<f32>,
}

impl CosPowerRow {
    /// Tabulates `F(·, m)`; `m` must be finite and at least 0 (clamped otherwise).
    pub fn new(exponent: f32) -> Self {
        let m = if exponent.is_finite() {
            f64::from(exponent.max(0.0))
        } else {
            0.0
        };
        let h = FRAC_PI_2 / SAMPLES as f64;
        let mut values = Vec::with_capacity(SAMPLES + 1);
        let mut sum = 0.0f64;
        values.push(0.0);
        for i in 0..SAMPLES {
            sum += gauss_legendre(m, i as f64 * h, (i + 1) as f64 * h);
            values.push(sum as f32);
        }
        Self {
            exponent: m as f32,
            values,
        }
    }

    /// The exponent `m`.
    pub fn exponent(&self) -> f32 {
        self.exponent
    }

    /// The `SAMPLES + 1` values `F(i · (π/2) / SAMPLES, m)`, as the shader receives them.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// `F(φ, m)` for φ ∈ [−π/2, π/2] (odd in φ; clamped outside), as the shader computes it.
    pub fn eval(&self, phi: f32) -> f32 {
        let sign = phi.signum();
        let phi = phi.abs().min(std::f32::consts::FRAC_PI_2);
        let h = std::f32::consts::FRAC_PI_2 / SAMPLES as f32;
        let x = phi / h;
        let i = (x as usize).min(SAMPLES - 1);
        let t = x - i as f32;
        let slope = |k: usize| (k as f32 * h).cos().max(0.0).powf(self.exponent) * h;
        let (f0, f1) = (self.values[i], self.values[i + 1]);
        let (t2, t3) = (t * t, t * t * t);
        let value = (2.0 * t3 - 3.0 * t2 + 1.0) * f0
            + (t3 - 2.0 * t2 + t) * slope(i)
            + (-2.0 * t3 + 3.0 * t2) * f1
            + (t3 - t2) * slope(i + 1);
        sign * value
    }
}

/// `∫ₐᵇ cos^m θ dθ` by 8-point Gauss–Legendre on 4 sub-panels (exact to ~1e-15 on grid intervals).
fn gauss_legendre(m: f64, a: f64, b: f64) -> f64 {
    const NODES: [(f64, f64); 4] = [
        (0.183_434_642_495_649_8, 0.362_683_783_378_362),
        (0.525_532_409_916_329, 0.313_706_645_877_887_3),
        (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
        (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    ];
    let panels = 4;
    let width = (b - a) / f64::from(panels);
    let mut sum = 0.0;
    for p in 0..panels {
        let center = a + (f64::from(p) + 0.5) * width;
        for (x, w) in NODES {
            for s in [-1.0, 1.0] {
                sum += w * (center + s * x * width * 0.5).cos().max(0.0).powf(m);
            }
        }
    }
    sum * width * 0.5
}

/// `F(φ, m)` in f64 by adaptive Simpson quadrature, independent of the table's grid: the reference.
pub fn reference(phi: f64, m: f64) -> f64 {
    let f = |x: f64| x.cos().max(0.0).powf(m);
    /// One Simpson panel: its ends `(x, f(x))`, the value at its middle and its estimate.
    fn refine(
        f: &dyn Fn(f64) -> f64,
        a: (f64, f64),
        b: (f64, f64),
        fm: f64,
        whole: f64,
        depth: u32,
    ) -> f64 {
        let mid = 0.5 * (a.0 + b.0);
        let (flm, frm) = (f(0.5 * (a.0 + mid)), f(0.5 * (mid + b.0)));
        let left = (mid - a.0) / 6.0 * (a.1 + 4.0 * flm + fm);
        let right = (b.0 - mid) / 6.0 * (fm + 4.0 * frm + b.1);
        if depth == 0 || (left + right - whole).abs() < 1e-14 {
            return left + right + (left + right - whole) / 15.0;
        }
        refine(f, a, (mid, fm), flm, left, depth - 1)
            + refine(f, (mid, fm), b, frm, right, depth - 1)
    }
    let b = phi.abs().min(FRAC_PI_2);
    let (fa, fm, fb) = (f(0.0), f(0.5 * b), f(b));
    let whole = b / 6.0 * (fa + 4.0 * fm + fb);
    phi.signum() * refine(&f, (0.0, fa), (b, fb), fm, whole, 40)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_forms_hold() {
        // F(φ, 1) = sin φ, F(φ, 2) = φ/2 + sin 2φ / 4, F(π/2, m) = √π Γ((m+1)/2) / (2 Γ(m/2 + 1)).
        for phi in [0.0, 0.3, 1.0, 1.5] {
            assert!((reference(phi, 1.0) - f64::sin(phi)).abs() < 1e-12);
            assert!((reference(phi, 2.0) - (phi / 2.0 + (2.0 * phi).sin() / 4.0)).abs() < 1e-12);
        }
        // F(π/2, 4) = 3π/16, F(π/2, 128) = π/2 · C(128, 64) / 2^128.
        assert!((reference(FRAC_PI_2, 4.0) - 3.0 * std::f64::consts::PI / 16.0).abs() < 1e-12);
        let wallis_128: f64 = (1..=64)
            .map(|k| (2 * k - 1) as f64 / (2 * k) as f64)
            .product::<f64>()
            * FRAC_PI_2;
        assert!((reference(FRAC_PI_2, 128.0) - wallis_128).abs() < 1e-12);
    }

    #[test]
    fn rows_are_within_2e_6_of_f64_quadrature_for_any_exponent() {
        let mut exponents: Vec<f32> = (1..=129).map(|m| m as f32).collect();
        exponents.extend([
            1.25, 1.5, 2.7, 3.3, 7.77, 12.5, 31.9, 63.5, 100.01, 127.5, 128.9,
        ]);
        let mut worst = (0.0f64, 0.0f32, 0.0f32);
        for &m in &exponents {
            let row = CosPowerRow::new(m);
            for k in 0..=2000 {
                let phi = k as f32 / 2000.0 * std::f32::consts::FRAC_PI_2;
                let error =
                    (f64::from(row.eval(phi)) - reference(f64::from(phi), f64::from(m))).abs();
                if error > worst.0 {
                    worst = (error, m, phi);
                }
                // Odd symmetry, for arcs that cross the highlight's centre.
                assert_eq!(row.eval(-phi), -row.eval(phi));
            }
        }
        eprintln!(
            "max error {:.3e} at m = {}, φ = {}",
            worst.0, worst.1, worst.2
        );
        assert!(
            worst.0 <= 2.0e-6,
            "max error {:.3e} at m = {}, φ = {}",
            worst.0,
            worst.1,
            worst.2
        );
        assert_eq!(std::mem::size_of_val(CosPowerRow::new(64.0).values()), 516);
    }

    #[test]
    fn linear_interpolation_on_the_same_grid_would_not_do() {
        // Why the slopes: reading the same 129 values linearly is off by far more than 2e-6.
        let m = 128.0;
        let row = CosPowerRow::new(m);
        let h = std::f32::consts::FRAC_PI_2 / SAMPLES as f32;
        let worst = (0..SAMPLES * 8)
            .map(|k| {
                let phi = k as f32 * h / 8.0;
                let i = (phi / h) as usize;
                let t = phi / h - i as f32;
                let linear = row.values()[i] * (1.0 - t) + row.values()[i + 1] * t;
                (f64::from(linear) - reference(f64::from(phi), f64::from(m))).abs()
            })
            .fold(0.0, f64::max);
        assert!(worst > 1e-4, "{worst}");
    }
}
