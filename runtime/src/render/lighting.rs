//! The light and material of the chamfer highlight (seed 000, and glTF's metallic-roughness model of
//! issue 29) and of the mesh pass that matches it.

use glam::Vec3;

use super::layout::PunctualLight;
use crate::highlight::ggx::PbrMaterial;
use crate::highlight::strip::Material;

/// A light, in model space (KHR_lights_punctual's kinds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Parallel light arriving from this direction (towards the light).
    Directional([f32; 3]),
    /// A point light at this position.
    Point([f32; 3]),
    /// A spot light at `position` shining along `direction`: full within `inner_deg` of its axis,
    /// fading as KHR_lights_punctual's smooth cone to nothing at `outer_deg`.
    Spot {
        /// Where the light is.
        position: [f32; 3],
        /// The way it shines.
        direction: [f32; 3],
        /// Half-angle of the full cone, degrees.
        inner_deg: f32,
        /// Half-angle past which nothing is lit, degrees.
        outer_deg: f32,
    },
}

/// How a chamfer strip (and the mesh pass matching it) is shaded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shading {
    /// Seed 000's Blinn model (eq. 1); lights do not fall off with distance.
    Blinn(Material),
    /// glTF's metallic-roughness model (GGX, height-correlated Smith, Schlick, Lambert weighted by
    /// 1 − F), integrated over the arc by `highlight::ggx`. Point and spot lights fall off as 1/d²
    /// (d in model units), so the light's colour is its intensity; a directional light's colour is its
    /// illuminance: π lights a white Lambertian face seen head-on to 1.
    Pbr(PbrMaterial),
}

/// The chamfer highlight's light and material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Highlight {
    /// The light.
    pub light: Light,
    /// The light's colour × intensity (linear RGB; for Blinn, 1 = white).
    pub color: [f32; 3],
    /// The model the strip is shaded with.
    pub shading: Shading,
    /// Share of the diffuse colour lit regardless of the light (0 in the paper); under
    /// [`Shading::Pbr`] the radiance of a uniform white environment, as [`super::MeshStyle::ambient`].
    pub ambient: f32,
    /// `K` of the seed's blend weight `W = K r_e / (d r_max)` (§3.2), which strengthens strips nearer
    /// than `K` and weakens farther ones; `None`: no distance factor, every strip blends by exactly the
    /// share of the pixel it covers (as a real fillet does, at any distance).
    pub k: Option<f32>,
    /// Where two or three chamfer edges of one radius meet at a convex vertex, draw the corner the
    /// rounded solid has (a sphere patch, its cylinders meeting it; issue 29) instead of letting the
    /// strips end in a notch as seed 000 does.
    pub rounded_corners: bool,
}

/// The direction towards the default light (model space): above, to the right and in front.
pub const DEFAULT_LIGHT_DIRECTION: [f32; 3] = [0.4, 0.8, 0.45];

impl Default for Highlight {
    fn default() -> Self {
        Self {
            light: Light::Directional(DEFAULT_LIGHT_DIRECTION),
            color: [1.0; 3],
            shading: Shading::Blinn(Material {
                diffuse: 0.7,
                specular: 0.5,
                shininess: 32.0,
            }),
            ambient: 0.0,
            k: None,
            rounded_corners: true,
        }
    }
}

/// `light` as the shaders' `PunctualLight` (brdf.wgsl); `falloff`: dim point and spot lights by 1/d².
pub(crate) fn punctual(light: &Light, color: [f32; 3], falloff: bool) -> PunctualLight {
    let finite = |v: [f32; 3]| Vec3::from(v).is_finite().then(|| Vec3::from(v));
    let [r, g, b] = color.map(|c| if c.is_finite() { c.max(0.0) } else { 0.0 });
    let mut out = PunctualLight {
        color: [r, g, b, if falloff { 1.0 } else { 0.0 }],
        ..PunctualLight::default()
    };
    match *light {
        Light::Directional(towards) => {
            let d = finite(towards).map_or(Vec3::Z, |d| d.normalize_or(Vec3::Z));
            out.position = d.extend(0.0).to_array();
        }
        Light::Point(position) => {
            out.position = finite(position)
                .unwrap_or(Vec3::ZERO)
                .extend(1.0)
                .to_array();
        }
        Light::Spot {
            position,
            direction,
            inner_deg,
            outer_deg,
        } => {
            out.position = finite(position)
                .unwrap_or(Vec3::ZERO)
                .extend(1.0)
                .to_array();
            let axis = finite(direction).map_or(-Vec3::Z, |d| d.normalize_or(-Vec3::Z));
            let degrees = |a: f32| {
                if a.is_finite() {
                    a.clamp(0.0, 90.0)
                } else {
                    45.0
                }
            };
            let outer = degrees(outer_deg);
            let inner = degrees(inner_deg).min(outer);
            out.spot = axis.extend(outer.to_radians().cos()).to_array();
            out.cone = [inner.to_radians().cos(), 0.0, 0.0, 0.0];
        }
    }
    out
}
