//! A pose: one matrix per joint and one weight per morph target, from node transforms or from an
//! animation sampled at a time.

use glam::Mat4;

use super::{Rig, Target, Transform, sample};

/// What a frame needs to pose an asset.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Per joint of [`Rig::joints`], the matrix that takes a stored position to its posed one:
    /// `world(joint) · inverse_bind`.
    pub joints: Vec<Mat4>,
    /// Per morph target, its weight.
    pub weights: Vec<f32>,
}

impl Pose {
    /// The rig at rest: every node at its rest transform, the morph targets at their rest weights.
    pub fn rest(rig: &Rig) -> Self {
        let locals: Vec<Transform> = rig.nodes.iter().map(|n| n.rest).collect();
        Self::of_nodes(rig, &locals, rig.morph_weights.clone())
    }

    /// Animation `animation` of `rig` at `time` seconds (held at its first and last keys outside
    /// its range); `None` if there is no such animation. Nodes and weights no channel of it moves
    /// stay at rest.
    ///
    /// Contract: `rig` passed [`Rig::validate`] (decoded assets always have).
    pub fn sampled(rig: &Rig, animation: usize, time: f32) -> Option<Self> {
        let animation = rig.animations.get(animation)?;
        let mut locals: Vec<Transform> = rig.nodes.iter().map(|n| n.rest).collect();
        let mut weights = rig.morph_weights.clone();
        let mut value = Vec::new();
        for channel in &animation.channels {
            value.resize(channel.target.components(), 0.0);
            sample::sample(channel, time, &mut value);
            match channel.target {
                Target::Translation(n) => {
                    locals[n as usize].translation = [value[0], value[1], value[2]]
                }
                Target::Rotation(n) => {
                    locals[n as usize].rotation = [value[0], value[1], value[2], value[3]]
                }
                Target::Scale(n) => locals[n as usize].scale = [value[0], value[1], value[2]],
                Target::Weights { first, count } => {
                    let first = first as usize;
                    weights[first..first + count as usize].copy_from_slice(&value);
                }
            }
        }
        Some(Self::of_nodes(rig, &locals, weights))
    }

    /// The pose of nodes at `locals` (one per [`Rig::nodes`], relative to its parent) with morph
    /// weights `weights`.
    ///
    /// Contract: `locals` has one transform per node and the rig passed [`Rig::validate`].
    pub fn of_nodes(rig: &Rig, locals: &[Transform], weights: Vec<f32>) -> Self {
        let mut world: Vec<Mat4> = Vec::with_capacity(rig.nodes.len());
        for (node, local) in rig.nodes.iter().zip(locals) {
            let parent = node.parent.map_or(Mat4::IDENTITY, |p| world[p as usize]);
            world.push(parent * local.matrix());
        }
        let joints = rig
            .joints
            .iter()
            .map(|j| world[j.node as usize] * Mat4::from_cols_array(&j.inverse_bind))
            .collect();
        Self { joints, weights }
    }
}
