//! The numbers of a frame's look as one schema (issue 40): the edges' width and depth scaling, the
//! samples per pixel, and the chamfer highlight's material, light intensity and blend. `chamfer
//! render`'s flags and the page's view settings are made from this table, and both build the
//! highlight and the mesh pass from it with [`StyleSettings::highlight`] and
//! [`StyleSettings::mesh_style`], so their pictures agree and no front end restates a default.
//! (Directions, colours, and the technique's and classes' names are still each front end's own.)

use super::{EdgeStyle, Highlight, Light, MeshLight, MeshStyle, Shading};
use crate::highlight::ggx::PbrMaterial;
use crate::highlight::strip::Material;
use crate::schema::{FINITE, Schema, SchemaError};

crate::schema! {
    /// How edges and the chamfer highlight look: `chamfer render`'s flags of the same names
    /// (kebab-case there) and the page's view settings. [`StyleSettings::check`] refuses values
    /// out of range.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct StyleSettings {
        /// Edge width in pixels.
        edge_width: f32 = 2.0, { group: "style", value: "PX", range: Some((0.0, 1000.0)),
            example: 4.0, conflicts: [], requires: [] },
        /// Scale edge widths with depth (thesis §9.1), never below 1 px.
        depth_scaled: bool = false, { group: "style", value: "", range: None, example: true,
            conflicts: [], requires: [] },
        /// Samples per pixel (1 or 4).
        samples: u64 = 4, { group: "style", value: "N", range: Some((1.0, 4.0)), example: 1,
            conflicts: [], requires: [] },
        /// The chamfer highlight's (and its faces') diffuse reflectance R_d (Blinn).
        diffuse: f32 = 0.75, { group: "style", value: "F", range: Some((0.0, 10.0)),
            example: 0.4, conflicts: [], requires: [] },
        /// The chamfer highlight's specular reflectance R_s (Blinn).
        specular: f32 = 0.5, { group: "style", value: "F", range: Some((0.0, 10.0)),
            example: 1.5, conflicts: [], requires: [] },
        /// Share of the diffuse colour lit regardless of the light, with the chamfer highlight (0
        /// in the paper).
        ambient: f32 = 0.2, { group: "style", value: "F", range: Some((0.0, 1.0)),
            example: 0.6, conflicts: [], requires: [] },
        /// The chamfer highlight's specular exponent n, 1 to 128 (Blinn).
        shininess: f32 = 32.0, { group: "style", value: "N", range: Some((1.0, 128.0)),
            example: 4.0, conflicts: [], requires: [] },
        /// The chamfer highlight's perceptual roughness (PBR).
        roughness: f32 = 0.4, { group: "style", value: "F", range: Some((0.0, 1.0)),
            example: 0.9, conflicts: [], requires: [] },
        /// The chamfer highlight's metallic, 0 (dielectric) to 1 (metal) (PBR).
        metallic: f32 = 0.0, { group: "style", value: "F", range: Some((0.0, 1.0)),
            example: 1.0, conflicts: [], requires: [] },
        /// The light's intensity with the chamfer highlight. [default: 1 for Blinn; π for PBR,
        /// which lights a white face seen head-on to 1; point and spot lights fall off as 1/d²
        /// under PBR]
        light_intensity: Option<f32> = None, { group: "style", value: "F",
            range: Some((0.0, 1e9)), example: Some(3.0), conflicts: [], requires: [] },
        /// K of the chamfer highlight's blend weight W = K r_e / (d r_max). [default: the
        /// camera's distance to the model's centre]
        k: Option<f32> = None, { group: "style", value: "K", range: Some((0.0, FINITE)),
            example: Some(0.5), conflicts: [], requires: [] },
        /// Let the chamfer highlight's strips end in a notch where chamfer edges meet, as seed 000
        /// does, instead of drawing the rounded corner (a sphere patch) there.
        sharp_corners: bool = false, { group: "style", value: "", range: None, example: true,
            conflicts: [], requires: [] },
    }
}

impl StyleSettings {
    /// The base colour of the PBR material where a front end gives none (linear RGB).
    pub const BASE_COLOR: [f32; 3] = [0.8; 3];

    /// Refuses numbers that are not finite, values out of their ranges and samples other than 1
    /// or 4.
    pub fn check(&self) -> Result<(), SchemaError> {
        self.check_combinations()?;
        self.check_ranges()?;
        if self.samples != 1 && self.samples != 4 {
            return Err(SchemaError::Invalid {
                name: "samples",
                reason: format!("must be 1 or 4, not {}", self.samples),
            });
        }
        Ok(())
    }

    /// The Blinn material (seed 000) of the highlight and its faces.
    pub fn blinn(&self) -> Material {
        Material {
            diffuse: self.diffuse,
            specular: self.specular,
            shininess: self.shininess,
        }
    }

    /// The metallic-roughness material of the highlight and its faces, of `base_color` (linear
    /// RGB).
    pub fn pbr(&self, base_color: [f32; 3]) -> PbrMaterial {
        PbrMaterial {
            base_color,
            metallic: self.metallic,
            roughness: self.roughness,
        }
    }

    /// The chamfer highlight lit by `light` and shaded by `shading` (made with
    /// [`blinn`](Self::blinn) or [`pbr`](Self::pbr)).
    pub fn highlight(&self, light: Light, shading: Shading) -> Highlight {
        let intensity = self.light_intensity.unwrap_or(match shading {
            Shading::Blinn(_) => 1.0,
            Shading::Pbr(_) => std::f32::consts::PI,
        });
        Highlight {
            light,
            color: [intensity; 3],
            shading,
            ambient: self.ambient,
            k: self.k,
            rounded_corners: !self.sharp_corners,
        }
    }

    /// The mesh pass under `highlight`: the highlight's own model and light, so a strip and the
    /// faces around it are lit alike.
    pub fn mesh_style(&self, highlight: &Highlight) -> MeshStyle {
        MeshStyle {
            color: [self.diffuse, self.diffuse, self.diffuse, 1.0],
            light: MeshLight::Model(highlight.light),
            light_color: highlight.color,
            ambient: self.ambient,
            specular: self.specular,
            shininess: self.shininess,
            pbr: match highlight.shading {
                Shading::Pbr(material) => Some(material),
                Shading::Blinn(_) => None,
            },
            ..MeshStyle::default()
        }
    }

    /// `style` with this width and depth scaling.
    pub fn edges(&self, style: EdgeStyle) -> EdgeStyle {
        EdgeStyle {
            width_px: self.edge_width,
            depth_scaled: self.depth_scaled,
            ..style
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each entry's example is valid and changes the highlight, the mesh pass or the edges (so the
    /// front ends' tests, which set each example, prove the value arrives); wrong values are
    /// refused.
    #[test]
    fn every_example_changes_the_look_and_bad_values_are_refused() {
        let looks = |s: &StyleSettings| {
            let blinn = s.highlight(
                Light::Directional([0.4, 0.8, 0.45]),
                Shading::Blinn(s.blinn()),
            );
            let pbr = s.highlight(
                Light::Directional([0.4, 0.8, 0.45]),
                Shading::Pbr(s.pbr([0.8; 3])),
            );
            let edges = s.edges(EdgeStyle::default());
            (
                blinn,
                pbr,
                s.mesh_style(&blinn),
                edges.width_px,
                edges.depth_scaled,
                s.samples,
            )
        };
        let default = looks(&StyleSettings::default());
        assert_eq!(StyleSettings::default().check(), Ok(()));
        for entry in StyleSettings::ENTRIES {
            let mut settings = StyleSettings::default();
            entry.set_example(&mut settings);
            assert_eq!(settings.check(), Ok(()), "{}", entry.name);
            assert_ne!(looks(&settings), default, "{}", entry.name);
        }
        for bad in [
            StyleSettings {
                samples: 2,
                ..StyleSettings::default()
            },
            StyleSettings {
                shininess: 0.5,
                ..StyleSettings::default()
            },
            StyleSettings {
                edge_width: f32::NAN,
                ..StyleSettings::default()
            },
            StyleSettings {
                k: Some(-1.0),
                ..StyleSettings::default()
            },
        ] {
            assert!(bad.check().is_err(), "{bad:?}");
        }
        let error = StyleSettings {
            samples: 3,
            ..StyleSettings::default()
        }
        .check();
        assert_eq!(
            error.map_err(|e| e.spelled(crate::schema::flag)),
            Err("--samples must be 1 or 4, not 3".into())
        );
    }
}
