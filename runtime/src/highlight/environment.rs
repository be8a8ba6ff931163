//! Image-based light for physically based shading (issue 29): an equirectangular environment,
//! prefiltered on the CPU for one roughness at a time (as the seed's table row is made for the
//! exponent in use), with the split-sum approximation (Karis 2013) the engines use.
//!
//! - [`Environment`]: linear radiance per texel, +Y up, row 0 looking up; column `u` (0..1) faces
//!   `(sin φ, ·, −cos φ)` with `φ = 2π u − π` (so the image's middle faces −Z).
//! - [`Environment::prefilter`]: the radiance map for one GGX `α` (each direction `R` the mean of the
//!   environment weighted by `D(R·H) (R·L)₊ dω`, the lobe seen along its own axis) and the irradiance
//!   map (`∫ L (N·L)₊ dω / π`), both small equirectangular maps the shaders read bilinearly.
//!   The shaders multiply them by the specular lobe's directional albedo (Karis' analytic DFG fit) and
//!   by the diffuse colour; a uniform environment of radiance 1 gives both maps 1 everywhere.

use glam::Vec3;

/// Columns and rows of the prefiltered radiance map.
pub const SPECULAR_SIZE: [u32; 2] = [64, 32];
/// Columns and rows of the irradiance map.
pub const IRRADIANCE_SIZE: [u32; 2] = [32, 16];
/// The resolution the environment is reduced to before filtering.
const SOURCE_SIZE: [u32; 2] = [128, 64];
/// The narrowest lobe filtered: about a source texel (2.8°); a smoother surface shows the map's own
/// detail at this resolution.
const MIN_ALPHA: f32 = 0.05;

/// Why an environment was refused.
#[derive(Debug, thiserror::Error)]
pub enum EnvironmentError {
    /// Dimensions zero, too large or not matching the texels.
    #[error(
        "an environment of {width}x{height} needs {expected} texels, got {got} (at most 16384 a side)"
    )]
    Size {
        /// Columns.
        width: u32,
        /// Rows.
        height: u32,
        /// What the size needs.
        expected: u64,
        /// What was given.
        got: usize,
    },
    /// A texel not finite or negative.
    #[error("texel {index} of the environment is not a finite non-negative radiance")]
    Texel {
        /// Its index, row by row.
        index: usize,
    },
}

/// An equirectangular environment of linear radiance.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    width: u32,
    height: u32,
    texels: Vec<[f32; 3]>,
    last_filtered: LastFiltered,
}

/// The maps last made by [`Environment::prefiltered`]: the mesh pass and the highlight share one
/// environment and one roughness, so the second asks for what the first made. Not part of the
/// environment's value (a clone starts empty; equality ignores it).
#[derive(Default)]
struct LastFiltered(std::sync::Mutex<Option<(u32, std::sync::Arc<Prefiltered>)>>);

impl Clone for LastFiltered {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl PartialEq for LastFiltered {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl std::fmt::Debug for LastFiltered {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("LastFiltered")
    }
}

/// An environment filtered for one roughness: what the shaders read.
#[derive(Clone, Debug, PartialEq)]
pub struct Prefiltered {
    /// [`SPECULAR_SIZE`] texels, row by row (RGB and 1).
    pub specular: Vec<[f32; 4]>,
    /// [`IRRADIANCE_SIZE`] texels, row by row.
    pub irradiance: Vec<[f32; 4]>,
}

/// The unit direction of equirectangular coordinates `(u, v)` in [0, 1]².
pub fn direction(u: f32, v: f32) -> Vec3 {
    let theta = v * std::f32::consts::PI;
    let phi = u * std::f32::consts::TAU - std::f32::consts::PI;
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        -theta.sin() * phi.cos(),
    )
}

impl Environment {
    /// An environment of `width` × `height` texels, row by row from the top.
    pub fn new(width: u32, height: u32, texels: Vec<[f32; 3]>) -> Result<Self, EnvironmentError> {
        let expected = u64::from(width) * u64::from(height);
        if width == 0
            || height == 0
            || width > 16_384
            || height > 16_384
            || expected != texels.len() as u64
        {
            return Err(EnvironmentError::Size {
                width,
                height,
                expected,
                got: texels.len(),
            });
        }
        if let Some(index) = texels
            .iter()
            .position(|t| !t.iter().all(|c| c.is_finite() && *c >= 0.0))
        {
            return Err(EnvironmentError::Texel { index });
        }
        Ok(Self {
            width,
            height,
            texels,
            last_filtered: LastFiltered::default(),
        })
    }

    /// The same radiance from every direction.
    pub fn uniform(radiance: [f32; 3]) -> Result<Self, EnvironmentError> {
        Self::new(1, 1, vec![radiance])
    }

    /// Columns and rows.
    pub fn size(&self) -> [u32; 2] {
        [self.width, self.height]
    }

    /// The environment reduced to [`SOURCE_SIZE`] (box filter), each texel with its direction and
    /// solid angle.
    fn reduced(&self) -> Vec<(Vec3, f32, Vec3)> {
        let [w, h] = SOURCE_SIZE;
        let mut sums = vec![(Vec3::ZERO, 0.0f32); (w * h) as usize];
        for y in 0..self.height {
            // Texels of a row near the poles cover less sphere: weight by sin θ.
            let weight = (((y as f32 + 0.5) / self.height as f32) * std::f32::consts::PI).sin();
            let row = (u64::from(y) * u64::from(h) / u64::from(self.height)) as u32;
            for x in 0..self.width {
                let column = (u64::from(x) * u64::from(w) / u64::from(self.width)) as u32;
                let texel = Vec3::from(self.texels[(y * self.width + x) as usize]);
                let cell = &mut sums[(row * w + column) as usize];
                cell.0 += texel * weight;
                cell.1 += weight;
            }
        }
        let mut out = Vec::with_capacity(sums.len());
        for row in 0..h {
            let v = (row as f32 + 0.5) / h as f32;
            let solid_angle = (v * std::f32::consts::PI).sin()
                * (std::f32::consts::PI / h as f32)
                * (std::f32::consts::TAU / w as f32);
            for column in 0..w {
                let (sum, weight) = sums[(row * w + column) as usize];
                // A small environment leaves cells empty: they take the nearest filled one.
                let radiance = if weight > 0.0 {
                    sum / weight
                } else {
                    let y = (u64::from(row) * u64::from(self.height) / u64::from(h)) as u32;
                    let x = (u64::from(column) * u64::from(self.width) / u64::from(w)) as u32;
                    Vec3::from(self.texels[(y * self.width + x) as usize])
                };
                let u = (column as f32 + 0.5) / w as f32;
                out.push((direction(u, v), solid_angle, radiance));
            }
        }
        out
    }

    /// [`prefilter`](Self::prefilter)'s maps for `alpha`, made once while the same `alpha` is asked
    /// for again (by every renderer sharing this environment).
    pub fn prefiltered(&self, alpha: f32) -> std::sync::Arc<Prefiltered> {
        let key = alpha.to_bits();
        // A poisoned lock only means a panic elsewhere while it was held: the cache is still valid
        // or empty.
        let mut last = self
            .last_filtered
            .0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some((_, maps)) = last.as_ref().filter(|(held, _)| *held == key) {
            return maps.clone();
        }
        let maps = std::sync::Arc::new(self.prefilter(alpha));
        *last = Some((key, maps.clone()));
        maps
    }

    /// The maps for GGX `alpha` (`roughness²`); a few tens of milliseconds of CPU.
    pub fn prefilter(&self, alpha: f32) -> Prefiltered {
        let source = self.reduced();
        let alpha = if alpha.is_finite() {
            alpha.clamp(MIN_ALPHA, 1.0)
        } else {
            1.0
        };
        let a2 = alpha * alpha;
        let map = |[w, h]: [u32; 2], weight: &dyn Fn(Vec3, Vec3) -> f32| {
            let mut texels = Vec::with_capacity((w * h) as usize);
            for row in 0..h {
                for column in 0..w {
                    let n = direction(
                        (column as f32 + 0.5) / w as f32,
                        (row as f32 + 0.5) / h as f32,
                    );
                    let (mut sum, mut total) = (Vec3::ZERO, 0.0f32);
                    for &(l, solid_angle, radiance) in &source {
                        let k = weight(n, l) * solid_angle;
                        sum += radiance * k;
                        total += k;
                    }
                    let value = if total > 0.0 { sum / total } else { Vec3::ZERO };
                    texels.push(value.extend(1.0).to_array());
                }
            }
            texels
        };
        let specular = map(SPECULAR_SIZE, &|n, l| {
            let n_dot_l = n.dot(l);
            if n_dot_l <= 0.0 {
                return 0.0;
            }
            let n_dot_h = (n + l).normalize_or_zero().dot(n);
            let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
            a2 / (d * d) * n_dot_l
        });
        let irradiance = map(IRRADIANCE_SIZE, &|n, l| n.dot(l).max(0.0));
        Prefiltered {
            specular,
            irradiance,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_environment_filters_to_itself() {
        let maps = Environment::uniform([0.5, 1.0, 2.0])
            .expect("uniform")
            .prefilter(0.3);
        for texel in maps.specular.iter().chain(&maps.irradiance) {
            for (c, want) in texel.iter().zip([0.5, 1.0, 2.0, 1.0]) {
                assert!((c - want).abs() < 1e-4, "{texel:?}");
            }
        }
    }

    #[test]
    fn a_sky_lights_what_faces_it() {
        // Bright above the horizon, dark below.
        let (w, h) = (64, 32);
        let texels = (0..w * h)
            .map(|i| if i / w < h / 2 { [1.0; 3] } else { [0.0; 3] })
            .collect();
        let sky = Environment::new(w, h, texels).expect("sky");
        let maps = sky.prefilter(0.2);
        let [sw, sh] = IRRADIANCE_SIZE;
        let top = maps.irradiance[(sw / 2) as usize][0];
        let bottom = maps.irradiance[((sh - 1) * sw + sw / 2) as usize][0];
        // Facing up sees the whole sky (irradiance 1); facing down none of it.
        assert!(top > 0.95 && bottom < 0.05, "{top} {bottom}");
        // A smooth mirror facing the horizon reflects half sky, half ground: about 0.5.
        let [pw, ph] = SPECULAR_SIZE;
        let horizon = maps.specular[((ph / 2) * pw) as usize][0];
        assert!((0.3..0.7).contains(&horizon), "{horizon}");
    }

    #[test]
    fn bad_environments_are_refused() {
        assert!(Environment::new(0, 1, vec![]).is_err());
        // Asked twice for one roughness, the maps are made once; another roughness makes new ones.
        let sky = Environment::new(4, 2, (0..8).map(|i| [i as f32; 3]).collect()).expect("sky");
        let first = sky.prefiltered(0.25);
        assert!(std::sync::Arc::ptr_eq(&first, &sky.prefiltered(0.25)));
        assert_eq!(*first, sky.prefilter(0.25));
        let other = sky.prefiltered(0.5);
        assert!(!std::sync::Arc::ptr_eq(&first, &other));
        assert_eq!(*other, sky.prefilter(0.5));
        assert_eq!(sky.clone(), sky);
        assert!(Environment::new(2, 2, vec![[0.0; 3]; 3]).is_err());
        assert!(Environment::new(1, 1, vec![[f32::NAN, 0.0, 0.0]]).is_err());
        assert!(Environment::new(1, 1, vec![[-1.0, 0.0, 0.0]]).is_err());
        assert!(Environment::new(20_000, 1, vec![[0.0; 3]; 20_000]).is_err());
    }
}
