//! The chamfer highlight's per-frame uniforms (seed 000): the F(φ, n + 1) row of the material's
//! exponent, rewritten only when the exponent changes (Blinn shading), and the light and material.

use super::super::FrameContext;
use crate::render::environment::EnvironmentBuffer;
use crate::render::layout::{SHADE_ENVIRONMENT, SHADE_PBR};
use crate::render::lighting::{Shading, punctual};
use crate::render::{Pipelines as Cache, layout};

/// The highlight's buffers.
#[derive(Debug)]
pub(super) struct HighlightUniforms {
    pub(super) cos_power: wgpu::Buffer,
    pub(super) lighting: wgpu::Buffer,
    /// The environment's maps for the material's roughness.
    pub(super) environment: EnvironmentBuffer,
    /// The exponent the cos-power row holds now.
    row_exponent: Option<f32>,
}

impl HighlightUniforms {
    pub(super) fn new(cache: &Cache) -> Self {
        let device = cache.device();
        let buffer = |label, size: usize, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Self {
            cos_power: buffer(
                "cos power row",
                4 * (crate::highlight::table::SAMPLES + 1),
                wgpu::BufferUsages::STORAGE,
            ),
            lighting: buffer(
                "highlight lighting",
                std::mem::size_of::<layout::Lighting>(),
                wgpu::BufferUsages::UNIFORM,
            ),
            environment: EnvironmentBuffer::new(device),
            row_exponent: None,
        }
    }

    /// Writes the row and lighting for the style's highlight; false if it has none.
    pub(super) fn prepare(&mut self, cx: &FrameContext<'_>) -> bool {
        let Some(highlight) = &cx.style.highlight else {
            return false;
        };
        // 0: no distance factor (the shaders blend by coverage alone).
        let k = highlight
            .k
            .filter(|k| k.is_finite() && *k > 0.0)
            .unwrap_or(0.0);
        let ambient = highlight.ambient.clamp(0.0, 1.0);
        let (material, base, shade) = match highlight.shading {
            Shading::Blinn(material) => {
                let exponent = material.shininess.clamp(1.0, 128.0) + 1.0;
                if self.row_exponent != Some(exponent) {
                    let row = crate::highlight::table::CosPowerRow::new(exponent);
                    cx.queue
                        .write_buffer(&self.cos_power, 0, bytemuck::cast_slice(row.values()));
                    self.row_exponent = Some(exponent);
                }
                let material = [material.diffuse, material.specular, exponent - 1.0, ambient];
                (material, [0.0; 3], 0)
            }
            Shading::Pbr(material) => {
                let metallic = material.clamped_metallic();
                let base = material.clamped_base().to_array();
                let lit_by_environment =
                    self.environment
                        .update(cx.queue, cx.environment, material.alpha());
                let shade = SHADE_PBR
                    | if lit_by_environment {
                        SHADE_ENVIRONMENT
                    } else {
                        0
                    };
                ([metallic, material.alpha(), 0.0, ambient], base, shade)
            }
        };
        let [r, g, b] = base;
        let lighting = layout::Lighting {
            light: punctual(&highlight.light, highlight.color, shade != 0),
            material,
            base: [r, g, b, k],
            pbr: shade,
            corners: u32::from(highlight.rounded_corners),
            _pad1: 0,
            _pad2: 0,
        };
        cx.queue
            .write_buffer(&self.lighting, 0, bytemuck::bytes_of(&lighting));
        true
    }

    pub(super) fn gpu_bytes(&self) -> u64 {
        self.cos_power.size() + self.lighting.size() + self.environment.buffer.size()
    }
}
