//! Skeletons, morph targets and animations: what moves an animated asset (issue 41), and the pose
//! they give at a time.
//!
//! A [`Rig`] is the part of a glTF node graph that moves the mesh: the nodes that are joints and
//! their ancestors, each with its rest transform; the joints, each a node and the matrix that takes
//! a baked position into that node's space; the morph targets' rest weights; and the animations,
//! as keyframes the runtime samples ([`sample`]). A [`Pose`] is what a frame needs from it: one
//! matrix per joint and one weight per morph target. Posing a vertex follows the glTF skinning
//! formula (glTF 2.0 §3.7.3): first the morph targets, `p + Σ wₖ δₖ`, then the skin,
//! `Σ wᵢ · Jᵢ · p` with `Jᵢ = world(jointᵢ) · inverse_bindᵢ`. The bake folds the skinned mesh
//! node's own transform into `inverse_bind`, so a joint matrix applies to the asset's positions
//! as they are stored; a vertex with no joint weights is not skinned (it keeps its morphed
//! position).
//!
//! Creases are a property of the model: the bake classifies them on the stored (rest) positions,
//! and only what depends on the view (contours, caps, the highlight) follows the pose.

mod pose;
pub mod sample;
mod settings;

pub use pose::Pose;
pub use settings::{AnimationSettings, names as animation_names};

use serde::{Deserialize, Serialize};

/// The most joints a vertex is bound to: glTF's `JOINTS_0`/`WEIGHTS_0`; further sets are folded
/// into these by keeping the largest weights.
pub const INFLUENCES: usize = 4;

/// Joint indices are `u16`: at most this many joints per asset.
pub const MAX_JOINTS: usize = 1 << 16;

/// A translation, rotation (unit quaternion `x y z w`) and scale, applied scale first.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Transform {
    /// Translation.
    pub translation: [f32; 3],
    /// Rotation, a unit quaternion `[x, y, z, w]`.
    pub rotation: [f32; 4],
    /// Scale per axis.
    pub scale: [f32; 3],
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    /// No motion at all.
    pub const IDENTITY: Self = Self {
        translation: [0.0; 3],
        rotation: [0.0, 0.0, 0.0, 1.0],
        scale: [1.0; 3],
    };

    /// The matrix `T · R · S`.
    pub fn matrix(&self) -> glam::Mat4 {
        glam::Mat4::from_scale_rotation_translation(
            self.scale.into(),
            glam::Quat::from_array(self.rotation),
            self.translation.into(),
        )
    }

    fn is_finite(&self) -> bool {
        self.translation
            .iter()
            .chain(&self.rotation)
            .chain(&self.scale)
            .all(|x| x.is_finite())
    }
}

/// One node of the moving part of the scene graph.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Node {
    /// The node's name in the source file (may be empty).
    pub name: String,
    /// Its parent, an earlier node of [`Rig::nodes`]; `None` for a root.
    pub parent: Option<u32>,
    /// Its transform relative to its parent when no animation moves it.
    pub rest: Transform,
}

/// A joint: a node whose motion moves the vertices bound to it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    /// The node, an index into [`Rig::nodes`].
    pub node: u32,
    /// Column-major matrix from the asset's stored positions into the node's space at rest
    /// (glTF's inverse bind matrix times the inverse of the skinned mesh node's transform).
    pub inverse_bind: [f32; 16],
}

/// What a channel animates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Target {
    /// A node's translation (3 numbers a key).
    Translation(u32),
    /// A node's rotation (a quaternion, 4 numbers a key).
    Rotation(u32),
    /// A node's scale (3 numbers a key).
    Scale(u32),
    /// The weights of `count` morph targets from `first` on (`count` numbers a key).
    Weights {
        /// The first morph target.
        first: u32,
        /// How many.
        count: u32,
    },
}

impl Target {
    /// Numbers per key value.
    pub fn components(self) -> usize {
        match self {
            Self::Translation(_) | Self::Scale(_) => 3,
            Self::Rotation(_) => 4,
            Self::Weights { count, .. } => count as usize,
        }
    }
}

/// How values between keys are found (glTF 2.0 §3.11.4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Interpolation {
    /// Straight lines (rotations: spherical).
    #[default]
    Linear,
    /// The value of the key before.
    Step,
    /// Cubic Hermite splines with in- and out-tangents at each key.
    CubicSpline,
}

impl Interpolation {
    /// Values stored per key: the value, or in-tangent, value and out-tangent.
    pub fn values_per_key(self) -> usize {
        match self {
            Self::CubicSpline => 3,
            _ => 1,
        }
    }
}

/// One animated property: keyframe times and the values at them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Channel {
    /// What it moves.
    pub target: Target,
    /// How it goes from key to key.
    pub interpolation: Interpolation,
    /// Key times in seconds, strictly increasing.
    pub times: Vec<f32>,
    /// `times.len() × values_per_key × components` numbers, key after key.
    pub values: Vec<f32>,
}

impl Channel {
    /// Checks the channel against a rig of `nodes` nodes and `morph_targets` morph targets: its
    /// target exists, its key times are finite and strictly increasing, and its values are finite
    /// and fill its keys.
    pub fn check(&self, nodes: usize, morph_targets: usize) -> Result<(), String> {
        match self.target {
            Target::Translation(n) | Target::Rotation(n) | Target::Scale(n)
                if n as usize >= nodes =>
            {
                return Err(format!("targets node {n}, of {nodes}"));
            }
            Target::Weights { first, count }
                if u64::from(first) + u64::from(count) > morph_targets as u64 || count == 0 =>
            {
                return Err(format!(
                    "sets morph targets {first}..{} of {morph_targets}",
                    u64::from(first) + u64::from(count),
                ));
            }
            _ => {}
        }
        sample::check_keys(
            &self.times,
            &self.values,
            self.target.components() * self.interpolation.values_per_key(),
        )
    }
}

/// A named animation: channels played together.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Animation {
    /// The name in the source file (may be empty).
    pub name: String,
    /// Its channels.
    pub channels: Vec<Channel>,
}

impl Animation {
    /// The time of its last key (its first starts at or after 0).
    pub fn duration(&self) -> f32 {
        self.channels
            .iter()
            .filter_map(|c| c.times.last().copied())
            .fold(0.0, f32::max)
    }
}

/// Everything that moves an animated asset but its per-vertex data.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Rig {
    /// Nodes, every parent before its children.
    pub nodes: Vec<Node>,
    /// Joints the vertices' joint indices refer to.
    pub joints: Vec<Joint>,
    /// Each morph target's weight when no animation sets it.
    pub morph_weights: Vec<f32>,
    /// Each morph target's name (empty when the file gives none).
    pub morph_names: Vec<String>,
    /// Animations.
    pub animations: Vec<Animation>,
}

impl Rig {
    /// True if there is nothing to move: no joint, no morph target.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty() && self.morph_weights.is_empty()
    }

    /// The animation called `name`, or numbered `name` when no animation has that name.
    pub fn animation(&self, name: &str) -> Option<usize> {
        self.animations
            .iter()
            .position(|a| a.name == name)
            .or_else(|| {
                name.parse()
                    .ok()
                    .filter(|&i: &usize| i < self.animations.len())
            })
    }

    /// Checks the rules [`sample`] and [`Pose`] rely on: parents before children, indices in
    /// range, finite numbers, strictly increasing key times and values that fill their keys.
    /// The message names the first broken rule.
    pub fn validate(&self) -> Result<(), String> {
        if self.joints.len() > MAX_JOINTS {
            return Err(format!(
                "{} joints, more than the {MAX_JOINTS} a joint index can name",
                self.joints.len()
            ));
        }
        for (i, node) in self.nodes.iter().enumerate() {
            if node.parent.is_some_and(|p| p as usize >= i) {
                return Err(format!("node {i} comes before its parent"));
            }
            if !node.rest.is_finite() {
                return Err(format!("node {i} has a non-finite rest transform"));
            }
        }
        let nodes = self.nodes.len();
        for (i, joint) in self.joints.iter().enumerate() {
            if joint.node as usize >= nodes {
                return Err(format!(
                    "joint {i} refers to node {}, of {nodes}",
                    joint.node
                ));
            }
            if !joint.inverse_bind.iter().all(|x| x.is_finite()) {
                return Err(format!("joint {i} has a non-finite inverse bind matrix"));
            }
        }
        if self.morph_names.len() != self.morph_weights.len() {
            return Err(format!(
                "{} morph target names for {} weights",
                self.morph_names.len(),
                self.morph_weights.len()
            ));
        }
        if let Some(t) = self.morph_weights.iter().position(|w| !w.is_finite()) {
            return Err(format!("morph target {t} has a non-finite weight"));
        }
        for (a, animation) in self.animations.iter().enumerate() {
            for (c, channel) in animation.channels.iter().enumerate() {
                channel
                    .check(self.nodes.len(), self.morph_weights.len())
                    .map_err(|e| format!("animation {a} channel {c}: {e}"))?;
            }
        }
        Ok(())
    }
}
