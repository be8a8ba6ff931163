//! What moves a glTF's meshes (issue 41): skins (`JOINTS_n`/`WEIGHTS_n`, inverse bind matrices),
//! morph targets (position deltas, sparse accessors included) and animations (translation,
//! rotation, scale and weights; STEP, LINEAR and CUBICSPLINE), read into an [`InputMotion`] per
//! loaded vertex.
//!
//! Every drawn instance is bound the way the file moves it. A skinned one follows its skin's
//! joints, its weights folded into the four largest (all sets read, normalized). A rigid one under
//! an animated node follows that node as a joint of weight 1. Any other one does not move. A
//! joint's matrix maps the *loaded* positions (which the mesh node's transform has placed), so its
//! inverse bind matrix is followed by the inverse of that transform. Morph targets are numbered
//! per node that draws a mesh with targets, so each node's animated weights move its own copy.
//!
//! glTF allows a skin without inverse bind matrices (they are then identities); a skin that names
//! an accessor that is missing or too short is refused.

use std::collections::HashMap;

use chamfer_runtime::rig::{
    self, Animation, Channel, INFLUENCES, Interpolation, Joint, Node, Rig, Target, Transform,
};
use glam::{Mat3, Mat4, Vec3};
use gltf::json::{self, validation::Checked};

use super::accessor::Accessors;
use super::local_transform;
use crate::motion::InputMotion;

/// How far a vertex's weights may sum from 1 before the file is refused (quantized weights
/// round; the kept ones are normalized exactly).
const WEIGHT_SUM_SLACK: f32 = 0.01;

/// A node's parent in the file's graph.
#[derive(Clone, Copy, PartialEq)]
enum Parent {
    Root,
    Of(usize),
    /// Listed as a child of two nodes (or twice): no single ancestry to pose it by.
    Several,
}

/// One drawn primitive: where its vertices went in the loaded mesh, and the node that drew it.
pub(super) struct Drawn<'a> {
    pub mesh_index: usize,
    pub primitive: &'a json::mesh::Primitive,
    pub node: Option<usize>,
    pub world: Mat4,
    /// Drawn through `EXT_mesh_gpu_instancing` (skins are not applied to those).
    pub gpu_instanced: bool,
    pub first_vertex: u32,
    pub vertices: usize,
}

pub(super) struct MotionReader<'a> {
    root: &'a json::Root,
    accessors: &'a Accessors<'a>,
    max_joints: u64,
    parents: Vec<Parent>,
    /// Nodes a translation, rotation or scale channel moves.
    animated: Vec<bool>,
    rig_node: Vec<Option<u32>>,
    rig: Rig,
    joint_of: HashMap<(u32, [u32; 16]), u16>,
    /// (node, mesh) → its morph targets' first index and count.
    morph_ranges: HashMap<(Option<usize>, usize), (u32, u32)>,
    inverse_binds: HashMap<usize, Vec<Mat4>>,
    joints: Vec<[u16; INFLUENCES]>,
    weights: Vec<[f32; INFLUENCES]>,
    targets: Vec<Vec<(u32, [f32; 3])>>,
    moving: bool,
    folded: u64,
    ungrouped_skins: u64,
}

impl<'a> MotionReader<'a> {
    pub fn new(root: &'a json::Root, accessors: &'a Accessors<'a>, max_joints: u64) -> Self {
        let mut parents = vec![Parent::Root; root.nodes.len()];
        for (p, node) in root.nodes.iter().enumerate() {
            for child in node.children.iter().flatten() {
                if let Some(slot) = parents.get_mut(child.value()) {
                    *slot = match *slot {
                        Parent::Root => Parent::Of(p),
                        _ => Parent::Several,
                    };
                }
            }
        }
        let mut animated = vec![false; root.nodes.len()];
        for channel in root.animations.iter().flat_map(|a| &a.channels) {
            let trs = !matches!(
                channel.target.path,
                Checked::Valid(json::animation::Property::MorphTargetWeights)
            );
            if let Some(slot) = animated.get_mut(channel.target.node.value()) {
                *slot |= trs;
            }
        }
        Self {
            root,
            accessors,
            max_joints: max_joints.min(rig::MAX_JOINTS as u64),
            parents,
            animated,
            rig_node: vec![None; root.nodes.len()],
            rig: Rig::default(),
            joint_of: HashMap::new(),
            morph_ranges: HashMap::new(),
            inverse_binds: HashMap::new(),
            joints: Vec::new(),
            weights: Vec::new(),
            targets: Vec::new(),
            moving: false,
            folded: 0,
            ungrouped_skins: 0,
        }
    }

    /// Binds one drawn primitive's vertices (they follow the ones added before).
    pub fn add(&mut self, drawn: &Drawn) -> Result<(), String> {
        debug_assert_eq!(self.joints.len(), drawn.first_vertex as usize);
        let node = drawn.node.and_then(|n| Some((n, self.root.nodes.get(n)?)));
        let skin = node.and_then(|(_, n)| n.skin).map(|s| s.value());
        match (node, skin) {
            (Some(_), Some(_)) if drawn.gpu_instanced => {
                self.ungrouped_skins += 1;
                self.rest(drawn.vertices);
            }
            (Some(_), Some(skin)) => self.skinned(drawn, skin)?,
            (Some((n, _)), None) if self.moves(n)? => {
                let joint = self.joint(n, drawn.world.inverse(), drawn.world)?;
                self.joints
                    .extend(std::iter::repeat_n([joint, 0, 0, 0], drawn.vertices));
                self.weights
                    .extend(std::iter::repeat_n([1.0, 0.0, 0.0, 0.0], drawn.vertices));
                self.moving = true;
            }
            _ => self.rest(drawn.vertices),
        }
        self.morphs(drawn)
    }

    /// Vertices nothing moves.
    fn rest(&mut self, vertices: usize) {
        self.joints.extend(std::iter::repeat_n([0; 4], vertices));
        self.weights.extend(std::iter::repeat_n([0.0; 4], vertices));
    }

    /// Whether node `n` or one of its ancestors is animated.
    fn moves(&self, mut n: usize) -> Result<bool, String> {
        for _ in 0..=self.parents.len() {
            if self.animated[n] {
                return Ok(true);
            }
            match self.parents[n] {
                Parent::Root => return Ok(false),
                Parent::Of(p) => n = p,
                Parent::Several => {
                    return Err(format!(
                        "node {n} has more than one parent, so its motion is ambiguous"
                    ));
                }
            }
        }
        Err(format!("node {n} is part of a cycle"))
    }

    /// The rig node of file node `n`, adding it and its ancestors (parents first).
    fn rig_node(&mut self, n: usize) -> Result<u32, String> {
        let mut chain = Vec::new();
        let mut at = n;
        while self.rig_node[at].is_none() {
            chain.push(at);
            if chain.len() > self.parents.len() {
                return Err(format!("node {n} is part of a cycle"));
            }
            match self.parents[at] {
                Parent::Root => break,
                Parent::Of(p) => at = p,
                Parent::Several => {
                    return Err(format!(
                        "node {at} has more than one parent, so the joints under it cannot be posed"
                    ));
                }
            }
        }
        for &node in chain.iter().rev() {
            let parent = match self.parents[node] {
                Parent::Of(p) => self.rig_node[p],
                _ => None,
            };
            let file = &self.root.nodes[node];
            let (scale, rotation, translation) =
                local_transform(file).to_scale_rotation_translation();
            self.rig_node[node] = Some(self.rig.nodes.len() as u32);
            self.rig.nodes.push(Node {
                name: file.name.clone().unwrap_or_default(),
                parent,
                rest: Transform {
                    translation: translation.to_array(),
                    rotation: rotation.to_array(),
                    scale: scale.to_array(),
                },
            });
        }
        self.rig_node[n].ok_or_else(|| format!("node {n} could not be added"))
    }

    /// The joint that is file node `n` with inverse bind matrix `inverse_bind`, for an instance
    /// placed by `world` (which must be invertible).
    fn joint(&mut self, n: usize, inverse_bind: Mat4, world: Mat4) -> Result<u16, String> {
        let determinant = world.determinant();
        if determinant == 0.0 || !determinant.is_finite() {
            return Err(format!(
                "the transform of the node drawing a moving mesh under node {n} cannot be inverted"
            ));
        }
        let matrix = inverse_bind.to_cols_array();
        if !matrix.iter().all(|x| x.is_finite()) {
            return Err(format!(
                "joint node {n}'s inverse bind matrix is not finite"
            ));
        }
        let node = self.rig_node(n)?;
        let key = (node, matrix.map(f32::to_bits));
        if let Some(&j) = self.joint_of.get(&key) {
            return Ok(j);
        }
        let count = self.rig.joints.len() as u64 + 1;
        if count > self.max_joints {
            return Err(format!(
                "the skins bind more than {} joints (raise it with --max-joints; an asset holds at most {})",
                self.max_joints,
                rig::MAX_JOINTS
            ));
        }
        let j = self.rig.joints.len() as u16;
        self.rig.joints.push(Joint {
            node,
            inverse_bind: matrix,
        });
        self.joint_of.insert(key, j);
        Ok(j)
    }

    fn skinned(&mut self, drawn: &Drawn, skin_index: usize) -> Result<(), String> {
        let skin = self
            .root
            .skins
            .get(skin_index)
            .ok_or_else(|| format!("skin {skin_index} does not exist"))?;
        if skin.joints.len() as u64 > self.max_joints {
            return Err(format!(
                "skin {skin_index} has {} joints, more than {} (raise it with --max-joints; an asset holds at most {})",
                skin.joints.len(),
                self.max_joints,
                rig::MAX_JOINTS
            ));
        }
        let inverse_binds = self.inverse_binds(skin_index)?;
        let world_inverse = drawn.world.inverse();
        let mut table = Vec::with_capacity(skin.joints.len());
        for (j, node) in skin.joints.iter().enumerate() {
            let n = node.value();
            if n >= self.root.nodes.len() {
                return Err(format!(
                    "skin {skin_index}'s joint {j} is node {n}, which does not exist"
                ));
            }
            table.push(self.joint(n, inverse_binds[j] * world_inverse, drawn.world)?);
        }
        let sets = self.influence_sets(drawn)?;
        if sets.is_empty() {
            return Err(format!(
                "it is drawn with skin {skin_index} but has no JOINTS_0 and WEIGHTS_0"
            ));
        }
        for v in 0..drawn.vertices {
            let mut pairs: Vec<(usize, f32)> = Vec::with_capacity(4 * sets.len());
            for (joints, weights) in &sets {
                for k in 0..4 {
                    let (joint, weight) = (joints[v][k], weights[v][k]);
                    if weight < 0.0 {
                        return Err(format!("vertex {v} has a negative joint weight {weight}"));
                    }
                    if weight == 0.0 {
                        continue;
                    }
                    let joint = joint as usize;
                    if joint >= table.len() {
                        return Err(format!(
                            "vertex {v} is bound to joint {joint}, but skin {skin_index} has {} joints",
                            table.len()
                        ));
                    }
                    match pairs.iter_mut().find(|(j, _)| *j == joint) {
                        Some(pair) => pair.1 += weight,
                        None => pairs.push((joint, weight)),
                    }
                }
            }
            let sum: f32 = pairs.iter().map(|p| p.1).sum();
            if (sum - 1.0).abs() > WEIGHT_SUM_SLACK {
                return Err(format!("vertex {v}'s joint weights sum to {sum}, not 1"));
            }
            if pairs.len() > INFLUENCES {
                self.folded += 1;
                // The largest weights; ties to the lower joint, so the bake is deterministic.
                pairs.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
                pairs.truncate(INFLUENCES);
            }
            let kept: f32 = pairs.iter().map(|p| p.1).sum();
            let (mut joints, mut weights) = ([0u16; INFLUENCES], [0f32; INFLUENCES]);
            for (k, &(joint, weight)) in pairs.iter().enumerate() {
                joints[k] = table[joint];
                weights[k] = weight / kept;
            }
            self.joints.push(joints);
            self.weights.push(weights);
        }
        self.moving = true;
        Ok(())
    }

    /// The skin's inverse bind matrices, one per joint (identities when the skin has none).
    fn inverse_binds(&mut self, skin_index: usize) -> Result<Vec<Mat4>, String> {
        if let Some(m) = self.inverse_binds.get(&skin_index) {
            return Ok(m.clone());
        }
        let skin = &self.root.skins[skin_index];
        let matrices = match skin.inverse_bind_matrices {
            None => vec![Mat4::IDENTITY; skin.joints.len()],
            Some(accessor) => {
                let m = self
                    .accessors
                    .read_vectors::<16>(accessor.value())
                    .map_err(|e| format!("skin {skin_index}'s inverse bind matrices: {e}"))?;
                if m.len() < skin.joints.len() {
                    return Err(format!(
                        "skin {skin_index} has {} joints but {} inverse bind matrices",
                        skin.joints.len(),
                        m.len()
                    ));
                }
                m.iter().map(Mat4::from_cols_array).collect()
            }
        };
        self.inverse_binds.insert(skin_index, matrices.clone());
        Ok(matrices)
    }

    /// Each `JOINTS_n`/`WEIGHTS_n` pair of the primitive, read, in set order.
    #[allow(clippy::type_complexity)]
    fn influence_sets(&self, drawn: &Drawn) -> Result<Vec<(Vec<[f32; 4]>, Vec<[f32; 4]>)>, String> {
        use json::mesh::Semantic;
        let attribute = |semantic: Semantic| {
            drawn
                .primitive
                .attributes
                .get(&Checked::Valid(semantic))
                .map(|a| a.value())
        };
        let mut sets = Vec::new();
        for set in 0u32.. {
            let (joints, weights) = (
                attribute(Semantic::Joints(set)),
                attribute(Semantic::Weights(set)),
            );
            let (joints, weights) = match (joints, weights) {
                (None, None) => break,
                (Some(j), Some(w)) => (j, w),
                _ => {
                    return Err(format!("JOINTS_{set} and WEIGHTS_{set} must come together"));
                }
            };
            let read = |name: &str, accessor: usize| -> Result<Vec<[f32; 4]>, String> {
                let values = self
                    .accessors
                    .read_vectors::<4>(accessor)
                    .map_err(|e| format!("{name}_{set}: {e}"))?;
                if values.len() != drawn.vertices {
                    return Err(format!(
                        "{name}_{set} has {} elements, the primitive {} vertices",
                        values.len(),
                        drawn.vertices
                    ));
                }
                Ok(values)
            };
            sets.push((read("JOINTS", joints)?, read("WEIGHTS", weights)?));
        }
        Ok(sets)
    }

    /// The primitive's morph targets, numbered in the range of the node that draws it.
    fn morphs(&mut self, drawn: &Drawn) -> Result<(), String> {
        let Some(targets) = drawn.primitive.targets.as_ref().filter(|t| !t.is_empty()) else {
            return Ok(());
        };
        let mesh = &self.root.meshes[drawn.mesh_index];
        let count = targets.len();
        let key = (drawn.node, drawn.mesh_index);
        let (first, range_count) = match self.morph_ranges.get(&key) {
            Some(&range) => range,
            None => {
                let first = self.rig.morph_weights.len() as u32;
                let weights = drawn
                    .node
                    .and_then(|n| self.root.nodes.get(n)?.weights.clone())
                    .or_else(|| mesh.weights.clone())
                    .unwrap_or_else(|| vec![0.0; count]);
                if weights.len() != count || !weights.iter().all(|w| w.is_finite()) {
                    return Err(format!(
                        "{} default morph weights for {count} targets",
                        weights.len()
                    ));
                }
                let names = target_names(mesh, count);
                self.rig.morph_weights.extend(weights);
                self.rig.morph_names.extend(names);
                self.targets.resize(self.targets.len() + count, Vec::new());
                self.morph_ranges.insert(key, (first, count as u32));
                (first, count as u32)
            }
        };
        if range_count as usize != count {
            return Err(format!(
                "it has {count} morph targets, another primitive of its mesh {range_count}"
            ));
        }
        let linear = Mat3::from_mat4(drawn.world);
        for (t, target) in targets.iter().enumerate() {
            let Some(accessor) = target.positions else {
                continue;
            };
            let deltas = self
                .accessors
                .read_vectors::<3>(accessor.value())
                .map_err(|e| format!("morph target {t}: {e}"))?;
            if deltas.len() != drawn.vertices {
                return Err(format!(
                    "morph target {t} has {} positions, the primitive {} vertices",
                    deltas.len(),
                    drawn.vertices
                ));
            }
            let list = &mut self.targets[first as usize + t];
            for (v, delta) in deltas.into_iter().enumerate() {
                if delta != [0.0; 3] {
                    let moved = linear * Vec3::from(delta);
                    list.push((drawn.first_vertex + v as u32, moved.to_array()));
                }
            }
        }
        self.moving = true;
        Ok(())
    }

    /// The motion of every vertex added, with the file's animations; `None` when nothing moves.
    pub fn finish(mut self, warnings: &mut Vec<String>) -> Result<Option<InputMotion>, String> {
        if !self.moving && self.root.animations.is_empty() {
            return Ok(None);
        }
        for (a, animation) in self.root.animations.iter().enumerate() {
            let mut channels = Vec::new();
            for (c, channel) in animation.channels.iter().enumerate() {
                let context = |e: String| format!("animation {a} channel {c}: {e}");
                if let Some(kept) = self.channel(animation, channel).map_err(context)? {
                    channels.push(kept);
                }
            }
            self.rig.animations.push(Animation {
                name: animation.name.clone().unwrap_or_default(),
                channels,
            });
        }
        if self.folded > 0 {
            warnings.push(format!(
                "{} vertices are bound to more than {INFLUENCES} joints: the {INFLUENCES} largest weights are kept",
                self.folded
            ));
        }
        if self.ungrouped_skins > 0 {
            warnings.push(format!(
                "{} skinned primitives drawn through EXT_mesh_gpu_instancing are baked unskinned",
                self.ungrouped_skins
            ));
        }
        let skinned = self.weights.iter().any(|w| w[0] != 0.0);
        self.rig.validate()?;
        Ok(Some(InputMotion {
            joints: if skinned { self.joints } else { Vec::new() },
            weights: if skinned { self.weights } else { Vec::new() },
            targets: self.targets,
            rig: self.rig,
        }))
    }

    /// One channel, if it moves something baked (a rig node, or a node's morph targets).
    fn channel(
        &self,
        animation: &json::Animation,
        channel: &json::animation::Channel,
    ) -> Result<Option<Channel>, String> {
        use json::animation::{Interpolation as I, Property};
        let sampler = animation
            .samplers
            .get(channel.sampler.value())
            .ok_or_else(|| format!("sampler {} does not exist", channel.sampler.value()))?;
        let node = channel.target.node.value();
        if node >= self.root.nodes.len() {
            return Err(format!("targets node {node}, which does not exist"));
        }
        let property = match channel.target.path {
            Checked::Valid(p) => p,
            Checked::Invalid => return Err("targets an unknown property".into()),
        };
        let target = match property {
            Property::MorphTargetWeights => {
                let mesh = self.root.nodes[node].mesh.map(|m| m.value());
                match mesh.and_then(|m| self.morph_ranges.get(&(Some(node), m))) {
                    Some(&(first, count)) => Target::Weights { first, count },
                    None => return Ok(None),
                }
            }
            _ => {
                let Some(rig_node) = self.rig_node[node] else {
                    return Ok(None);
                };
                match property {
                    Property::Translation => Target::Translation(rig_node),
                    Property::Rotation => Target::Rotation(rig_node),
                    _ => Target::Scale(rig_node),
                }
            }
        };
        let interpolation = match sampler.interpolation {
            Checked::Valid(I::Linear) => Interpolation::Linear,
            Checked::Valid(I::Step) => Interpolation::Step,
            Checked::Valid(I::CubicSpline) => Interpolation::CubicSpline,
            Checked::Invalid => return Err("unknown interpolation".into()),
        };
        let times: Vec<f32> = self
            .accessors
            .read_vectors::<1>(sampler.input.value())
            .map_err(|e| format!("key times: {e}"))?
            .into_iter()
            .map(|[t]| t)
            .collect();
        let output = sampler.output.value();
        let values: Vec<f32> = match target.components() {
            3 if !matches!(target, Target::Weights { .. }) => {
                flat(self.accessors.read_vectors::<3>(output))
            }
            4 if matches!(target, Target::Rotation(_)) => {
                flat(self.accessors.read_vectors::<4>(output))
            }
            _ => flat(self.accessors.read_vectors::<1>(output)),
        }
        .map_err(|e| format!("key values: {e}"))?;
        let channel = Channel {
            target,
            interpolation,
            times,
            values,
        };
        channel.check(self.rig.nodes.len(), self.rig.morph_weights.len())?;
        Ok(Some(channel))
    }
}

fn flat<const N: usize>(values: Result<Vec<[f32; N]>, String>) -> Result<Vec<f32>, String> {
    values.map(|v| v.into_iter().flatten().collect())
}

/// The mesh's `extras.targetNames` (the convention of Blender and three.js), or empty names.
fn target_names(mesh: &json::Mesh, count: usize) -> Vec<String> {
    #[derive(serde::Deserialize)]
    struct Extras {
        #[serde(rename = "targetNames")]
        target_names: Vec<String>,
    }
    mesh.extras
        .as_ref()
        .and_then(|raw| serde_json::from_str::<Extras>(raw.get()).ok())
        .map(|e| e.target_names)
        .filter(|names| names.len() == count)
        .unwrap_or_else(|| vec![String::new(); count])
}
