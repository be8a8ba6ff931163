//! The frame's lists, sized by slots (what can be drawn), not by edges: grown from what frames
//! want, never shrunk while the renderer lives.

use crate::render::layout::drawn::COLOR_COUNT;
use crate::render::layout::{self, ChamferRecord, DRAWN_BYTES, JOIN_BYTES_PER_END, ScreenRecord};
use crate::render::target::checked;
use crate::render::{Pipelines as Cache, RenderError};

/// The slots a frame starts with: every edge of every instance up to this many, then a share.
pub(super) const FIRST_SLOTS: u64 = 1 << 14;

/// The frame's lists: drawn edges, their joins, screen and chamfer records, the cap list, each
/// instance's first slot and colours. Sized by slots (what can be drawn), not by edges.
#[derive(Debug)]
pub(super) struct Lists {
    pub(super) capacity: u32,
    pub(super) instances: u32,
    pub(super) chamfers: bool,
    pub(super) drawn: wgpu::Buffer,
    pub(super) joins: wgpu::Buffer,
    pub(super) out: wgpu::Buffer,
    pub(super) dispatch: wgpu::Buffer,
    pub(super) screen: wgpu::Buffer,
    pub(super) chamfer_records: wgpu::Buffer,
    pub(super) starts: wgpu::Buffer,
    pub(super) colors: wgpu::Buffer,
    pub(super) bytes: u64,
}

impl Lists {
    pub(super) fn new(
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
