//! [`Technique::Joined`](crate::render::Technique::Joined), the default: compacted edges with
//! gap-free joins (thesis §10 non-duplicate detection, §13 next-index capping, §8.3 half quads, §9.1
//! depth-scaled widths) and the chamfer highlight of seed 000.
//!
//! Per frame on the GPU (`shaders/classify.wgsl`, `args.wgsl`, `joins.wgsl`, `chamfers.wgsl`, then
//! `edges.wgsl` and `caps.wgsl` in the application's pass): classify tests every edge against the
//! face planes computed at upload and appends the drawn ones to a compact list that is the instance
//! count of an indirect draw, projecting each drawn edge once into a screen record; an args pass sizes
//! the indirect join dispatch; joins find each drawn end's nearest drawn neighbours by screen angle
//! (next-index walk or cap-buffer head), cut overlapping quads apart and emit round caps for outer
//! gaps, so no pixel is covered twice and translucent colours blend once.

use std::sync::Arc;

use glam::Vec3;

use super::{FrameContext, TechniqueFrame};
use crate::render::layout::{self, ChamferRecord, DRAWN_BYTES, JOIN_BYTES_PER_END, ScreenRecord};
use crate::render::lighting::Light;
use crate::render::pipelines::{Access, BindingSet, RenderPipeline, workgroups};
use crate::render::target::checked;
use crate::render::{CapMethod, DrawCounts, GpuAsset, RenderError, modules};

use Access::{Read, Uniform, Write};

const COMPUTE: wgpu::ShaderStages = wgpu::ShaderStages::COMPUTE;

// Binding numbers are the shaders' (common.wgsl, compute.wgsl, draw.wgsl); each pass binds only what
// it uses, which keeps every stage within wgpu's default limit of 8 storage buffers.
const CLASSIFY: BindingSet = BindingSet {
    label: "classify",
    stages: COMPUTE,
    entries: &[
        (0, Uniform),
        (1, Read),
        (2, Read),
        (3, Read),
        (5, Write),
        (6, Write),
        (8, Write),
        (9, Read),
        (10, Write),
    ],
};
const JOINS: BindingSet = BindingSet {
    label: "joins",
    stages: COMPUTE,
    entries: &[
        (0, Uniform),
        (4, Read),
        (5, Write),
        (6, Write),
        (7, Write),
        (8, Write),
        (10, Write),
    ],
};
const RECORDS: BindingSet = BindingSet {
    label: "chamfer records",
    stages: COMPUTE,
    entries: &[
        (0, Uniform),
        (1, Read),
        (2, Read),
        (3, Read),
        (6, Write),
        (8, Write),
        (9, Read),
        (10, Write),
        (11, Write),
    ],
};
const ARGS: BindingSet = BindingSet {
    label: "edge args",
    stages: COMPUTE,
    entries: &[(0, Read), (1, Write)],
};
const DRAW: BindingSet = BindingSet {
    label: "edge draw",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[
        (0, Uniform),
        (6, Read),
        (7, Read),
        (8, Read),
        (10, Read),
        (11, Read),
        (12, Read),
        (13, Uniform),
    ],
};

/// Offset of the cap draw's arguments in the `out` buffer.
const CAP_DRAW_OFFSET: u64 = std::mem::size_of::<layout::DrawArgs>() as u64;

/// The technique's pipelines and layouts, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    classify_layout: wgpu::BindGroupLayout,
    joins_layout: wgpu::BindGroupLayout,
    records_layout: wgpu::BindGroupLayout,
    args_layout: wgpu::BindGroupLayout,
    draw_layout: wgpu::BindGroupLayout,
    reset: wgpu::ComputePipeline,
    classify: wgpu::ComputePipeline,
    finish: wgpu::ComputePipeline,
    args: wgpu::ComputePipeline,
    joins_next: wgpu::ComputePipeline,
    joins_heads: wgpu::ComputePipeline,
    clear_joins: wgpu::ComputePipeline,
    chamfer_records: wgpu::ComputePipeline,
    edges: wgpu::RenderPipeline,
    caps: wgpu::RenderPipeline,
}

impl Pipelines {
    pub(crate) fn new(cache: &crate::render::Pipelines) -> Result<Self, RenderError> {
        let layouts = [CLASSIFY, JOINS, RECORDS, ARGS, DRAW].map(|set| cache.layout(&set));
        let [
            classify_layout,
            joins_layout,
            records_layout,
            args_layout,
            draw_layout,
        ] = layouts;
        let classify = cache.module("classify.wgsl", &modules::classify())?;
        let joins = cache.module("joins.wgsl", &modules::joins())?;
        let args = cache.module("args.wgsl", &modules::args())?;
        let records = cache.module("chamfers.wgsl", &modules::chamfers())?;
        let target = cache.target();
        let draw = |label, module: &wgpu::ShaderModule, vertex, fragment| {
            cache.render_pipeline(
                &[&draw_layout],
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
            &cache.module("edges.wgsl", &modules::edges())?,
            "edge_vertex_main",
            "edge_fragment",
        )?;
        let caps = draw(
            "caps",
            &cache.module("caps.wgsl", &modules::caps())?,
            "cap_vertex_main",
            "cap_fragment",
        )?;
        Ok(Self {
            reset: cache.compute_pipeline(&classify_layout, &classify, "reset")?,
            classify: cache.compute_pipeline(&classify_layout, &classify, "classify")?,
            finish: cache.compute_pipeline(&classify_layout, &classify, "finish")?,
            args: cache.compute_pipeline(&args_layout, &args, "args")?,
            joins_next: cache.compute_pipeline(&joins_layout, &joins, "joins_next")?,
            joins_heads: cache.compute_pipeline(&joins_layout, &joins, "joins_heads")?,
            clear_joins: cache.compute_pipeline(&joins_layout, &joins, "clear_joins")?,
            chamfer_records: cache.compute_pipeline(
                &records_layout,
                &records,
                "chamfer_records",
            )?,
            edges,
            caps,
            classify_layout,
            joins_layout,
            records_layout,
            args_layout,
            draw_layout,
        })
    }
}

/// One asset's per-frame lists and uniforms.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    frame: wgpu::Buffer,
    out: wgpu::Buffer,
    dispatch: wgpu::Buffer,
    cos_power: wgpu::Buffer,
    lighting: wgpu::Buffer,
    classify_group: wgpu::BindGroup,
    joins_group: wgpu::BindGroup,
    records_group: wgpu::BindGroup,
    args_group: wgpu::BindGroup,
    draw_group: wgpu::BindGroup,
    /// The exponent the cos-power row holds now.
    row_exponent: Option<f32>,
    highlight: bool,
    caps: CapMethod,
    edge_count: u32,
    head_count: u32,
    bytes: u64,
}

impl Frame {
    /// Allocates the lists for `asset`.
    ///
    /// Fails with [`RenderError::TooLarge`] if a list exceeds the device's binding limit.
    pub(crate) fn new(
        cache: &crate::render::Pipelines,
        asset: &GpuAsset,
    ) -> Result<Self, RenderError> {
        let pipelines = cache.joined()?;
        let device = cache.device();
        let edges = u64::from(asset.edge_count);
        let cap_capacity = edges + 64;
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
        let record = |size: usize| size as u64;
        let state = storage("edge state", 4 * edges, none)?;
        let drawn = storage("drawn edges", DRAWN_BYTES * edges, none)?;
        let joins = storage("joins", 2 * JOIN_BYTES_PER_END * edges, none)?;
        let indirect = wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_SRC;
        let out_bytes = record(std::mem::size_of::<layout::Out>())
            + record(std::mem::size_of::<layout::Cap>()) * cap_capacity;
        let out = storage("edge draw lists", out_bytes, indirect)?;
        let dispatch = storage("joins dispatch", 16, indirect)?;
        let screen = storage(
            "screen quads",
            record(std::mem::size_of::<ScreenRecord>()) * edges,
            none,
        )?;
        // Highlight records, only where the asset has chamfer edges to highlight.
        let chamfer_slots = if asset.has_chamfers { edges } else { 0 };
        let chamfers = storage(
            "chamfer records",
            record(std::mem::size_of::<ChamferRecord>()) * chamfer_slots,
            none,
        )?;
        let cos_power = storage(
            "cos power row",
            4 * (crate::highlight::table::SAMPLES as u64 + 1),
            wgpu::BufferUsages::COPY_DST,
        )?;
        let uniform = |label, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let frame = uniform("edge frame", std::mem::size_of::<layout::Frame>());
        let lighting = uniform(
            "highlight lighting",
            std::mem::size_of::<layout::Lighting>(),
        );
        bytes +=
            (std::mem::size_of::<layout::Frame>() + std::mem::size_of::<layout::Lighting>()) as u64;

        let buffers: [(u32, &wgpu::Buffer); 14] = [
            (0, &frame),
            (1, &asset.topology_positions),
            (2, &asset.edge_vertices),
            (3, &asset.edge_attributes),
            (4, &asset.rings),
            (5, &state),
            (6, &drawn),
            (7, &joins),
            (8, &out),
            (9, &asset.face_planes),
            (10, &screen),
            (11, &chamfers),
            (12, &cos_power),
            (13, &lighting),
        ];
        let group = |set: BindingSet, layout| set.group(device, layout, &buffers);
        let args_group = ARGS.group(device, &pipelines.args_layout, &[(0, &out), (1, &dispatch)]);
        Ok(Self {
            classify_group: group(CLASSIFY, &pipelines.classify_layout),
            joins_group: group(JOINS, &pipelines.joins_layout),
            records_group: group(RECORDS, &pipelines.records_layout),
            draw_group: group(DRAW, &pipelines.draw_layout),
            args_group,
            pipelines,
            frame,
            out,
            dispatch,
            cos_power,
            lighting,
            row_exponent: None,
            highlight: false,
            caps: CapMethod::NextIndex,
            edge_count: asset.edge_count,
            head_count: asset.head_count,
            bytes,
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let (camera, style, asset) = (cx.camera, cx.style, cx.asset);
        let mut uniform = super::frame_uniform(cx, 0);
        uniform.cap_capacity = (u64::from(asset.edge_count) + 64).min(u64::from(u32::MAX)) as u32;
        self.highlight = false;
        if let Some(highlight) = &style.highlight {
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
            let k = highlight
                .k
                .unwrap_or_else(|| camera.eye().truncate().distance(asset.center()));
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
        uniform.highlight = u32::from(self.highlight);
        self.caps = if asset.has_rings {
            style.caps
        } else {
            CapMethod::None
        };
        cx.queue
            .write_buffer(&self.frame, 0, bytemuck::bytes_of(&uniform));
        self.record(encoder);
        Ok(())
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let pipelines = &self.pipelines;
        pass.set_bind_group(0, &self.draw_group, &[]);
        pass.set_pipeline(&pipelines.edges);
        pass.draw_indirect(&self.out, 0);
        if self.caps != CapMethod::None {
            pass.set_pipeline(&pipelines.caps);
            pass.draw_indirect(&self.out, CAP_DRAW_OFFSET);
        }
    }

    fn read_counts(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Option<Result<DrawCounts, RenderError>> {
        let read = || {
            let words = crate::render::offscreen::read_buffer(device, queue, &self.out, 32)?;
            let words: &[u32] = bytemuck::cast_slice(&words);
            Ok(DrawCounts {
                edges: words[1],
                caps: if self.caps == CapMethod::None {
                    0
                } else {
                    words[5]
                },
            })
        };
        Some(read())
    }

    fn gpu_bytes(&self) -> u64 {
        self.bytes
    }
}

impl Frame {
    /// Records this frame's classification and joins.
    fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        let pipelines = &self.pipelines;
        let joins = self.caps != CapMethod::None || self.highlight;
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("chamfer classify"),
                timestamp_writes: None,
            });
            let [x, y] = workgroups(self.edge_count);
            pass.set_bind_group(0, &self.classify_group, &[]);
            pass.set_pipeline(&pipelines.reset);
            pass.dispatch_workgroups(1, 1, 1);
            pass.set_pipeline(&pipelines.classify);
            pass.dispatch_workgroups(x, y, 1);
            if joins {
                pass.set_bind_group(0, &self.args_group, &[]);
                pass.set_pipeline(&pipelines.args);
                pass.dispatch_workgroups(1, 1, 1);
            }
        }
        if !joins {
            return;
        }
        // A new pass: the dispatch arguments written above are read as an indirect buffer here.
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("chamfer joins"),
            timestamp_writes: None,
        });
        if self.highlight {
            // One thread per drawn edge end: twice as many as records need; the rest return.
            pass.set_bind_group(0, &self.records_group, &[]);
            pass.set_pipeline(&pipelines.chamfer_records);
            pass.dispatch_workgroups_indirect(&self.dispatch, 0);
        }
        pass.set_bind_group(0, &self.joins_group, &[]);
        match self.caps {
            CapMethod::NextIndex => {
                pass.set_pipeline(&pipelines.joins_next);
                pass.dispatch_workgroups_indirect(&self.dispatch, 0);
            }
            CapMethod::CapBuffer => {
                pass.set_pipeline(&pipelines.clear_joins);
                pass.dispatch_workgroups_indirect(&self.dispatch, 0);
                pass.set_pipeline(&pipelines.joins_heads);
                let [x, y] = workgroups(self.head_count);
                pass.dispatch_workgroups(x, y, 1);
            }
            CapMethod::None => {}
        }
        pass.set_bind_group(0, &self.classify_group, &[]);
        pass.set_pipeline(&pipelines.finish);
        pass.dispatch_workgroups(1, 1, 1);
    }
}
