//! Which pose to show (issue 41): the one schema `chamfer render`'s flags, the page's animation
//! panel, Bevy's component and Python's `pose` read, and the [`Pose`] it picks from a rig.

use crate::schema::{FINITE, Numbers, Schema, SchemaError};

use super::{Pose, Rig};

crate::schema! {
    /// The pose an animated asset is shown in: an animation sampled at a time, and morph weights.
    /// With neither, an asset is drawn as it is stored (its bind pose).
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct AnimationSettings {
        /// Pose the asset by its animation of this number (`chamfer inspect` lists them).
        animation: Option<u64> = None, { group: "animation", value: "INDEX", range: None,
            example: Some(0), conflicts: [], requires: [] },
        /// ... sampled at this time, in seconds (held at its first and last keys outside them;
        /// `chamfer render` also takes the animation by name, so this requires none here).
        time: f32 = 0.0, { group: "animation", value: "SECONDS", range: Some((-FINITE, FINITE)),
            example: 0.5, conflicts: [], requires: [] },
        /// The morph targets' weights, one per target (over the animation's).
        pose: Option<Numbers> = None, { group: "animation", value: "W,W,...", range: None,
            example: Some(Numbers::from_array([0.5])), conflicts: [], requires: [] },
    }
}

impl AnimationSettings {
    /// Refuses values out of range (the pose's fit to a rig is [`Self::pose_of`]'s).
    pub fn check(&self) -> Result<(), SchemaError> {
        self.check_combinations()?;
        self.check_ranges()
    }

    /// True when a pose is asked for.
    pub fn poses(&self) -> bool {
        self.animation.is_some() || self.pose.is_some()
    }

    /// The pose of `rig` these settings ask for; `None` when they ask for none (draw the asset as
    /// stored). Fails naming the entry when the rig has no such animation or another number of
    /// morph targets (`rig` is `None` for a still asset).
    pub fn pose_of(&self, rig: Option<&Rig>) -> Result<Option<Pose>, SchemaError> {
        self.check()?;
        if !self.poses() {
            return Ok(None);
        }
        let Some(rig) = rig.filter(|r| !r.is_empty()) else {
            let name = if self.animation.is_some() {
                "animation"
            } else {
                "pose"
            };
            return Err(SchemaError::Invalid {
                name,
                reason:
                    "needs an animated asset (this one has no skin, morph targets or animations)"
                        .into(),
            });
        };
        let mut pose = match self.animation {
            None => Pose::rest(rig),
            Some(index) => {
                let sampled = usize::try_from(index)
                    .ok()
                    .and_then(|i| Pose::sampled(rig, i, self.time));
                sampled.ok_or_else(|| SchemaError::Invalid {
                    name: "animation",
                    reason: format!(
                        "must be below {}, not {index} ({})",
                        rig.animations.len(),
                        names(rig)
                    ),
                })?
            }
        };
        if let Some(weights) = &self.pose {
            let weights = weights.as_slice();
            if weights.len() != pose.weights.len() {
                return Err(SchemaError::Invalid {
                    name: "pose",
                    reason: format!(
                        "must be {} weights, one per morph target, not {}",
                        pose.weights.len(),
                        weights.len()
                    ),
                });
            }
            pose.weights.copy_from_slice(weights);
        }
        Ok(Some(pose))
    }
}

/// The rig's animations, numbered, for messages: `0 "walk", 1 "run"`.
pub fn names(rig: &Rig) -> String {
    if rig.animations.is_empty() {
        return "it has none".into();
    }
    rig.animations
        .iter()
        .enumerate()
        .map(|(i, a)| format!("{i} {:?}", a.name))
        .collect::<Vec<_>>()
        .join(", ")
}
