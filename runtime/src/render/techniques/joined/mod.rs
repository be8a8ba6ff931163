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
//!
//! The folder is split by concern: [`bindings`] (what each pass binds), [`pipelines`], [`lists`]
//! (the frame's lists), [`readback`] (how many slots frames want, read without waiting),
//! [`planes`] (the cull pass's frustum), [`highlight`] (the highlight's uniforms) and [`record`]
//! (the frame's groups and compute pass); this file puts a frame together.

mod bindings;
mod highlight;
mod lists;
mod pipelines;
mod planes;
mod readback;
mod record;

use std::sync::Arc;

use self::bindings::*;
use self::highlight::HighlightUniforms;
use self::lists::{FIRST_SLOTS, Lists};
use self::pipelines::JoinedPipelines;
use self::readback::Needed;
use self::record::{AssetGroups, Run, Work};
use super::{Blocks, FrameContext, FrameOptions, Module, PerAsset, TechniqueFrame};
use crate::render::bindings::{Binding, asset as section};
use crate::render::layout::{self, ChamferRecord, ScreenRecord};
use crate::render::modules::Shader;
use crate::render::target::checked;
use crate::render::{CapMethod, DrawCounts, GpuAsset, Pipelines as Cache, RenderError, Target};

pub(crate) static MODULE: Joined = Joined;

/// The module.
pub(crate) struct Joined;

impl Module for Joined {
    fn shaders(&self, _target: &Target) -> Vec<Shader> {
        pipelines::shaders()
    }

    fn new_frame(
        &self,
        cache: &Cache,
        options: &FrameOptions,
    ) -> Result<Box<dyn TechniqueFrame>, RenderError> {
        Ok(Box::new(Frame::new(cache, options)?))
    }
}

/// Offset of the cap draw's arguments in the `out` buffer.
const CAP_DRAW_OFFSET: u64 = std::mem::size_of::<layout::DrawArgs>() as u64;

/// A frame's state: the lists, one block per instance, per-asset groups, and what each instance runs.
#[derive(Debug)]
struct Frame {
    pipelines: Arc<JoinedPipelines>,
    cache: Cache,
    blocks: Blocks,
    lists: Option<Lists>,
    assets: PerAsset<AssetGroups>,
    args_group: Option<wgpu::BindGroup>,
    draw_group: Option<wgpu::BindGroup>,
    highlight: HighlightUniforms,
    needed: Needed,
    /// Per drawn instance, what its passes run over.
    runs: Vec<Run>,
    /// Cull clusters before classifying edges.
    culling: bool,
    /// This frame draws chamfer edges as highlight strips.
    highlighted: bool,
    caps: CapMethod,
    /// The slots the next lists must have, at least.
    wanted_slots: u64,
}

/// Where each binding of the technique's sets comes from in this frame: the blocks, the lists, the
/// highlight's uniforms, and for an asset's groups its sections, edge state and cull lists.
struct Resources<'r> {
    blocks: &'r Blocks,
    lists: &'r Lists,
    highlight: &'r HighlightUniforms,
    asset: Option<(&'r GpuAsset, [&'r wgpu::Buffer; 3])>,
    /// The edge section's window of the chunk a group is for.
    window: Option<wgpu::BufferBinding<'r>>,
}

impl<'r> Resources<'r> {
    fn get(&self, binding: Binding) -> Result<wgpu::BindingResource<'r>, RenderError> {
        let lists = self.lists;
        let buffers: [(Binding, &wgpu::Buffer); 10] = [
            (DRAWN, &lists.drawn),
            (JOINS, &lists.joins),
            (OUT, &lists.out),
            (SCREEN, &lists.screen),
            (CHAMFERS, &lists.chamfer_records),
            (STARTS, &lists.starts),
            (COLORS, &lists.colors),
            (DISPATCH, &lists.dispatch),
            (COS_POWER, &self.highlight.cos_power),
            (LIGHTING, &self.highlight.lighting),
        ];
        if binding == crate::render::bindings::FRAME {
            return Ok(self.blocks.binding());
        }
        // The draw passes bind the lists read-only: the same buffers.
        if let Some((_, buffer)) = buffers.iter().find(|(b, _)| b.index == binding.index) {
            return Ok(buffer.as_entire_binding());
        }
        let missing =
            || RenderError::Internal(format!("the joined technique binds no {}", binding.name));
        let (asset, [state, survivors, cull_dispatch]) = self.asset.ok_or_else(missing)?;
        Ok(match binding {
            STATE => state.as_entire_binding(),
            SURVIVORS => survivors.as_entire_binding(),
            CULL_DISPATCH => cull_dispatch.as_entire_binding(),
            section::EDGE_VERTICES => match &self.window {
                Some(window) => wgpu::BindingResource::Buffer(window.clone()),
                None => return Err(missing()),
            },
            other => asset.resource(other, "joined")?,
        })
    }
}

impl Frame {
    fn new(cache: &Cache, options: &FrameOptions) -> Result<Self, RenderError> {
        Ok(Self {
            pipelines: cache.get::<JoinedPipelines>()?,
            cache: cache.clone(),
            blocks: Blocks::new(cache, "edge frame", std::mem::size_of::<layout::Frame>()),
            lists: None,
            assets: PerAsset::default(),
            args_group: None,
            draw_group: None,
            highlight: HighlightUniforms::new(cache),
            needed: Needed::new(cache),
            runs: Vec::new(),
            culling: true,
            highlighted: false,
            caps: CapMethod::NextIndex,
            wanted_slots: options.first_slots,
        })
    }

    /// The lists for this frame, made or remade when they are too small.
    fn ensure_lists(&mut self, cx: &FrameContext<'_>) -> Result<(), RenderError> {
        let instances = (cx.instances.len() as u32).max(1);
        // Highlight records only where an asset has chamfer edges to highlight.
        let chamfers = self.highlighted && cx.instances.iter().any(|d| d.asset.has_chamfers);
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

    /// One block per chunk of each instance's edges (the first is the instance's own), and per
    /// instance its blocks' indices and edges.
    fn blocks(
        &self,
        cx: &FrameContext<'_>,
        lists: &Lists,
    ) -> (Vec<layout::Frame>, Vec<Vec<(usize, u32)>>) {
        let mut frames: Vec<layout::Frame> = Vec::new();
        let mut chunk_blocks = Vec::with_capacity(cx.instances.len());
        for (i, d) in cx.instances.iter().enumerate() {
            let mut uniform = super::frame_uniform(cx, d, i);
            uniform.capacity = lists.capacity;
            uniform.cap_capacity = lists.capacity + 64;
            uniform.highlight = u32::from(self.highlighted);
            // Off-screen edges are left out only while an edge's reach on screen is bounded: not
            // with depth-scaled widths (unbounded near the camera) or highlight strips.
            if !self.highlighted && uniform.depth_ref == 0.0 {
                let reach = uniform.width.max(uniform.min_width) + 2.0;
                uniform.frustum =
                    planes::side_planes(d.camera.view_projection(), uniform.viewport, reach);
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
        (frames, chunk_blocks)
    }
}

/// The per-asset state of `asset`: its edge state and cull lists, and its groups.
fn asset_groups(
    cache: &Cache,
    asset: &GpuAsset,
    shared: &Resources<'_>,
) -> Result<AssetGroups, RenderError> {
    let device = cache.device();
    let buffer = |label: &'static str, size: u64, usage: wgpu::BufferUsages| {
        checked(device, label, || {
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
    let own = Resources {
        asset: Some((asset, [&state, &survivors, &cull_dispatch])),
        window: None,
        ..*shared
    };
    let group = |set: &'static crate::render::bindings::Bindings, resources: &Resources<'_>| {
        set.group(device, &cache.layout(set), |b| resources.get(b))
    };
    // Per chunk, the edge section's window.
    let per_chunk = |set: &'static crate::render::bindings::Bindings| {
        asset
            .edge_chunks()
            .map(|chunk| {
                let windowed = Resources {
                    window: Some(asset.edge_window(chunk)),
                    ..own
                };
                group(set, &windowed)
            })
            .collect::<Result<Vec<_>, RenderError>>()
    };
    Ok(AssetGroups {
        segments: if asset.intersection_count > 0 {
            Some(group(&SEGMENTS, &own)?)
        } else {
            None
        },
        classify: per_chunk(&CLASSIFY)?,
        cull: group(&CULL, &own)?,
        joins: group(&JOIN, &own)?,
        records: per_chunk(&RECORDS)?,
        state,
        survivors,
        cull_dispatch,
    })
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
        self.highlighted = self.highlight.prepare(cx);
        self.ensure_lists(cx)?;
        let Some(lists) = &self.lists else {
            return Err(super::mismatch(cx));
        };
        self.culling = cx.style.cluster_culling;
        let (frames, chunk_blocks) = self.blocks(cx, lists);
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
        let shared = Resources {
            blocks: &self.blocks,
            lists,
            highlight: &self.highlight,
            asset: None,
            window: None,
        };
        let group = |set: &'static crate::render::bindings::Bindings| {
            set.group(&device, &cx.pipelines.layout(set), |b| shared.get(b))
        };
        if self.args_group.is_none() {
            self.args_group = Some(group(&ARGS)?);
        }
        if self.draw_group.is_none() {
            self.draw_group = Some(group(&DRAW)?);
        }
        self.assets.retain(cx.instances);
        self.runs.clear();
        for (drawn, chunks) in cx.instances.iter().zip(chunk_blocks) {
            let made = self.assets.index(drawn.asset, |asset| {
                asset_groups(cx.pipelines, asset, &shared)
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
            cx.style.caps
        } else {
            CapMethod::None
        };
        if let Some(args_group) = &self.args_group {
            Work {
                pipelines: &self.pipelines,
                assets: &self.assets,
                runs: &self.runs,
                args_group,
                dispatch: &lists.dispatch,
                culling: self.culling,
                highlight: self.highlighted,
                caps: self.caps,
            }
            .record(encoder);
        }
        self.needed.copy(encoder, &lists.out);
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
            let bytes = crate::render::offscreen::read_buffer(device, queue, &lists.out, size)?;
            let out: layout::Out = bytemuck::try_pod_read_unaligned(&bytes)
                .map_err(|e| RenderError::Readback(format!("the draw lists' counts: {e}")))?;
            Ok(DrawCounts {
                edges: out.edges.instance_count,
                caps: if self.caps == CapMethod::None {
                    0
                } else {
                    out.caps.instance_count
                },
                wanted: out.needed,
                clusters_kept: out.kept_clusters,
            })
        };
        Some(read())
    }

    fn gpu_bytes(&self) -> u64 {
        let lists = self.lists.as_ref().map_or(0, |l| l.bytes);
        let state: u64 = self.assets.iter().map(AssetGroups::gpu_bytes).sum();
        lists + state + self.blocks.gpu_bytes() + self.highlight.gpu_bytes()
    }
}
