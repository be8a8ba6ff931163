//! Bake settings: parsed once (by the CLI or a build script) and passed by reference to every step.

use glam::Vec3;

use crate::Limits;

/// How to bake a mesh. Start from [`BakeOptions::DEFAULT`] and change fields with the `with_*` setters.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct BakeOptions {
    /// Which positions weld into one vertex. Default [`WeldTolerance::DEFAULT`]: within 1e-6 of the
    /// distance from the origin to the bounding box's farthest corner, which joins the copies of a
    /// vertex that CAD exports leave a few ULPs apart (measured in BENCHMARKS.md) and changes none of
    /// the shared test meshes. `WeldTolerance::Absolute(0.0)` welds only bit-identical positions.
    pub weld: WeldTolerance,
    /// Drop interior edges whose face normals differ by less than this many degrees (thesis §6.2),
    /// unless they are marked or a material seam. Default 0.01°. Must be in [0, `crease_deg`).
    pub coplanar_deg: f32,
    /// An edge whose face normals differ by this many degrees or more is a crease; normals are split
    /// across it. Default 30°. Must be in (0, 180].
    pub crease_deg: f32,
    /// The chamfer radius given to ridge creases (and marked edges without a radius of their own).
    /// Marks with a radius in the file always win. Default: none.
    pub radius: Radius,
    /// Also give [`radius`](Self::radius) to valley creases. Default false.
    pub radius_valleys: bool,
    /// How much work one input file may ask for (triangles, vertices, glTF instances, bytes).
    /// Default [`Limits::DEFAULT`]. Limits never change an asset, only whether a file is refused,
    /// so they are not part of [`describe`](Self::describe).
    pub limits: Limits,
    /// Also find intersection edges, where triangles cut through each other (thesis §2.2), and
    /// store them in the asset. Default false.
    pub intersections: bool,
    /// Close the cracks between separately tessellated faces of CAD and BIM exports
    /// ([`stitch`](crate::stitch)): boundary vertices this close join, and a boundary vertex this
    /// close to another boundary edge splits it. Default [`Stitch::DEFAULT`].
    pub stitch: Stitch,
}

/// How close boundary geometry must be for [`stitch`](crate::stitch) to join it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stitch {
    /// No stitching: every boundary edge the weld leaves stays a boundary.
    Off,
    /// Within this distance, in mesh units. Must be finite and > 0.
    Absolute(f32),
    /// Within this fraction of the bounding box's diagonal. Must be in (0, 0.01].
    Relative(f32),
}

impl Stitch {
    /// The default fraction of the diagonal: 1e-4 (BENCHMARKS.md, "STL and 3MF").
    pub const DEFAULT_FRACTION: f32 = 1e-4;
    /// [`DEFAULT_FRACTION`](Self::DEFAULT_FRACTION) of the bounding box's diagonal.
    pub const DEFAULT: Self = Self::Relative(Self::DEFAULT_FRACTION);

    /// The stitch distance for these positions, or `None` when off.
    pub fn distance(self, positions: &[Vec3]) -> Option<f32> {
        match self {
            Self::Off => None,
            Self::Absolute(distance) => Some(distance),
            Self::Relative(fraction) => {
                let (lo, hi) = crate::mesh::bounds(positions);
                Some(fraction * (hi - lo).length()).filter(|d| d.is_finite())
            }
        }
    }
}

impl Default for Stitch {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The chamfer radius rule.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Radius {
    /// Only marks in the file carry radii.
    #[default]
    None,
    /// This radius, in mesh units.
    Absolute(f32),
    /// This fraction of the bounding box's diagonal.
    Relative(f32),
}

/// How close two positions must be to weld into one topology vertex ([`weld`](crate::weld)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WeldTolerance {
    /// Within this distance, in mesh units; 0 welds only bit-identical positions (with -0.0 equal
    /// to 0.0). Must be finite and non-negative.
    Absolute(f32),
    /// Within this fraction of the distance from the origin to the bounding box's farthest corner
    /// (the length of the largest absolute coordinate on each axis). An f32's spacing grows with
    /// its magnitude, not with the model's extent, so this is a number of ULPs of the largest
    /// coordinate: 1e-6 is at least 8 of them. Must be in [0, 0.01].
    Relative(f32),
}

impl WeldTolerance {
    /// The default fraction: 1e-6 (chosen from the measurement in BENCHMARKS.md).
    pub const DEFAULT_FRACTION: f32 = 1e-6;
    /// [`DEFAULT_FRACTION`](Self::DEFAULT_FRACTION) of the farthest corner's distance.
    pub const DEFAULT: Self = Self::Relative(Self::DEFAULT_FRACTION);
    /// Only bit-identical positions.
    pub const EXACT: Self = Self::Absolute(0.0);

    /// The weld distance for these positions.
    pub fn distance(self, positions: &[Vec3]) -> f32 {
        match self {
            Self::Absolute(distance) => distance,
            Self::Relative(fraction) => {
                let farthest = positions.iter().fold(Vec3::ZERO, |m, p| m.max(p.abs()));
                fraction * farthest.length()
            }
        }
    }
}

impl Default for WeldTolerance {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Why options were refused.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("invalid option {name} = {value}: {reason}")]
pub struct OptionsError {
    /// The option.
    pub name: &'static str,
    /// Its value.
    pub value: f32,
    /// What it must be.
    pub reason: &'static str,
}

impl BakeOptions {
    /// Weld within 1e-6 of the farthest corner's distance, 0.01° coplanar threshold, 30° creases.
    pub const DEFAULT: Self = Self {
        weld: WeldTolerance::DEFAULT,
        coplanar_deg: 0.01,
        crease_deg: 30.0,
        radius: Radius::None,
        radius_valleys: false,
        limits: Limits::DEFAULT,
        intersections: false,
        stitch: Stitch::DEFAULT,
    };

    /// Sets [`weld`](Self::weld).
    pub fn with_weld(self, weld: WeldTolerance) -> Self {
        Self { weld, ..self }
    }

    /// Sets [`weld`](Self::weld) to this absolute distance (0: exact).
    pub fn with_weld_epsilon(self, distance: f32) -> Self {
        self.with_weld(WeldTolerance::Absolute(distance))
    }

    /// Sets [`coplanar_deg`](Self::coplanar_deg).
    pub fn with_coplanar_deg(self, coplanar_deg: f32) -> Self {
        Self {
            coplanar_deg,
            ..self
        }
    }

    /// Sets [`crease_deg`](Self::crease_deg).
    pub fn with_crease_deg(self, crease_deg: f32) -> Self {
        Self { crease_deg, ..self }
    }

    /// Sets [`radius`](Self::radius).
    pub fn with_radius(self, radius: Radius) -> Self {
        Self { radius, ..self }
    }

    /// Sets [`radius_valleys`](Self::radius_valleys).
    pub fn with_radius_valleys(self, radius_valleys: bool) -> Self {
        Self {
            radius_valleys,
            ..self
        }
    }

    /// Sets [`limits`](Self::limits).
    pub fn with_limits(self, limits: Limits) -> Self {
        Self { limits, ..self }
    }

    /// Sets [`intersections`](Self::intersections).
    pub fn with_intersections(self, intersections: bool) -> Self {
        Self {
            intersections,
            ..self
        }
    }

    /// Sets [`stitch`](Self::stitch).
    pub fn with_stitch(self, stitch: Stitch) -> Self {
        Self { stitch, ..self }
    }

    /// Checks every field's range.
    pub fn validate(&self) -> Result<(), OptionsError> {
        let check = |ok: bool, name, value, reason| {
            if ok {
                Ok(())
            } else {
                Err(OptionsError {
                    name,
                    value,
                    reason,
                })
            }
        };
        match self.weld {
            WeldTolerance::Absolute(d) => check(
                d.is_finite() && d >= 0.0,
                "weld-epsilon",
                d,
                "must be a finite number >= 0",
            )?,
            WeldTolerance::Relative(f) => check(
                (0.0..=0.01).contains(&f),
                "weld-rel",
                f,
                "must be in [0, 0.01]",
            )?,
        }
        check(
            self.crease_deg > 0.0 && self.crease_deg <= 180.0,
            "crease-deg",
            self.crease_deg,
            "must be in (0, 180]",
        )?;
        check(
            self.coplanar_deg >= 0.0 && self.coplanar_deg < self.crease_deg,
            "coplanar-deg",
            self.coplanar_deg,
            "must be >= 0 and below crease-deg",
        )?;
        match self.stitch {
            Stitch::Off => {}
            Stitch::Absolute(d) => check(
                d.is_finite() && d > 0.0,
                "stitch-epsilon",
                d,
                "must be a finite number > 0",
            )?,
            Stitch::Relative(f) => check(
                f > 0.0 && f <= 0.01,
                "stitch-rel",
                f,
                "must be in (0, 0.01]",
            )?,
        }
        match self.radius {
            Radius::None => Ok(()),
            Radius::Absolute(r) => check(
                r.is_finite() && r > 0.0,
                "radius",
                r,
                "must be a finite number > 0",
            ),
            Radius::Relative(f) => check(
                f.is_finite() && f > 0.0 && f <= 1.0,
                "radius-rel",
                f,
                "must be in (0, 1]",
            ),
        }
    }

    /// The settings as `(name, value)` pairs, recorded in the asset for provenance.
    pub fn describe(&self) -> Vec<(String, String)> {
        vec![
            (
                "weld".into(),
                match self.weld {
                    WeldTolerance::Absolute(0.0) => "exact".into(),
                    WeldTolerance::Absolute(d) => d.to_string(),
                    WeldTolerance::Relative(f) => format!("{f} x farthest corner"),
                },
            ),
            ("coplanar_deg".into(), self.coplanar_deg.to_string()),
            ("crease_deg".into(), self.crease_deg.to_string()),
            (
                "radius".into(),
                match self.radius {
                    Radius::None => "marks only".into(),
                    Radius::Absolute(r) => r.to_string(),
                    Radius::Relative(f) => format!("{f} x diagonal"),
                },
            ),
            ("radius_valleys".into(), self.radius_valleys.to_string()),
            ("intersections".into(), self.intersections.to_string()),
            (
                "stitch".into(),
                match self.stitch {
                    Stitch::Off => "off".into(),
                    Stitch::Absolute(d) => d.to_string(),
                    Stitch::Relative(f) => format!("{f} x diagonal"),
                },
            ),
        ]
    }
}

impl Default for BakeOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
