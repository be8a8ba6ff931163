//! The light and material of the chamfer highlight (seed 000) and of the mesh pass that matches it.

/// A light, in model space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Parallel light arriving from this direction (towards the light).
    Directional([f32; 3]),
    /// A point light at this position.
    Point([f32; 3]),
}

/// The chamfer highlight's light and material (seed 000: Blinn's model, eq. 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Highlight {
    /// The light.
    pub light: Light,
    /// The light's colour (linear RGB, intensity 1 = white).
    pub color: [f32; 3],
    /// Diffuse `R_d`, specular `R_s` and shininess `n` (1 to 128, any real value).
    pub material: crate::highlight::strip::Material,
    /// Share of `R_d` lit regardless of the light (0 in the paper), as [`super::MeshStyle::ambient`].
    pub ambient: f32,
    /// `K` of the blend weight `W = K r_e / (d r_max)` (§3.2); `None`: the camera's distance to the
    /// model's centre, so a strip at that distance blends by exactly the share of the pixel it covers.
    pub k: Option<f32>,
}

impl Default for Highlight {
    fn default() -> Self {
        Self {
            light: Light::Directional([0.4, 0.8, 0.45]),
            color: [1.0; 3],
            material: crate::highlight::strip::Material {
                diffuse: 0.7,
                specular: 0.5,
                shininess: 32.0,
            },
            ambient: 0.0,
            k: None,
        }
    }
}
