//! Writing a [`Drawing`] as SVG a CAD or BIM user can use as is: millimetre units with the scale
//! stated, one `<g>` layer per line role ([`Role`]: `id="cut"`, …, an Inkscape layer too) holding
//! a `<g>` per line class (`class="contour"`, …), a `<style>` block with each role's weight,
//! colour and dashes (ISO 128 by default; override these rules to restyle), polylines chained end
//! to end, and a view box that fits the lines. The output depends only on the drawing and the
//! options.

use std::fmt::Write as _;
use std::io::{self, Write};

use super::paper::{PaperOptions, Sheet, layers};
use super::style::{DrawingStyle, Role};
use super::{Drawing, LineClass};

/// The style block: each role's weight, colour and dashes, in millimetres, the drawing's user
/// units.
fn style_rules(style: &DrawingStyle) -> String {
    let mut rules = String::from(
        "    polyline { fill: none; stroke-linecap: round; stroke-linejoin: round; }\n",
    );
    for role in Role::ALL {
        let s = style.role(role);
        let dash = if s.dash_mm.is_empty() {
            String::new()
        } else {
            let lengths: Vec<String> = s.dash_mm.iter().map(|&d| number(d)).collect();
            format!(" stroke-dasharray: {};", lengths.join(" "))
        };
        let _ = writeln!(
            rules,
            "    #{} polyline {{ stroke: {}; stroke-width: {};{dash} }}",
            role.name(),
            s.hex(),
            number(s.weight_mm),
        );
    }
    rules
}

/// Writes `drawing` as an SVG document. Coordinates are millimetres (to 1 µm) from the frame's
/// top-left corner, so the view box's origin says where the lines lie in the frame.
pub fn write_svg(
    drawing: &Drawing,
    style: &DrawingStyle,
    options: &PaperOptions,
    out: &mut impl Write,
) -> io::Result<()> {
    let Sheet { k, lo, hi } = Sheet::new(drawing, style, options);
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
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" version=\"1.1\" width=\"{w}mm\" height=\"{h}mm\" viewBox=\"{x} {y} {w} {h}\">",
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
        "  <style>\n    /* Line roles: weights (mm), colours and dashes; override these rules to restyle. */\n{}  </style>",
        style_rules(style)
    );
    out.write_all(text.as_bytes())?;
    for (role, sets) in layers(drawing) {
        writeln!(
            out,
            "  <g id=\"{0}\" class=\"{0}\" inkscape:groupmode=\"layer\" inkscape:label=\"{0}\">",
            role.name()
        )?;
        for set in sets {
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
        out.write_all(b"  </g>\n")?;
    }
    out.write_all(b"</svg>\n")
}

fn class_name(class: LineClass) -> &'static str {
    class.name()
}

/// Millimetres to 1 µm, without a negative zero.
pub(crate) fn mm(v: f64) -> String {
    let rounded = (v * 1000.0).round() / 1000.0;
    format!("{:.3}", rounded + 0.0)
}

/// A number to f32 precision, in the shortest form that reads back the same.
pub(crate) fn number(v: f64) -> String {
    format!("{}", v as f32)
}

pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
