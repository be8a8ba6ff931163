//! The frame's lists, sized by slots (what can be drawn), not by edges or instances: grown from what
//! frames want, never shrunk while the renderer lives; and the frame's instances.

use crate::render::layout::drawn::COLOR_COUNT;
use crate::render::layout::{self, ChamferRecord, DRAWN_BYTES, JOIN_BYTES_PER_END, ScreenRecord};
use crate::render::target::checked;
use crate::render::{Pipelines as Cache, RenderError};

/// The slots a frame starts with: every edge of every instance up to this many, then a share.
pub(super) const FIRST_SLOTS: u64 = 1 << 14;

/// The frame's lists: drawn edges, their joins, screen and chamfer records, the cap list, the slot
/// table, each batch's first slot and each instance's colours. Sized by slots (what can be drawn),
/// not by edges.
#[derive(Debug)]
pub(super) struct Lists {
    pub(super) capacity: u32,
    pub(super) instances: u32,
    pub(super) chamfers: bool,
    /// Entries of the slot table less one (a power of two less one, at least twice the slots).
    pub(super) table_mask: u32,
    pub(super) table: wgpu::Buffer,
    pub(super) drawn: wgpu::Buffer,
    pub(super) joins: wgpu::Buffer,
    pub(super) out: wgpu::Buffer,
    pub(super) dispatch: wgpu::Buffer,
    pub(super) screen: wgpu::Buffer,
    pub(super) chamfer_records: wgpu::Buffer,
    pub(super) starts: wgpu::Buffer,
    pub(super) colors: wgpu::Buffer,
    /// Sized by slots while hidden lines are patterned (else a stub): the chains the joins found,
    /// the ranking's two buffers and the phases (phase.wgsl).
    pub(super) patterned: bool,
    pub(super) chains: wgpu::Buffer,
    pub(super) ranks: [wgpu::Buffer; 2],
    pub(super) phases: wgpu::Buffer,
    pub(super) bytes: u64,
}

impl Lists {
    pub(super) fn new(
        cache: &Cache,
        capacity: u32,
        instances: u32,
        chamfers: bool,
        patterned: bool,
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
        // At most half full: a probe finds a free entry or its key within a few steps.
        let table_entries = (2 * slots).next_power_of_two().max(64);
        let chained = if patterned { slots } else { 1 };
        Ok(Self {
            chains: storage("chains", 2 * 4 * chained, wgpu::BufferUsages::COPY_DST)?,
            ranks: [
                storage("ranks a", 2 * layout::RANK_BYTES * chained, none)?,
                storage("ranks b", 2 * layout::RANK_BYTES * chained, none)?,
            ],
            phases: storage("dash phases", 8 * chained, none)?,
            patterned,
            table: storage(
                "slot table",
                4 * table_entries,
                wgpu::BufferUsages::COPY_DST,
            )?,
            table_mask: (table_entries - 1) as u32,
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
            starts: storage("batch starts", 4 * u64::from(instances), none)?,
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

/// The frame's instances: each one's camera (written by the host, `visible` by the place pass), the
/// clusters the cull passes keep with their instance, and the dispatch over them. Grown, never
/// shrunk.
#[derive(Debug)]
pub(super) struct Instances {
    pub(super) capacity: u32,
    pub(super) survivor_capacity: u32,
    pub(super) frames: wgpu::Buffer,
    pub(super) survivors: wgpu::Buffer,
    pub(super) cull_dispatch: wgpu::Buffer,
}

impl Instances {
    pub(super) fn new(
        cache: &Cache,
        capacity: u32,
        survivor_capacity: u32,
    ) -> Result<Self, RenderError> {
        let device = cache.device();
        let limit = device.limits().max_storage_buffer_binding_size;
        let storage = |what: &'static str, size: u64, usage: wgpu::BufferUsages| {
            if size > limit {
                return Err(RenderError::TooLarge {
                    what,
                    bytes: size,
                    limit,
                });
            }
            checked(device, what, || {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(what),
                    size: size.max(64),
                    usage: wgpu::BufferUsages::STORAGE | usage,
                    mapped_at_creation: false,
                })
            })
        };
        Ok(Self {
            frames: storage(
                "instance frames",
                std::mem::size_of::<layout::InstanceFrame>() as u64 * u64::from(capacity),
                wgpu::BufferUsages::COPY_DST,
            )?,
            survivors: storage(
                "kept clusters",
                std::mem::size_of::<layout::Survivors>() as u64 + 8 * u64::from(survivor_capacity),
                wgpu::BufferUsages::empty(),
            )?,
            cull_dispatch: storage("cluster dispatch", 16, wgpu::BufferUsages::INDIRECT)?,
            capacity,
            survivor_capacity,
        })
    }

    pub(super) fn gpu_bytes(&self) -> u64 {
        self.frames.size() + self.survivors.size() + self.cull_dispatch.size()
    }
}
