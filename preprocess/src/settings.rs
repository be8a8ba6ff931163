//! The bake's settings as data (JSON for the web page, RON in a Bevy `.meta` file): the flags of
//! `chamfer bake` that shape an asset, with the command's defaults, so every front end bakes the
//! same file into the same bytes. Unknown keys are refused; values are checked by [`options`].
//!
//! [`options`]: BakeSettings::options

use chamfer_runtime::asset::CompactOptions;
use serde::{Deserialize, Serialize};

use crate::{BakeOptions, OptionsError, Radius, WeldTolerance};

/// What to bake and how to encode it (`chamfer bake`'s flags of the same names).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct BakeSettings {
    /// `--weld-rel`.
    pub weld_rel: f32,
    /// `--coplanar-deg`.
    pub coplanar_deg: f32,
    /// `--crease-deg`.
    pub crease_deg: f32,
    /// `--radius-rel`: give ridges this chamfer radius, a share of the bounding box's diagonal.
    pub radius_rel: Option<f32>,
    /// `--compact`, with `--position-bits` and `--normal-bits`.
    pub compact: bool,
    /// `--position-bits`.
    pub position_bits: u32,
    /// `--normal-bits`.
    pub normal_bits: u32,
}

impl Default for BakeSettings {
    fn default() -> Self {
        let compact = CompactOptions::default();
        Self {
            weld_rel: WeldTolerance::DEFAULT_FRACTION,
            coplanar_deg: BakeOptions::DEFAULT.coplanar_deg,
            crease_deg: BakeOptions::DEFAULT.crease_deg,
            radius_rel: None,
            compact: false,
            position_bits: compact.position_bits,
            normal_bits: compact.normal_bits,
        }
    }
}

/// Why settings cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum SettingsError {
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
        let options = BakeOptions::DEFAULT
            .with_weld(WeldTolerance::Relative(self.weld_rel))
            .with_coplanar_deg(self.coplanar_deg)
            .with_crease_deg(self.crease_deg)
            .with_radius(self.radius_rel.map_or(Radius::None, Radius::Relative));
        options.validate()?;
        let compact = CompactOptions {
            position_bits: self.position_bits,
            normal_bits: self.normal_bits,
        };
        compact.check().map_err(SettingsError::Compact)?;
        Ok((options, self.compact.then_some(compact)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_commands() {
        let (options, compact) = BakeSettings::default().options().expect("valid");
        assert_eq!(options, BakeOptions::DEFAULT);
        assert!(compact.is_none());
    }

    #[test]
    fn out_of_range_values_are_refused() {
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
    }
}
