//! What the page asks for, as JSON: the bake options and the view (camera, technique, style). Unknown
//! keys and values out of range are errors; the defaults are `chamfer bake`'s and `chamfer render`'s,
//! so the page and the commands make the same asset and the same picture.

use chamfer_preprocess::draw::LineClass;
pub use chamfer_preprocess::schema::BakeSettings;
use chamfer_runtime::highlight::ggx::PbrMaterial;
use chamfer_runtime::highlight::strip::Material;
use chamfer_runtime::render::{
    Camera, EdgeClasses, EdgeStyle, Highlight, Light, MeshLight, MeshStyle, Orbit, Shading,
    Technique,
};
use serde::Deserialize;

/// How the chamfer highlight is shaded, if at all (`chamfer render --style chamfer --shading`).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum HighlightModel {
    /// Plain lines (`--style edges`).
    #[default]
    Off,
    /// Seed 000's Blinn model.
    Blinn,
    /// glTF's metallic-roughness model.
    Pbr,
}

/// The view's settings (`chamfer render`'s flags of the same names).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct ViewSettings {
    /// `--azimuth`, degrees.
    pub azimuth: f32,
    /// `--elevation`, degrees.
    pub elevation: f32,
    /// `--distance`, mesh units (`None`: frame the model).
    pub distance: Option<f32>,
    /// `--ortho`.
    pub ortho: bool,
    /// `--technique`, by name.
    pub technique: String,
    /// `--edge-width`, pixels.
    pub edge_width: f32,
    /// `--classes`, by name.
    pub classes: Vec<String>,
    /// `--samples` (1 or 4).
    pub samples: u32,
    /// `--style chamfer --shading blinn|pbr`, or plain edges.
    pub highlight: HighlightModel,
    /// Colour of every edge class, linear RGBA 0 to 1 (`None`: the runtime's colours per class).
    pub edge_color: Option<[f32; 4]>,
    /// The background, linear RGBA 0 to 1 (`chamfer render`: white).
    pub background: [f32; 4],
}

impl Default for ViewSettings {
    fn default() -> Self {
        Self {
            azimuth: 35.0,
            elevation: 25.0,
            distance: None,
            ortho: false,
            technique: Technique::default().name().to_owned(),
            edge_width: 2.0,
            classes: CLASSES.iter().map(|(name, _)| (*name).to_owned()).collect(),
            samples: 4,
            highlight: HighlightModel::Off,
            edge_color: None,
            background: [1.0; 4],
        }
    }
}

/// The edge classes by name, as `chamfer render --classes` spells them.
pub const CLASSES: [(&str, EdgeClasses); 6] = [
    ("contour", EdgeClasses::CONTOUR),
    ("boundary", EdgeClasses::BOUNDARY),
    ("marked", EdgeClasses::MARKED),
    ("ridge", EdgeClasses::RIDGE),
    ("valley", EdgeClasses::VALLEY),
    ("intersection", EdgeClasses::INTERSECTION),
];

/// The chamfer highlight's light: `chamfer render --light-dir`'s default.
const LIGHT: Light = Light::Directional([0.4, 0.8, 0.45]);
/// `chamfer render`'s Blinn material (`--diffuse`, `--specular`, `--shininess`) and `--ambient`.
const BLINN: Material = Material {
    diffuse: 0.75,
    specular: 0.5,
    shininess: 32.0,
};
const AMBIENT: f32 = 0.2;
/// `chamfer render`'s PBR material (`--base-color`, `--metallic`, `--roughness`).
const PBR: PbrMaterial = PbrMaterial {
    base_color: [0.8; 3],
    metallic: 0.0,
    roughness: 0.4,
};

/// Reads bake settings from JSON; an empty string is the defaults.
pub fn bake_settings(json: &str) -> Result<BakeSettings, String> {
    if json.trim().is_empty() {
        return Ok(BakeSettings::default());
    }
    serde_json::from_str(json).map_err(|e| format!("bake settings: {e}"))
}

impl ViewSettings {
    /// Reads settings from JSON and checks them; an empty string is the defaults.
    pub fn from_json(json: &str) -> Result<Self, String> {
        let settings: Self = if json.trim().is_empty() {
            Self::default()
        } else {
            serde_json::from_str(json).map_err(|e| format!("view settings: {e}"))?
        };
        settings.check()?;
        Ok(settings)
    }

    fn check(&self) -> Result<(), String> {
        if !self.azimuth.is_finite() || !self.elevation.is_finite() {
            return Err("azimuth and elevation must be finite".into());
        }
        if self.distance.is_some_and(|d| !(d.is_finite() && d > 0.0)) {
            return Err("distance must be a positive number".into());
        }
        if !(self.edge_width.is_finite() && (0.0..=1000.0).contains(&self.edge_width)) {
            return Err(format!(
                "edge_width must be 0 to 1000 pixels, not {}",
                self.edge_width
            ));
        }
        if self.samples != 1 && self.samples != 4 {
            return Err(format!("samples must be 1 or 4, not {}", self.samples));
        }
        let unit = |c: &[f32; 4]| c.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v));
        if !unit(&self.background) || self.edge_color.as_ref().is_some_and(|c| !unit(c)) {
            return Err("colours are four numbers from 0 to 1".into());
        }
        self.technique()?;
        self.classes()?;
        Ok(())
    }

    /// The technique named.
    pub fn technique(&self) -> Result<Technique, String> {
        Technique::from_name(&self.technique).ok_or_else(|| {
            format!(
                "no technique '{}' (one of {})",
                self.technique,
                Technique::names().join(", ")
            )
        })
    }

    fn classes(&self) -> Result<EdgeClasses, String> {
        self.classes
            .iter()
            .try_fold(EdgeClasses::NONE, |all, name| {
                let (_, class) = CLASSES
                    .iter()
                    .find(|(known, _)| known == name)
                    .ok_or_else(|| format!("no edge class '{name}'"))?;
                Ok(EdgeClasses(all.0 | class.0))
            })
    }

    /// The drawing's line classes for the classes drawn (ridges and valleys are its creases).
    pub fn line_classes(&self) -> Result<Vec<LineClass>, String> {
        let drawn = self.classes()?;
        let mut lines: Vec<LineClass> = [
            (EdgeClasses::CONTOUR, LineClass::Contour),
            (EdgeClasses::BOUNDARY, LineClass::Boundary),
            (EdgeClasses::MARKED, LineClass::Marked),
            (EdgeClasses::CREASE, LineClass::Crease),
            (EdgeClasses::INTERSECTION, LineClass::Intersection),
        ]
        .into_iter()
        .filter(|(class, _)| drawn.intersects(*class))
        .map(|(_, line)| line)
        .collect();
        lines.dedup();
        Ok(lines)
    }

    /// The orbit camera framing `bounds` in a `viewport`, as `chamfer render` places it.
    pub fn camera(&self, bounds: [[f32; 3]; 2], viewport: [u32; 2]) -> Camera {
        let orbit = Orbit {
            azimuth_deg: self.azimuth,
            elevation_deg: self.elevation,
            distance: self.distance,
            orthographic: self.ortho,
            ..Orbit::default()
        };
        Camera::orbit(bounds, &orbit, viewport)
    }

    /// The edges' style, as `chamfer render` builds it from the same flags.
    pub fn edge_style(&self) -> Result<EdgeStyle, String> {
        let highlight = self.shading().map(|shading| Highlight {
            light: LIGHT,
            color: [self.light_intensity(); 3],
            shading,
            ambient: AMBIENT,
            k: None,
            ..Highlight::default()
        });
        let mut style = EdgeStyle {
            technique: self.technique()?,
            classes: self.classes()?,
            highlight,
            width_px: self.edge_width,
            ..EdgeStyle::default()
        };
        if let Some(color) = self.edge_color {
            style.colors = chamfer_runtime::render::EdgeColors::all(color);
        }
        Ok(style)
    }

    /// The mesh pass's style: the runtime's default, or with a highlight the highlight's own model
    /// (as `chamfer render --style chamfer`), so strips and faces are lit alike.
    pub fn mesh_style(&self) -> MeshStyle {
        match self.shading() {
            None => MeshStyle::default(),
            Some(shading) => MeshStyle {
                color: [BLINN.diffuse, BLINN.diffuse, BLINN.diffuse, 1.0],
                light: MeshLight::Model(LIGHT),
                light_color: [self.light_intensity(); 3],
                ambient: AMBIENT,
                specular: BLINN.specular,
                shininess: BLINN.shininess,
                pbr: match shading {
                    Shading::Pbr(material) => Some(material),
                    Shading::Blinn(_) => None,
                },
            },
        }
    }

    fn shading(&self) -> Option<Shading> {
        match self.highlight {
            HighlightModel::Off => None,
            HighlightModel::Blinn => Some(Shading::Blinn(BLINN)),
            HighlightModel::Pbr => Some(Shading::Pbr(PBR)),
        }
    }

    /// `chamfer render --light-intensity`'s default: 1 for Blinn, π for PBR.
    fn light_intensity(&self) -> f32 {
        match self.highlight {
            HighlightModel::Pbr => std::f32::consts::PI,
            _ => 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_settings_are_the_commands_defaults() {
        let view = ViewSettings::from_json("").expect("defaults");
        assert_eq!(view, ViewSettings::default());
        let style = view.edge_style().expect("style");
        assert_eq!(style.technique, Technique::default());
        assert_eq!(style.classes, EdgeClasses::ALL);
        assert_eq!(style.width_px, 2.0);
        let (options, compact) = bake_settings("{}")
            .and_then(|b| b.options().map_err(|e| e.to_string()))
            .expect("bake defaults");
        assert_eq!(options, chamfer_preprocess::BakeOptions::DEFAULT);
        assert!(compact.is_none());
    }

    #[test]
    fn bad_settings_are_refused_with_the_reason() {
        for (json, expected) in [
            (r#"{"technique": "crayon"}"#, "no technique 'crayon'"),
            (r#"{"classes": ["ridge", "seam"]}"#, "no edge class 'seam'"),
            (r#"{"samples": 3}"#, "samples must be 1 or 4"),
            (r#"{"edge_width": -1}"#, "edge_width must be 0 to 1000"),
            (
                r#"{"background": [1, 1, 2, 1]}"#,
                "colours are four numbers",
            ),
            (r#"{"zoom": 2}"#, "unknown field `zoom`"),
            (r#"{"azimuth": "left"}"#, "view settings"),
        ] {
            let error = ViewSettings::from_json(json).expect_err(json);
            assert!(error.contains(expected), "{json}: {error}");
        }
        for (json, expected) in [
            (r#"{"crease_deg": -5}"#, "crease"),
            (r#"{"position_bits": 40}"#, "position"),
            (r#"{"stitch": 1}"#, "unknown field `stitch`"),
            (
                r#"{"radius": 1, "radius_rel": 0.01}"#,
                "cannot both be given",
            ),
        ] {
            let error = bake_settings(json)
                .and_then(|b| b.options().map(|_| ()).map_err(|e| e.to_string()))
                .expect_err(json);
            assert!(error.contains(expected), "{json}: {error}");
        }
    }

    #[test]
    fn a_highlight_lights_strips_and_faces_with_one_model() {
        let view = ViewSettings::from_json(r#"{"highlight": "pbr"}"#).expect("pbr");
        let highlight = view.edge_style().expect("style").highlight.expect("on");
        assert_eq!(highlight.shading, Shading::Pbr(PBR));
        assert_eq!(view.mesh_style().pbr, Some(PBR));
        assert_eq!(highlight.color, [std::f32::consts::PI; 3]);
    }
}
