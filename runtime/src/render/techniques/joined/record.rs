//! What a frame records: per asset the groups its passes run over, per batch (instances of one
//! asset) the chunks of its edge section, and the compute pass of the frame (place, then cull,
//! classify and joins batch after batch, then the clamp of the lists).

use super::pipelines::{JoinedPipelines, PhasePipelines};
use crate::render::CapMethod;
use crate::render::layout::CLUSTER_EDGES;
use crate::render::pipelines::workgroups;
use crate::render::techniques::PerAsset;

/// Per asset: the compute groups over its sections, the lists and the instances; classification
/// and chamfer records have a group per chunk of the edge section.
#[derive(Debug)]
pub(super) struct AssetGroups {
    pub(super) classify: Vec<wgpu::BindGroup>,
    pub(super) cull: wgpu::BindGroup,
    pub(super) joins: wgpu::BindGroup,
    pub(super) records: Vec<wgpu::BindGroup>,
    /// Over the asset's intersection segments, if it has any (drawn instance by instance).
    pub(super) segments: Option<wgpu::BindGroup>,
    /// Over the asset's rounded corners, if it has any (drawn instance by instance).
    pub(super) corners: Option<wgpu::BindGroup>,
}

/// What one batch's passes run over.
#[derive(Debug)]
pub(super) struct Batch {
    /// Its asset's groups.
    pub(super) asset: usize,
    /// Per chunk of the asset's edge section: its uniform block's offset and its edges.
    pub(super) chunks: Vec<(u32, u32)>,
    /// The instances in the batch.
    pub(super) instances: u32,
    /// The asset's capped vertices.
    pub(super) head_count: u32,
}

impl Batch {
    /// The batch's first uniform block.
    pub(super) fn block(&self) -> u32 {
        self.chunks.first().map_or(0, |&(block, _)| block)
    }
}

/// What the frame's compute pass runs.
pub(super) struct Work<'a> {
    pub(super) pipelines: &'a JoinedPipelines,
    pub(super) assets: &'a PerAsset<AssetGroups>,
    pub(super) batches: &'a [Batch],
    pub(super) args_group: &'a wgpu::BindGroup,
    pub(super) place_group: &'a wgpu::BindGroup,
    /// The frame's instances.
    pub(super) instances: u32,
    /// The join pass's indirect dispatch.
    pub(super) dispatch: &'a wgpu::Buffer,
    /// The indirect dispatch over the kept clusters.
    pub(super) cull_dispatch: &'a wgpu::Buffer,
    pub(super) culling: bool,
    pub(super) highlight: bool,
    pub(super) caps: CapMethod,
    /// The dash phases, while hidden lines are patterned.
    pub(super) phases: Option<Phases<'a>>,
}

/// The dash phases' passes: their pipelines, the groups ranking into the second buffer and into
/// the first, and the jumping rounds that cover the longest possible chain.
pub(super) struct Phases<'a> {
    pub(super) pipelines: &'a PhasePipelines,
    pub(super) groups: &'a [wgpu::BindGroup; 2],
    pub(super) rounds: u32,
}

/// Rounds of pointer jumping that end every walk among the items of `capacity` slots: each round
/// doubles the reach, and a walk passes at most every item.
pub(super) fn rounds(capacity: u32) -> u32 {
    (2 * u64::from(capacity).max(1))
        .next_power_of_two()
        .trailing_zeros()
}

impl Phases<'_> {
    /// Ranks the chains (phase.wgsl): init, jumps, the cut of closed loops, jumps again, the
    /// phases. Every dispatch runs one thread per item, sized by the frame's drawn edges.
    fn record(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        args_group: &wgpu::BindGroup,
        dispatch: &wgpu::Buffer,
    ) {
        let p = self.pipelines;
        pass.set_bind_group(0, args_group, &[0]);
        pass.set_pipeline(&p.args);
        pass.dispatch_workgroups(1, 1, 1);
        // groups[k] reads ranks[k] and writes the other: into ranks[0] first.
        pass.set_bind_group(0, &self.groups[1], &[0]);
        pass.set_pipeline(&p.init);
        pass.dispatch_workgroups_indirect(dispatch, 0);
        let mut current = 0;
        let mut step = |pass: &mut wgpu::ComputePass<'_>, pipeline: &wgpu::ComputePipeline| {
            pass.set_bind_group(0, &self.groups[current], &[0]);
            pass.set_pipeline(pipeline);
            pass.dispatch_workgroups_indirect(dispatch, 0);
            current = 1 - current;
        };
        for _ in 0..self.rounds {
            step(pass, &p.jump);
        }
        step(pass, &p.cut);
        for _ in 0..self.rounds {
            step(pass, &p.jump);
        }
        step(pass, &p.finish);
    }
}

impl Work<'_> {
    /// Records the frame: which instances are in view, then each batch's classification and
    /// joins, then the clamp.
    pub(super) fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        let pipelines = self.pipelines;
        let joins = self.caps != CapMethod::None || self.highlight;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("chamfer edges"),
            timestamp_writes: None,
        });
        pass.set_bind_group(0, self.args_group, &[0]);
        pass.set_pipeline(&pipelines.reset);
        pass.dispatch_workgroups(1, 1, 1);
        if self.instances > 0 {
            pass.set_bind_group(0, self.place_group, &[0]);
            pass.set_pipeline(&pipelines.place);
            let [x, y] = workgroups(self.instances);
            pass.dispatch_workgroups(x, y, 1);
        }
        for batch in self.batches {
            let (_, groups) = self.assets.get(batch.asset);
            let offset = batch.block();
            pass.set_bind_group(0, &groups.classify[0], &[offset]);
            pass.set_pipeline(&pipelines.mark);
            pass.dispatch_workgroups(1, 1, 1);
            for (classify, &(block, edges)) in groups.classify.iter().zip(&batch.chunks) {
                if self.culling {
                    pass.set_bind_group(0, &groups.cull, &[block]);
                    pass.set_pipeline(&pipelines.cull);
                    let [x, y] = workgroups(edges.div_ceil(CLUSTER_EDGES) * batch.instances);
                    pass.dispatch_workgroups(x, y, 1);
                    pass.set_pipeline(&pipelines.cull_args);
                    pass.dispatch_workgroups(1, 1, 1);
                    pass.set_bind_group(0, classify, &[block]);
                    pass.set_pipeline(&pipelines.classify_clusters);
                    pass.dispatch_workgroups_indirect(self.cull_dispatch, 0);
                } else {
                    pass.set_bind_group(0, classify, &[block]);
                    pass.set_pipeline(&pipelines.classify);
                    let [x, y] = workgroups(edges * batch.instances);
                    pass.dispatch_workgroups(x, y, 1);
                }
            }
            if !joins {
                continue;
            }
            // The join dispatch is sized by what this batch drew (each dispatch is its own usage
            // scope, so the arguments written here are read as indirect ones below).
            pass.set_bind_group(0, self.args_group, &[offset]);
            pass.set_pipeline(&pipelines.args);
            pass.dispatch_workgroups(1, 1, 1);
            if self.highlight {
                // One thread per drawn edge end: twice as many as records need; the rest return.
                // Each chunk records its own edges.
                for (records, &(block, _)) in groups.records.iter().zip(&batch.chunks) {
                    pass.set_bind_group(0, records, &[block]);
                    pass.set_pipeline(&pipelines.chamfer_records);
                    pass.dispatch_workgroups_indirect(self.dispatch, 0);
                }
            }
            pass.set_bind_group(0, &groups.joins, &[offset]);
            match self.caps {
                CapMethod::NextIndex => {
                    pass.set_pipeline(&pipelines.joins_next);
                    pass.dispatch_workgroups_indirect(self.dispatch, 0);
                }
                CapMethod::CapBuffer => {
                    pass.set_pipeline(&pipelines.clear_joins);
                    pass.dispatch_workgroups_indirect(self.dispatch, 0);
                    pass.set_pipeline(&pipelines.joins_heads);
                    let [x, y] = workgroups(batch.head_count * batch.instances);
                    pass.dispatch_workgroups(x, y, 1);
                }
                CapMethod::None => {}
            }
        }
        pass.set_bind_group(0, self.args_group, &[0]);
        pass.set_pipeline(&pipelines.finish);
        pass.dispatch_workgroups(1, 1, 1);
        if let Some(phases) = &self.phases {
            phases.record(&mut pass, self.args_group, self.dispatch);
        }
    }
}
