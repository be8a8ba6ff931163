//! How many slots (and kept clusters) a frame wanted, read back without ever waiting: copied at the end of one frame's
//! compute, mapped at the next prepare, read at a later one.

use std::sync::Arc;

use crate::render::Pipelines as Cache;
use crate::render::layout;

/// The staging buffer and where its readback is.
#[derive(Debug)]
pub(super) struct Needed {
    staging: wgpu::Buffer,
    state: Arc<std::sync::atomic::AtomicU8>,
}

const IDLE: u8 = 0;
const COPIED: u8 = 1;
const MAPPING: u8 = 2;
const MAPPED: u8 = 3;

impl Needed {
    pub(super) fn new(cache: &Cache) -> Self {
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

    /// Moves the readback along; returns the slots and the kept clusters an earlier frame wanted,
    /// once known.
    pub(super) fn poll(&self, device: &wgpu::Device) -> Option<(u32, u32)> {
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
                let needed = self.staging.get_mapped_range(..).ok().and_then(|bytes| {
                    bytemuck::try_from_bytes::<layout::Out>(&bytes)
                        .ok()
                        .map(|out| (out.needed, out.survivors_wanted))
                });
                self.staging.unmap();
                self.state.store(IDLE, Ordering::Release);
                needed
            }
            _ => None,
        }
    }

    /// Records the copy of this frame's counts, if no readback is under way.
    pub(super) fn copy(&self, encoder: &mut wgpu::CommandEncoder, out: &wgpu::Buffer) {
        use std::sync::atomic::Ordering;
        if self.state.load(Ordering::Acquire) == IDLE {
            encoder.copy_buffer_to_buffer(out, 0, &self.staging, 0, self.staging.size());
            self.state.store(COPIED, Ordering::Release);
        }
    }
}
