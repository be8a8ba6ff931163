//! Line roles and their styles for drawings (issue 43): every line of a drawing has one role —
//! cut, hatch, silhouette, boundary, visible, intersection or hidden — and each role is a layer
//! (an SVG group, a PDF optional content group, a DXF layer) with its own weight, colour and dash
//! pattern. The styles are one schema ([`DrawingStyle`]) that `chamfer draw`'s flags, a JSON style
//! file and Python's keywords are made from. The default weights follow ISO 128-2: wide (0.7 mm)
//! for cut outlines, 0.5 for outlines, 0.35 for edges, 0.25 dashed (12 d dashes, 3 d gaps) for
//! hidden lines, 0.18 for hatches (ISO 128-50).

use std::path::{Path, PathBuf};

use chamfer_runtime::schema::{Numbers, Schema, SchemaError};

use super::LineClass;

/// What a line is on paper.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Role {
    /// The cut outline.
    Cut,
    /// The hatch of cut faces.
    Hatch,
    /// Visible contours.
    Silhouette,
    /// Visible boundaries.
    Boundary,
    /// Visible creases and marked edges.
    Visible,
    /// Visible intersection edges.
    Intersection,
    /// The hidden part of any line.
    Hidden,
}

impl Role {
    /// Every role, in drawing order (hidden lines first, under the rest).
    pub const ALL: [Self; 7] = [
        Self::Hidden,
        Self::Hatch,
        Self::Visible,
        Self::Intersection,
        Self::Boundary,
        Self::Silhouette,
        Self::Cut,
    ];

    /// The role's name: its layer's name, and the prefix of its style entries.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Cut => "cut",
            Self::Hatch => "hatch",
            Self::Silhouette => "silhouette",
            Self::Boundary => "boundary",
            Self::Visible => "visible",
            Self::Intersection => "intersection",
            Self::Hidden => "hidden",
        }
    }

    /// The role of a line of `class`, hidden or not.
    pub const fn of(class: LineClass, hidden: bool) -> Self {
        if hidden {
            return Self::Hidden;
        }
        match class {
            LineClass::Contour => Self::Silhouette,
            LineClass::Boundary => Self::Boundary,
            LineClass::Marked | LineClass::Crease => Self::Visible,
            LineClass::Intersection => Self::Intersection,
            LineClass::Cut => Self::Cut,
            LineClass::Hatch => Self::Hatch,
        }
    }
}

chamfer_runtime::schema! {
    /// How each role is drawn, and the hatch's layout. JSON style files use the same names;
    /// unknown keys are refused.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct DrawingStyle {
        /// Line weight of the `cut` role, millimetres on paper. The cut outline: where the section plane meets the surface.
        cut_weight: f32 = 0.7, { group: "drawing_style", value: "MM", range: Some((0.01, 10.0)),
            example: 1.4, conflicts: [], requires: [] },
        /// Colour of the `cut` role, red,green,blue from 0 to 1.
        cut_color: Numbers = Numbers::from_array([0.0, 0.0, 0.0]), { group: "drawing_style",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.8, 0.1, 0.1]), conflicts: [], requires: [] },
        /// Dash pattern of the `cut` role, millimetres: dash,gap[,dash,gap...]; empty: solid.
        cut_dash: Numbers = Numbers::EMPTY, { group: "drawing_style", value: "DASH,GAP",
            range: Some((0.0, 1000.0)), example: Numbers::from_array([2.0, 1.0]),
            conflicts: [], requires: [] },
        /// Line weight of the `hatch` role, millimetres on paper. The hatch of the cut faces.
        hatch_weight: f32 = 0.18, { group: "drawing_style", value: "MM", range: Some((0.01, 10.0)),
            example: 0.36, conflicts: [], requires: [] },
        /// Colour of the `hatch` role, red,green,blue from 0 to 1.
        hatch_color: Numbers = Numbers::from_array([0.0, 0.0, 0.0]), { group: "drawing_style",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.8, 0.1, 0.1]), conflicts: [], requires: [] },
        /// Dash pattern of the `hatch` role, millimetres: dash,gap[,dash,gap...]; empty: solid.
        hatch_dash: Numbers = Numbers::EMPTY, { group: "drawing_style", value: "DASH,GAP",
            range: Some((0.0, 1000.0)), example: Numbers::from_array([2.0, 1.0]),
            conflicts: [], requires: [] },
        /// Line weight of the `silhouette` role, millimetres on paper. Contours (silhouettes): one face towards the eye, one away.
        silhouette_weight: f32 = 0.5, { group: "drawing_style", value: "MM", range: Some((0.01, 10.0)),
            example: 1.0, conflicts: [], requires: [] },
        /// Colour of the `silhouette` role, red,green,blue from 0 to 1.
        silhouette_color: Numbers = Numbers::from_array([0.0, 0.0, 0.0]), { group: "drawing_style",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.8, 0.1, 0.1]), conflicts: [], requires: [] },
        /// Dash pattern of the `silhouette` role, millimetres: dash,gap[,dash,gap...]; empty: solid.
        silhouette_dash: Numbers = Numbers::EMPTY, { group: "drawing_style", value: "DASH,GAP",
            range: Some((0.0, 1000.0)), example: Numbers::from_array([2.0, 1.0]),
            conflicts: [], requires: [] },
        /// Line weight of the `boundary` role, millimetres on paper. Boundaries: edges with one face, or more than two.
        boundary_weight: f32 = 0.5, { group: "drawing_style", value: "MM", range: Some((0.01, 10.0)),
            example: 1.0, conflicts: [], requires: [] },
        /// Colour of the `boundary` role, red,green,blue from 0 to 1.
        boundary_color: Numbers = Numbers::from_array([0.0, 0.0, 0.0]), { group: "drawing_style",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.8, 0.1, 0.1]), conflicts: [], requires: [] },
        /// Dash pattern of the `boundary` role, millimetres: dash,gap[,dash,gap...]; empty: solid.
        boundary_dash: Numbers = Numbers::EMPTY, { group: "drawing_style", value: "DASH,GAP",
            range: Some((0.0, 1000.0)), example: Numbers::from_array([2.0, 1.0]),
            conflicts: [], requires: [] },
        /// Line weight of the `visible` role, millimetres on paper. Visible creases and marked edges.
        visible_weight: f32 = 0.35, { group: "drawing_style", value: "MM", range: Some((0.01, 10.0)),
            example: 0.7, conflicts: [], requires: [] },
        /// Colour of the `visible` role, red,green,blue from 0 to 1.
        visible_color: Numbers = Numbers::from_array([0.0, 0.0, 0.0]), { group: "drawing_style",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.8, 0.1, 0.1]), conflicts: [], requires: [] },
        /// Dash pattern of the `visible` role, millimetres: dash,gap[,dash,gap...]; empty: solid.
        visible_dash: Numbers = Numbers::EMPTY, { group: "drawing_style", value: "DASH,GAP",
            range: Some((0.0, 1000.0)), example: Numbers::from_array([2.0, 1.0]),
            conflicts: [], requires: [] },
        /// Line weight of the `intersection` role, millimetres on paper. Visible intersection edges.
        intersection_weight: f32 = 0.35, { group: "drawing_style", value: "MM", range: Some((0.01, 10.0)),
            example: 0.7, conflicts: [], requires: [] },
        /// Colour of the `intersection` role, red,green,blue from 0 to 1.
        intersection_color: Numbers = Numbers::from_array([0.0, 0.0, 0.0]), { group: "drawing_style",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.8, 0.1, 0.1]), conflicts: [], requires: [] },
        /// Dash pattern of the `intersection` role, millimetres: dash,gap[,dash,gap...]; empty: solid.
        intersection_dash: Numbers = Numbers::EMPTY, { group: "drawing_style", value: "DASH,GAP",
            range: Some((0.0, 1000.0)), example: Numbers::from_array([2.0, 1.0]),
            conflicts: [], requires: [] },
        /// Line weight of the `hidden` role, millimetres on paper. Hidden parts of every line.
        hidden_weight: f32 = 0.25, { group: "drawing_style", value: "MM", range: Some((0.01, 10.0)),
            example: 0.5, conflicts: [], requires: [] },
        /// Colour of the `hidden` role, red,green,blue from 0 to 1.
        hidden_color: Numbers = Numbers::from_array([0.0, 0.0, 0.0]), { group: "drawing_style",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.8, 0.1, 0.1]), conflicts: [], requires: [] },
        /// Dash pattern of the `hidden` role, millimetres: dash,gap[,dash,gap...]; empty: solid.
        hidden_dash: Numbers = Numbers::from_array([3.0, 0.75]), { group: "drawing_style",
            value: "DASH,GAP", range: Some((0.0, 1000.0)),
            example: Numbers::from_array([1.0, 1.0]), conflicts: [], requires: [] },
        /// Distance between hatch lines, millimetres on paper; 0: cut faces are not hatched.
        hatch_spacing: f32 = 2.0, { group: "drawing_style", value: "MM", range: Some((0.0, 1000.0)),
            example: 3.0, conflicts: [], requires: [] },
        /// Direction of the hatch lines, degrees counter-clockwise from the paper's x axis.
        hatch_angle: f32 = 45.0, { group: "drawing_style", value: "DEG",
            range: Some((-360.0, 360.0)), example: 135.0, conflicts: [], requires: [] },
    }
}

/// The finest dash pattern and hatch spacing taken, millimetres: finer than a pen or a printer
/// draws, and a bound on the work of a hatch (its rows) and of a PDF or SVG reader (its dashes).
pub const MIN_LENGTH_MM: f32 = 0.05;

/// One role's style, in paper millimetres.
#[derive(Clone, Debug, PartialEq)]
pub struct RoleStyle {
    /// Line weight.
    pub weight_mm: f64,
    /// Colour, red, green, blue from 0 to 1.
    pub color: [f32; 3],
    /// Dash and gap lengths, alternating; empty: solid.
    pub dash_mm: Vec<f64>,
}

impl RoleStyle {
    /// The colour as `#rrggbb`.
    pub fn hex(&self) -> String {
        let [r, g, b] = self
            .color
            .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8);
        format!("#{r:02x}{g:02x}{b:02x}")
    }
}

impl DrawingStyle {
    /// Refuses values out of range, colours that are not three numbers, and dash patterns that
    /// are not pairs of lengths (at most four pairs) with some dash.
    pub fn check(&self) -> Result<(), SchemaError> {
        self.check_ranges()?;
        if self.hatch_spacing != 0.0 && self.hatch_spacing < MIN_LENGTH_MM {
            return Err(SchemaError::Invalid {
                name: "hatch_spacing",
                reason: format!(
                    "must be 0 (no hatch) or at least {MIN_LENGTH_MM} mm, not {}",
                    self.hatch_spacing
                ),
            });
        }
        for entry in Self::ENTRIES {
            let Some(chamfer_runtime::schema::Value::Numbers(numbers)) = entry.get(self) else {
                continue;
            };
            let n = numbers.as_slice();
            let reason = if entry.name.ends_with("_color") {
                (n.len() != 3).then(|| format!("must be three numbers r,g,b, not {}", n.len()))
            } else if n.len() % 2 != 0 || n.len() > 8 {
                Some(format!(
                    "must be dash,gap pairs (up to four), not {} numbers",
                    n.len()
                ))
            } else if !n.is_empty() && n.iter().sum::<f32>() < MIN_LENGTH_MM {
                Some(format!(
                    "must be at least {MIN_LENGTH_MM} mm long in all (a pattern finer than that is a solid line to any printer)"
                ))
            } else {
                None
            };
            if let Some(reason) = reason {
                return Err(SchemaError::Invalid {
                    name: entry.name,
                    reason,
                });
            }
        }
        Ok(())
    }

    /// The hatch laid out in a frame of `mm_per_px` paper millimetres per pixel.
    pub fn hatch(&self, mm_per_px: f64) -> super::Hatch {
        super::Hatch {
            spacing_px: f64::from(self.hatch_spacing) / mm_per_px,
            angle_deg: f64::from(self.hatch_angle),
        }
    }

    /// The style of `role`.
    pub fn role(&self, role: Role) -> RoleStyle {
        let (weight, color, dash): (f32, &Numbers, &Numbers) = match role {
            Role::Cut => (self.cut_weight, &self.cut_color, &self.cut_dash),
            Role::Hatch => (self.hatch_weight, &self.hatch_color, &self.hatch_dash),
            Role::Silhouette => (
                self.silhouette_weight,
                &self.silhouette_color,
                &self.silhouette_dash,
            ),
            Role::Boundary => (
                self.boundary_weight,
                &self.boundary_color,
                &self.boundary_dash,
            ),
            Role::Visible => (self.visible_weight, &self.visible_color, &self.visible_dash),
            Role::Intersection => (
                self.intersection_weight,
                &self.intersection_color,
                &self.intersection_dash,
            ),
            Role::Hidden => (self.hidden_weight, &self.hidden_color, &self.hidden_dash),
        };
        let c = color.as_slice();
        RoleStyle {
            weight_mm: f64::from(weight),
            color: [0, 1, 2].map(|k| c.get(k).copied().unwrap_or(0.0)),
            dash_mm: dash.as_slice().iter().map(|&x| f64::from(x)).collect(),
        }
    }
}

/// The largest style file read.
pub const MAX_STYLE_FILE: u64 = 1 << 20;

/// Why a style file cannot be used; every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum StyleFileError {
    /// The file cannot be opened or read, or is not a regular file.
    #[error("{}: cannot read the style file: {reason}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// The file is larger than [`MAX_STYLE_FILE`].
    #[error("{}: a style file is at most {MAX_STYLE_FILE} bytes", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
    },
    /// The file is not a JSON object of style entries (unknown keys are refused).
    #[error("{}: not a style file: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// serde_json's message (with the line and column).
        message: String,
    },
    /// A value the style's check refuses.
    #[error("{}: {error}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The entry and why.
        error: SchemaError,
    },
}

/// Reads a JSON style file: an object with [`DrawingStyle`]'s entry names as keys (those left out
/// keep their defaults), checked. Reads at most [`MAX_STYLE_FILE`] bytes of a regular file.
pub fn read_style_file(path: &Path) -> Result<DrawingStyle, StyleFileError> {
    use std::io::Read;
    let read_error = |reason: String| StyleFileError::Read {
        path: path.to_owned(),
        reason,
    };
    // Refused before it is opened: opening a FIFO blocks until someone writes to it.
    if !std::fs::metadata(path)
        .map_err(|e| read_error(e.to_string()))?
        .is_file()
    {
        return Err(read_error("not a regular file".into()));
    }
    let file = std::fs::File::open(path).map_err(|e| read_error(e.to_string()))?;
    // And checked again on what was opened, in case the path changed in between.
    if !file
        .metadata()
        .map_err(|e| read_error(e.to_string()))?
        .is_file()
    {
        return Err(read_error("not a regular file".into()));
    }
    let mut bytes = Vec::new();
    file.take(MAX_STYLE_FILE + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| read_error(e.to_string()))?;
    if bytes.len() as u64 > MAX_STYLE_FILE {
        return Err(StyleFileError::TooLarge {
            path: path.to_owned(),
        });
    }
    let style: DrawingStyle =
        serde_json::from_slice(&bytes).map_err(|e| StyleFileError::Parse {
            path: path.to_owned(),
            message: e.to_string(),
        })?;
    style.check().map_err(|error| StyleFileError::Invalid {
        path: path.to_owned(),
        error,
    })?;
    Ok(style)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_role_has_its_three_entries_and_bad_patterns_are_refused() {
        for role in Role::ALL {
            for part in ["weight", "color", "dash"] {
                let name = format!("{}_{part}", role.name());
                assert!(DrawingStyle::entry(&name).is_ok(), "{name}");
            }
        }
        let style = DrawingStyle::default();
        assert_eq!(style.check(), Ok(()));
        assert_eq!(style.role(Role::Hidden).dash_mm, [3.0, 0.75]);
        assert_eq!(style.role(Role::Cut).weight_mm, 0.7f32 as f64);
        let odd = DrawingStyle {
            cut_dash: Numbers::from_array([1.0]),
            ..style
        };
        assert!(
            odd.check()
                .expect_err("odd")
                .to_string()
                .contains("cut_dash")
        );
        let grey = DrawingStyle {
            hatch_color: Numbers::from_array([0.5, 0.5]),
            ..style
        };
        assert!(
            grey.check()
                .expect_err("two")
                .to_string()
                .contains("hatch_color")
        );
        let bright = DrawingStyle {
            hatch_color: Numbers::from_array([0.5, 0.5, 2.0]),
            ..style
        };
        assert!(bright.check().is_err());
        assert_eq!(
            DrawingStyle {
                cut_color: Numbers::from_array([1.0, 0.5, 0.0]),
                ..style
            }
            .role(Role::Cut)
            .hex(),
            "#ff8000"
        );
    }
}
