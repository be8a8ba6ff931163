//! The render pass the renderers draw into: its formats, sample count and depth convention.

use super::RenderError;

/// The formats and depth convention of the render pass the renderers draw into.
///
/// Build it with [`Target::new`]; [`Target::with_reverse_z`] declares a reverse-Z depth buffer
/// (cleared to 0, nearer is greater), which every pipeline then tests with `Greater` instead of `Less`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Target {
    /// Format of the color attachment.
    pub color_format: wgpu::TextureFormat,
    /// Format of the depth attachment; `None` draws without a depth test.
    pub depth_format: Option<wgpu::TextureFormat>,
    /// MSAA sample count of the attachments.
    pub sample_count: u32,
    /// Depth 1 is near and 0 far (the projection maps the near plane to 1).
    pub reverse_z: bool,
}

impl Target {
    /// A standard-depth target (0 near, 1 far, cleared to 1).
    pub fn new(
        color_format: wgpu::TextureFormat,
        depth_format: Option<wgpu::TextureFormat>,
        sample_count: u32,
    ) -> Self {
        Self {
            color_format,
            depth_format,
            sample_count,
            reverse_z: false,
        }
    }

    /// The same target with a reverse-Z depth convention (or not).
    pub fn with_reverse_z(self, reverse_z: bool) -> Self {
        Self { reverse_z, ..self }
    }

    /// Refuses targets the renderer would draw wrongly.
    pub(crate) fn check(&self) -> Result<(), RenderError> {
        if !matches!(self.sample_count, 1 | 2 | 4 | 8 | 16) {
            return Err(RenderError::Target(format!(
                "a sample count of {} (1, 2, 4, 8 or 16)",
                self.sample_count
            )));
        }
        if let Some(format) = self.depth_format
            && !format.has_depth_aspect()
        {
            return Err(RenderError::Target(format!(
                "{format:?} as the depth format: it has no depth aspect"
            )));
        }
        if self.reverse_z && self.depth_format.is_none() {
            return Err(RenderError::Target(
                "reverse Z without a depth format".into(),
            ));
        }
        if self.color_format.has_depth_aspect() || self.color_format.has_stencil_aspect() {
            return Err(RenderError::Target(format!(
                "{:?} as the colour format",
                self.color_format
            )));
        }
        Ok(())
    }

    /// True if the depth attachment has a stencil aspect.
    pub fn has_stencil(&self) -> bool {
        self.depth_format.is_some_and(|f| f.has_stencil_aspect())
    }

    /// `compare` as this target's depth convention needs it: `Less` means "nearer".
    pub(crate) fn nearer(&self, compare: wgpu::CompareFunction) -> wgpu::CompareFunction {
        use wgpu::CompareFunction as C;
        if !self.reverse_z {
            return compare;
        }
        match compare {
            C::Less => C::Greater,
            C::LessEqual => C::GreaterEqual,
            C::Greater => C::Less,
            C::GreaterEqual => C::LessEqual,
            other => other,
        }
    }

    /// The depth state of a pass that tests with `compare` (written for standard depth; flipped for
    /// reverse Z) and writes depth if `write`.
    pub(crate) fn depth(
        &self,
        write: bool,
        compare: wgpu::CompareFunction,
    ) -> Option<wgpu::DepthStencilState> {
        self.depth_with_stencil(write, compare, wgpu::StencilState::default())
    }

    /// [`Target::depth`] with a stencil state (the target must have a stencil aspect).
    pub(crate) fn depth_with_stencil(
        &self,
        write: bool,
        compare: wgpu::CompareFunction,
        stencil: wgpu::StencilState,
    ) -> Option<wgpu::DepthStencilState> {
        self.depth_format.map(|format| wgpu::DepthStencilState {
            format,
            depth_write_enabled: Some(write),
            depth_compare: Some(self.nearer(compare)),
            stencil,
            bias: wgpu::DepthBiasState::default(),
        })
    }

    /// The attachments' sample count.
    pub(crate) fn multisample(&self) -> wgpu::MultisampleState {
        wgpu::MultisampleState {
            count: self.sample_count,
            ..Default::default()
        }
    }

    /// The colour attachment, alpha-blended (straight alpha).
    pub(crate) fn blended_color(&self) -> wgpu::ColorTargetState {
        self.color(Some(wgpu::BlendState::ALPHA_BLENDING))
    }

    /// The colour attachment with `blend`.
    pub(crate) fn color(&self, blend: Option<wgpu::BlendState>) -> wgpu::ColorTargetState {
        wgpu::ColorTargetState {
            format: self.color_format,
            blend,
            write_mask: wgpu::ColorWrites::ALL,
        }
    }

    /// The depth a cleared attachment holds: the far plane.
    pub fn far_depth(&self) -> f32 {
        if self.reverse_z { 0.0 } else { 1.0 }
    }
}

/// Runs `create` inside validation and out-of-memory error scopes, so a resource or pipeline the
/// device refuses becomes a typed error instead of reaching wgpu's default handler (which panics).
///
/// In a browser the scopes' answers arrive on a later turn of the page's event loop, which a
/// frame cannot wait for: there `create` runs unchecked and the device's uncaptured-error handler
/// (which the page sets) reports a refusal.
#[cfg(target_arch = "wasm32")]
pub(crate) fn checked<T>(
    _device: &wgpu::Device,
    _what: &str,
    create: impl FnOnce() -> T,
) -> Result<T, RenderError> {
    Ok(create())
}

/// Runs `create` inside validation and out-of-memory error scopes, so a resource or pipeline the
/// device refuses becomes a typed error instead of reaching wgpu's default handler (which panics).
#[cfg(not(target_arch = "wasm32"))]
pub(crate) fn checked<T>(
    device: &wgpu::Device,
    what: &str,
    create: impl FnOnce() -> T,
) -> Result<T, RenderError> {
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = create();
    let invalid = pollster::block_on(validation.pop());
    let out_of_memory = pollster::block_on(memory.pop());
    match out_of_memory.or(invalid) {
        None => Ok(value),
        Some(error) => Err(RenderError::Gpu {
            what: what.to_owned(),
            message: describe(&error),
        }),
    }
}

/// The most specific causes of a device error, on one line (wgpu's own text is "Validation Error";
/// the reason is in its source chain).
#[cfg_attr(target_arch = "wasm32", allow(dead_code))]
fn describe(error: &wgpu::Error) -> String {
    let mut causes = Vec::new();
    let mut source = std::error::Error::source(error);
    while let Some(cause) = source {
        let text = cause.to_string();
        if !text.is_empty() && !causes.contains(&text) {
            causes.push(text);
        }
        source = cause.source();
    }
    if causes.is_empty() {
        causes.push(error.to_string());
    }
    causes.join(": ").replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_resource_the_device_refuses_is_a_typed_error_not_a_panic() {
        let gpu = crate::render::Offscreen::new().expect("a GPU adapter (scripts/setup.sh)");
        let too_big = gpu.device.limits().max_buffer_size.saturating_add(1 << 20);
        let result = checked(&gpu.device, "a huge buffer", || {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("huge"),
                size: too_big,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        });
        match result {
            Err(RenderError::Gpu { what, message }) => {
                assert_eq!(what, "a huge buffer");
                assert!(!message.is_empty());
            }
            other => panic!("expected a GPU error, got {other:?}"),
        }
        // And a buffer the device accepts passes through.
        assert!(
            checked(&gpu.device, "a small buffer", || {
                gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("small"),
                    size: 64,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                })
            })
            .is_ok()
        );
    }

    #[test]
    fn targets_that_would_draw_wrongly_are_refused() {
        let color = wgpu::TextureFormat::Rgba8Unorm;
        assert!(
            Target::new(color, Some(wgpu::TextureFormat::Depth32Float), 1)
                .check()
                .is_ok()
        );
        assert!(
            Target::new(color, None, 1)
                .with_reverse_z(true)
                .check()
                .is_err()
        );
        assert!(
            Target::new(color, Some(wgpu::TextureFormat::Rgba8Unorm), 1)
                .check()
                .is_err()
        );
        assert!(
            Target::new(color, Some(wgpu::TextureFormat::Depth32Float), 3)
                .check()
                .is_err()
        );
        let reverse =
            Target::new(color, Some(wgpu::TextureFormat::Depth32Float), 1).with_reverse_z(true);
        assert_eq!(
            reverse.nearer(wgpu::CompareFunction::Less),
            wgpu::CompareFunction::Greater
        );
        assert_eq!(reverse.far_depth(), 0.0);
    }
}
