//! [`Technique::Joined`](crate::render::Technique::Joined), the default: compacted edges with
//! gap-free joins (thesis §10 non-duplicate detection, §13 next-index capping, §8.3 half quads, §9.1
//! depth-scaled widths) and the chamfer highlight of seed 000.
//!
//! Per frame on the GPU (`shaders/instances.wgsl`, `classify.wgsl`, `args.wgsl`, `joins.wgsl`,
//! `chamfers.wgsl`, then `edges.wgsl` and `caps.wgsl` in the application's pass): a place pass marks
//! the instances in view; then, per asset, for all its instances at once (a *batch*, issue 28): a cull
//! pass (`cull.wgsl`) keeps the (instance, edge cluster) pairs that may hold a drawn edge (facing cone
//! and sphere, frustum, with the camera in each instance's model space), classify tests the edges of
//! those clusters only and appends the drawn ones to a compact list that is the instance count of an
//! indirect draw, projecting each drawn edge once into a screen record and noting its slot in a
//! table keyed by (instance, edge); an args pass sizes the indirect join dispatch; joins find each
//! drawn end's nearest drawn neighbours of the same instance by screen angle (next-index walk or
//! cap-buffer head), cut overlapping quads apart and emit round caps for outer gaps, so no pixel is
//! covered twice and translucent colours blend once. Highlighted chamfer edges get a record each
//! (`chamfers.wgsl`) and, where chamfer edges of one radius meet, a rounded corner drawn instance by
//! instance (`corner_draw.wgsl`) takes over the pixels around the vertex from the strips. The work per frame is a few passes per asset,
//! whatever the number of its instances; the host writes each instance's camera and colours.
//!
//! The folder is split by concern: [`bindings`] (what each pass binds), [`pipelines`], [`lists`]
//! (the frame's lists), [`readback`] (how many slots frames want, read without waiting),
//! [`planes`] (the cull pass's frustum), [`highlight`] (the highlight's uniforms) and [`record`]
//! (the frame's groups and compute pass); this file puts a frame together.

mod bindings;
mod highlight;
mod lists;
mod outline;
mod pipelines;
mod planes;
mod readback;
mod record;

use std::sync::Arc;

use self::bindings::*;
use self::highlight::HighlightUniforms;
use self::lists::{FIRST_SLOTS, Instances, Lists};
use self::pipelines::{HiddenPipelines, JoinedPipelines, PhasePipelines};
use self::readback::Needed;
use self::record::{AssetGroups, Batch, Work};
use super::{Blocks, FrameContext, FrameOptions, Module, PerAsset, TechniqueFrame};
use crate::render::bindings::{Binding, asset as section};
use crate::render::layout::{self, ChamferRecord, InstanceFrame, ScreenRecord};
use crate::render::modules::Shader;
use crate::render::{CapMethod, DrawCounts, GpuAsset, Pipelines as Cache, RenderError, Target};

pub(crate) static MODULE: Joined = Joined;

/// The module.
pub(crate) struct Joined;

impl Module for Joined {
    fn presets(&self) -> &'static [crate::render::Preset] {
        &[crate::render::Preset {
            name: "joined",
            summary: "compacted edges with gap-free joins and round caps (thesis §10, §13; the default)",
            technique: crate::render::Technique::Joined,
        }]
    }

    fn shaders(&self, target: &Target) -> Vec<Shader> {
        let mut all = pipelines::shaders(target);
        all.push(pipelines::phase_shader());
        all
    }

    fn new_frame(
        &self,
        cache: &Cache,
        options: &FrameOptions,
    ) -> Result<Box<dyn TechniqueFrame>, RenderError> {
        Ok(Box::new(Frame::new(cache, options)?))
    }

    fn draws_hidden(&self) -> bool {
        true
    }

    fn culls_on_gpu(&self) -> bool {
        true
    }
}

/// Offset of the cap draw's arguments in the `out` buffer.
const CAP_DRAW_OFFSET: u64 = std::mem::size_of::<layout::DrawArgs>() as u64;

/// The kept-cluster list a frame starts with, at most (it grows from what frames want).
const FIRST_SURVIVORS: u64 = 1 << 18;

/// Threads one dispatch of a batch may run: its instances are split into batches below it.
const MAX_THREADS: u64 = 1 << 31;

/// A frame's state: the lists, the instances, one uniform block per chunk of each batch, per-asset
/// groups, and what each batch runs.
#[derive(Debug)]
struct Frame {
    pipelines: Arc<JoinedPipelines>,
    /// The hidden pass's pipelines, while the style draws hidden edges.
    hidden: Option<Arc<HiddenPipelines>>,
    /// The dash phases' pipelines and groups (into the second ranks buffer, into the first), while
    /// the hidden lines' pattern continues along chains.
    phases: Option<(Arc<PhasePipelines>, [wgpu::BindGroup; 2])>,
    /// This frame's hidden lines are patterned and joined: their phases run along chains.
    patterned: bool,
    cache: Cache,
    /// Block 0 is the place pass's (every instance); then one per chunk of each batch.
    blocks: Blocks,
    /// One per instance of an asset with intersection edges or (highlighted) rounded corners: they
    /// are drawn instance by instance.
    instance_blocks: Blocks,
    lists: Option<Lists>,
    instances: Option<Instances>,
    assets: PerAsset<AssetGroups>,
    args_group: Option<wgpu::BindGroup>,
    place_group: Option<wgpu::BindGroup>,
    draw_group: Option<wgpu::BindGroup>,
    highlight: HighlightUniforms,
    needed: Needed,
    /// Per batch, what its passes run over.
    batches: Vec<Batch>,
    /// Per instance drawn on its own: its asset's groups and its block.
    instance_runs: Vec<(usize, u32)>,
    /// The frame's instances.
    instance_count: u32,
    /// Cull clusters before classifying edges.
    culling: bool,
    /// This frame draws chamfer edges as highlight strips.
    highlighted: bool,
    /// ... and some of its assets have chamfer edges: `finish` rounds their outline.
    outlined: bool,
    outline: outline::Outline,
    caps: CapMethod,
    /// The slots the next lists must have, at least.
    wanted_slots: u64,
    /// The kept clusters the next list must hold, at least.
    wanted_survivors: u64,
}

/// Where each binding of the technique's sets comes from in this frame: the blocks, the lists, the
/// instances, the highlight's uniforms, and for an asset's groups its sections.
struct Resources<'r> {
    blocks: &'r Blocks,
    lists: &'r Lists,
    instances: &'r Instances,
    highlight: &'r HighlightUniforms,
    asset: Option<&'r GpuAsset>,
    /// The edge section's window of the chunk a group is for.
    window: Option<wgpu::BufferBinding<'r>>,
}

impl<'r> Resources<'r> {
    fn get(&self, binding: Binding) -> Result<wgpu::BindingResource<'r>, RenderError> {
        let (lists, instances) = (self.lists, self.instances);
        let buffers: [(Binding, &wgpu::Buffer); 17] = [
            (CHAINS, &lists.chains),
            (PHASES, &lists.phases),
            (DRAWN, &lists.drawn),
            (JOINS, &lists.joins),
            (OUT, &lists.out),
            (SCREEN, &lists.screen),
            (CHAMFERS, &lists.chamfer_records),
            (STARTS, &lists.starts),
            (COLORS, &lists.colors),
            (DISPATCH, &lists.dispatch),
            (TABLE, &lists.table),
            (INSTANCE_FRAMES, &instances.frames),
            (SURVIVORS, &instances.survivors),
            (CULL_DISPATCH, &instances.cull_dispatch),
            (COS_POWER, &self.highlight.cos_power),
            (LIGHTING, &self.highlight.lighting),
            (ENVIRONMENT, &self.highlight.environment.buffer),
        ];
        if binding.index == crate::render::bindings::FRAME.index {
            return Ok(self.blocks.binding());
        }
        // The draw passes bind the lists read-only, the place pass the instances read-write: the
        // same buffers.
        if let Some((_, buffer)) = buffers.iter().find(|(b, _)| b.index == binding.index) {
            return Ok(buffer.as_entire_binding());
        }
        let missing =
            || RenderError::Internal(format!("the joined technique binds no {}", binding.name));
        let asset = self.asset.ok_or_else(missing)?;
        Ok(match binding {
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
        let block = std::mem::size_of::<layout::Frame>();
        Ok(Self {
            pipelines: cache.get::<JoinedPipelines>()?,
            hidden: None,
            phases: None,
            patterned: false,
            cache: cache.clone(),
            blocks: Blocks::new(cache, "edge batches", block),
            instance_blocks: Blocks::new(cache, "instances drawn one by one", block),
            lists: None,
            instances: None,
            assets: PerAsset::default(),
            args_group: None,
            place_group: None,
            draw_group: None,
            highlight: HighlightUniforms::new(cache),
            needed: Needed::new(cache),
            batches: Vec::new(),
            instance_runs: Vec::new(),
            instance_count: 0,
            culling: true,
            highlighted: false,
            outlined: false,
            outline: outline::Outline::default(),
            caps: CapMethod::NextIndex,
            wanted_slots: options.first_slots,
            wanted_survivors: 0,
        })
    }

    /// Forgets every group (what they bind was remade).
    fn forget_groups(&mut self) {
        self.assets.clear();
        self.phases = None;
        self.args_group = None;
        self.place_group = None;
        self.draw_group = None;
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
        // The largest per-slot list must fit one storage binding (the slot table, at up to four
        // entries a slot, too).
        let per_slot = if chamfers {
            std::mem::size_of::<ChamferRecord>()
        } else {
            std::mem::size_of::<ScreenRecord>()
        } as u64;
        let limit = self.cache.device().limits().max_storage_buffer_binding_size / per_slot.max(16);
        let enough = self.lists.as_ref().is_some_and(|l| {
            u64::from(l.capacity) >= wanted.min(limit)
                && l.instances >= instances
                && (l.chamfers || !chamfers)
                && (l.patterned || !self.patterned)
        });
        if !enough {
            let capacity = wanted.min(limit) as u32;
            self.lists = None;
            self.lists = Some(Lists::new(
                &self.cache,
                capacity,
                instances.next_power_of_two(),
                chamfers,
                self.patterned,
            )?);
            self.forget_groups();
        }
        // The kept clusters: every (instance, cluster) of a chunk up to FIRST_SURVIVORS, grown from
        // what frames want.
        let clusters = |d: &super::Drawn<'_>| {
            u64::from(d.asset.chunk_edges.min(d.asset.edge_count)).div_ceil(64)
        };
        let survivors = self
            .wanted_survivors
            .max(
                cx.instances
                    .iter()
                    .map(clusters)
                    .sum::<u64>()
                    .min(FIRST_SURVIVORS),
            )
            .max(64);
        let limit = self.cache.device().limits().max_storage_buffer_binding_size / 8 - 2;
        let count = cx.instances.len() as u32;
        let enough = self.instances.as_ref().is_some_and(|i| {
            i.capacity >= count && u64::from(i.survivor_capacity) >= survivors.min(limit)
        });
        if !enough {
            let capacity = count.max(1).next_power_of_two();
            self.instances = None;
            self.instances = Some(Instances::new(
                &self.cache,
                capacity,
                survivors.min(limit) as u32,
            )?);
            self.forget_groups();
        }
        Ok(())
    }

    /// The frame's instances grouped by asset (each group a batch, split where its dispatches
    /// would run too many threads), each instance's camera, and the uniform blocks: the place
    /// pass's, then one per chunk of each batch.
    fn plan(
        &self,
        cx: &FrameContext<'_>,
        lists: &Lists,
        instances: &Instances,
    ) -> (
        Vec<usize>,
        Vec<InstanceFrame>,
        Vec<layout::Frame>,
        Vec<PlannedBatch>,
    ) {
        // Instances of one asset next to each other, assets in the order they first appear.
        let order = super::by_asset(cx.instances);
        let reach = |u: &layout::Frame| u.width.max(u.min_width) + 2.0;
        let mut frames = Vec::with_capacity(order.len());
        for (i, &d) in order.iter().enumerate() {
            let drawn = &cx.instances[d];
            let uniform = super::frame_uniform(cx, drawn, i);
            // Off-screen edges are left out only while an edge's reach on screen is bounded: not
            // with depth-scaled widths (unbounded near the camera) or highlight strips.
            let frustum = if !self.highlighted && uniform.depth_ref == 0.0 {
                planes::side_planes(
                    drawn.camera.view_projection(),
                    uniform.viewport,
                    reach(&uniform),
                )
            } else {
                [[0.0; 4]; 4]
            };
            frames.push(InstanceFrame {
                // The place pass decides.
                visible: 0,
                ..super::instance_view(cx, drawn, i, frustum)
            });
        }
        let block = |drawn: &super::Drawn<'_>, first: usize| {
            let mut uniform = super::frame_uniform(cx, drawn, first);
            uniform.capacity = lists.capacity;
            uniform.cap_capacity = lists.capacity + 64;
            uniform.highlight = u32::from(self.highlighted);
            if self.patterned {
                uniform.display.flags |= layout::DISPLAY_CHAINED;
            }
            uniform.table_mask = lists.table_mask;
            uniform.survivor_capacity = instances.survivor_capacity;
            uniform
        };
        let mut blocks = Vec::new();
        let mut batches = Vec::new();
        // The place pass's block: every instance.
        let mut place = match cx.instances.first() {
            Some(drawn) => block(drawn, 0),
            None => {
                let mut empty: layout::Frame = bytemuck::Zeroable::zeroed();
                empty.capacity = lists.capacity;
                empty.cap_capacity = lists.capacity + 64;
                empty.table_mask = lists.table_mask;
                empty
            }
        };
        place.batch_instances = order.len() as u32;
        blocks.push(place);
        let mut start = 0;
        while start < order.len() {
            let drawn = &cx.instances[order[start]];
            let asset = drawn.asset;
            let same = order[start..]
                .iter()
                .take_while(|&&d| Arc::ptr_eq(&cx.instances[d].asset.key, &asset.key))
                .count();
            // Threads a dispatch runs per instance: the most of its edges (without culling), its
            // clusters and its capped vertices.
            let per_instance = u64::from(asset.chunk_edges.min(asset.edge_count))
                .max(u64::from(asset.head_count))
                .max(1);
            let most = (MAX_THREADS / per_instance).max(1) as usize;
            let count = same.min(most);
            let index = batches.len() as u32;
            let mut chunks = Vec::new();
            for (first_edge, edges) in asset.edge_chunks() {
                let mut uniform = block(drawn, start);
                uniform.first_edge = first_edge;
                uniform.edge_count = edges;
                uniform.batch = index;
                uniform.batch_instances = count as u32;
                chunks.push((blocks.len(), edges));
                blocks.push(uniform);
            }
            batches.push(PlannedBatch {
                first: start,
                count,
                chunks,
            });
            start += count;
        }
        (order, frames, blocks, batches)
    }
}

/// A batch as planned: its first instance and instances (in the frame's order), and per chunk its
/// block and edges.
struct PlannedBatch {
    first: usize,
    count: usize,
    chunks: Vec<(usize, u32)>,
}

/// The per-asset state of `asset`: its groups.
fn asset_groups(
    cache: &Cache,
    asset: &GpuAsset,
    shared: &Resources<'_>,
    instance_blocks: &Blocks,
) -> Result<AssetGroups, RenderError> {
    let device = cache.device();
    let own = Resources {
        asset: Some(asset),
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
    let classify = per_chunk(&CLASSIFY)?;
    let cull = group(&CULL, &own)?;
    let joins = group(&JOIN, &own)?;
    let records = per_chunk(&RECORDS)?;
    let one_by_one = Resources {
        blocks: instance_blocks,
        ..own
    };
    let segments = if asset.intersection_count > 0 {
        Some(group(&SEGMENTS, &one_by_one)?)
    } else {
        None
    };
    let corners = if asset.corner_count > 0 {
        Some(group(&CORNER_DRAW, &one_by_one)?)
    } else {
        None
    };
    Ok(AssetGroups {
        segments,
        corners,
        classify,
        cull,
        joins,
        records,
    })
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let device = cx.pipelines.device().clone();
        if let Some((needed, survivors)) = self.needed.poll(&device) {
            // An earlier frame wanted more than the lists hold: a quarter more next time.
            if self.lists.as_ref().is_some_and(|l| needed > l.capacity) {
                self.wanted_slots = u64::from(needed) + u64::from(needed) / 4;
            }
            if self
                .instances
                .as_ref()
                .is_some_and(|i| survivors > i.survivor_capacity)
            {
                self.wanted_survivors = u64::from(survivors) + u64::from(survivors) / 4;
            }
        }
        self.highlighted = self.highlight.prepare(cx);
        self.hidden = match cx.style.display.hidden {
            Some(_) => Some(cx.pipelines.get::<HiddenPipelines>()?),
            None => None,
        };
        // A pattern continues along chains where the joins find them (which needs rings).
        let joined =
            cx.style.caps != CapMethod::None && cx.instances.iter().all(|d| d.asset.has_rings);
        let patterned = joined
            && cx
                .style
                .display
                .hidden
                .is_some_and(|h| h.pattern != crate::render::LinePattern::Solid);
        if patterned != self.patterned {
            self.patterned = patterned;
            self.phases = None;
        }
        self.outlined = self.highlighted && cx.instances.iter().any(|d| d.asset.has_chamfers);
        self.ensure_lists(cx)?;
        let (Some(lists), Some(instances)) = (&self.lists, &self.instances) else {
            return Err(super::mismatch(cx));
        };
        self.culling = cx.style.cluster_culling;
        // (The starts list holds one entry per instance, so any split of the batches fits it.)
        let (order, frames, blocks, planned) = self.plan(cx, lists, instances);
        let grown = self.blocks.write(cx.pipelines, cx.queue, &blocks);
        // Intersection edges and rounded corners are drawn instance by instance, each with its own
        // block.
        let one_by_one: Vec<(usize, layout::Frame)> = order
            .iter()
            .enumerate()
            .filter(|(_, d)| {
                let asset = cx.instances[**d].asset;
                asset.intersection_count > 0 || (self.highlighted && asset.corner_count > 0)
            })
            .map(|(i, &d)| (i, super::frame_uniform(cx, &cx.instances[d], i)))
            .collect();
        let uniforms: Vec<layout::Frame> = one_by_one.iter().map(|(_, f)| *f).collect();
        let one_by_one_grown = !uniforms.is_empty()
            && self
                .instance_blocks
                .write(cx.pipelines, cx.queue, &uniforms);
        if grown || one_by_one_grown {
            self.forget_groups();
        }
        let (Some(lists), Some(instances)) = (&self.lists, &self.instances) else {
            return Err(super::mismatch(cx));
        };
        if !frames.is_empty() {
            cx.queue
                .write_buffer(&instances.frames, 0, bytemuck::cast_slice(&frames));
        }
        let colors: Vec<[f32; 4]> = order
            .iter()
            .flat_map(|&d| cx.instances[d].colors.array())
            .collect();
        if !colors.is_empty() {
            cx.queue
                .write_buffer(&lists.colors, 0, bytemuck::cast_slice(&colors));
        }
        let shared = Resources {
            blocks: &self.blocks,
            lists,
            instances,
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
        if self.place_group.is_none() {
            self.place_group = Some(group(&PLACE)?);
        }
        if self.draw_group.is_none() {
            self.draw_group = Some(group(&DRAW)?);
        }
        if self.patterned && self.phases.is_none() {
            let layout = cx.pipelines.layout(&PHASE);
            let ranking = |from: usize| {
                PHASE.group(&device, &layout, |b| match b.index {
                    i if i == RANKS_IN.index => Ok(lists.ranks[from].as_entire_binding()),
                    i if i == RANKS_OUT.index => Ok(lists.ranks[1 - from].as_entire_binding()),
                    _ => shared.get(b),
                })
            };
            self.phases = Some((
                cx.pipelines.get::<PhasePipelines>()?,
                [ranking(0)?, ranking(1)?],
            ));
        }
        let kept: Vec<super::Drawn<'_>> = order.iter().map(|&d| cx.instances[d].clone()).collect();
        self.assets.retain(&kept);
        self.batches.clear();
        for batch in &planned {
            let drawn = &cx.instances[order[batch.first]];
            let made = self.assets.index(drawn.asset, |asset| {
                asset_groups(cx.pipelines, asset, &shared, &self.instance_blocks)
            })?;
            self.batches.push(Batch {
                asset: made,
                chunks: batch
                    .chunks
                    .iter()
                    .map(|&(block, edges)| (self.blocks.offset(block), edges))
                    .collect(),
                instances: batch.count as u32,
                head_count: drawn.asset.head_count,
            });
        }
        self.instance_runs.clear();
        for (k, &(i, _)) in one_by_one.iter().enumerate() {
            let made = self.assets.index(cx.instances[order[i]].asset, |_| {
                Err(RenderError::Internal(
                    "an instance's asset has no groups".into(),
                ))
            })?;
            self.instance_runs
                .push((made, self.instance_blocks.offset(k)));
        }
        // Without rings there is nothing to join by.
        self.caps = if cx.instances.iter().all(|d| d.asset.has_rings) {
            cx.style.caps
        } else {
            CapMethod::None
        };
        self.instance_count = frames.len() as u32;
        // The slot table starts every frame empty; so do the chains (the joins write those of
        // the ends they join).
        encoder.clear_buffer(&lists.table, 0, None);
        if self.patterned {
            encoder.clear_buffer(&lists.chains, 0, None);
        }
        if let (Some(args_group), Some(place_group)) = (&self.args_group, &self.place_group) {
            Work {
                pipelines: &self.pipelines,
                assets: &self.assets,
                batches: &self.batches,
                args_group,
                place_group,
                instances: self.instance_count,
                dispatch: &lists.dispatch,
                cull_dispatch: &instances.cull_dispatch,
                culling: self.culling,
                highlight: self.highlighted,
                caps: self.caps,
                phases: self
                    .phases
                    .as_ref()
                    .map(|(pipelines, groups)| record::Phases {
                        pipelines,
                        groups,
                        rounds: record::rounds(lists.capacity),
                    }),
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
        // Hidden edges first: a visible line crossing a hidden one is drawn over it.
        if let Some(hidden) = self.hidden.as_ref().and_then(|h| h.0.as_ref()) {
            pass.set_bind_group(0, draw_group, &[0]);
            pass.set_pipeline(&hidden.edges);
            pass.draw_indirect(&lists.out, 0);
            if self.caps != CapMethod::None {
                pass.set_pipeline(&hidden.caps);
                pass.draw_indirect(&lists.out, CAP_DRAW_OFFSET);
            }
            for &(asset, block) in &self.instance_runs {
                let (gpu, groups) = self.assets.get(asset);
                if let Some(segments) = &groups.segments {
                    pass.set_bind_group(0, segments, &[block]);
                    pass.set_pipeline(&hidden.segments);
                    pass.draw(0..18, 0..gpu.intersection_count);
                }
            }
        }
        pass.set_bind_group(0, draw_group, &[0]);
        pass.set_pipeline(&pipelines.edges);
        pass.draw_indirect(&lists.out, 0);
        if self.highlighted {
            pass.set_pipeline(&pipelines.strips);
            pass.draw_indirect(&lists.out, 0);
        }
        if self.caps != CapMethod::None {
            pass.set_pipeline(&pipelines.caps);
            pass.draw_indirect(&lists.out, CAP_DRAW_OFFSET);
        }
        for &(asset, block) in &self.instance_runs {
            let (gpu, groups) = self.assets.get(asset);
            if let Some(segments) = &groups.segments {
                pass.set_bind_group(0, segments, &[block]);
                pass.set_pipeline(&pipelines.segments);
                pass.draw(0..18, 0..gpu.intersection_count);
            }
            if let (true, Some(corners)) = (self.highlighted, &groups.corners) {
                pass.set_bind_group(0, corners, &[block]);
                pass.set_pipeline(&pipelines.corners);
                pass.draw(0..6, 0..gpu.corner_count);
            }
        }
    }

    fn finish(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        views: &crate::render::FrameViews<'_>,
    ) -> Result<(), RenderError> {
        outline::record(self, encoder, views)
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
                instances_in_view: out.instances_in_view,
            })
        };
        Some(read())
    }

    fn gpu_bytes(&self) -> u64 {
        let lists = self.lists.as_ref().map_or(0, |l| l.bytes);
        let instances = self.instances.as_ref().map_or(0, Instances::gpu_bytes);
        lists
            + instances
            + self.blocks.gpu_bytes()
            + self.instance_blocks.gpu_bytes()
            + self.highlight.gpu_bytes()
            + self.outline.gpu_bytes()
    }
}
