//! Section planes (issue 43): the half-spaces that cut a model open, declared once as a schema
//! (`Section`) that `chamfer render` and `chamfer draw` flags, Python's keywords, the page's
//! section panel and Bevy's section component are made from. A plane `n·p = d` keeps the points
//! with `n·p <= d`: its normal points at the part that is cut away, towards a viewer looking at
//! the cut face. A box keeps what lies inside it (six planes).

use crate::schema::{FINITE, Numbers, Schema, SchemaError};

/// The most planes a section has (a box is six).
pub const MAX_PLANES: usize = 6;

crate::schema! {
    /// Where the model is cut. No plane and no box: the model is whole.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct Section {
        /// Section planes, four numbers each: `nx,ny,nz,d` keeps the points p with n·p <= d (n
        /// points at the part cut away; it need not be unit length). Up to six planes, one after
        /// the other; all of them cut.
        section: Option<Numbers> = None, { group: "section", value: "NX,NY,NZ,D",
            range: None,
            example: Some(Numbers::from_array([1.0, 0.0, 0.0, 0.0])),
            conflicts: [section_box], requires: [] },
        /// A section box, `xmin,ymin,zmin,xmax,ymax,zmax` in model units: keeps what lies inside.
        section_box: Option<Numbers> = None, { group: "section", value: "X0,Y0,Z0,X1,Y1,Z1",
            range: None,
            example: Some(Numbers::from_array([-0.25, -0.25, -0.25, 0.25, 0.25, 0.25])),
            conflicts: [section], requires: [] },
    }
}

crate::schema! {
    /// How a renderer shows a section's cuts: the cut faces of closed meshes (solid, or hatched on
    /// the screen or on the model) and the cut outline. `chamfer render`'s flags, the page's section
    /// panel and Bevy's section component are made from it; `CutStyle::from_settings` (in
    /// `render`) turns it into the renderer's style.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct CutSettings {
        /// Leave the cut faces open instead of filling them.
        no_caps: bool = false, { group: "section", value: "", range: None, example: true,
            conflicts: [], requires: [] },
        /// Colour of the cut faces, red,green,blue from 0 to 1.
        cap_color: Numbers = Numbers::from_array([0.55, 0.2, 0.2]), { group: "section",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.2, 0.5, 0.8]), conflicts: [], requires: [] },
        /// Hatch lines over the cut faces, this far apart: pixels, or model units with
        /// --cap-hatch-in-model; 0: a solid fill.
        cap_hatch_spacing: f32 = 0.0, { group: "section", value: "D", range: Some((0.0, FINITE)),
            example: 8.0, conflicts: [], requires: [] },
        /// Angle of the hatch lines, degrees counter-clockwise from the screen's x axis (or the
        /// plane's first axis on the model).
        cap_hatch_angle: f32 = 45.0, { group: "section", value: "DEG", range: Some((-360.0, 360.0)),
            example: -30.0, conflicts: [], requires: [] },
        /// Width of the hatch lines, pixels.
        cap_hatch_width: f32 = 1.5, { group: "section", value: "PX", range: Some((0.0, 1000.0)),
            example: 3.0, conflicts: [], requires: [] },
        /// Colour of the hatch lines, red,green,blue from 0 to 1.
        cap_hatch_color: Numbers = Numbers::from_array([0.1, 0.1, 0.1]), { group: "section",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([1.0, 1.0, 1.0]), conflicts: [], requires: [] },
        /// Fix the hatch to the model (spacing in model units) instead of the screen.
        cap_hatch_in_model: bool = false, { group: "section", value: "", range: None,
            example: true, conflicts: [], requires: [] },
        /// Width of the cut outline (where the plane meets the surface), pixels; 0: none.
        cut_outline_width: f32 = 2.5, { group: "section", value: "PX", range: Some((0.0, 1000.0)),
            example: 5.0, conflicts: [], requires: [] },
        /// Colour of the cut outline, red,green,blue from 0 to 1.
        cut_outline_color: Numbers = Numbers::from_array([0.05, 0.05, 0.05]), { group: "section",
            value: "R,G,B", range: Some((0.0, 1.0)),
            example: Numbers::from_array([0.9, 0.6, 0.0]), conflicts: [], requires: [] },
    }
}

impl CutSettings {
    /// Refuses values out of range and colours that are not three numbers.
    pub fn check(&self) -> Result<(), SchemaError> {
        self.check_combinations()?;
        self.check_ranges()?;
        for (name, color) in [
            ("cap_color", &self.cap_color),
            ("cap_hatch_color", &self.cap_hatch_color),
            ("cut_outline_color", &self.cut_outline_color),
        ] {
            if color.as_slice().len() != 3 {
                return Err(SchemaError::Invalid {
                    name,
                    reason: format!(
                        "must be three numbers r,g,b, not {}",
                        color.as_slice().len()
                    ),
                });
            }
        }
        Ok(())
    }

    /// The cap colour, hatch colour and outline colour as opaque RGBA (a colour that is not three
    /// numbers, which [`check`](Self::check) refuses, reads as black).
    pub fn colors(&self) -> [[f32; 4]; 3] {
        [
            &self.cap_color,
            &self.cap_hatch_color,
            &self.cut_outline_color,
        ]
        .map(|c| match c.as_slice() {
            &[r, g, b] => [r, g, b, 1.0],
            _ => [0.0, 0.0, 0.0, 1.0],
        })
    }
}

/// A plane `normal·p = offset` that keeps `normal·p <= offset`; the normal is unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal, pointing at the part cut away.
    pub normal: [f64; 3],
    /// Signed distance of the plane from the origin along the normal.
    pub offset: f64,
}

impl Plane {
    /// Signed distance of `p` from the plane: positive on the side cut away.
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        let [x, y, z] = self.normal;
        x * p[0] + y * p[1] + z * p[2] - self.offset
    }

    /// The plane as `[nx, ny, nz, -d]` in f32, for shaders: `dot(plane, vec4(p, 1)) >= 0` is cut
    /// (a point on the plane is cut away, as the drawings' exact cut has it).
    pub fn to_vec4(&self) -> [f32; 4] {
        let [x, y, z] = self.normal;
        [x as f32, y as f32, z as f32, -self.offset as f32]
    }
}

impl Section {
    /// True when nothing is cut.
    pub fn is_empty(&self) -> bool {
        self.section.is_none() && self.section_box.is_none()
    }

    /// Refuses what cannot be a section: a plane list that is not 1 to 6 planes of four finite
    /// numbers with a non-zero normal, a box that is not six finite numbers with min <= max.
    pub fn check(&self) -> Result<(), SchemaError> {
        self.check_combinations()?;
        self.check_ranges()?;
        self.planes().map(|_| ())
    }

    /// The planes, normals made unit length (a box gives six); empty when nothing is cut.
    pub fn planes(&self) -> Result<Vec<Plane>, SchemaError> {
        let invalid = |name, reason: String| SchemaError::Invalid { name, reason };
        if let Some(numbers) = &self.section {
            let numbers = numbers.as_slice();
            if numbers.is_empty() || numbers.len() % 4 != 0 || numbers.len() > 4 * MAX_PLANES {
                return Err(invalid(
                    "section",
                    format!(
                        "must be 1 to {MAX_PLANES} planes of four numbers (nx,ny,nz,d), not {} numbers",
                        numbers.len()
                    ),
                ));
            }
            return numbers
                .chunks_exact(4)
                .map(|p| {
                    let n = [p[0], p[1], p[2]].map(f64::from);
                    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                    let finite = p.iter().all(|x| x.is_finite());
                    if !(finite && length > 0.0 && length.is_finite()) {
                        return Err(invalid(
                            "section",
                            format!("needs a finite plane with a non-zero normal, not {p:?}"),
                        ));
                    }
                    Ok(Plane {
                        normal: n.map(|c| c / length),
                        offset: f64::from(p[3]) / length,
                    })
                })
                .collect();
        }
        if let Some(numbers) = &self.section_box {
            let b = numbers.as_slice();
            let ordered = b.len() == 6 && (0..3).all(|k| b[k] <= b[k + 3]);
            if !ordered || !b.iter().all(|x| x.is_finite()) {
                return Err(invalid(
                    "section_box",
                    format!(
                        "must be six finite numbers xmin,ymin,zmin,xmax,ymax,zmax with each min <= max, not {b:?}"
                    ),
                ));
            }
            return Ok((0..3)
                .flat_map(|k| {
                    let mut normal = [0.0; 3];
                    normal[k] = 1.0;
                    let max = Plane {
                        normal,
                        offset: f64::from(b[k + 3]),
                    };
                    normal[k] = -1.0;
                    let min = Plane {
                        normal,
                        offset: -f64::from(b[k]),
                    };
                    [min, max]
                })
                .collect());
        }
        Ok(Vec::new())
    }
}

/// Section planes as the renderer's shaders take them: up to [`MAX_PLANES`] rows `[nx, ny, nz, -d]`
/// ([`Plane::to_vec4`]); a point `p` with `dot(row, (p, 1)) >= 0` for any row is cut away. Rows past
/// the planes given are `[0, 0, 0, -1]`, which cut nothing, so shaders loop over all of them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipPlanes {
    rows: [[f32; 4]; MAX_PLANES],
    count: usize,
}

impl Default for ClipPlanes {
    fn default() -> Self {
        Self::NONE
    }
}

impl ClipPlanes {
    /// No plane: nothing is cut.
    pub const NONE: Self = Self {
        rows: [[0.0, 0.0, 0.0, -1.0]; MAX_PLANES],
        count: 0,
    };

    /// The first [`MAX_PLANES`] of `planes` (a checked [`Section`] has no more).
    pub fn new(planes: &[Plane]) -> Self {
        let mut out = Self::NONE;
        for (row, plane) in out.rows.iter_mut().zip(planes) {
            *row = plane.to_vec4();
        }
        out.count = planes.len().min(MAX_PLANES);
        out
    }

    /// The planes of `section`, or its error ([`Section::check`]).
    pub fn from_section(section: &Section) -> Result<Self, SchemaError> {
        section.check()?;
        Ok(Self::new(&section.planes()?))
    }

    /// The planes given, as rows.
    pub fn planes(&self) -> &[[f32; 4]] {
        &self.rows[..self.count]
    }

    /// True when nothing is cut.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// All rows, the unused ones included: what a uniform holds.
    pub fn rows(&self) -> [[f32; 4]; MAX_PLANES] {
        self.rows
    }

    /// These planes (in world space) in the model space of an instance placed by `model_to_world`:
    /// a plane row `P` becomes `Mᵀ P` (so `P·(M p) = (Mᵀ P)·p`), normal made unit length again so
    /// distances stay in model units. A row the transform degenerates (a zero scale) cuts nothing.
    pub fn to_model(&self, model_to_world: glam::Mat4) -> Self {
        let mut out = *self;
        for row in &mut out.rows[..self.count] {
            let p = model_to_world.transpose() * glam::Vec4::from_array(*row);
            let length = p.truncate().length();
            *row = if length > 0.0 && length.is_finite() {
                (p / length).to_array()
            } else {
                [0.0, 0.0, 0.0, -1.0]
            };
        }
        out
    }

    /// True if `p` is cut away, as the shaders decide it (`section_cuts` in
    /// `shaders/section.wgsl`).
    pub fn cuts(&self, p: [f32; 3]) -> bool {
        self.planes()
            .iter()
            .any(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3] >= 0.0)
    }

    /// Whether the box `lo..hi` is wholly cut away by one plane (nothing of it is drawn) and which
    /// planes pass through it (those that cut it and may need a cap there), as bits.
    pub fn against_box(&self, lo: [f32; 3], hi: [f32; 3]) -> (bool, u32) {
        let mut crossing = 0;
        for (k, r) in self.planes().iter().enumerate() {
            // The box's corner farthest along the normal, and the nearest.
            let pick = |toward: bool| {
                [0, 1, 2].map(|i| {
                    if (r[i] >= 0.0) == toward {
                        hi[i]
                    } else {
                        lo[i]
                    }
                })
            };
            let distance = |p: [f32; 3]| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3];
            if distance(pick(false)) >= 0.0 {
                return (true, 0);
            }
            if distance(pick(true)) >= 0.0 {
                crossing |= 1 << k;
            }
        }
        (false, crossing)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_are_unit_and_a_box_is_six_planes_keeping_its_inside() {
        let section = Section {
            section: Some(Numbers::from_array([0.0, 2.0, 0.0, 1.0])),
            ..Section::default()
        };
        let planes = section.planes().expect("a plane");
        assert_eq!(planes.len(), 1);
        assert_eq!(planes[0].normal, [0.0, 1.0, 0.0]);
        assert_eq!(planes[0].offset, 0.5);
        assert!(planes[0].distance([0.0, 0.4, 0.0]) < 0.0);

        let boxed = Section {
            section_box: Some(Numbers::from_array([-1.0, -2.0, -3.0, 1.0, 2.0, 3.0])),
            ..Section::default()
        };
        let planes = boxed.planes().expect("a box");
        assert_eq!(planes.len(), 6);
        assert!(planes.iter().all(|p| p.distance([0.9, 1.9, -2.9]) < 0.0));
        assert!(planes.iter().any(|p| p.distance([0.0, 0.0, 3.1]) > 0.0));
        assert!(Section::default().planes().expect("none").is_empty());
    }

    #[test]
    fn clip_planes_follow_an_instance_and_sort_boxes() {
        let x = Plane {
            normal: [1.0, 0.0, 0.0],
            offset: 1.0,
        };
        let planes = ClipPlanes::new(&[x]);
        assert!(planes.cuts([1.0, 0.0, 0.0]) && !planes.cuts([0.99, 5.0, 0.0]));
        assert!(!ClipPlanes::NONE.cuts([1e30, 0.0, 0.0]));
        // An instance moved by +3 in x and scaled by 2: world x = 1 is model x = -1.
        let m = glam::Mat4::from_translation(glam::Vec3::new(3.0, 0.0, 0.0))
            * glam::Mat4::from_scale(glam::Vec3::splat(2.0));
        let model = planes.to_model(m);
        assert!(model.cuts([-0.999, 0.0, 0.0]) && !model.cuts([-1.001, 0.0, 0.0]));
        assert!(
            (model.planes()[0][3] - 1.0).abs() < 1e-6,
            "unit normal, model units"
        );
        assert_eq!(planes.against_box([-2.0; 3], [0.0; 3]), (false, 0));
        assert_eq!(planes.against_box([0.0; 3], [2.0; 3]), (false, 1));
        assert_eq!(planes.against_box([1.0; 3], [2.0; 3]), (true, 0));
    }

    #[test]
    fn malformed_sections_are_refused_by_name() {
        let bad = |section: Section| section.check().expect_err("refused").to_string();
        let planes = |v: &[f32]| Section {
            section: Numbers::new(v),
            ..Section::default()
        };
        assert!(bad(planes(&[1.0, 0.0, 0.0])).contains("section must be 1 to 6 planes"));
        assert!(bad(planes(&[0.0, 0.0, 0.0, 1.0])).contains("non-zero normal"));
        assert!(bad(planes(&[f32::NAN, 0.0, 0.0, 1.0])).contains("section"));
        assert!(Numbers::new(&[1.0; 25]).is_none());
        assert_eq!(planes(&[1.0, 0.0, 0.0, 0.0].repeat(6)).check(), Ok(()));
        let boxed = Section {
            section_box: Some(Numbers::from_array([1.0, 0.0, 0.0, 0.0, 1.0, 1.0])),
            ..Section::default()
        };
        assert!(bad(boxed).contains("section_box must be six finite numbers"));
        let both = Section {
            section: Some(Numbers::from_array([1.0, 0.0, 0.0, 0.0])),
            section_box: Some(Numbers::from_array([0.0; 6])),
        };
        assert!(bad(both).contains("cannot both be given"));
    }
}
