//! Writing a [`Drawing`] as a one-page vector PDF (pdf-writer): the page is the sheet that fits
//! the lines (as the SVG's view box), in PostScript points (1 mm = 72/25.4 pt, so printing at
//! 100 % keeps the scale), and each line role is an optional content group (a layer a PDF viewer lists and can hide) holding
//! its polylines, stroked with the role's weight, colour and dashes, round caps and joins.

use std::io::{self, Write};

use pdf_writer::types::{LineCapStyle, LineJoinStyle};
use pdf_writer::{Content, Name, Pdf, Rect, Ref, TextStr};

use super::Drawing;
use super::paper::{PaperOptions, Sheet, layers};
use super::style::DrawingStyle;

/// Points per millimetre.
const PT_PER_MM: f64 = 72.0 / 25.4;

/// Writes `drawing` as PDF 1.7.
pub fn write_pdf(
    drawing: &Drawing,
    style: &DrawingStyle,
    options: &PaperOptions,
    out: &mut impl Write,
) -> io::Result<()> {
    let Sheet { k, lo, hi } = Sheet::new(drawing, style, options);
    let [width, height] = [(hi[0] - lo[0]) * PT_PER_MM, (hi[1] - lo[1]) * PT_PER_MM];
    // Frame pixels to page points: PDF's y points up.
    let to_page = |p: [f32; 2]| {
        (
            ((f64::from(p[0]) * k - lo[0]) * PT_PER_MM) as f32,
            ((hi[1] - f64::from(p[1]) * k) * PT_PER_MM) as f32,
        )
    };
    let layers = layers(drawing);

    let mut ids = (1..).map(Ref::new);
    let mut next = || ids.next().unwrap_or(Ref::new(1));
    let (catalog, tree, page, content, info) = (next(), next(), next(), next(), next());
    let groups: Vec<Ref> = layers.iter().map(|_| next()).collect();

    let mut pdf = Pdf::new();
    pdf.set_version(1, 7);
    {
        let mut root = pdf.catalog(catalog);
        root.pages(tree);
        let mut properties = root.insert(Name(b"OCProperties")).dict();
        properties
            .insert(Name(b"OCGs"))
            .array()
            .items(groups.iter().copied());
        let mut config = properties.insert(Name(b"D")).dict();
        config
            .insert(Name(b"Order"))
            .array()
            .items(groups.iter().copied());
        config.pair(Name(b"BaseState"), Name(b"ON"));
    }
    pdf.pages(tree).kids([page]).count(1);
    for ((role, _), &id) in layers.iter().zip(&groups) {
        let mut group = pdf.indirect(id).dict();
        group.pair(Name(b"Type"), Name(b"OCG"));
        group.pair(Name(b"Name"), TextStr(role.name()));
    }
    let names: Vec<String> = (0..layers.len()).map(|i| format!("L{i}")).collect();
    {
        let mut p = pdf.page(page);
        p.parent(tree)
            .media_box(Rect::new(0.0, 0.0, width as f32, height as f32))
            .contents(content);
        let mut resources = p.resources();
        let mut list = resources.insert(Name(b"Properties")).dict();
        for (name, &id) in names.iter().zip(&groups) {
            list.pair(Name(name.as_bytes()), id);
        }
    }
    let mut stream = Content::new();
    stream.set_line_cap(LineCapStyle::RoundCap);
    stream.set_line_join(LineJoinStyle::RoundJoin);
    for ((role, sets), name) in layers.iter().zip(&names) {
        let s = style.role(*role);
        stream
            .begin_marked_content_with_properties(Name(b"OC"))
            .properties_named(Name(name.as_bytes()));
        let [r, g, b] = s.color;
        stream.set_stroke_rgb(r, g, b);
        stream.set_line_width((s.weight_mm * PT_PER_MM) as f32);
        stream.set_dash_pattern(s.dash_mm.iter().map(|&d| (d * PT_PER_MM) as f32), 0.0);
        for set in sets {
            for polyline in &set.polylines {
                let Some((&first, rest)) = polyline.split_first() else {
                    continue;
                };
                let (x, y) = to_page(first);
                stream.move_to(x, y);
                for &p in rest {
                    let (x, y) = to_page(p);
                    stream.line_to(x, y);
                }
                stream.stroke();
            }
        }
        stream.end_marked_content();
    }
    let bytes = stream.finish();
    pdf.stream(content, &bytes);
    {
        let mut document = pdf.document_info(info);
        document.title(TextStr(&options.title));
        document.producer(TextStr("chamfer"));
        document.subject(TextStr(&options.description));
    }
    out.write_all(&pdf.finish())
}
