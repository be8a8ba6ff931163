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
    pub(crate) joints: u32,
    pub(crate) _pad0: u32,
    pub(crate) _pad1: u32,
    pub(crate) _pad2: u32,
}

const POSE: Binding = Binding::new(0, "pose", Kind::Uniform);
const SKIN: Binding = Binding::new(40, "skin", Kind::Read);
const POSE_DATA: Binding = Binding::new(42, "pose_data", Kind::Read);
const MORPHS: Binding = Binding::new(44, "morphs", Kind::Read);
const POSED_TOPOLOGY: Binding = Binding::new(47, "posed_topology", Kind::ReadWrite);
const POSED_TOPOLOGY_IN: Binding = Binding::new(52, "posed_topology_in", Kind::Read);
const POSED_RENDER: Binding = Binding::new(48, "posed_render", Kind::ReadWrite);
const POSED_NORMALS: Binding = Binding::new(49, "posed_normals", Kind::ReadWrite);
const POSED_VERTEX_NORMALS: Binding = Binding::new(50, "posed_vertex_normals", Kind::ReadWrite);

/// The topology pass: seven storage buffers (WebGPU guarantees eight per stage).
static VERTICES: Bindings = Bindings::compute(
    "pose vertices",
    &[
        POSE,
        bindings::asset::TOPOLOGY,
        SKIN,
        POSE_DATA,
        MORPHS,
        POSED_TOPOLOGY,
        bindings::asset::VERTEX_NORMALS,
        POSED_VERTEX_NORMALS,
    ],
);

/// The render-vertex pass: seven storage buffers.
static RENDER: Bindings = Bindings::compute(
    "pose render vertices",
    &[
        POSE,
        SKIN,
        POSE_DATA,
        POSED_TOPOLOGY_IN,
        bindings::asset::RENDER_NORMALS,
        bindings::asset::RENDER_TO_TOPOLOGY,
        POSED_RENDER,
        POSED_NORMALS,
    ],
);

/// The posing module.
pub(crate) fn shader() -> Shader {
    Shader::new(
        "pose.wgsl",
        &[chamfer_shaders::POSE],
        vec![
            Program::compute("pose_vertices", &VERTICES),
            Program::compute("pose_render", &RENDER),
        ],
    )
}

/// The structs `pose.wgsl` shares with Rust.
#[cfg(test)]
pub(crate) fn structs() -> Vec<super::layout::Layout> {
    vec![super::layout::layout!(
        "PoseFrame",
        PoseFrame,
        [
            vertices,
            render_vertices,
            skinned,
            vertex_normals,
            joints,
            _pad0,
            _pad1,
            _pad2
        ]
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
    /// Per vertex its joints and weights, six words.
    skin: wgpu::Buffer,
    skinned: bool,
    /// Each vertex's first morph entry (V + 1 words), then four words an entry.
    morphs: wgpu::Buffer,
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
        let entries_at = ranges.len();
        let mut morphs = ranges;
        morphs.resize(entries_at + 4 * motion.morph_vertices.len(), 0);
        let mut morph_reach = vec![Vec3::ZERO; motion.morph_starts.len()];
        for (target, reach) in morph_reach.iter_mut().enumerate() {
            let (list, deltas) = motion.morph_target(target);
            for (&v, d) in list.iter().zip(deltas) {
                let slot = &mut next[v as usize];
                let at = entries_at + 4 * *slot as usize;
                morphs[at..at + 4].copy_from_slice(&[
                    d[0].to_bits(),
                    d[1].to_bits(),
                    d[2].to_bits(),
                    target as u32,
                ]);
                *slot += 1;
                *reach = reach.max(Vec3::from(*d).abs());
            }
        }
        let skin: Vec<u32> = motion
            .joints
            .iter()
            .zip(&motion.weights)
            .flat_map(|(j, w)| {
                let pair = |a: u16, b: u16| u32::from(a) | (u32::from(b) << 16);
                [pair(j[0], j[1]), pair(j[2], j[3])]
                    .into_iter()
                    .chain(w.map(f32::to_bits))
            })
            .collect();
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
            skin: upload("skin", bytemuck::cast_slice(&skin)),
            skinned: motion.is_skinned(),
            morphs: upload("morph targets by vertex", bytemuck::cast_slice(&morphs)),
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
    vertices_group: wgpu::BindGroup,
    render_group: wgpu::BindGroup,
    frame: wgpu::Buffer,
    /// The joint matrices, their normal matrices and the morph weights (`pose_data`).
    data: wgpu::Buffer,
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
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pose frame"),
            size: std::mem::size_of::<PoseFrame>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let data = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pose data"),
            size: pose_data_bytes(&motion.rig),
            usage: storage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
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
        let group = |set: &'static Bindings| {
            let layout = pipelines.layout(set);
            set.group(device, &layout, |binding| {
                let resource = match binding {
                    POSE => &frame,
                    SKIN => &motion.skin,
                    POSE_DATA => &data,
                    MORPHS => &motion.morphs,
                    bindings::asset::TOPOLOGY => &asset.topology_positions,
                    bindings::asset::RENDER_NORMALS => &asset.render_normals,
                    bindings::asset::VERTEX_NORMALS => {
                        asset.vertex_normals.as_ref().unwrap_or(&no_normals)
                    }
                    bindings::asset::RENDER_TO_TOPOLOGY => &motion.render_to_topology,
                    POSED_TOPOLOGY | POSED_TOPOLOGY_IN => &posed.topology_positions,
                    POSED_RENDER => &posed.render_positions,
                    POSED_NORMALS => &posed.render_normals,
                    POSED_VERTEX_NORMALS => {
                        posed.vertex_normals.as_ref().unwrap_or(&no_posed_normals)
                    }
                    other => return Err(bindings::unbound(set, other)),
                };
                Ok(resource.as_entire_binding())
            })
        };
        let (vertices_group, render_group) = (group(&VERTICES)?, group(&RENDER)?);
        Ok(Self {
            vertex_normals: posed.vertex_normals.is_some(),
            posed,
            motion,
            pipelines: pose_pipelines,
            vertices_group,
            render_group,
            frame,
            data,
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
        // The matrices, their normal matrices, the weights (padded to whole vec4s).
        let mut data: Vec<f32> = pose.joints.iter().flat_map(Mat4::to_cols_array).collect();
        data.extend(
            pose.joints
                .iter()
                .flat_map(|m| Mat4::from_mat3(normal_matrix(Mat3::from_mat4(*m))).to_cols_array()),
        );
        data.extend(&pose.weights);
        data.resize(data.len().next_multiple_of(4).max(4), 0.0);
        queue.write_buffer(
            &self.frame,
            0,
            bytemuck::bytes_of(&PoseFrame {
                vertices: self.motion.vertices,
                render_vertices: self.motion.render_vertices,
                skinned: u32::from(self.motion.skinned),
                vertex_normals: u32::from(self.vertex_normals),
                joints: rig.joints.len() as u32,
                _pad0: 0,
                _pad1: 0,
                _pad2: 0,
            }),
        );
        queue.write_buffer(&self.data, 0, bytemuck::cast_slice(&data));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("pose"),
            timestamp_writes: None,
        });
        for (pipeline, group, items) in [
            (
                &self.pipelines.vertices,
                &self.vertices_group,
                self.motion.vertices,
            ),
            (
                &self.pipelines.render,
                &self.render_group,
                self.motion.render_vertices,
            ),
        ] {
            let [x, y] = workgroups(items);
            if x > 0 {
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(x, y, 1);
            }
        }
        drop(pass);
        self.posed.bounds = self.motion.bounds(pose);
        Ok(())
    }
}

/// Bytes of `pose_data` for `rig`: two matrices a joint, the weights in whole vec4s (one at least).
fn pose_data_bytes(rig: &Rig) -> u64 {
    let floats = 32 * rig.joints.len() + rig.morph_weights.len().next_multiple_of(4);
    4 * floats.max(4) as u64
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
