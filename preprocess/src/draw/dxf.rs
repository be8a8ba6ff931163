//! Writing a [`Drawing`] as DXF (the `dxf` crate; AutoCAD 2004 text, the first with true colours): one layer per line role,
//! named after it, with a line type holding the role's dash pattern; each polyline an LWPOLYLINE on
//! its role's layer (closed where it is a loop) in the role's colour (true colour) and line weight
//! (the nearest of DXF's standard weights, at most 2.11 mm; set per entity, because the crate's
//! `LineWeight` has no public constructor for a layer's value). The line types carry no shape
//! codes (group 74), which ezdxf reads and which strict readers may want.
//! Units are millimetres on paper ($INSUNITS 4, $MEASUREMENT metric), y up, the sheet's lower
//! left corner at the origin. The header's dates are the Unix epoch and its GUIDs nil, so the
//! output depends only on the drawing and the options.

use std::io::{self, Write};

use dxf::entities::{Entity, EntityType, LwPolyline};
use dxf::enums::{AcadVersion, Units};
use dxf::tables::{Layer, LineType};
use dxf::{Color, LwPolylineVertex};

use super::Drawing;
use super::paper::{PaperOptions, Sheet, layers};
use super::style::DrawingStyle;

/// Writes `drawing` as DXF.
pub fn write_dxf(
    drawing: &Drawing,
    style: &DrawingStyle,
    options: &PaperOptions,
    out: &mut impl Write,
) -> io::Result<()> {
    let Sheet { k, lo, hi } = Sheet::new(drawing, style, options);
    let to_paper = |p: [f32; 2]| (f64::from(p[0]) * k - lo[0], hi[1] - f64::from(p[1]) * k);
    let mut dxf = dxf::Drawing::new();
    dxf.header.version = AcadVersion::R2004;
    dxf.header.default_drawing_units = Units::Millimeters;
    dxf.header.drawing_units = dxf::enums::DrawingUnits::Metric;
    dxf.header.project_name = options.title.clone();
    // The same drawing gives the same file: no clock, no random GUIDs.
    let epoch = chrono::DateTime::<chrono::Utc>::UNIX_EPOCH;
    dxf.header.creation_date_universal = epoch;
    dxf.header.update_date_universal = epoch;
    if let Some(local) =
        chrono::TimeZone::from_local_datetime(&chrono::Local, &epoch.naive_utc()).earliest()
    {
        dxf.header.creation_date = local;
        dxf.header.update_date = local;
    }
    dxf.header.fingerprint_guid = uuid::Uuid::nil();
    dxf.header.version_guid = uuid::Uuid::nil();
    for (role, sets) in layers(drawing) {
        let s = style.role(role);
        let line_type = if s.dash_mm.is_empty() {
            "CONTINUOUS".to_owned()
        } else {
            let name = format!("CHAMFER_{}", role.name().to_uppercase());
            // DXF dash lengths: positive dashes, negative gaps.
            let elements: Vec<f64> = s
                .dash_mm
                .iter()
                .enumerate()
                .map(|(i, &d)| if i % 2 == 0 { d } else { -d })
                .collect();
            dxf.add_line_type(LineType {
                name: name.clone(),
                description: format!("{} lines", role.name()),
                total_pattern_length: s.dash_mm.iter().sum(),
                element_count: elements.len() as i32,
                dash_dot_space_lengths: elements,
                ..LineType::default()
            });
            name
        };
        let [r, g, b] = s.color.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as i32);
        dxf.add_layer(Layer {
            name: role.name().to_owned(),
            line_type_name: line_type,
            // ACI 7 (black on paper, white on a dark screen) where the true colour is black,
            // which DXF writers leave out as "unset".
            color: Color::from_index(7),
            ..Layer::default()
        });
        let true_color = (r << 16) | (g << 8) | b;
        let weight = standard_lineweight(s.weight_mm);
        for set in sets {
            for polyline in &set.polylines {
                let closed = polyline.len() > 2 && polyline.first() == polyline.last();
                let points = if closed {
                    &polyline[..polyline.len() - 1]
                } else {
                    &polyline[..]
                };
                let mut entity = LwPolyline::default();
                entity.vertices = points
                    .iter()
                    .map(|&p| {
                        let (x, y) = to_paper(p);
                        LwPolylineVertex {
                            x,
                            y,
                            ..LwPolylineVertex::default()
                        }
                    })
                    .collect();
                entity.set_is_closed(closed);
                let mut entity = Entity::new(EntityType::LwPolyline(entity));
                entity.common.layer = role.name().to_owned();
                entity.common.color_24_bit = true_color;
                entity.common.lineweight_enum_value = weight;
                dxf.add_entity(entity);
            }
        }
    }
    dxf.save(out).map_err(|e| io::Error::other(e.to_string()))
}

/// The DXF line weights (hundredths of a millimetre): readers accept only these.
const LINEWEIGHTS: [i16; 24] = [
    0, 5, 9, 13, 15, 18, 20, 25, 30, 35, 40, 50, 53, 60, 70, 80, 90, 100, 106, 120, 140, 158, 200,
    211,
];

/// The DXF line weight nearest `mm`.
fn standard_lineweight(mm: f64) -> i16 {
    let wanted = mm * 100.0;
    LINEWEIGHTS
        .into_iter()
        .min_by(|&a, &b| {
            (f64::from(a) - wanted)
                .abs()
                .total_cmp(&(f64::from(b) - wanted).abs())
        })
        .unwrap_or(0)
}
