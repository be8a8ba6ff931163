//! What the page asks for, as JSON: the bake options and the view (camera, technique, style). Unknown
//! keys and values out of range are errors; the defaults are `chamfer bake`'s and `chamfer render`'s,
//! so the page and the commands make the same asset and the same picture.

use chamfer_preprocess::draw::LineClass;
pub use chamfer_preprocess::schema::BakeSettings;
use chamfer_runtime::render::{
    Camera, DEFAULT_LIGHT_DIRECTION, DisplaySettings, EdgeClasses, EdgeStyle, Light, MeshStyle,
    Orbit, Shading, StyleSettings, Technique,
};
use chamfer_runtime::rig::AnimationSettings;
use chamfer_runtime::schema::{Schema, Value};
use chamfer_runtime::section::{ClipPlanes, CutSettings, Section};
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

/// The view's settings (`chamfer render`'s flags of the same names). The camera's keys are the
/// view schema's ([`Orbit`], which the page's view panel is made from), beside the others in one
/// JSON object.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct ViewSettings {
    /// `--azimuth`, `--elevation`, `--distance`, `--fov-y`, `--ortho`: read from the object's keys
    /// of those names (see [`ViewSettings::from_json`]).
    #[serde(skip)]
    pub orbit: Orbit,
    /// `--edge-width`, `--samples`, the highlight's material and light numbers: read from the
    /// object's keys of the style schema's names.
    #[serde(skip)]
    pub look: StyleSettings,
    /// `--section`, `--section-box`: read from the object's keys of the section schema's names
    /// (the page's section slider sets `section`).
    #[serde(skip)]
    pub section: Section,
    /// `--no-caps`, `--cap-*`, `--cut-outline-*`: the keys of the cut schema's names.
    #[serde(skip)]
    pub cut: CutSettings,
    /// `--hidden-line`, `--xray`, `--wireframe`, `--hidden-*`, `--fade-*`: the keys of the display
    /// schema's names.
    #[serde(skip)]
    pub display: DisplaySettings,
    /// `--animation`, `--time`, `--pose`: the keys of the animation schema's names.
    #[serde(skip)]
    pub animation: AnimationSettings,
    /// `--technique`, by name.
    pub technique: String,
    /// The technique's own parameters by their names in its table (`{"step": 3}` for a `hybrid-*`
    /// technique: `chamfer render --hybrid-step 3`), set over the preset's.
    pub parameters: serde_json::Map<String, serde_json::Value>,
    /// `--classes`, by name.
    pub classes: Vec<String>,
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
            orbit: Orbit::default(),
            look: StyleSettings::default(),
            section: Section::default(),
            cut: CutSettings::default(),
            display: DisplaySettings::default(),
            animation: AnimationSettings::default(),
            technique: Technique::default().name().to_owned(),
            parameters: serde_json::Map::new(),
            classes: EdgeClasses::names().map(str::to_owned).collect(),
            highlight: HighlightModel::Off,
            edge_color: None,
            background: [1.0; 4],
        }
    }
}

/// Reads bake settings from JSON; an empty string is the defaults.
pub fn bake_settings(json: &str) -> Result<BakeSettings, String> {
    if json.trim().is_empty() {
        return Ok(BakeSettings::default());
    }
    serde_json::from_str(json).map_err(|e| format!("bake settings: {e}"))
}

impl ViewSettings {
    /// Reads settings from JSON and checks them; an empty string is the defaults. The keys of
    /// the view schema's entries go to the camera, the style schema's to the look, the others to
    /// the rest, each refusing what it does not know (serde's `flatten` cannot refuse unknown
    /// keys).
    pub fn from_json(json: &str) -> Result<Self, String> {
        if json.trim().is_empty() {
            return Ok(Self::default());
        }
        let error = |e: serde_json::Error| format!("view settings: {e}");
        let mut keys: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(json).map_err(error)?;
        let camera = take_keys(&mut keys, Orbit::ENTRIES.iter().map(|e| e.name));
        let look = take_keys(&mut keys, StyleSettings::ENTRIES.iter().map(|e| e.name));
        let section = take_keys(&mut keys, Section::ENTRIES.iter().map(|e| e.name));
        let cut = take_keys(&mut keys, CutSettings::ENTRIES.iter().map(|e| e.name));
        let display = take_keys(&mut keys, DisplaySettings::ENTRIES.iter().map(|e| e.name));
        let animation = take_keys(&mut keys, AnimationSettings::ENTRIES.iter().map(|e| e.name));
        let mut settings: Self =
            serde_json::from_value(serde_json::Value::Object(keys)).map_err(error)?;
        settings.orbit = serde_json::from_value(camera).map_err(error)?;
        settings.look = serde_json::from_value(look).map_err(error)?;
        settings.section = serde_json::from_value(section).map_err(error)?;
        settings.cut = serde_json::from_value(cut).map_err(error)?;
        settings.display = serde_json::from_value(display).map_err(error)?;
        settings.animation = serde_json::from_value(animation).map_err(error)?;
        settings.check()?;
        Ok(settings)
    }

    fn check(&self) -> Result<(), String> {
        self.orbit.check().map_err(|e| e.to_string())?;
        self.look.check().map_err(|e| e.to_string())?;
        self.section.check().map_err(|e| e.to_string())?;
        self.cut.check().map_err(|e| e.to_string())?;
        self.animation.check().map_err(|e| e.to_string())?;
        let unit = |c: &[f32; 4]| c.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v));
        if !unit(&self.background) || self.edge_color.as_ref().is_some_and(|c| !unit(c)) {
            return Err("colours are four numbers from 0 to 1".into());
        }
        self.display
            .check_for(&self.technique()?, self.look.edge_width)
            .map_err(|e| e.to_string())?;
        self.classes()?;
        Ok(())
    }

    /// The technique named, with the parameters given set over its preset's and checked.
    pub fn technique(&self) -> Result<Technique, String> {
        let mut technique = Technique::from_name(&self.technique).ok_or_else(|| {
            format!(
                "no technique '{}' (one of {})",
                self.technique,
                Technique::names().join(", ")
            )
        })?;
        for (name, json) in &self.parameters {
            let known = technique
                .parameters()
                .map(|p| p.names())
                .unwrap_or_default();
            let kind = technique
                .parameters()
                .and_then(|p| p.kind(name))
                .ok_or_else(|| {
                    format!(
                        "technique {}: no parameter {name} (its parameters: {})",
                        self.technique,
                        if known.is_empty() {
                            "none".into()
                        } else {
                            known.join(", ")
                        }
                    )
                })?;
            let value = Value::from_json(kind, json).ok_or_else(|| {
                format!(
                    "technique {}: parameter {name} must be a {}, not {json}",
                    self.technique,
                    kind.name()
                )
            })?;
            technique
                .set_parameter(name, value)
                .map_err(|e| format!("technique {}: {e}", self.technique))?;
        }
        technique
            .check_parameters()
            .map_err(|e| format!("technique {}: {e}", self.technique))?;
        Ok(technique)
    }

    fn classes(&self) -> Result<EdgeClasses, String> {
        EdgeClasses::from_names(self.classes.iter().map(String::as_str))
            .map_err(|name| format!("no edge class '{name}'"))
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
        Camera::orbit(bounds, &self.orbit, viewport)
    }

    /// The edges' style, as `chamfer render` builds it from the same flags.
    pub fn edge_style(&self) -> Result<EdgeStyle, String> {
        let mut style = self.look.edges(EdgeStyle {
            technique: self.technique()?,
            classes: self.classes()?,
            highlight: self
                .shading()
                .map(|shading| self.look.highlight(LIGHT, shading)),
            section: self.clip_planes(),
            display: self.display.display(),
            ..EdgeStyle::default()
        });
        if let Some(color) = self.edge_color {
            style.colors = chamfer_runtime::render::EdgeColors::all(color);
        }
        Ok(style)
    }

    /// The mesh pass's style in the display's face mode over the background; `None`: no faces
    /// (wireframe).
    pub fn faces_style(&self) -> Option<MeshStyle> {
        self.display
            .faces()
            .mesh_style(self.mesh_style(), self.background)
    }

    /// The mesh pass's style: the runtime's default, or with a highlight the highlight's own model
    /// (as `chamfer render --style chamfer`), so strips and faces are lit alike.
    pub fn mesh_style(&self) -> MeshStyle {
        let style = match self.shading() {
            None => MeshStyle::default(),
            Some(shading) => self.look.mesh_style(&self.look.highlight(LIGHT, shading)),
        };
        MeshStyle {
            section: self.clip_planes(),
            ..style
        }
    }

    /// The section's planes (checked when the settings were read), as `chamfer render --section`
    /// makes them.
    pub fn clip_planes(&self) -> ClipPlanes {
        ClipPlanes::from_section(&self.section).unwrap_or_default()
    }

    /// The cut faces' and outline's style, as `chamfer render` makes it from the same flags.
    pub fn cut_style(&self) -> chamfer_runtime::render::CutStyle {
        chamfer_runtime::render::CutStyle::from_settings(self.clip_planes(), &self.cut)
    }

    fn shading(&self) -> Option<Shading> {
        match self.highlight {
            HighlightModel::Off => None,
            HighlightModel::Blinn => Some(Shading::Blinn(self.look.blinn())),
            HighlightModel::Pbr => Some(Shading::Pbr(self.look.pbr(StyleSettings::BASE_COLOR))),
        }
    }
}

/// The chamfer highlight's light: `chamfer render --light-dir`'s default.
const LIGHT: Light = Light::Directional(DEFAULT_LIGHT_DIRECTION);

/// The entries of `keys` named in `names`, taken out of it, as one JSON object.
fn take_keys<'a>(
    keys: &mut serde_json::Map<String, serde_json::Value>,
    names: impl Iterator<Item = &'a str>,
) -> serde_json::Value {
    serde_json::Value::Object(names.filter_map(|name| keys.remove_entry(name)).collect())
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
            (r#"{"elevation": 95}"#, "elevation must be -90 to 90"),
            (r#"{"fov_y": 0}"#, "fov_y must be 1 to 170"),
            ("[1, 2]", "view settings"),
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

    /// Every entry of the style schema set to its example in the page's JSON reaches the look,
    /// and changes the edges, the highlight or the mesh pass (with the highlight on).
    #[test]
    fn every_style_schema_entry_sets_the_look() {
        let looks = |view: &ViewSettings| {
            (
                view.edge_style().expect("style"),
                view.mesh_style(),
                view.look.samples,
            )
        };
        for highlight in ["blinn", "pbr"] {
            let json = serde_json::json!({ "highlight": highlight });
            let default = looks(&ViewSettings::from_json(&json.to_string()).expect("defaults"));
            for entry in StyleSettings::ENTRIES {
                let example = entry.example().expect("an example").to_json();
                let json = serde_json::json!({ entry.name: example, "highlight": highlight });
                let view = ViewSettings::from_json(&json.to_string()).expect(entry.name);
                let mut look = StyleSettings::default();
                entry.set_example(&mut look);
                assert_eq!(view.look, look, "{}", entry.name);
                // The Blinn numbers do not change a PBR highlight, nor the PBR ones a Blinn one.
                let blinn_only = ["diffuse", "specular", "shininess"].contains(&entry.name);
                let pbr_only = ["roughness", "metallic"].contains(&entry.name);
                if (highlight == "pbr" && !blinn_only) || (highlight == "blinn" && !pbr_only) {
                    assert_ne!(looks(&view), default, "{} with {highlight}", entry.name);
                }
            }
        }
    }

    /// Every entry of the view schema set to its example in the page's JSON reaches the camera.
    #[test]
    fn every_view_schema_entry_sets_the_camera() {
        let bounds = [[-1.0; 3], [1.0; 3]];
        let default = ViewSettings::default().camera(bounds, [64, 48]);
        for entry in Orbit::ENTRIES {
            let example = entry.example().expect("an example").to_json();
            let json = serde_json::json!({ entry.name: example, "technique": "joined" });
            let view = ViewSettings::from_json(&json.to_string()).expect(entry.name);
            let mut orbit = Orbit::default();
            entry.set_example(&mut orbit);
            assert_eq!(view.orbit, orbit, "{}", entry.name);
            assert_ne!(view.camera(bounds, [64, 48]), default, "{}", entry.name);
        }
    }

    /// Every entry of the section and cut schemas set to its example in the page's JSON reaches
    /// the section (the mesh's and the edges' planes) or the cut style, as `chamfer render`'s flags
    /// of the same names set them; malformed ones are refused with the reason.
    #[test]
    fn every_section_and_cut_entry_sets_the_view() {
        for entry in Section::ENTRIES {
            let example = entry.example().expect("an example").to_json();
            let json = serde_json::json!({ entry.name: example });
            let view = ViewSettings::from_json(&json.to_string()).expect(entry.name);
            let mut section = Section::default();
            entry.set_example(&mut section);
            assert_eq!(view.section, section, "{}", entry.name);
            let planes = ClipPlanes::from_section(&section).expect("planes");
            assert!(!planes.is_empty());
            assert_eq!(view.edge_style().expect("style").section, planes);
            assert_eq!(view.mesh_style().section, planes);
            assert_eq!(view.cut_style().section, planes);
        }
        let base = serde_json::json!({ "section": [1, 0, 0, 0], "cap_hatch_spacing": 4 });
        let default = ViewSettings::from_json(&base.to_string())
            .expect("base")
            .cut_style();
        for entry in CutSettings::ENTRIES {
            let mut json = base.clone();
            json[entry.name] = entry.example().expect("an example").to_json();
            let view = ViewSettings::from_json(&json.to_string()).expect(entry.name);
            assert_ne!(view.cut_style(), default, "{}", entry.name);
        }
        for (json, expected) in [
            (r#"{"section": [1, 0, 0]}"#, "section must be 1 to 6 planes"),
            (r#"{"section": "1,0,0,0"}"#, "view settings"),
            (
                r#"{"cap_color": [1, 0]}"#,
                "cap_color must be three numbers",
            ),
            (r#"{"cut_outline_width": -1}"#, "cut_outline_width must be"),
        ] {
            let message = ViewSettings::from_json(json).expect_err(json);
            assert!(message.contains(expected), "{json}: {message}");
        }
    }

    /// Every display schema entry, given with its example (over hidden edges and a fade, which
    /// some entries style), reaches the edge style or the faces as `chamfer render`'s flag of the
    /// same name does; conflicting modes and a hidden line wider than the edges are refused.
    #[test]
    fn every_display_entry_reaches_the_edges_or_the_faces() {
        let base = serde_json::json!({ "hidden_edges": true, "fade_start": 0.5, "fade_end": 8 });
        let looks = |view: &ViewSettings| {
            (
                view.edge_style().expect("style").display,
                view.faces_style(),
            )
        };
        for entry in DisplaySettings::ENTRIES {
            // Hidden edges off where the entry is hidden edges or wireframe (which excludes them).
            let mut before = base.clone();
            if ["hidden_edges", "wireframe"].contains(&entry.name) {
                before["hidden_edges"] = false.into();
            }
            let plain = ViewSettings::from_json(&before.to_string()).expect("base");
            let mut json = before.clone();
            json[entry.name] = entry.example().expect("an example").to_json();
            let view = ViewSettings::from_json(&json.to_string()).expect(entry.name);
            let mut display = plain.display;
            entry.set_example(&mut display);
            assert_eq!(view.display, display, "{}", entry.name);
            assert_ne!(looks(&view), looks(&plain), "{}", entry.name);
        }
        for (json, expected) in [
            (
                r#"{"hidden_line": true, "xray": 0.5}"#,
                "hidden_line and xray cannot both be given",
            ),
            (
                r#"{"hidden_edges": true, "hidden_width": 3}"#,
                "hidden_width must be at most the edge width 2",
            ),
            (
                r#"{"hidden_edges": true, "technique": "plug"}"#,
                "hidden_edges needs a technique that draws hidden edges",
            ),
            (r#"{"fade_end": 3}"#, "fade_end needs option fade_start"),
        ] {
            let message = ViewSettings::from_json(json).expect_err(json);
            assert!(message.contains(expected), "{json}: {message}");
        }
    }

    /// Every parameter of every technique that has some, given with its example in the view
    /// settings' `parameters`, reaches the edge style's technique, as `chamfer render`'s flag of
    /// the same entry sets it (preprocess/tests/cli.rs); a parameter of another technique, one of
    /// the wrong kind and one out of range are refused.
    #[test]
    fn every_technique_parameter_sets_the_technique() {
        let mut set = 0;
        for preset in Technique::presets() {
            let Some(table) = preset.technique.parameters() else {
                continue;
            };
            for entry in table.schema_json().as_array().expect("a table") {
                let name = entry["name"].as_str().expect("a name");
                let json = serde_json::json!({
                    "technique": preset.name,
                    "parameters": { name: entry["example"] },
                });
                let view = ViewSettings::from_json(&json.to_string()).expect(name);
                let technique = view.edge_style().expect("a style").technique;
                let value = Value::from_json(table.kind(name).expect("a kind"), &entry["example"]);
                assert_eq!(
                    technique.parameters().and_then(|p| p.get(name)),
                    value,
                    "{name}"
                );
                assert_ne!(technique, preset.technique, "{} {name}", preset.name);
                set += 1;
            }
        }
        assert!(set >= 9, "{set} parameters");
        for (json, error) in [
            (
                r#"{"technique": "joined", "parameters": {"step": 3}}"#,
                "no parameter step (its parameters: none)",
            ),
            (
                r#"{"technique": "hybrid-edges", "parameters": {"thickness": 3}}"#,
                "no parameter thickness",
            ),
            (
                r#"{"technique": "hybrid-edges", "parameters": {"step": true}}"#,
                "must be a number",
            ),
            (
                r#"{"technique": "hybrid-edges", "parameters": {"step": 900}}"#,
                "step must be 1 to 64",
            ),
        ] {
            let message = ViewSettings::from_json(json).expect_err(json);
            assert!(message.contains(error), "{json}: {message}");
        }
    }

    #[test]
    fn a_highlight_lights_strips_and_faces_with_one_model() {
        let view = ViewSettings::from_json(r#"{"highlight": "pbr"}"#).expect("pbr");
        let highlight = view.edge_style().expect("style").highlight.expect("on");
        let pbr = StyleSettings::default().pbr(StyleSettings::BASE_COLOR);
        assert_eq!(highlight.shading, Shading::Pbr(pbr));
        assert_eq!(view.mesh_style().pbr, Some(pbr));
        assert_eq!(highlight.color, [std::f32::consts::PI; 3]);
    }
}
