//! [`Technique::Joined`](crate::render::Technique::Joined), the default: compacted edges with
//! gap-free joins (thesis §10 non-duplicate detection, §13 next-index capping, §8.3 half quads, §9.1
//! depth-scaled widths) and the chamfer highlight of seed 000.
//!
//! Per frame on the GPU (`shaders/classify.wgsl`, `args.wgsl`, `joins.wgsl`, `chamfers.wgsl`, then
//! `edges.wgsl` and `caps.wgsl` in the application's pass): a cull pass (`cull.wgsl`) keeps the
//! asset's edge clusters that may hold a drawn edge (facing cone and sphere, frustum), classify tests
//! the edges of those clusters only and appends the drawn ones to a compact list that is the instance
//! count of an indirect draw, projecting each drawn edge once into a screen record; an args pass sizes
//! the indirect join dispatch; joins find each drawn end's nearest drawn neighbours by screen angle
//! (next-index walk or cap-buffer head), cut overlapping quads apart and emit round caps for outer
//! gaps, so no pixel is covered twice and translucent colours blend once.

use std::sync::Arc;

use glam::Vec3;

use super::{Blocks, FrameContext, PerAsset, TechniqueFrame};
use crate::render::layout::drawn::COLOR_COUNT;
use crate::render::layout::{self, ChamferRecord, DRAWN_BYTES, JOIN_BYTES_PER_END, ScreenRecord};
use crate::render::lighting::Light;
use crate::render::pipelines::{Access, BindingSet, RenderPipeline, workgroups};
use crate::render::target::checked;
use crate::render::{CapMethod, DrawCounts, Pipelines as Cache, RenderError, modules};

use Access::{Instance, Read, Uniform, Write};

const COMPUTE: wgpu::ShaderStages = wgpu::ShaderStages::COMPUTE;

// Binding numbers are the shaders' (common.wgsl, compute.wgsl, draw.wgsl); each pass binds only what
// it uses, which keeps every stage within wgpu's default limit of 8 storage buffers.
const CLASSIFY: BindingSet = BindingSet {
    label: "classify",
    stages: COMPUTE,
    entries: &[
        (0, Instance),
        (14, Write),
        (1, Read),
        (2, Read),
        (3, Read),
        (5, Write),
        (6, Write),
        (8, Write),
        (10, Write),
        (18, Write),
    ],
};
const CULL: BindingSet = BindingSet {
    label: "cull",
    stages: COMPUTE,
    entries: &[
        (0, Instance),
        (8, Write),
        (18, Write),
        (19, Read),
        (21, Write),
    ],
};
const JOINS: BindingSet = BindingSet {
    label: "joins",
    stages: COMPUTE,
    entries: &[
        (0, Instance),
        (14, Write),
        (4, Read),
        (5, Write),
        (6, Write),
        (7, Write),
        (8, Write),
        (10, Write),
        (20, Read),
    ],
};
const RECORDS: BindingSet = BindingSet {
    label: "chamfer records",
    stages: COMPUTE,
    entries: &[
        (0, Instance),
        (1, Read),
        (2, Read),
        (3, Read),
        (6, Write),
        (8, Write),
        (10, Write),
        (11, Write),
        (14, Write),
    ],
};
const ARGS: BindingSet = BindingSet {
    label: "edge lists",
    stages: COMPUTE,
    entries: &[(0, Instance), (8, Write), (14, Write), (16, Write)],
};
const DRAW: BindingSet = BindingSet {
    label: "edge draw",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[
        (0, Instance),
        (15, Read),
        (6, Read),
        (7, Read),
        (8, Read),
        (10, Read),
        (11, Read),
        (12, Read),
        (13, Uniform),
    ],
};

const SEGMENTS: BindingSet = BindingSet {
    label: "intersection edges",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Instance), (17, Read)],
};

/// Offset of the cap draw's arguments in the `out` buffer.
const CAP_DRAW_OFFSET: u64 = std::mem::size_of::<layout::DrawArgs>() as u64;

/// The technique's pipelines and layouts, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    classify_layout: wgpu::BindGroupLayout,
    cull_layout: wgpu::BindGroupLayout,
    joins_layout: wgpu::BindGroupLayout,
    records_layout: wgpu::BindGroupLayout,
    args_layout: wgpu::BindGroupLayout,
    draw_layout: wgpu::BindGroupLayout,
    reset: wgpu::ComputePipeline,
    mark: wgpu::ComputePipeline,
    classify: wgpu::ComputePipeline,
    cull: wgpu::ComputePipeline,
    cull_args: wgpu::ComputePipeline,
    classify_clusters: wgpu::ComputePipeline,
    finish: wgpu::ComputePipeline,
    args: wgpu::ComputePipeline,
    joins_next: wgpu::ComputePipeline,
    joins_heads: wgpu::ComputePipeline,
    clear_joins: wgpu::ComputePipeline,
    chamfer_records: wgpu::ComputePipeline,
    edges: wgpu::RenderPipeline,
    caps: wgpu::RenderPipeline,
    segments_layout: wgpu::BindGroupLayout,
    segments: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layouts =
            [CLASSIFY, CULL, JOINS, RECORDS, ARGS, DRAW, SEGMENTS].map(|set| cache.layout(&set));
        let [
            classify_layout,
            cull_layout,
            joins_layout,
            records_layout,
            args_layout,
            draw_layout,
            segments_layout,
        ] = layouts;
        let classify = cache.module("classify.wgsl", &modules::classify())?;
        let joins = cache.module("joins.wgsl", &modules::joins())?;
        let args = cache.module("args.wgsl", &modules::args())?;
        let records = cache.module("chamfers.wgsl", &modules::chamfers())?;
        let target = cache.target();
        let draw = |label,
                    layout: &wgpu::BindGroupLayout,
                    module: &wgpu::ShaderModule,
                    vertex,
                    fragment| {
            cache.render_pipeline(
                &[layout],
                RenderPipeline {
                    label,
                    module,
                    vertex,
                    fragment: Some(fragment),
                    buffers: &[],
                    primitive: wgpu::PrimitiveState::default(),
                    depth_stencil: target.depth(false, wgpu::CompareFunction::LessEqual),
                    multisample: target.multisample(),
                    color: Some(target.blended_color()),
                },
            )
        };
        let edges = draw(
            "edges",
            &draw_layout,
            &cache.module("edges.wgsl", &modules::edges())?,
            "edge_vertex_main",
            "edge_fragment",
        )?;
        let caps = draw(
            "caps",
            &draw_layout,
            &cache.module("caps.wgsl", &modules::caps())?,
            "cap_vertex_main",
            "cap_fragment",
        )?;
        Ok(Self {
            reset: cache.compute_pipeline(&args_layout, &args, "reset")?,
            mark: cache.compute_pipeline(&classify_layout, &classify, "mark")?,
            classify: cache.compute_pipeline(&classify_layout, &classify, "classify")?,
            cull: cache.compute_pipeline(&cull_layout, &classify, "cull")?,
            cull_args: cache.compute_pipeline(&cull_layout, &classify, "cull_args")?,
            classify_clusters: cache.compute_pipeline(
                &classify_layout,
                &classify,
                "classify_clusters",
            )?,
            finish: cache.compute_pipeline(&args_layout, &args, "finish")?,
            args: cache.compute_pipeline(&args_layout, &args, "args")?,
            joins_next: cache.compute_pipeline(&joins_layout, &joins, "joins_next")?,
            joins_heads: cache.compute_pipeline(&joins_layout, &joins, "joins_heads")?,
            clear_joins: cache.compute_pipeline(&joins_layout, &joins, "clear_joins")?,
            chamfer_records: cache.compute_pipeline(
                &records_layout,
                &records,
                "chamfer_records",
            )?,
            segments: draw(
                "intersection edges",
                &segments_layout,
                &cache.module("intersections.wgsl", &modules::intersections())?,
                "segment_vertex",
                "segment_fragment",
            )?,
            edges,
            caps,
            segments_layout,
            classify_layout,
            cull_layout,
            joins_layout,
            records_layout,
            args_layout,
            draw_layout,
        })
    }
}

/// The slots a frame starts with: every edge of every instance up to this many, then a share.
const FIRST_SLOTS: u64 = 1 << 14;

/// The frame's lists: drawn edges, their joins, screen and chamfer records, the cap list, each
/// instance's first slot and colours. Sized by slots (what can be drawn), not by edges.
#[derive(Debug)]
struct Lists {
    capacity: u32,
    instances: u32,
    chamfers: bool,
    drawn: wgpu::Buffer,
    joins: wgpu::Buffer,
    out: wgpu::Buffer,
    dispatch: wgpu::Buffer,
    screen: wgpu::Buffer,
    chamfer_records: wgpu::Buffer,
    starts: wgpu::Buffer,
    colors: wgpu::Buffer,
    bytes: u64,
}

impl Lists {
    fn new(
        cache: &Cache,
        capacity: u32,
        instances: u32,
        chamfers: bool,
    ) -> Result<Self, RenderError> {
        let device = cache.device();
        let limit = device.limits().max_storage_buffer_binding_size;
        let mut bytes = 0;
        let mut storage = |what: &'static str, size: u64, usage: wgpu::BufferUsages| {
            if size > limit {
                return Err(RenderError::TooLarge {
                    what,
                    bytes: size,
                    limit,
                });
            }
            let size = size.max(64);
            bytes += size;
            checked(device, what, || {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(what),
                    size,
                    usage: wgpu::BufferUsages::STORAGE | usage,
                    mapped_at_creation: false,
                })
            })
        };
        let none = wgpu::BufferUsages::empty();
        let slots = u64::from(capacity);
        let size = |t: usize| t as u64;
        let indirect = wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_SRC;
        let out_bytes = size(std::mem::size_of::<layout::Out>())
            + size(std::mem::size_of::<layout::Cap>()) * (slots + 64);
        Ok(Self {
            drawn: storage("drawn edges", DRAWN_BYTES * slots, none)?,
            joins: storage("joins", 2 * JOIN_BYTES_PER_END * slots, none)?,
            out: storage("edge draw lists", out_bytes, indirect)?,
            dispatch: storage("joins dispatch", 16, indirect)?,
            screen: storage(
                "screen quads",
                size(std::mem::size_of::<ScreenRecord>()) * slots,
                none,
            )?,
            // Highlight records only while a style asks for the highlight.
            chamfer_records: storage(
                "chamfer records",
                size(std::mem::size_of::<ChamferRecord>()) * if chamfers { slots } else { 1 },
                none,
            )?,
            starts: storage("instance starts", 4 * u64::from(instances), none)?,
            colors: storage(
                "instance colours",
                16 * u64::from(COLOR_COUNT) * u64::from(instances),
                wgpu::BufferUsages::COPY_DST,
            )?,
            capacity,
            instances,
            chamfers,
            bytes,
        })
    }
}

/// Per asset: the edge state (slot + 1 per edge, shared by the asset's instances in turn), the
/// clusters a chunk's cull pass kept, and the compute groups over them, the asset's sections and the
/// lists; classification and chamfer records have a group per chunk of the edge section.
#[derive(Debug)]
struct AssetGroups {
    state: wgpu::Buffer,
    survivors: wgpu::Buffer,
    /// The indirect dispatch over the kept clusters.
    cull_dispatch: wgpu::Buffer,
    classify: Vec<wgpu::BindGroup>,
    cull: wgpu::BindGroup,
    joins: wgpu::BindGroup,
    records: Vec<wgpu::BindGroup>,
    /// Over the asset's intersection segments, if it has any.
    segments: Option<wgpu::BindGroup>,
}

/// What one drawn instance's passes run over.
#[derive(Debug)]
struct Run {
    /// Its asset's groups.
    asset: usize,
    /// Per chunk of the asset's edge section: its uniform block's offset and its edges. The first
    /// block is the instance's.
    chunks: Vec<(u32, u32)>,
    /// The asset's capped vertices.
    head_count: u32,
}

impl Run {
    /// The instance's uniform block.
    fn block(&self) -> u32 {
        self.chunks.first().map_or(0, |&(block, _)| block)
    }
}

/// The four side planes of the view through `mvp` in model space, each moved out by `reach_px`
/// pixels and scaled to a unit normal: a point `p` with `dot(plane, (p, 1)) > 0` projects more than
/// `reach_px` beyond that side of the viewport (whatever its depth, behind the camera included,
/// since the test is linear in clip space). Zeros, which nothing is beyond, for a degenerate plane.
fn side_planes(mvp: glam::Mat4, viewport: [f32; 2], reach_px: f32) -> [[f32; 4]; 4] {
    let mvp = mvp.as_dmat4();
    let [x, y, w] = [0, 1, 3].map(|i| mvp.row(i));
    let pad = |size: f32| 1.0 + 2.0 * f64::from(reach_px) / f64::from(size.max(1.0));
    let (px, py) = (pad(viewport[0]), pad(viewport[1]));
    [x - px * w, -x - px * w, y - py * w, -y - py * w].map(|plane| {
        let length = plane.truncate().length();
        if length > 0.0 && length.is_finite() && plane.is_finite() {
            (plane / length).as_vec4().to_array()
        } else {
            [0.0; 4]
        }
    })
}

/// The readback of how many slots a frame wanted, without ever waiting: copied at the end of one
/// frame's compute, mapped at the next prepare, read at a later one.
#[derive(Debug)]
struct Needed {
    staging: wgpu::Buffer,
    state: Arc<std::sync::atomic::AtomicU8>,
}

const IDLE: u8 = 0;
const COPIED: u8 = 1;
const MAPPING: u8 = 2;
const MAPPED: u8 = 3;

impl Needed {
    fn new(cache: &Cache) -> Self {
        Self {
            staging: cache.device().create_buffer(&wgpu::BufferDescriptor {
                label: Some("needed slots readback"),
                size: std::mem::size_of::<layout::Out>() as u64,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            }),
            state: Arc::new(std::sync::atomic::AtomicU8::new(IDLE)),
        }
    }

    /// Moves the readback along; returns the slots an earlier frame wanted, once known.
    fn poll(&self, device: &wgpu::Device) -> Option<u32> {
        use std::sync::atomic::Ordering;
        match self.state.load(Ordering::Acquire) {
            COPIED => {
                // The frame that copied has been submitted by now (or dropped: then stale zeros).
                self.state.store(MAPPING, Ordering::Release);
                let state = self.state.clone();
                self.staging
                    .map_async(wgpu::MapMode::Read, .., move |result| {
                        state.store(
                            if result.is_ok() { MAPPED } else { IDLE },
                            Ordering::Release,
                        );
                    });
                let _ = device.poll(wgpu::PollType::Poll);
                None
            }
            MAPPING => {
                let _ = device.poll(wgpu::PollType::Poll);
                None
            }
            MAPPED => {
                let needed = self.staging.get_mapped_range(..).ok().map(|bytes| {
                    let words: &[u32] = bytemuck::cast_slice(&bytes);
                    words[8]
                });
                self.staging.unmap();
                self.state.store(IDLE, Ordering::Release);
                needed
            }
            _ => None,
        }
    }

    /// Records the copy of this frame's counts, if no readback is under way.
    fn copy(&self, encoder: &mut wgpu::CommandEncoder, out: &wgpu::Buffer) {
        use std::sync::atomic::Ordering;
        if self.state.load(Ordering::Acquire) == IDLE {
            encoder.copy_buffer_to_buffer(out, 0, &self.staging, 0, self.staging.size());
            self.state.store(COPIED, Ordering::Release);
        }
    }
}

/// A frame's state: the lists, one block per instance, per-asset groups, and what each instance runs.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    cache: Cache,
    blocks: Blocks,
    lists: Option<Lists>,
    assets: PerAsset<AssetGroups>,
    args_group: Option<wgpu::BindGroup>,
    draw_group: Option<wgpu::BindGroup>,
    cos_power: wgpu::Buffer,
    lighting: wgpu::Buffer,
    needed: Needed,
    /// Per drawn instance, what its passes run over.
    runs: Vec<Run>,
    /// Cull clusters before classifying edges.
    culling: bool,
    /// The exponent the cos-power row holds now.
    row_exponent: Option<f32>,
    highlight: bool,
    caps: CapMethod,
    /// The slots the next lists must have, at least.
    wanted_slots: u64,
}

impl Frame {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        Self::with_capacity(cache, 0)
    }

    /// A frame whose lists start with `slots` slots (at least 64; 0: sized from the first frame).
    pub(crate) fn with_capacity(cache: &Cache, slots: u64) -> Result<Self, RenderError> {
        let device = cache.device();
        let uniform = |label, size: usize, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Ok(Self {
            pipelines: cache.joined()?,
            cache: cache.clone(),
            blocks: Blocks::new(cache, "edge frame", std::mem::size_of::<layout::Frame>()),
            lists: None,
            assets: PerAsset::default(),
            args_group: None,
            draw_group: None,
            cos_power: uniform(
                "cos power row",
                4 * (crate::highlight::table::SAMPLES + 1),
                wgpu::BufferUsages::STORAGE,
            ),
            lighting: uniform(
                "highlight lighting",
                std::mem::size_of::<layout::Lighting>(),
                wgpu::BufferUsages::UNIFORM,
            ),
            needed: Needed::new(cache),
            runs: Vec::new(),
            culling: true,
            row_exponent: None,
            highlight: false,
            caps: CapMethod::NextIndex,
            wanted_slots: slots,
        })
    }

    /// Writes the highlight's row and lighting for `style`.
    fn prepare_highlight(&mut self, cx: &FrameContext<'_>) {
        let Some(highlight) = &cx.style.highlight else {
            self.highlight = false;
            return;
        };
        self.highlight = true;
        let material = highlight.material;
        let exponent = material.shininess.clamp(1.0, 128.0) + 1.0;
        if self.row_exponent != Some(exponent) {
            let row = crate::highlight::table::CosPowerRow::new(exponent);
            cx.queue
                .write_buffer(&self.cos_power, 0, bytemuck::cast_slice(row.values()));
            self.row_exponent = Some(exponent);
        }
        let light = match highlight.light {
            Light::Directional(d) => {
                let d = Vec3::from(d).normalize_or(Vec3::Z);
                [d.x, d.y, d.z, 0.0]
            }
            Light::Point([x, y, z]) => [x, y, z, 1.0],
        };
        // K by the first instance (for one asset: the camera's distance to its centre).
        let k = highlight.k.unwrap_or_else(|| {
            cx.instances.first().map_or(1.0, |d| {
                d.camera.eye().truncate().distance(d.asset.center())
            })
        });
        let [r, g, b] = highlight.color;
        let lighting = layout::Lighting {
            light,
            color: [r, g, b, k],
            material: [
                material.diffuse,
                material.specular,
                exponent - 1.0,
                highlight.ambient.clamp(0.0, 1.0),
            ],
        };
        cx.queue
            .write_buffer(&self.lighting, 0, bytemuck::bytes_of(&lighting));
    }

    /// The lists for this frame, made or remade when they are too small.
    fn ensure_lists(&mut self, cx: &FrameContext<'_>) -> Result<(), RenderError> {
        let instances = (cx.instances.len() as u32).max(1);
        // Highlight records only where an asset has chamfer edges to highlight.
        let chamfers = self.highlight && cx.instances.iter().any(|d| d.asset.has_chamfers);
        let upper: u64 = cx
            .instances
            .iter()
            .map(|d| u64::from(d.asset.edge_count))
            .sum();
        // Every edge up to FIRST_SLOTS, then a sixteenth (unless the frame was told): far more than
        // a view draws of a large mesh. Grown from what frames want.
        let first = if self.wanted_slots > 0 {
            0
        } else {
            upper.min(FIRST_SLOTS.max(upper / 16))
        };
        let wanted = self.wanted_slots.max(first).max(64);
        // The largest per-slot list must fit one storage binding.
        let per_slot = if chamfers {
            std::mem::size_of::<ChamferRecord>()
        } else {
            std::mem::size_of::<ScreenRecord>()
        } as u64;
        let limit = self.cache.device().limits().max_storage_buffer_binding_size / per_slot;
        let enough = self.lists.as_ref().is_some_and(|l| {
            u64::from(l.capacity) >= wanted.min(limit)
                && l.instances >= instances
                && (l.chamfers || !chamfers)
        });
        if enough {
            return Ok(());
        }
        let capacity = wanted.min(limit) as u32;
        let instances = instances.next_power_of_two();
        self.lists = None;
        self.lists = Some(Lists::new(&self.cache, capacity, instances, chamfers)?);
        self.assets.clear();
        self.args_group = None;
        self.draw_group = None;
        Ok(())
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let device = cx.pipelines.device().clone();
        if let Some(needed) = self.needed.poll(&device)
            && let Some(lists) = &self.lists
            && needed > lists.capacity
        {
            // An earlier frame wanted more slots than the lists have: a quarter more next time.
            self.wanted_slots = u64::from(needed) + u64::from(needed) / 4;
        }
        self.prepare_highlight(cx);
        self.ensure_lists(cx)?;
        let Some(lists) = &self.lists else {
            return Err(super::mismatch(cx));
        };
        let caps = cx.style.caps;
        self.culling = cx.style.cluster_culling;
        // One block per chunk of each instance's edges (the first is the instance's own).
        let mut frames: Vec<layout::Frame> = Vec::new();
        let mut chunk_blocks: Vec<Vec<(usize, u32)>> = Vec::with_capacity(cx.instances.len());
        for (i, d) in cx.instances.iter().enumerate() {
            let mut uniform = super::frame_uniform(cx, d, i, 0);
            uniform.capacity = lists.capacity;
            uniform.cap_capacity = lists.capacity + 64;
            uniform.highlight = u32::from(self.highlight);
            // Off-screen edges are left out only while an edge's reach on screen is bounded: not
            // with depth-scaled widths (unbounded near the camera) or highlight strips.
            if !self.highlight && uniform.depth_ref == 0.0 {
                let reach = uniform.width.max(uniform.min_width) + 2.0;
                uniform.frustum = side_planes(d.camera.view_projection(), uniform.viewport, reach);
            }
            let mut blocks = Vec::new();
            for (first, edges) in d.asset.edge_chunks() {
                let mut chunk = uniform;
                chunk.first_edge = first;
                chunk.edge_count = edges;
                blocks.push((frames.len(), edges));
                frames.push(chunk);
            }
            chunk_blocks.push(blocks);
        }
        if frames.is_empty() {
            // The bookkeeping passes still run (the draws must find empty lists).
            let mut uniform: layout::Frame = bytemuck::Zeroable::zeroed();
            uniform.capacity = lists.capacity;
            uniform.cap_capacity = lists.capacity + 64;
            frames.push(uniform);
        }
        if self.blocks.write(cx.pipelines, cx.queue, &frames) {
            self.assets.clear();
            self.args_group = None;
            self.draw_group = None;
        }
        let colors: Vec<[f32; 4]> = cx.instances.iter().flat_map(|d| d.colors.array()).collect();
        if !colors.is_empty() {
            cx.queue
                .write_buffer(&lists.colors, 0, bytemuck::cast_slice(&colors));
        }
        let pipelines = self.pipelines.clone();
        let group =
            |set: &BindingSet, layout: &wgpu::BindGroupLayout, buffers: &[(u32, &wgpu::Buffer)]| {
                set.group(&device, layout, buffers)
            };
        let blocks = self.blocks.buffer().clone();
        if self.args_group.is_none() {
            self.args_group = Some(group(
                &ARGS,
                &pipelines.args_layout,
                &[
                    (0, &blocks),
                    (8, &lists.out),
                    (14, &lists.starts),
                    (16, &lists.dispatch),
                ],
            ));
        }
        if self.draw_group.is_none() {
            self.draw_group = Some(group(
                &DRAW,
                &pipelines.draw_layout,
                &[
                    (0, &blocks),
                    (6, &lists.drawn),
                    (7, &lists.joins),
                    (8, &lists.out),
                    (10, &lists.screen),
                    (11, &lists.chamfer_records),
                    (12, &self.cos_power),
                    (13, &self.lighting),
                    (15, &lists.colors),
                ],
            ));
        }
        self.assets.retain(cx.instances);
        self.runs.clear();
        for (drawn, chunks) in cx.instances.iter().zip(chunk_blocks) {
            let made = self.assets.index(drawn.asset, |asset| {
                let buffer = |label: &'static str, size: u64, usage: wgpu::BufferUsages| {
                    checked(&device, label, || {
                        device.create_buffer(&wgpu::BufferDescriptor {
                            label: Some(label),
                            size: size.max(64),
                            usage: wgpu::BufferUsages::STORAGE | usage,
                            mapped_at_creation: false,
                        })
                    })
                };
                let state = buffer(
                    "edge state",
                    4 * u64::from(asset.edge_count),
                    wgpu::BufferUsages::empty(),
                )?;
                let chunk_clusters = asset
                    .chunk_edges
                    .min(asset.edge_count)
                    .div_ceil(layout::CLUSTER_EDGES);
                let survivors = buffer(
                    "kept clusters",
                    std::mem::size_of::<layout::Survivors>() as u64 + 4 * u64::from(chunk_clusters),
                    wgpu::BufferUsages::empty(),
                )?;
                let cull_dispatch = buffer("cluster dispatch", 16, wgpu::BufferUsages::INDIRECT)?;
                let buffers: [(u32, &wgpu::Buffer); 17] = [
                    (0, &blocks),
                    (1, &asset.topology_positions),
                    (2, &asset.edge_vertices),
                    (3, &asset.edge_attributes),
                    (4, &asset.rings),
                    (5, &state),
                    (6, &lists.drawn),
                    (7, &lists.joins),
                    (8, &lists.out),
                    (10, &lists.screen),
                    (11, &lists.chamfer_records),
                    (14, &lists.starts),
                    (13, &self.lighting),
                    (18, &survivors),
                    (19, &asset.clusters),
                    (20, &asset.cap_heads),
                    (21, &cull_dispatch),
                ];
                let segments = (asset.intersection_count > 0).then(|| {
                    group(
                        &SEGMENTS,
                        &pipelines.segments_layout,
                        &[(0, &blocks), (17, &asset.intersection_segments)],
                    )
                });
                // Per chunk, the edge section's window.
                let per_chunk = |set: &BindingSet, layout: &wgpu::BindGroupLayout| {
                    asset
                        .edge_chunks()
                        .map(|chunk| {
                            set.group_with_window(
                                &device,
                                layout,
                                &buffers,
                                Some((2, asset.edge_window(chunk))),
                            )
                        })
                        .collect()
                };
                Ok(AssetGroups {
                    segments,
                    classify: per_chunk(&CLASSIFY, &pipelines.classify_layout),
                    cull: group(&CULL, &pipelines.cull_layout, &buffers),
                    joins: group(&JOINS, &pipelines.joins_layout, &buffers),
                    records: per_chunk(&RECORDS, &pipelines.records_layout),
                    state,
                    survivors,
                    cull_dispatch,
                })
            })?;
            self.runs.push(Run {
                asset: made,
                chunks: chunks
                    .into_iter()
                    .map(|(block, edges)| (self.blocks.offset(block), edges))
                    .collect(),
                head_count: drawn.asset.head_count,
            });
        }
        // Without rings there is nothing to join by.
        self.caps = if cx.instances.iter().all(|d| d.asset.has_rings) {
            caps
        } else {
            CapMethod::None
        };
        self.record(encoder);
        if let Some(lists) = &self.lists {
            self.needed.copy(encoder, &lists.out);
        }
        Ok(())
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let (Some(lists), Some(draw_group)) = (&self.lists, &self.draw_group) else {
            return;
        };
        let pipelines = &self.pipelines;
        pass.set_bind_group(0, draw_group, &[0]);
        pass.set_pipeline(&pipelines.edges);
        pass.draw_indirect(&lists.out, 0);
        if self.caps != CapMethod::None {
            pass.set_pipeline(&pipelines.caps);
            pass.draw_indirect(&lists.out, CAP_DRAW_OFFSET);
        }
        for run in &self.runs {
            let (gpu, groups) = self.assets.get(run.asset);
            if let Some(segments) = &groups.segments {
                pass.set_bind_group(0, segments, &[run.block()]);
                pass.set_pipeline(&pipelines.segments);
                pass.draw(0..18, 0..gpu.intersection_count);
            }
        }
    }

    fn read_counts(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Option<Result<DrawCounts, RenderError>> {
        let lists = self.lists.as_ref()?;
        let read = || {
            let size = std::mem::size_of::<layout::Out>() as u64;
            let words = crate::render::offscreen::read_buffer(device, queue, &lists.out, size)?;
            let words: &[u32] = bytemuck::cast_slice(&words);
            Ok(DrawCounts {
                edges: words[1],
                caps: if self.caps == CapMethod::None {
                    0
                } else {
                    words[5]
                },
                wanted: words[8],
                clusters_kept: words[9],
            })
        };
        Some(read())
    }

    fn gpu_bytes(&self) -> u64 {
        let lists = self.lists.as_ref().map_or(0, |l| l.bytes);
        let state: u64 = self
            .assets
            .iter()
            .map(|a| a.state.size() + a.survivors.size() + a.cull_dispatch.size())
            .sum();
        lists + state + self.blocks.gpu_bytes() + self.cos_power.size() + self.lighting.size()
    }
}

impl Frame {
    /// Records the frame's classification and joins: instance after instance, then the clamp.
    fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        let (Some(args_group), Some(lists)) = (&self.args_group, &self.lists) else {
            return;
        };
        let dispatch = &lists.dispatch;
        let pipelines = &self.pipelines;
        let joins = self.caps != CapMethod::None || self.highlight;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("chamfer edges"),
            timestamp_writes: None,
        });
        pass.set_bind_group(0, args_group, &[0]);
        pass.set_pipeline(&pipelines.reset);
        pass.dispatch_workgroups(1, 1, 1);
        for run in &self.runs {
            let (_, groups) = self.assets.get(run.asset);
            let offset = run.block();
            pass.set_bind_group(0, &groups.classify[0], &[offset]);
            pass.set_pipeline(&pipelines.mark);
            pass.dispatch_workgroups(1, 1, 1);
            for (classify, &(block, edges)) in groups.classify.iter().zip(&run.chunks) {
                if self.culling {
                    pass.set_bind_group(0, &groups.cull, &[block]);
                    pass.set_pipeline(&pipelines.cull);
                    let [x, y] = workgroups(edges.div_ceil(layout::CLUSTER_EDGES));
                    pass.dispatch_workgroups(x, y, 1);
                    pass.set_pipeline(&pipelines.cull_args);
                    pass.dispatch_workgroups(1, 1, 1);
                    pass.set_bind_group(0, classify, &[block]);
                    pass.set_pipeline(&pipelines.classify_clusters);
                    pass.dispatch_workgroups_indirect(&groups.cull_dispatch, 0);
                } else {
                    pass.set_bind_group(0, classify, &[block]);
                    pass.set_pipeline(&pipelines.classify);
                    let [x, y] = workgroups(edges);
                    pass.dispatch_workgroups(x, y, 1);
                }
            }
            if !joins {
                continue;
            }
            // The join dispatch is sized by what this instance drew (each dispatch is its own
            // usage scope, so the arguments written here are read as indirect ones below).
            pass.set_bind_group(0, args_group, &[offset]);
            pass.set_pipeline(&pipelines.args);
            pass.dispatch_workgroups(1, 1, 1);
            if self.highlight {
                // One thread per drawn edge end: twice as many as records need; the rest return.
                // Each chunk records its own edges.
                for (records, &(block, _)) in groups.records.iter().zip(&run.chunks) {
                    pass.set_bind_group(0, records, &[block]);
                    pass.set_pipeline(&pipelines.chamfer_records);
                    pass.dispatch_workgroups_indirect(dispatch, 0);
                }
            }
            pass.set_bind_group(0, &groups.joins, &[offset]);
            match self.caps {
                CapMethod::NextIndex => {
                    pass.set_pipeline(&pipelines.joins_next);
                    pass.dispatch_workgroups_indirect(dispatch, 0);
                }
                CapMethod::CapBuffer => {
                    pass.set_pipeline(&pipelines.clear_joins);
                    pass.dispatch_workgroups_indirect(dispatch, 0);
                    pass.set_pipeline(&pipelines.joins_heads);
                    let [x, y] = workgroups(run.head_count);
                    pass.dispatch_workgroups(x, y, 1);
                }
                CapMethod::None => {}
            }
        }
        pass.set_bind_group(0, args_group, &[0]);
        pass.set_pipeline(&pipelines.finish);
        pass.dispatch_workgroups(1, 1, 1);
    }
}
