//! A drawing on paper, for every vector format ([`svg`](super::svg), [`pdf`](super::pdf),
//! [`dxf`](super::dxf)): the scale (paper millimetres per model unit, or 96 dpi), the sheet that
//! fits the lines with a margin, and the layers (one per line role) in drawing order.

use super::style::{DrawingStyle, Role};
use super::{Drawing, LineSet};

/// Millimetres per pixel of the frame when no scale is given: 96 pixels per inch, the CSS pixel,
/// so a browser shows the drawing at the size of the equivalent `chamfer render`.
pub const MM_PER_PX_96_DPI: f64 = 25.4 / 96.0;

/// How to lay a drawing out on paper, for every format. Start from [`PaperOptions::DEFAULT`] and change it with the `with_*` setters.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PaperOptions {
    /// Paper millimetres per model unit, in the plane through the model's centre facing the camera
    /// (everywhere for an orthographic camera); `None`: 1 px of the frame is 1/96 inch.
    pub mm_per_unit: Option<f64>,
    /// The drawing's title (e.g. the source file's name).
    pub title: String,
    /// Free text for the `<desc>` element (e.g. the camera), after the units and scale.
    pub description: String,
}

/// The widest line of `style`, for the margin around the lines.
pub(crate) fn widest_mm(style: &DrawingStyle) -> f64 {
    Role::ALL
        .iter()
        .map(|&role| style.role(role).weight_mm)
        .fold(0.0, f64::max)
}

/// The roles with lines in `drawing`, in drawing order, with their sets.
pub(crate) fn layers(drawing: &Drawing) -> Vec<(Role, Vec<&LineSet>)> {
    Role::ALL
        .iter()
        .map(|&role| {
            let sets: Vec<&LineSet> = drawing
                .lines
                .iter()
                .filter(|set| Role::of(set.class, set.hidden) == role && !set.polylines.is_empty())
                .collect();
            (role, sets)
        })
        .filter(|(_, sets)| !sets.is_empty())
        .collect()
}

impl PaperOptions {
    /// 96 dpi, no title.
    pub const DEFAULT: Self = Self {
        mm_per_unit: None,
        title: String::new(),
        description: String::new(),
    };

    /// Sets [`mm_per_unit`](Self::mm_per_unit).
    pub fn with_mm_per_unit(self, mm_per_unit: Option<f64>) -> Self {
        Self {
            mm_per_unit,
            ..self
        }
    }

    /// Sets [`title`](Self::title).
    pub fn with_title(self, title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            ..self
        }
    }

    /// Sets [`description`](Self::description).
    pub fn with_description(self, description: impl Into<String>) -> Self {
        Self {
            description: description.into(),
            ..self
        }
    }
}

impl Default for PaperOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Millimetres per frame pixel for these options.
pub fn mm_per_px(drawing: &Drawing, options: &PaperOptions) -> f64 {
    options.mm_per_px_at(drawing.units_per_px)
}

impl PaperOptions {
    /// Millimetres per frame pixel for a drawing of `units_per_px` model units per pixel
    /// ([`units_per_px`](super::units_per_px)), known before drawing.
    pub fn mm_per_px_at(&self, units_per_px: f64) -> f64 {
        match self.mm_per_unit {
            Some(mm) if mm.is_finite() && mm > 0.0 && units_per_px > 0.0 => mm * units_per_px,
            _ => MM_PER_PX_96_DPI,
        }
    }
}

/// The sheet: millimetres per frame pixel and the corners of the area the lines fill (with a
/// margin of the widest line plus 1 mm; the whole frame when nothing is drawn), in millimetres
/// from the frame's top-left corner, y down.
pub(crate) struct Sheet {
    pub k: f64,
    pub lo: [f64; 2],
    pub hi: [f64; 2],
}

impl Sheet {
    pub(crate) fn new(drawing: &Drawing, style: &DrawingStyle, options: &PaperOptions) -> Self {
        let k = mm_per_px(drawing, options);
        let (lo, hi) = drawing
            .lines
            .iter()
            .flat_map(|set| set.polylines.iter().flatten())
            .fold(
                ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                |(lo, hi), p| {
                    let p = p.map(|c| f64::from(c) * k);
                    (
                        [lo[0].min(p[0]), lo[1].min(p[1])],
                        [hi[0].max(p[0]), hi[1].max(p[1])],
                    )
                },
            );
        let (lo, hi) = if lo[0] <= hi[0] {
            let margin = widest_mm(style) + 1.0;
            (
                [lo[0] - margin, lo[1] - margin],
                [hi[0] + margin, hi[1] + margin],
            )
        } else {
            let [w, h] = drawing.viewport.map(|v| f64::from(v) * k);
            ([0.0, 0.0], [w, h])
        };
        Self { k, lo, hi }
    }
}

/// The words a drawing's description gives its section plane, so the same section can be asked
/// for again (the flag's `nx,ny,nz,d`, normal made unit).
pub fn section_note(plane: &chamfer_runtime::section::Plane) -> String {
    let [x, y, z] = plane.normal.map(|c| c as f32);
    format!(" Section: --section {x},{y},{z},{}.", plane.offset as f32)
}

/// What one model unit is, for scales written as ratios (`1:50`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelUnit {
    /// Millimetres (3MF's default, and STL's by convention).
    Millimetre,
    /// Centimetres.
    Centimetre,
    /// Metres (glTF's).
    Metre,
    /// Inches.
    Inch,
    /// Feet.
    Foot,
}

impl ModelUnit {
    /// Every unit, with its name on the command line and in Python.
    pub const ALL: [(&'static str, Self); 5] = [
        ("mm", Self::Millimetre),
        ("cm", Self::Centimetre),
        ("m", Self::Metre),
        ("in", Self::Inch),
        ("ft", Self::Foot),
    ];

    /// The unit named `name` (`mm`, `cm`, `m`, `in`, `ft`).
    pub fn named(name: &str) -> Result<Self, String> {
        Self::ALL
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, unit)| unit)
            .ok_or_else(|| format!("unknown unit {name:?} (mm, cm, m, in, ft)"))
    }

    /// Its length in millimetres.
    pub const fn millimetres(self) -> f64 {
        match self {
            Self::Millimetre => 1.0,
            Self::Centimetre => 10.0,
            Self::Metre => 1000.0,
            Self::Inch => 25.4,
            Self::Foot => 304.8,
        }
    }
}

/// Paper millimetres per model unit from a scale as drafters write it: a number (millimetres per
/// model unit) or a ratio `A:B` (A paper lengths for B real ones: `1:50`, `2:1`), real lengths in
/// `unit`. Refuses what is not a positive finite scale.
pub fn parse_scale(text: &str, unit: ModelUnit) -> Result<f64, String> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    let refused = || {
        format!(
            "a scale is millimetres per model unit (20) or a ratio paper:real (1:50), not {text:?}"
        )
    };
    let mm_per_unit = match text.split_once(':') {
        Some((paper, real)) => {
            let paper: f64 = paper.trim().parse().map_err(|_| refused())?;
            let real: f64 = real.trim().parse().map_err(|_| refused())?;
            if !(positive(paper) && positive(real)) {
                return Err(refused());
            }
            unit.millimetres() * paper / real
        }
        None => text.trim().parse().map_err(|_| refused())?,
    };
    if positive(mm_per_unit) {
        Ok(mm_per_unit)
    } else {
        Err(refused())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scales_are_numbers_or_ratios_of_the_model_unit() {
        assert_eq!(parse_scale("20", ModelUnit::Millimetre), Ok(20.0));
        assert_eq!(parse_scale("1:50", ModelUnit::Millimetre), Ok(0.02));
        assert_eq!(parse_scale("1:50", ModelUnit::Metre), Ok(20.0));
        assert_eq!(parse_scale("2:1", ModelUnit::Inch), Ok(50.8));
        for bad in ["0", "-1", "1:0", "a:b", "1:-5", "NaN", "inf", "", "1:50:2"] {
            assert!(parse_scale(bad, ModelUnit::Metre).is_err(), "{bad}");
        }
        assert_eq!(ModelUnit::named("ft"), Ok(ModelUnit::Foot));
        assert!(ModelUnit::named("yd").is_err());
    }
}
