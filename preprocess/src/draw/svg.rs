//! Writing a [`Drawing`] as SVG a CAD or BIM user can use as is: millimetre units with the scale
//! stated, one `<g>` per line class (`class="contour"`, …) inside a `visible` and a `hidden` group,
//! a `<style>` block with ISO 128 line widths and types that the user can override, polylines
//! chained end to end, and a view box that fits the lines. The output depends only on the drawing
//! and the options.

use std::fmt::Write as _;
use std::io::{self, Write};

use super::{Drawing, LineClass};

/// Millimetres per pixel of the frame when no scale is given: 96 pixels per inch, the CSS pixel,
/// so a browser shows the drawing at the size of the equivalent `chamfer render`.
pub const MM_PER_PX_96_DPI: f64 = 25.4 / 96.0;

/// How to write the SVG. Start from [`SvgOptions::DEFAULT`] and change it with the `with_*` setters.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SvgOptions {
    /// Paper millimetres per model unit, in the plane through the model's centre facing the camera
    /// (everywhere for an orthographic camera); `None`: 1 px of the frame is 1/96 inch.
    pub mm_per_unit: Option<f64>,
    /// The drawing's title (e.g. the source file's name).
    pub title: String,
    /// Free text for the `<desc>` element (e.g. the camera), after the units and scale.
    pub description: String,
}

impl SvgOptions {
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

impl Default for SvgOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The line widths and types (ISO 128-2 type 01.2 continuous wide for outlines, 01.1 continuous
/// narrow-to-medium for edges, 02.1 dashed narrow for hidden lines: dashes of 12 d, gaps of 3 d),
/// in millimetres, which are the drawing's user units.
const STYLE: &str = concat!(
    "    polyline { fill: none; stroke: #000; stroke-linecap: round; stroke-linejoin: round; }\n",
    "    .visible .contour, .visible .boundary { stroke-width: 0.5; }\n",
    "    .visible .crease, .visible .marked, .visible .intersection { stroke-width: 0.35; }\n",
    "    .hidden polyline { stroke-width: 0.25; stroke-dasharray: 3 0.75; }\n",
);

/// The widest line, for the margin around the view box.
const WIDEST_MM: f64 = 0.5;

/// Millimetres per frame pixel for these options.
pub fn mm_per_px(drawing: &Drawing, options: &SvgOptions) -> f64 {
    match options.mm_per_unit {
        Some(mm) if mm.is_finite() && mm > 0.0 && drawing.units_per_px > 0.0 => {
            mm * drawing.units_per_px
        }
        _ => MM_PER_PX_96_DPI,
    }
}

/// Writes `drawing` as an SVG document. Coordinates are millimetres (to 1 µm) from the frame's
/// top-left corner, so the view box's origin says where the lines lie in the frame.
pub fn write_svg(drawing: &Drawing, options: &SvgOptions, out: &mut impl Write) -> io::Result<()> {
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
        let margin = WIDEST_MM + 1.0;
        (
            [lo[0] - margin, lo[1] - margin],
            [hi[0] + margin, hi[1] + margin],
        )
    } else {
        // Nothing drawn: the whole frame.
        let [w, h] = drawing.viewport.map(|v| f64::from(v) * k);
        ([0.0, 0.0], [w, h])
    };
    let (width, height) = (hi[0] - lo[0], hi[1] - lo[1]);
    let scale = match options.mm_per_unit {
        Some(mm) => format!("1 model unit = {} mm", number(mm)),
        None => format!(
            "1 model unit = {} mm (1 px = 1/96 in)",
            number(k / drawing.units_per_px.max(1e-300))
        ),
    };
    let mut text = String::new();
    text += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    let _ = writeln!(
        text,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{w}mm\" height=\"{h}mm\" viewBox=\"{x} {y} {w} {h}\">",
        x = mm(lo[0]),
        y = mm(lo[1]),
        w = mm(width),
        h = mm(height),
    );
    let _ = writeln!(text, "  <title>{}</title>", escape(&options.title));
    let _ = writeln!(
        text,
        "  <desc>Hidden-line drawing by chamfer. Units: millimetres (1 user unit = 1 mm), measured \
         from the top-left corner of the {}x{} px frame, {} mm per px. Scale: {}, in the plane \
         through the model's centre facing the camera.{}{}</desc>",
        drawing.viewport[0],
        drawing.viewport[1],
        number(k),
        scale,
        if options.description.is_empty() {
            ""
        } else {
            " "
        },
        escape(&options.description)
    );
    let _ = writeln!(
        text,
        "  <style>\n    /* ISO 128 line widths (mm) and types; override these rules to restyle. */\n{STYLE}  </style>"
    );
    out.write_all(text.as_bytes())?;
    let mut open_group: Option<bool> = None;
    for set in &drawing.lines {
        if open_group != Some(set.hidden) {
            if open_group.is_some() {
                out.write_all(b"  </g>\n")?;
            }
            let name = if set.hidden { "hidden" } else { "visible" };
            writeln!(out, "  <g class=\"{name}\">")?;
            open_group = Some(set.hidden);
        }
        writeln!(out, "    <g class=\"{}\">", class_name(set.class))?;
        for polyline in &set.polylines {
            let mut line = String::with_capacity(16 * polyline.len() + 32);
            line += "      <polyline points=\"";
            for (i, p) in polyline.iter().enumerate() {
                if i > 0 {
                    line.push(' ');
                }
                let _ = write!(
                    line,
                    "{},{}",
                    mm(f64::from(p[0]) * k),
                    mm(f64::from(p[1]) * k)
                );
            }
            line += "\"/>\n";
            out.write_all(line.as_bytes())?;
        }
        out.write_all(b"    </g>\n")?;
    }
    if open_group.is_some() {
        out.write_all(b"  </g>\n")?;
    }
    out.write_all(b"</svg>\n")
}

fn class_name(class: LineClass) -> &'static str {
    class.name()
}

/// Millimetres to 1 µm, without a negative zero.
fn mm(v: f64) -> String {
    let rounded = (v * 1000.0).round() / 1000.0;
    format!("{:.3}", rounded + 0.0)
}

/// A number to f32 precision, in the shortest form that reads back the same.
fn number(v: f64) -> String {
    format!("{}", v as f32)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
