//! The bake's options as one schema (issue 40): every flag of `chamfer bake` that shapes an asset,
//! with its default, range, help and conflicts, declared once. The CLI's flags, Python's keywords
//! and `chamfer.OPTIONS`, the page's bake panel and Bevy's `.meta` settings are all made from this
//! table or deserialized into this struct (JSON, RON), so every front end bakes a file into the
//! same bytes. Unknown keys are refused; [`BakeSettings::options`] checks the combinations (from
//! the table) and the ranges (the library's own checks).

use chamfer_runtime::asset::CompactOptions;
use chamfer_runtime::schema::{FINITE, Schema, SchemaError};
use serde::{Deserialize, Serialize};

use crate::{BakeOptions, Limits, OptionsError, Radius, Stitch, WeldTolerance};

chamfer_runtime::schema! {
    /// What to bake and how to encode it: `chamfer bake`'s flags of the same names (kebab-case
    /// there), Python's keywords, the page's bake settings and Bevy's `.meta` settings.
    #[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
    #[serde(default, deny_unknown_fields)]
    pub struct BakeSettings {
        /// Weld positions closer than this distance, in mesh units; 0 welds only identical
        /// positions. [default: `weld_rel` 1e-6]
        weld_epsilon: Option<f32> = None, { group: "bake", value: "DIST",
            range: Some((0.0, FINITE)), example: Some(1e-4), conflicts: [weld_rel], requires: [] },
        /// Weld positions closer than this fraction of the distance from the origin to the
        /// bounding box's farthest corner (1e-6 is at least 8 ULPs of the largest coordinate: the
        /// copies of a vertex that CAD exports leave apart weld, distinct vertices do not).
        weld_rel: f32 = WeldTolerance::DEFAULT_FRACTION, { group: "bake", value: "F",
            range: Some((0.0, 0.01)), example: 1e-5, conflicts: [], requires: [] },
        /// Drop interior edges whose faces are coplanar within this many degrees (below
        /// `crease_deg`).
        coplanar_deg: f32 = BakeOptions::DEFAULT.coplanar_deg, { group: "bake", value: "DEG",
            range: Some((0.0, 180.0)), example: 1.0, conflicts: [], requires: [] },
        /// Edges whose faces meet at this many degrees or more are creases.
        crease_deg: f32 = BakeOptions::DEFAULT.crease_deg, { group: "bake", value: "DEG",
            range: Some((0.0, 180.0)), example: 40.0, conflicts: [], requires: [] },
        /// Give ridge creases (and marked edges without a radius) this chamfer radius, in mesh
        /// units. Radii marked in the file win.
        radius: Option<f32> = None, { group: "bake", value: "R", range: Some((0.0, FINITE)),
            example: Some(0.05), conflicts: [radius_rel], requires: [] },
        /// Like `radius`, as a fraction of the bounding box's diagonal (e.g. 0.005).
        radius_rel: Option<f32> = None, { group: "bake", value: "F", range: Some((0.0, 1.0)),
            example: Some(0.01), conflicts: [], requires: [] },
        /// Give valley creases the radius too.
        radius_valleys: bool = false, { group: "bake", value: "", range: None,
            example: true, conflicts: [], requires: [] },
        /// Refuse a mesh with more triangles than this (after fanning polygons and glTF
        /// instancing).
        max_triangles: u64 = Limits::DEFAULT.max_triangles, { group: "bake", value: "N",
            range: None, example: 1 << 20, conflicts: [], requires: [] },
        /// Refuse a mesh with more vertices than this (as loaded, before welding).
        max_vertices: u64 = Limits::DEFAULT.max_vertices, { group: "bake", value: "N",
            range: None, example: 1 << 20, conflicts: [], requires: [] },
        /// Refuse a glTF whose node graph (or a 3MF whose components and build) expands into
        /// more mesh instances than this.
        max_instances: u64 = Limits::DEFAULT.max_instances, { group: "bake", value: "N",
            range: None, example: 1 << 10, conflicts: [], requires: [] },
        /// Refuse a file (or a file it refers to) larger than this many bytes, after inflating
        /// .gz.
        max_input_bytes: u64 = Limits::DEFAULT.max_input_bytes, { group: "bake", value: "BYTES",
            range: None, example: 1 << 30, conflicts: [], requires: [] },
        /// Refuse a glTF whose skins (and animated rigid parts) have more joints than this
        /// (an asset holds at most 65,536).
        max_joints: u64 = Limits::DEFAULT.max_joints, { group: "bake", value: "N",
            range: None, example: 1 << 8, conflicts: [], requires: [] },
        /// Also find intersection edges, where triangles cut through each other (within one
        /// mesh and between the objects, primitives and instances of the file), and store them
        /// in the asset.
        intersections: bool = false, { group: "bake", value: "", range: None,
            example: true, conflicts: [], requires: [] },
        /// Stitch the cracks between separately tessellated faces (CAD/BIM exports): join
        /// boundary vertices closer than this fraction of the bounding box's diagonal and split
        /// boundary edges at boundary vertices this close to them (T-junctions). Open
        /// boundaries wider stay open.
        stitch_rel: f32 = Stitch::DEFAULT_FRACTION, { group: "bake", value: "F",
            range: Some((0.0, 0.01)), example: 1e-3, conflicts: [stitch_epsilon, no_stitch],
            requires: [] },
        /// Like `stitch_rel`, as a distance in mesh units.
        stitch_epsilon: Option<f32> = None, { group: "bake", value: "DIST",
            range: Some((0.0, FINITE)), example: Some(0.01), conflicts: [no_stitch],
            requires: [] },
        /// Do not stitch: every boundary edge the weld leaves stays a boundary.
        no_stitch: bool = false, { group: "bake", value: "", range: None, example: true,
            conflicts: [], requires: [] },
        /// Write the compact format for shipping: coded sections, positions on a grid of
        /// `position_bits` per axis over the bounding box, octahedral normals of `normal_bits`
        /// (`chamfer inspect` states each error bound). The loader decodes it to the same GPU
        /// sections.
        compact: bool = false, { group: "encoding", value: "", range: None, example: true,
            conflicts: [], requires: [] },
        /// Bits per axis of the compact positions' grid (1 to 16), or 32 to keep them exact.
        position_bits: u64 = u64::from(CompactOptions::DEFAULT.position_bits), {
            group: "encoding", value: "BITS", range: Some((1.0, 32.0)), example: 12,
            conflicts: [], requires: [compact] },
        /// The compact positions' largest error along an axis, model units, instead of
        /// `position_bits`: the grid gets the fewest bits that keep every position within it
        /// (exact where 16 bits cannot).
        position_error: Option<f32> = None, { group: "encoding", value: "LENGTH",
            range: Some((1e-30, FINITE)), example: Some(0.002), conflicts: [position_bits],
            requires: [compact] },
        /// Bits per component of the compact normals' octahedral code (2 to 16), or 32 to keep
        /// them exact.
        normal_bits: u64 = u64::from(CompactOptions::DEFAULT.normal_bits), {
            group: "encoding", value: "BITS", range: Some((2.0, 32.0)), example: 10,
            conflicts: [], requires: [compact] },
    }
}

/// Why settings cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum SettingsError {
    /// Two options exclude each other, or one lacks another it needs.
    #[error(transparent)]
    Combination(#[from] SchemaError),
    /// A bake option is out of range.
    #[error(transparent)]
    Options(#[from] OptionsError),
    /// The compact encoding's precision is out of range.
    #[error("compact encoding: {0}")]
    Compact(String),
}

impl BakeSettings {
    /// The bake options and, with `compact`, the compact encoding's; refused values say why.
    pub fn options(&self) -> Result<(BakeOptions, Option<CompactOptions>), SettingsError> {
        self.check_combinations()?;
        Ok((
            self.checked_bake_options()?,
            self.checked_compact_options()?,
        ))
    }

    /// The bake options (the "bake" group), checked.
    pub fn bake_options(&self) -> Result<BakeOptions, SettingsError> {
        self.check_combinations()?;
        self.checked_bake_options()
    }

    /// The bake options, the combinations already checked.
    fn checked_bake_options(&self) -> Result<BakeOptions, SettingsError> {
        let options = BakeOptions::DEFAULT
            .with_weld(match self.weld_epsilon {
                Some(distance) => WeldTolerance::Absolute(distance),
                None => WeldTolerance::Relative(self.weld_rel),
            })
            .with_coplanar_deg(self.coplanar_deg)
            .with_crease_deg(self.crease_deg)
            .with_radius(match (self.radius, self.radius_rel) {
                (Some(r), _) => Radius::Absolute(r),
                (None, Some(f)) => Radius::Relative(f),
                (None, None) => Radius::None,
            })
            .with_radius_valleys(self.radius_valleys)
            .with_limits(Limits {
                max_triangles: self.max_triangles,
                max_vertices: self.max_vertices,
                max_instances: self.max_instances,
                max_input_bytes: self.max_input_bytes,
                max_joints: self.max_joints,
            })
            .with_intersections(self.intersections)
            .with_stitch(match (self.no_stitch, self.stitch_epsilon) {
                (true, _) => Stitch::Off,
                (false, Some(distance)) => Stitch::Absolute(distance),
                (false, None) => Stitch::Relative(self.stitch_rel),
            });
        options.validate()?;
        Ok(options)
    }

    /// The compact encoding (the "encoding" group), checked; `None` for the uncompressed format.
    pub fn compact_options(&self) -> Result<Option<CompactOptions>, SettingsError> {
        self.check_combinations()?;
        self.checked_compact_options()
    }

    /// The compact encoding, the combinations already checked.
    fn checked_compact_options(&self) -> Result<Option<CompactOptions>, SettingsError> {
        let bits = |n: u64| u32::try_from(n).unwrap_or(u32::MAX);
        let compact = CompactOptions {
            position_bits: bits(self.position_bits),
            position_error: self.position_error,
            normal_bits: bits(self.normal_bits),
        };
        compact.check().map_err(SettingsError::Compact)?;
        Ok(self.compact.then_some(compact))
    }
}

#[cfg(test)]
mod tests {
    use chamfer_runtime::schema::{Kind, Value};

    use super::*;

    #[test]
    fn defaults_are_the_commands() {
        let (options, compact) = BakeSettings::default().options().expect("valid");
        assert_eq!(options, BakeOptions::DEFAULT);
        assert!(compact.is_none());
    }

    /// Each entry's example changes what is baked (so the front ends' tests, which set each
    /// example, prove the value arrives), and is valid on its own with what it requires.
    #[test]
    fn every_example_changes_the_options() {
        let defaults = BakeSettings::default().options().expect("valid");
        for entry in BakeSettings::ENTRIES {
            let mut settings = BakeSettings::default();
            entry.set_example(&mut settings);
            for needed in entry.requires {
                BakeSettings::entry(needed)
                    .expect("known")
                    .set_example(&mut settings);
            }
            let options = settings.options().expect(entry.name);
            assert_ne!(options, defaults, "{}", entry.name);
        }
    }

    /// The ranges the page's controls use hold the library's checks: a value inside is accepted
    /// (a number's middle; a count's bounds), values beyond either bound are refused.
    #[test]
    fn ranges_bound_the_accepted_values() {
        for entry in BakeSettings::ENTRIES {
            let Some((low, high)) = entry.range else {
                continue;
            };
            let at = |x: f64| {
                let mut settings = BakeSettings::default();
                for needed in entry.requires {
                    BakeSettings::entry(needed)
                        .expect("known")
                        .set_example(&mut settings);
                }
                let value = match entry.kind {
                    Kind::Number => Value::Number(x as f32),
                    _ => Value::Count(x as u64),
                };
                entry.set(&mut settings, value).expect("kind");
                settings.options()
            };
            let inside = match entry.kind {
                Kind::Number => vec![(low + high.min(1.0)) / 2.0],
                _ => vec![low, high],
            };
            for x in inside {
                assert!(at(x).is_ok(), "{} at {x}", entry.name);
            }
            let below = if entry.kind == Kind::Number {
                low - 1e-3
            } else {
                low - 1.0
            };
            if below >= 0.0 || entry.kind == Kind::Number {
                assert!(at(below).is_err(), "{} at {below}", entry.name);
            }
            if high < FINITE {
                assert!(at(high * 1.5 + 1.0).is_err(), "{} above {high}", entry.name);
            }
        }
    }

    #[test]
    fn out_of_range_values_and_combinations_are_refused() {
        let crease = BakeSettings {
            crease_deg: 0.0,
            ..BakeSettings::default()
        };
        assert!(matches!(crease.options(), Err(SettingsError::Options(_))));
        let bits = BakeSettings {
            compact: true,
            position_bits: 40,
            ..BakeSettings::default()
        };
        let err = bits.options().expect_err("refused");
        assert!(err.to_string().contains("position bits"), "{err}");
        let both = BakeSettings {
            radius: Some(1.0),
            radius_rel: Some(0.01),
            ..BakeSettings::default()
        };
        let err = both.options().expect_err("refused");
        assert!(err.to_string().contains("radius and radius_rel"), "{err}");
        let bits_alone = BakeSettings {
            normal_bits: 8,
            ..BakeSettings::default()
        };
        let err = bits_alone.options().expect_err("refused");
        assert!(
            err.to_string().contains("normal_bits needs option compact"),
            "{err}"
        );
    }

    #[test]
    fn json_and_ron_read_every_option() {
        let settings: BakeSettings = serde_json::from_str(
            r#"{"stitch_rel": 0.001, "max_triangles": 5, "radius_rel": 0.01}"#,
        )
        .expect("json");
        assert_eq!(settings.stitch_rel, 1e-3);
        assert_eq!(settings.max_triangles, 5);
        assert_eq!(settings.radius_rel, Some(0.01));
        let unknown = serde_json::from_str::<BakeSettings>(r#"{"stitch": 1}"#);
        assert!(unknown.is_err());
    }
}
