//! Display modes (issue 42): what CAD and BIM viewers show beyond shaded faces and visible edges —
//! the hidden part of every drawn edge in a style of its own, edges fading with distance, and the
//! faces drawn shaded, in the background colour (hidden-line), translucent (X-ray) or not at all
//! (wireframe). Declared once as a schema ([`DisplaySettings`]) that `chamfer render`'s flags, the
//! page's display panel, the viewer and Bevy's component are made from.
//!
//! A hidden edge is the part of a drawn edge that the scene's depth hides. The techniques that
//! draw it (joined, McGuire–Hughes, fins) draw their lists a second time through `*_hidden`
//! pipelines: the same shaders with `HIDDEN` overridden and the depth test reversed (`Greater`
//! against the same biased depth), so the visible and the hidden pass split each edge's pixels
//! exactly, and whatever wrote the depth (another object too) hides it.

use crate::schema::{FINITE, Numbers, Schema, SchemaError};

use super::layout::{DISPLAY_FADE, DISPLAY_FADE_ORTHO, DISPLAY_HIDDEN, DISPLAY_HIDDEN_COLOR};
use super::layout::{DISPLAY_PIXELS, DisplayFrame};
use super::{Camera, MeshStyle, Technique};

/// The most dash and gap lengths a [`LinePattern::Dashes`] holds.
pub const MAX_DASHES: usize = 8;

/// How a line is broken along its length, measured in screen pixels from the start of each drawn
/// edge (so a still line's pattern does not crawl as the camera moves).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LinePattern {
    /// Unbroken.
    Solid,
    /// Dash, gap, dash, gap, ... lengths in pixels (at most [`MAX_DASHES`]; an odd count repeats
    /// the whole list once more with dashes and gaps swapped, as SVG's `stroke-dasharray` does).
    Dashes {
        /// The lengths; only the first `count` are used.
        lengths: [f32; MAX_DASHES],
        /// How many lengths there are.
        count: usize,
    },
    /// A 32-pixel pattern repeated along the line: bit `i` set draws pixel `i` of each 32
    /// (iTwin.js's `LinePixels`: `0xCCCCCCCC` is 2 off, 2 on).
    Pixels(u32),
}

impl LinePattern {
    /// Dashes of `lengths` (pixels); `Solid` if there are none or none is a gap, `None` if there
    /// are more than [`MAX_DASHES`] or a length is negative or not finite.
    pub fn dashes(lengths: &[f32]) -> Option<Self> {
        if lengths.len() > MAX_DASHES || lengths.iter().any(|l| !l.is_finite() || *l < 0.0) {
            return None;
        }
        let total: f32 = lengths.iter().sum();
        let gaps = lengths.iter().skip(1).step_by(2).any(|&g| g > 0.0);
        if lengths.is_empty() || total <= 0.0 || (!gaps && lengths.len().is_multiple_of(2)) {
            return Some(Self::Solid);
        }
        let mut all = [0.0; MAX_DASHES];
        all[..lengths.len()].copy_from_slice(lengths);
        Some(Self::Dashes {
            lengths: all,
            count: lengths.len(),
        })
    }

    /// True if the pixel `along` pixels from the pattern's start is drawn (the CPU's reading of
    /// what `display.wgsl`'s `in_pattern` does, for tests and for documentation).
    pub fn draws(&self, along: f32) -> bool {
        match *self {
            Self::Solid => true,
            Self::Pixels(bits) => (bits >> (along.floor().rem_euclid(32.0) as u32)) & 1 == 1,
            Self::Dashes { lengths, count } => {
                let lengths = &lengths[..count];
                // An odd list is read twice, the second time with dashes and gaps swapped.
                let period: f32 =
                    lengths.iter().sum::<f32>() * if count % 2 == 1 { 2.0 } else { 1.0 };
                let mut t = along.rem_euclid(period);
                for k in 0..2 * count {
                    let length = lengths[k % count];
                    if t < length {
                        return k % 2 == 0;
                    }
                    t -= length;
                }
                true
            }
        }
    }
}

/// How the hidden part of each drawn edge looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HiddenStyle {
    /// Straight RGB for every hidden edge; `None`: each edge's class colour.
    pub color: Option<[f32; 3]>,
    /// Multiplies the colour's alpha, 0 to 1.
    pub opacity: f32,
    /// Line width in pixels, at most the visible lines' (a hidden line is drawn inside the visible
    /// line's quad).
    pub width_px: f32,
    /// How the line is broken.
    pub pattern: LinePattern,
}

impl Default for HiddenStyle {
    /// A thin dashed line at 60 % opacity in each class's colour (ISO 128's thin dashed hidden
    /// line).
    fn default() -> Self {
        Self {
            color: None,
            opacity: 0.6,
            width_px: 1.0,
            pattern: LinePattern::dashes(&[6.0, 4.0]).unwrap_or(LinePattern::Solid),
        }
    }
}

/// Edges fading with their distance along the view direction (xeokit's `edgeFadeStart/End`):
/// full opacity and width up to `start`, `opacity` × and `width` × at `end` and beyond, a linear
/// ramp between. Far edges then stop "clumping into a dark mass".
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceFade {
    /// View depth (world units in front of the camera) where the fade begins.
    pub start: f32,
    /// View depth where it ends; greater than `start`.
    pub end: f32,
    /// Opacity multiple at `end`, 0 to 1.
    pub opacity: f32,
    /// Width multiple at `end`, 0 to 1.
    pub width: f32,
}

/// How the faces are drawn under the edges.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum FaceMode {
    /// Lit faces (the mesh pass's own style).
    #[default]
    Shaded,
    /// Faces in the background colour: they hide what is behind them and show nothing themselves.
    HiddenLine,
    /// Faces at this opacity (0 to 1), depth written: the nearest face of each pixel is blended
    /// once, so no sorting is needed and the result does not depend on draw order; the faces
    /// behind it are not seen, the edges behind it are (in the hidden style).
    XRay(f32),
    /// No faces and no depth from them: every drawn edge is visible.
    Wireframe,
}

impl FaceMode {
    /// The mesh pass's style for this mode, from the shaded style and the background colour
    /// (straight RGBA); `None`: draw no mesh.
    pub fn mesh_style(self, shaded: MeshStyle, background: [f32; 4]) -> Option<MeshStyle> {
        match self {
            Self::Shaded => Some(shaded),
            // All ambient, no specular: the colour exactly.
            Self::HiddenLine => Some(MeshStyle {
                color: [background[0], background[1], background[2], 1.0],
                ambient: 1.0,
                specular: 0.0,
                pbr: None,
                ..shaded
            }),
            Self::XRay(opacity) => {
                let [r, g, b, a] = shaded.color;
                Some(MeshStyle {
                    color: [r, g, b, a * opacity.clamp(0.0, 1.0)],
                    ..shaded
                })
            }
            Self::Wireframe => None,
        }
    }
}

/// What a frame shows beyond visible edges, as an [`EdgeStyle`](super::EdgeStyle) carries it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Display {
    /// Draw the hidden part of each drawn edge in this style.
    pub hidden: Option<HiddenStyle>,
    /// Fade edges with distance.
    pub fade: Option<DistanceFade>,
}

impl Display {
    /// The uniform's part the draw passes read, for `camera`.
    pub(crate) fn frame(&self, camera: &Camera) -> DisplayFrame {
        let mut out = DisplayFrame::default();
        if let Some(hidden) = &self.hidden {
            out.flags |= DISPLAY_HIDDEN;
            if let Some([r, g, b]) = hidden.color {
                out.flags |= DISPLAY_HIDDEN_COLOR;
                out.hidden_color = [r, g, b, 1.0];
            }
            let width = if hidden.width_px.is_finite() {
                hidden.width_px.clamp(0.0, 4096.0)
            } else {
                0.0
            };
            out.hidden = [hidden.opacity.clamp(0.0, 1.0), width, 0.0, 0.0];
            match hidden.pattern {
                LinePattern::Solid => {}
                LinePattern::Pixels(bits) => {
                    out.flags |= DISPLAY_PIXELS;
                    out.pixels = bits;
                }
                LinePattern::Dashes { lengths, count } => {
                    let count = count.min(MAX_DASHES);
                    // An odd list is written twice over (dashes and gaps swapped the second time).
                    let doubled = if count % 2 == 1 { 2 * count } else { count };
                    let mut all = [0.0f32; 2 * MAX_DASHES];
                    for (k, slot) in all.iter_mut().take(doubled).enumerate() {
                        *slot = lengths[k % count];
                    }
                    out.hidden[2] = all.iter().sum();
                    out.hidden[3] = doubled as f32;
                    for (k, chunk) in all.chunks(4).enumerate() {
                        out.dashes[k].copy_from_slice(chunk);
                    }
                }
            }
        }
        if let Some(fade) = self.fade.filter(|f| f.start.is_finite() && f.end > f.start) {
            out.flags |= DISPLAY_FADE;
            let (start, end) = if camera.is_orthographic() {
                // Orthographic clip z is linear in depth: the fade ramps over it.
                out.flags |= DISPLAY_FADE_ORTHO;
                (clip_z(camera, fade.start), clip_z(camera, fade.end))
            } else {
                (fade.start, fade.end)
            };
            out.fade = [
                start,
                end,
                fade.opacity.clamp(0.0, 1.0),
                fade.width.clamp(0.0, 1.0),
            ];
        }
        out
    }
}

/// Clip z of a point `depth` in front of an orthographic camera (clip w is 1).
fn clip_z(camera: &Camera, depth: f32) -> f32 {
    -depth * camera.projection.z_axis.z + camera.projection.w_axis.z
}

crate::schema! {
    /// Display modes: how faces are drawn, the hidden edges' style and the distance fade.
    /// `chamfer render`'s flags, the page's display panel and Bevy's display component are made
    /// from it; [`DisplaySettings::display`] and [`DisplaySettings::faces`] turn it into the
    /// renderer's.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct DisplaySettings {
        /// Hidden-line mode: faces in the background colour, hiding what is behind them; with
        /// `hidden_edges`, hidden edges in their own style.
        hidden_line: bool = false, { group: "display", value: "", range: None, example: true,
            conflicts: [xray, wireframe], requires: [] },
        /// X-ray mode: faces at this opacity (0 to 1), the edges behind them seen through in the
        /// hidden style.
        xray: Option<f32> = None, { group: "display", value: "OPACITY", range: Some((0.0, 1.0)),
            example: Some(0.3), conflicts: [hidden_line, wireframe], requires: [] },
        /// Wireframe mode: no faces; every drawn edge shows (nothing hides another).
        wireframe: bool = false, { group: "display", value: "", range: None, example: true,
            conflicts: [hidden_line, xray, hidden_edges], requires: [] },
        /// Draw the hidden part of every drawn edge (behind a face of any object) in the hidden
        /// style (`hidden_color`, `hidden_opacity`, `hidden_width`, `hidden_dash` or
        /// `hidden_pixels`).
        hidden_edges: bool = false, { group: "display", value: "", range: None, example: true,
            conflicts: [wireframe], requires: [] },
        /// Colour of hidden edges, red,green,blue from 0 to 1. [default: each class's colour]
        hidden_color: Option<Numbers> = None, { group: "display", value: "R,G,B",
            range: Some((0.0, 1.0)), example: Some(Numbers::from_array([0.4, 0.4, 0.9])),
            conflicts: [], requires: [] },
        /// Opacity of hidden edges, 0 to 1.
        hidden_opacity: f32 = 0.6, { group: "display", value: "F", range: Some((0.0, 1.0)),
            example: 1.0, conflicts: [], requires: [] },
        /// Width of hidden edges, pixels, at most the visible edges' width.
        hidden_width: f32 = 1.0, { group: "display", value: "PX", range: Some((0.0, 1000.0)),
            example: 2.0, conflicts: [], requires: [] },
        /// The hidden edges' dash pattern: dash, gap, dash, ... lengths in pixels along the line
        /// (up to eight); `1,0` is solid.
        hidden_dash: Numbers = Numbers::from_array([6.0, 4.0]), { group: "display",
            value: "ON,OFF,...", range: Some((0.0, 1000.0)),
            example: Numbers::from_array([2.0, 2.0]), conflicts: [hidden_pixels], requires: [] },
        /// The hidden edges' pattern as 32 pixels, bit i set drawing pixel i of each 32
        /// (iTwin.js's LinePixels: 3435973836 = 0xCCCCCCCC is 2 off, 2 on).
        hidden_pixels: Option<u64> = None, { group: "display", value: "BITS",
            range: Some((0.0, 4294967295.0)), example: Some(0xF0F0_F0F0),
            conflicts: [hidden_dash], requires: [] },
        /// Edges fade from this view depth on (world units in front of the camera).
        fade_start: Option<f32> = None, { group: "display", value: "D", range: Some((0.0, FINITE)),
            example: Some(1.0), conflicts: [], requires: [fade_end] },
        /// ... to this one, where they reach `fade_opacity` and `fade_width`.
        fade_end: Option<f32> = None, { group: "display", value: "D", range: Some((0.0, FINITE)),
            example: Some(4.0), conflicts: [], requires: [fade_start] },
        /// Opacity multiple of edges at `fade_end` and beyond, 0 to 1.
        fade_opacity: f32 = 0.0, { group: "display", value: "F", range: Some((0.0, 1.0)),
            example: 0.5, conflicts: [], requires: [] },
        /// Width multiple of edges at `fade_end` and beyond, 0 to 1.
        fade_width: f32 = 0.5, { group: "display", value: "F", range: Some((0.0, 1.0)),
            example: 1.0, conflicts: [], requires: [] },
    }
}

impl DisplaySettings {
    /// Refuses values out of range, a colour that is not three numbers, a dash list longer than
    /// [`MAX_DASHES`] and a fade that ends before it starts.
    pub fn check(&self) -> Result<(), SchemaError> {
        self.check_combinations()?;
        self.check_ranges()?;
        if let Some(color) = &self.hidden_color
            && color.as_slice().len() != 3
        {
            return Err(SchemaError::Invalid {
                name: "hidden_color",
                reason: format!(
                    "must be three numbers r,g,b, not {}",
                    color.as_slice().len()
                ),
            });
        }
        if LinePattern::dashes(self.hidden_dash.as_slice()).is_none() {
            return Err(SchemaError::Invalid {
                name: "hidden_dash",
                reason: format!(
                    "must be at most {MAX_DASHES} lengths of at least 0, not {}",
                    self.hidden_dash
                ),
            });
        }
        if let (Some(start), Some(end)) = (self.fade_start, self.fade_end)
            && end <= start
        {
            return Err(SchemaError::Invalid {
                name: "fade_end",
                reason: format!("must be greater than the fade's start {start}, not {end}"),
            });
        }
        Ok(())
    }

    /// [`check`](Self::check), and refuses hidden edges that `technique` cannot draw or wider
    /// than the visible edges' `edge_width` (a hidden line is drawn inside the visible one's quad).
    pub fn check_for(&self, technique: &Technique, edge_width: f32) -> Result<(), SchemaError> {
        self.check()?;
        if self.hidden().is_none() {
            return Ok(());
        }
        if !technique.draws_hidden_edges() {
            return Err(SchemaError::Invalid {
                name: if self.hidden_edges {
                    "hidden_edges"
                } else {
                    "xray"
                },
                reason: format!(
                    "needs a technique that draws hidden edges (joined), not {}",
                    technique.name()
                ),
            });
        }
        if self.hidden_width > edge_width {
            return Err(SchemaError::Invalid {
                name: "hidden_width",
                reason: format!(
                    "must be at most the edge width {edge_width}, not {}",
                    self.hidden_width
                ),
            });
        }
        Ok(())
    }

    /// How the faces are drawn.
    pub fn faces(&self) -> FaceMode {
        match (self.hidden_line, self.xray, self.wireframe) {
            (true, _, _) => FaceMode::HiddenLine,
            (_, Some(opacity), _) => FaceMode::XRay(opacity),
            (_, _, true) => FaceMode::Wireframe,
            _ => FaceMode::Shaded,
        }
    }

    /// The hidden style, if hidden edges are drawn (asked for, or X-ray).
    pub fn hidden(&self) -> Option<HiddenStyle> {
        let shown = self.hidden_edges || (self.xray.is_some() && !self.wireframe);
        shown.then(|| HiddenStyle {
            color: self.hidden_color.and_then(|c| match c.as_slice() {
                &[r, g, b] => Some([r, g, b]),
                _ => None,
            }),
            opacity: self.hidden_opacity,
            width_px: self.hidden_width,
            pattern: match self.hidden_pixels {
                Some(bits) => LinePattern::Pixels(u32::try_from(bits).unwrap_or(u32::MAX)),
                None => {
                    LinePattern::dashes(self.hidden_dash.as_slice()).unwrap_or(LinePattern::Solid)
                }
            },
        })
    }

    /// The distance fade, if both its distances are given.
    pub fn fade(&self) -> Option<DistanceFade> {
        Some(DistanceFade {
            start: self.fade_start?,
            end: self.fade_end?,
            opacity: self.fade_opacity,
            width: self.fade_width,
        })
    }

    /// What the edges' style carries of it.
    pub fn display(&self) -> Display {
        Display {
            hidden: self.hidden(),
            fade: self.fade(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dash_patterns_read_as_svg_reads_them() {
        let p = LinePattern::dashes(&[6.0, 4.0]).expect("valid");
        let drawn: Vec<bool> = (0..20).map(|x| p.draws(x as f32 + 0.5)).collect();
        assert_eq!(drawn.iter().filter(|&&d| d).count(), 12);
        assert!(p.draws(0.5) && p.draws(5.5) && !p.draws(6.5) && !p.draws(9.5) && p.draws(10.5));
        // An odd list: 3 on 2 off 1 on 3 off 2 on 1 off.
        let odd = LinePattern::dashes(&[3.0, 2.0, 1.0]).expect("valid");
        let bits: String = (0..12)
            .map(|x| if odd.draws(x as f32 + 0.5) { '#' } else { '.' })
            .collect();
        assert_eq!(bits, "###..#...##.");
        assert_eq!(LinePattern::dashes(&[1.0, 0.0]), Some(LinePattern::Solid));
        assert_eq!(LinePattern::dashes(&[]), Some(LinePattern::Solid));
        assert_eq!(LinePattern::dashes(&[1.0; 9]), None);
        assert_eq!(LinePattern::dashes(&[1.0, -1.0]), None);
        let pixels = LinePattern::Pixels(0xCCCC_CCCC);
        let bits: String = (0..8)
            .map(|x| {
                if pixels.draws(x as f32 + 0.5) {
                    '#'
                } else {
                    '.'
                }
            })
            .collect();
        assert_eq!(bits, "..##..##");
    }

    /// Each entry's example is valid and changes what is drawn; wrong values are refused.
    #[test]
    fn every_example_changes_the_display_and_bad_values_are_refused() {
        let looks = |s: &DisplaySettings| (s.faces(), s.display());
        let default = DisplaySettings::default();
        assert_eq!(default.check(), Ok(()));
        assert_eq!(looks(&default), (FaceMode::Shaded, Display::default()));
        for entry in DisplaySettings::ENTRIES {
            let mut settings = DisplaySettings {
                hidden_edges: entry.name != "hidden_edges" && entry.name != "wireframe",
                ..DisplaySettings::default()
            };
            if entry.name.starts_with("fade") {
                settings.fade_start = Some(1.0);
                settings.fade_end = Some(4.0);
                if entry.name == "fade_start" {
                    settings.fade_start = None;
                } else if entry.name == "fade_end" {
                    settings.fade_end = None;
                }
            }
            let before = looks(&settings);
            entry.set_example(&mut settings);
            assert_eq!(settings.check(), Ok(()), "{}", entry.name);
            assert_ne!(looks(&settings), before, "{}", entry.name);
        }
        for (bad, message) in [
            (
                DisplaySettings {
                    hidden_line: true,
                    wireframe: true,
                    ..DisplaySettings::default()
                },
                "options hidden_line and wireframe cannot both be given",
            ),
            (
                DisplaySettings {
                    hidden_color: Some(Numbers::from_array([1.0, 0.0])),
                    ..DisplaySettings::default()
                },
                "option hidden_color must be three numbers r,g,b, not 2",
            ),
            (
                DisplaySettings {
                    hidden_dash: Numbers::from_array([1.0; 9]),
                    ..DisplaySettings::default()
                },
                "option hidden_dash must be at most 8 lengths of at least 0, not 1,1,1,1,1,1,1,1,1",
            ),
            (
                DisplaySettings {
                    fade_start: Some(5.0),
                    fade_end: Some(2.0),
                    ..DisplaySettings::default()
                },
                "option fade_end must be greater than the fade's start 5, not 2",
            ),
            (
                DisplaySettings {
                    fade_start: Some(5.0),
                    ..DisplaySettings::default()
                },
                "option fade_start needs option fade_end",
            ),
            (
                DisplaySettings {
                    xray: Some(1.5),
                    ..DisplaySettings::default()
                },
                "option xray must be 0 to 1, not 1.5",
            ),
        ] {
            assert_eq!(
                bad.check().map_err(|e| e.to_string()),
                Err(message.to_owned()),
                "{bad:?}"
            );
        }
    }

    #[test]
    fn hidden_edges_need_a_technique_that_draws_them_and_a_narrower_width() {
        let hidden = DisplaySettings {
            hidden_edges: true,
            ..DisplaySettings::default()
        };
        assert_eq!(hidden.check_for(&Technique::Joined, 2.0), Ok(()));
        let error = |s: &DisplaySettings, t: &Technique, w: f32| {
            s.check_for(t, w)
                .map_err(|e| e.spelled(crate::schema::flag))
        };
        assert_eq!(
            error(&hidden, &Technique::HalfHex, 2.0),
            Err(
                "--hidden-edges needs a technique that draws hidden edges (joined), not half-hex"
                    .into()
            )
        );
        assert_eq!(
            error(&hidden, &Technique::Joined, 0.5),
            Err("--hidden-width must be at most the edge width 0.5, not 1".into())
        );
        // Without hidden edges any technique and width will do.
        assert_eq!(
            DisplaySettings::default().check_for(&Technique::HalfHex, 0.5),
            Ok(())
        );
    }

    #[test]
    fn face_modes_style_the_mesh_pass() {
        let shaded = MeshStyle::default();
        let white = [1.0; 4];
        assert_eq!(FaceMode::Shaded.mesh_style(shaded, white), Some(shaded));
        let hidden_line = FaceMode::HiddenLine
            .mesh_style(shaded, white)
            .expect("drawn");
        assert_eq!((hidden_line.color, hidden_line.ambient), ([1.0; 4], 1.0));
        let xray = FaceMode::XRay(0.25)
            .mesh_style(shaded, white)
            .expect("drawn");
        assert_eq!(xray.color[3], 0.25);
        assert_eq!(FaceMode::Wireframe.mesh_style(shaded, white), None);
    }
}
