//! Drawing an animated asset in the pose the application gives each frame (issue 41,
//! `shaders/pose.wgsl`).
//!
//! A [`PosedAsset`] is a [`GpuAsset`] whose positions and normals are its own: each frame,
//! [`PosedAsset::prepare`] records a compute pass that writes the pose's topology positions, render
//! positions and normals (and the smooth vertex normals of the techniques that derive them) from
//! the rest sections and the skin, before any technique reads them. Every technique then draws the
//! posed mesh unchanged: contours, caps, joins and the highlight follow the pose; creases keep the
//! classes the bake gave them on the rest pose. The skin and the morph targets are uploaded once
//! per asset ([`GpuAsset`]), so instances in different poses share them: each instance has a
//! `PosedAsset` (its buffers are what differs).
//!
//! **Culling under motion.** The edge clusters' bounds hold for the rest pose only, so a posed
//! asset binds clusters that cull nothing (their flags kept); the instance's box is refitted each
//! frame on the CPU instead, as the box around every joint's rest box moved by that joint (a
//! skinned position is a weighted mean of its joints' images, so it lies in their union),
//! widened first by the reach of the morph targets. Intersection segments (baked in the rest pose)
//! and the highlight's rounded corners are not drawn on a posed asset.

use std::sync::Arc;

use glam::{Mat3, Mat4, Vec3};
use wgpu::util::DeviceExt;

use super::bindings::{self, Binding, Bindings, Kind};
use super::modules::{Program, Shader};
use super::pipelines::{PipelineSet, workgroups};
use super::{GpuAsset, Pipelines, RenderError};
use crate::asset::{Asset, EdgeCluster};
use crate::rig::{INFLUENCES, Pose, Rig};

/// `PoseFrame` in `shaders/pose.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct PoseFrame {
    pub(crate) vertices: u32,
    pub(crate) render_vertices: u32,
    pub(crate) skinned: u32,
    pub(crate) vertex_normals: u32,
}

const POSE: Binding = Binding::new(0, "pose", Kind::Uniform);
const SKIN_JOINTS: Binding = Binding::new(40, "skin_joints", Kind::Read);
const SKIN_WEIGHTS: Binding = Binding::new(41, "skin_weights", Kind::Read);
const JOINT_MATRICES: Binding = Binding::new(42, "joint_matrices", Kind::Read);
const JOINT_NORMALS: Binding = Binding::new(43, "joint_normals", Kind::Read);
const MORPH_RANGES: Binding = Binding::new(44, "morph_ranges", Kind::Read);
const MORPH_ENTRIES: Binding = Binding::new(45, "morph_entries", Kind::Read);
const MORPH_WEIGHTS: Binding = Binding::new(46, "morph_weights", Kind::Read);
const POSED_TOPOLOGY: Binding = Binding::new(47, "posed_topology", Kind::ReadWrite);
const POSED_RENDER: Binding = Binding::new(48, "posed_render", Kind::ReadWrite);
const POSED_NORMALS: Binding = Binding::new(49, "posed_normals", Kind::ReadWrite);
const POSED_VERTEX_NORMALS: Binding = Binding::new(50, "posed_vertex_normals", Kind::ReadWrite);

static POSE_BINDINGS: Bindings = Bindings::compute(
    "pose",
    &[
        POSE,
        bindings::asset::TOPOLOGY,
        bindings::asset::RENDER_NORMALS,
        bindings::asset::VERTEX_NORMALS,
        bindings::asset::RENDER_TO_TOPOLOGY,
        SKIN_JOINTS,
        SKIN_WEIGHTS,
        JOINT_MATRICES,
        JOINT_NORMALS,
        MORPH_RANGES,
        MORPH_ENTRIES,
        MORPH_WEIGHTS,
        POSED_TOPOLOGY,
        POSED_RENDER,
        POSED_NORMALS,
        POSED_VERTEX_NORMALS,
    ],
);

/// The posing module.
pub(crate) fn shader() -> Shader {
    Shader::new(
        "pose.wgsl",
        &[chamfer_shaders::POSE],
        vec![
            Program::compute("pose_vertices", &POSE_BINDINGS),
            Program::compute("pose_render", &POSE_BINDINGS),
        ],
    )
}

/// The structs `pose.wgsl` shares with Rust.
#[cfg(test)]
pub(crate) fn structs() -> Vec<super::layout::Layout> {
    vec![super::layout::layout!(
        "PoseFrame",
        PoseFrame,
        [vertices, render_vertices, skinned, vertex_normals]
    )]
}

#[derive(Debug)]
struct PosePipelines {
    vertices: wgpu::ComputePipeline,
    render: wgpu::ComputePipeline,
}

impl PipelineSet for PosePipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            vertices: compiled.compute("pose_vertices")?,
            render: compiled.compute("pose_render")?,
        })
    }
}

/// An asset's skin and morph targets on the GPU, shared by every pose of it.
#[derive(Debug)]
pub(crate) struct GpuMotion {
    rig: Rig,
    skin_joints: wgpu::Buffer,
    skin_weights: wgpu::Buffer,
    skinned: bool,
    morph_ranges: wgpu::Buffer,
    morph_entries: wgpu::Buffer,
    render_to_topology: wgpu::Buffer,
    /// The asset's clusters with bounds that cull nothing (their flags kept).
    open_clusters: wgpu::Buffer,
    vertices: u32,
    render_vertices: u32,
    /// Per joint, the rest box of the vertices it moves (`None`: none).
    joint_boxes: Vec<Option<[Vec3; 2]>>,
    /// The rest box of the vertices no joint moves.
    still_box: Option<[Vec3; 2]>,
    /// Per morph target, how far it moves any vertex along each axis at weight 1.
    morph_reach: Vec<Vec3>,
}

impl GpuMotion {
    /// The motion of `asset` uploaded, or `None` for a still asset. `render_to_topology` is the
    /// topology vertex of each render vertex.
    pub(crate) fn new(
        device: &wgpu::Device,
        asset: &Asset,
        render_to_topology: &[u32],
    ) -> Option<Self> {
        let motion = &asset.motion;
        if motion.is_empty() {
            return None;
        }
        let storage = wgpu::BufferUsages::STORAGE;
        // An empty section still binds a whole element of the widest array here (vec4).
        let upload = |label: &str, bytes: &[u8]| {
            let bytes = if bytes.is_empty() {
                &[0u8; 16][..]
            } else {
                bytes
            };
            super::gpu_asset::upload(device, label, bytes, storage)
        };
        let vertices = asset.topology_positions.len();
        // The morph targets by vertex: each vertex's entries (delta, target) in one run.
        let mut ranges = vec![0u32; vertices + 1];
        for &v in &motion.morph_vertices {
            ranges[v as usize + 1] += 1;
        }
        for v in 0..vertices {
            ranges[v + 1] += ranges[v];
        }
        let mut next = ranges.clone();
        let mut entries = vec![[0.0f32; 4]; motion.morph_vertices.len()];
        let mut morph_reach = vec![Vec3::ZERO; motion.morph_starts.len()];
        for (target, reach) in morph_reach.iter_mut().enumerate() {
            let (list, deltas) = motion.morph_target(target);
            for (&v, d) in list.iter().zip(deltas) {
                let slot = &mut next[v as usize];
                entries[*slot as usize] = [d[0], d[1], d[2], f32::from_bits(target as u32)];
                *slot += 1;
                *reach = reach.max(Vec3::from(*d).abs());
            }
        }
        let mut joint_boxes = vec![None; motion.rig.joints.len()];
        let mut still_box = None;
        let grow = |slot: &mut Option<[Vec3; 2]>, p: Vec3| {
            *slot = Some(slot.map_or([p, p], |[lo, hi]| [lo.min(p), hi.max(p)]));
        };
        for (v, p) in asset.topology_positions.iter().enumerate() {
            let p = Vec3::from(*p);
            match motion.weights.get(v) {
                Some(w) if w.iter().any(|&x| x != 0.0) => {
                    for k in (0..INFLUENCES).filter(|&k| w[k] != 0.0) {
                        grow(&mut joint_boxes[usize::from(motion.joints[v][k])], p);
                    }
                }
                _ => grow(&mut still_box, p),
            }
        }
        let open: Vec<EdgeCluster> = asset
            .clusters()
            .iter()
            .map(|c| {
                EdgeCluster::new(
                    [0.0; 3],
                    f32::MAX,
                    [0.0, 0.0, 1.0],
                    -1.0,
                    crate::asset::EdgeFlags(c.flags as u16),
                )
            })
            .collect();
        Some(Self {
            rig: motion.rig.clone(),
            skin_joints: upload("skin joints", bytemuck::cast_slice(&motion.joints)),
            skin_weights: upload("skin weights", bytemuck::cast_slice(&motion.weights)),
            skinned: motion.is_skinned(),
            morph_ranges: upload("morph ranges", bytemuck::cast_slice(&ranges)),
            morph_entries: upload("morph entries", bytemuck::cast_slice(&entries)),
            render_to_topology: upload(
                "render to topology",
                bytemuck::cast_slice(render_to_topology),
            ),
            open_clusters: upload("open clusters", bytemuck::cast_slice(&open)),
            vertices: vertices as u32,
            render_vertices: render_to_topology.len() as u32,
            joint_boxes,
            still_box,
            morph_reach,
        })
    }

    /// The rig: nodes, joints, morph weights, animations.
    pub(crate) fn rig(&self) -> &Rig {
        &self.rig
    }

    /// A box holding every vertex in `pose` (see the module's notes).
    fn bounds(&self, pose: &Pose) -> [[f32; 3]; 2] {
        let reach = self
            .morph_reach
            .iter()
            .zip(&pose.weights)
            .fold(Vec3::ZERO, |sum, (r, w)| sum + *r * w.abs());
        let mut out = [Vec3::INFINITY, Vec3::NEG_INFINITY];
        let mut hold = |[lo, hi]: [Vec3; 2], m: Mat4| {
            let (lo, hi) = (lo - reach, hi + reach);
            for k in 0..8 {
                let corner =
                    Vec3::select(glam::BVec3::new(k & 1 == 0, k & 2 == 0, k & 4 == 0), lo, hi);
                let p = m.transform_point3(corner);
                out = [out[0].min(p), out[1].max(p)];
            }
        };
        if let Some(b) = self.still_box {
            hold(b, Mat4::IDENTITY);
        }
        for (b, m) in self.joint_boxes.iter().zip(&pose.joints) {
            if let Some(b) = b {
                hold(*b, *m);
            }
        }
        [out[0].to_array(), out[1].to_array()]
    }
}

/// One pose of an animated asset: its own positions and normals, written each frame by
/// [`prepare`](Self::prepare); draw [`asset`](Self::asset) with any technique.
#[derive(Debug)]
pub struct PosedAsset {
    posed: GpuAsset,
    motion: Arc<GpuMotion>,
    pipelines: Arc<PosePipelines>,
    group: wgpu::BindGroup,
    frame: wgpu::Buffer,
    joints: wgpu::Buffer,
    normals: wgpu::Buffer,
    weights: wgpu::Buffer,
    vertex_normals: bool,
}

impl PosedAsset {
    /// A pose of `asset`, at rest until the first [`prepare`](Self::prepare). Fails with
    /// [`RenderError::Unsupported`] for a still asset (no joints, no morph targets).
    pub fn new(pipelines: &Pipelines, asset: &GpuAsset) -> Result<Self, RenderError> {
        let motion = asset
            .motion
            .clone()
            .ok_or_else(|| RenderError::Unsupported {
                technique: "PosedAsset",
                why: "it has no skin and no morph targets".into(),
            })?;
        let device = pipelines.device();
        let pose_pipelines = pipelines.get::<PosePipelines>()?;
        let storage = wgpu::BufferUsages::STORAGE;
        let copy = |label: &str, source: &wgpu::Buffer, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: source.size(),
                // Readable, for whoever needs the pose itself (picking, tests).
                usage: usage | storage | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let vertex = wgpu::BufferUsages::VERTEX;
        let mut posed = asset.clone();
        posed.topology_positions = copy("posed topology", &asset.topology_positions, storage);
        posed.render_positions = copy("posed render positions", &asset.render_positions, vertex);
        posed.render_normals = copy("posed render normals", &asset.render_normals, vertex);
        posed.vertex_normals = asset
            .vertex_normals
            .as_ref()
            .map(|n| copy("posed vertex normals", n, storage));
        posed.clusters = motion.open_clusters.clone();
        posed.intersection_count = 0;
        posed.corner_count = 0;
        posed.key = Arc::new(());
        // At least a mat4: a rig without joints still binds one.
        let buffer = |label: &str, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(64),
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let joint_bytes = 64 * motion.rig.joints.len() as u64;
        let frame = buffer("pose frame", 16, wgpu::BufferUsages::UNIFORM);
        let joints = buffer("joint matrices", joint_bytes, storage);
        let normals = buffer("joint normals", joint_bytes, storage);
        let weights = buffer(
            "morph weights",
            4 * motion.rig.morph_weights.len() as u64,
            storage,
        );
        // Without vertex normals, one placeholder to read and another to write (a buffer cannot
        // be both in one dispatch).
        let placeholder = |label| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: &[0u8; 16],
                usage: storage,
            })
        };
        let (no_normals, no_posed_normals) = (
            placeholder("no vertex normals"),
            placeholder("no posed vertex normals"),
        );
        let layout = pipelines.layout(&POSE_BINDINGS);
        let group = POSE_BINDINGS.group(device, &layout, |binding| {
            let resource = match binding {
                POSE => &frame,
                bindings::asset::TOPOLOGY => &asset.topology_positions,
                bindings::asset::RENDER_NORMALS => &asset.render_normals,
                bindings::asset::VERTEX_NORMALS => {
                    asset.vertex_normals.as_ref().unwrap_or(&no_normals)
                }
                bindings::asset::RENDER_TO_TOPOLOGY => &motion.render_to_topology,
                SKIN_JOINTS => &motion.skin_joints,
                SKIN_WEIGHTS => &motion.skin_weights,
                JOINT_MATRICES => &joints,
                JOINT_NORMALS => &normals,
                MORPH_RANGES => &motion.morph_ranges,
                MORPH_ENTRIES => &motion.morph_entries,
                MORPH_WEIGHTS => &weights,
                POSED_TOPOLOGY => &posed.topology_positions,
                POSED_RENDER => &posed.render_positions,
                POSED_NORMALS => &posed.render_normals,
                POSED_VERTEX_NORMALS => posed.vertex_normals.as_ref().unwrap_or(&no_posed_normals),
                other => return Err(bindings::unbound(&POSE_BINDINGS, other)),
            };
            Ok(resource.as_entire_binding())
        })?;
        Ok(Self {
            vertex_normals: posed.vertex_normals.is_some(),
            posed,
            motion,
            pipelines: pose_pipelines,
            group,
            frame,
            joints,
            normals,
            weights,
        })
    }

    /// The posed asset: draw it like any [`GpuAsset`] (after [`prepare`](Self::prepare) in the
    /// same encoder, before the passes that draw it).
    pub fn asset(&self) -> &GpuAsset {
        &self.posed
    }

    /// The rig the pose must fit: its joints, morph targets and animations.
    pub fn rig(&self) -> &Rig {
        &self.motion.rig
    }

    /// Records the pass that poses the asset in `pose` into `encoder`, and refits its bounds.
    /// Fails with [`RenderError::BadPose`] when the pose has another number of joint matrices or
    /// morph weights than the rig, or a number that is not finite.
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        pose: &Pose,
    ) -> Result<(), RenderError> {
        let rig = &self.motion.rig;
        if pose.joints.len() != rig.joints.len() || pose.weights.len() != rig.morph_weights.len() {
            return Err(RenderError::BadPose(format!(
                "{} joint matrices and {} morph weights for a rig of {} joints and {} morph targets",
                pose.joints.len(),
                pose.weights.len(),
                rig.joints.len(),
                rig.morph_weights.len()
            )));
        }
        if !pose.joints.iter().all(|m| m.is_finite()) || !pose.weights.iter().all(|w| w.is_finite())
        {
            return Err(RenderError::BadPose(
                "a joint matrix or morph weight is not finite".into(),
            ));
        }
        let matrices: Vec<[f32; 16]> = pose.joints.iter().map(Mat4::to_cols_array).collect();
        let normals: Vec<[f32; 16]> = pose
            .joints
            .iter()
            .map(|m| Mat4::from_mat3(normal_matrix(Mat3::from_mat4(*m))).to_cols_array())
            .collect();
        queue.write_buffer(
            &self.frame,
            0,
            bytemuck::bytes_of(&PoseFrame {
                vertices: self.motion.vertices,
                render_vertices: self.motion.render_vertices,
                skinned: u32::from(self.motion.skinned),
                vertex_normals: u32::from(self.vertex_normals),
            }),
        );
        if !pose.joints.is_empty() {
            queue.write_buffer(&self.joints, 0, bytemuck::cast_slice(&matrices));
            queue.write_buffer(&self.normals, 0, bytemuck::cast_slice(&normals));
        }
        if !pose.weights.is_empty() {
            queue.write_buffer(&self.weights, 0, bytemuck::cast_slice(&pose.weights));
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("pose"),
            timestamp_writes: None,
        });
        pass.set_bind_group(0, &self.group, &[]);
        for (pipeline, items) in [
            (&self.pipelines.vertices, self.motion.vertices),
            (&self.pipelines.render, self.motion.render_vertices),
        ] {
            let [x, y] = workgroups(items);
            if x > 0 {
                pass.set_pipeline(pipeline);
                pass.dispatch_workgroups(x, y, 1);
            }
        }
        drop(pass);
        self.posed.bounds = self.motion.bounds(pose);
        Ok(())
    }
}

/// The inverse transpose of `m` (its cofactor matrix, up to a positive scale that the shader's
/// normalization removes; negated when `m` mirrors, so normals keep their side).
fn normal_matrix(m: Mat3) -> Mat3 {
    let cofactor = Mat3::from_cols(
        m.y_axis.cross(m.z_axis),
        m.z_axis.cross(m.x_axis),
        m.x_axis.cross(m.y_axis),
    );
    if m.determinant() < 0.0 {
        -cofactor
    } else {
        cofactor
    }
}
