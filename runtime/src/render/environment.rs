//! The GPU side of image-based light (issue 29): an [`Environment`] prefiltered for the material in
//! use and uploaded to the `environment` storage binding of the mesh pass and the highlight, refiltered
//! only when the environment or the roughness changes (as the highlight's table row is rewritten only
//! when the exponent changes).

use std::sync::Arc;

use crate::highlight::environment::{Environment, IRRADIANCE_SIZE, SPECULAR_SIZE};

/// Texels of both maps, as `environment` holds them.
pub(crate) const TEXELS: u32 =
    SPECULAR_SIZE[0] * SPECULAR_SIZE[1] + IRRADIANCE_SIZE[0] * IRRADIANCE_SIZE[1];

/// The maps' buffer and what it holds now.
#[derive(Debug)]
pub(crate) struct EnvironmentBuffer {
    pub(crate) buffer: wgpu::Buffer,
    /// The environment and the `α` the buffer was filtered for.
    holds: Option<(Arc<Environment>, u32)>,
}

impl EnvironmentBuffer {
    pub(crate) fn new(device: &wgpu::Device) -> Self {
        Self {
            buffer: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("environment"),
                size: u64::from(TEXELS) * 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            holds: None,
        }
    }

    /// Makes the buffer hold `environment` filtered for `alpha`; false if there is none.
    pub(crate) fn update(
        &mut self,
        queue: &wgpu::Queue,
        environment: Option<&Arc<Environment>>,
        alpha: f32,
    ) -> bool {
        let Some(environment) = environment else {
            return false;
        };
        let current = self
            .holds
            .as_ref()
            .is_some_and(|(held, a)| Arc::ptr_eq(held, environment) && *a == alpha.to_bits());
        if !current {
            let maps = environment.prefiltered(alpha);
            // Both maps in one buffer, specular first, as `environment` holds them.
            let texels: Vec<[f32; 4]> = maps
                .specular
                .iter()
                .chain(&maps.irradiance)
                .copied()
                .collect();
            queue.write_buffer(&self.buffer, 0, bytemuck::cast_slice(&texels));
            self.holds = Some((environment.clone(), alpha.to_bits()));
        }
        true
    }
}
