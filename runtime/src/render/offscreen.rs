//! Rendering without a window: a device of its own and a texture to draw into and read back.
//! For tests, thumbnails and the `chamfer render` command; applications use their own device.

use super::target::checked;
use super::{FrameViews, RenderError, Target};

/// A headless GPU device (any adapter, hardware or software, picked like `WGPU_BACKEND`,
/// `WGPU_ADAPTER_NAME` and `WGPU_POWER_PREF` say).
#[derive(Debug)]
pub struct Offscreen {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What the adapter is (name, backend, driver).
    pub info: wgpu::AdapterInfo,
}

impl Offscreen {
    /// Opens a device with the adapter's own limits (software adapters bind up to 128 MiB) and, where
    /// the adapter has it, a 32-bit float depth format with stencil (for the stencil techniques).
    pub fn new() -> Result<Self, RenderError> {
        Self::with_limits(|_| {})
    }

    /// As [`Offscreen::new`], with the adapter's limits changed by `adjust` first: e.g. a smaller
    /// `max_storage_buffer_binding_size`, which makes an asset's edge section bind in several
    /// chunks. Limits past the adapter's are refused with [`RenderError::Device`].
    pub fn with_limits(adjust: impl FnOnce(&mut wgpu::Limits)) -> Result<Self, RenderError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter =
            pollster::block_on(
                instance.request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::from_env()
                        .unwrap_or(wgpu::PowerPreference::HighPerformance),
                    force_fallback_adapter: false,
                    compatible_surface: None,
                    apply_limit_buckets: false,
                }),
            )
            .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        let mut limits = adapter.limits();
        adjust(&mut limits);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("chamfer offscreen"),
            required_features: adapter.features() & wgpu::Features::DEPTH32FLOAT_STENCIL8,
            required_limits: limits,
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Self {
            device,
            queue,
            info: adapter.get_info(),
        })
    }

    /// The depth format of this device's offscreen targets: 32-bit float, with stencil where the
    /// device has the feature, else 24-bit with stencil.
    pub fn depth_format(&self) -> wgpu::TextureFormat {
        OffscreenTarget::depth_format(&self.device)
    }

    /// The formats of a `sample_count`-sample offscreen target (1 or 4): RGBA8 and
    /// [`Offscreen::depth_format`], standard depth.
    pub fn formats(&self, sample_count: u32) -> Target {
        Target::new(COLOR, Some(self.depth_format()), sample_count)
    }

    /// A `width` × `height` target of [`Offscreen::formats`].
    pub fn target(
        &self,
        width: u32,
        height: u32,
        sample_count: u32,
    ) -> Result<OffscreenTarget, RenderError> {
        self.target_with(width, height, self.formats(sample_count))
    }

    /// A `width` × `height` target of `formats` (colour RGBA8, any depth format, either depth
    /// convention). Fails with a typed error if the device refuses the textures (too large, say).
    pub fn target_with(
        &self,
        width: u32,
        height: u32,
        formats: Target,
    ) -> Result<OffscreenTarget, RenderError> {
        OffscreenTarget::new(&self.device, width, height, formats)
    }

    /// A command encoder for a frame.
    pub fn encoder(&self) -> wgpu::CommandEncoder {
        self.device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("offscreen frame"),
            })
    }

    /// Submits `encoder` and waits until the GPU is done; a command the device refuses becomes a
    /// typed error.
    pub fn submit(&self, encoder: wgpu::CommandEncoder) -> Result<(), RenderError> {
        checked(&self.device, "the frame's commands", || {
            self.queue.submit([encoder.finish()]);
        })?;
        self.wait()
    }

    /// Blocks until the GPU has finished all submitted work.
    pub fn wait(&self) -> Result<(), RenderError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| RenderError::Readback(e.to_string()))
    }
}

/// Colour (RGBA8, linear values as written) and depth attachments.
#[derive(Debug)]
pub struct OffscreenTarget {
    width: u32,
    height: u32,
    formats: Target,
    color: wgpu::Texture,
    multisampled: Option<wgpu::TextureView>,
    color_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
    depth_sampled: wgpu::TextureView,
}

/// The colour format of offscreen targets.
const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

impl OffscreenTarget {
    /// A `width` × `height` target of `formats` on any device (an application's, a web page's):
    /// colour RGBA8, any depth format, either depth convention. Fails with a typed error if the
    /// device refuses the textures (too large, say). [`OffscreenTarget::color_texture`] is then
    /// what to copy to a window's or a canvas's RGBA8 surface texture.
    pub fn new(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        formats: Target,
    ) -> Result<Self, RenderError> {
        formats.check()?;
        if formats.color_format != COLOR {
            return Err(RenderError::Target(format!(
                "{:?} as an offscreen colour format (offscreen targets are {COLOR:?})",
                formats.color_format
            )));
        }
        let limit = device.limits().max_texture_dimension_2d;
        if width > limit || height > limit {
            return Err(RenderError::Target(format!(
                "a size of {width}x{height}: this device's textures are at most {limit} pixels wide and high"
            )));
        }
        checked(device, "the offscreen target", || {
            Self::create(device, width.max(1), height.max(1), formats)
        })
    }

    /// The depth format for offscreen targets on `device`: 32-bit float with stencil where the
    /// device has the feature, else 24-bit with stencil.
    pub fn depth_format(device: &wgpu::Device) -> wgpu::TextureFormat {
        if device
            .features()
            .contains(wgpu::Features::DEPTH32FLOAT_STENCIL8)
        {
            wgpu::TextureFormat::Depth32FloatStencil8
        } else {
            wgpu::TextureFormat::Depth24PlusStencil8
        }
    }

    /// The resolved colour texture (RGBA8, `COPY_SRC`), finished once the frame's commands are.
    pub fn color_texture(&self) -> &wgpu::Texture {
        &self.color
    }

    fn create(device: &wgpu::Device, width: u32, height: u32, formats: Target) -> Self {
        let texture = |label, format, samples, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let samples = formats.sample_count;
        let color = texture(
            "offscreen color",
            COLOR,
            1,
            attachment | wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let multisampled = (samples > 1).then(|| {
            texture("offscreen msaa", COLOR, samples, attachment).create_view(&Default::default())
        });
        let depth_format = formats
            .depth_format
            .unwrap_or(wgpu::TextureFormat::Depth32Float);
        let depth = texture(
            "offscreen depth",
            depth_format,
            samples,
            attachment | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        Self {
            width,
            height,
            formats,
            color_view: color.create_view(&Default::default()),
            color,
            multisampled,
            depth_view: depth.create_view(&Default::default()),
            depth_sampled: depth.create_view(&wgpu::TextureViewDescriptor {
                label: Some("offscreen depth, sampled"),
                aspect: wgpu::TextureAspect::DepthOnly,
                ..Default::default()
            }),
        }
    }

    /// The formats renderers must be built for to draw here.
    pub fn formats(&self) -> Target {
        self.formats
    }

    /// Width and height in pixels.
    pub fn size(&self) -> [u32; 2] {
        [self.width, self.height]
    }

    /// Begins the frame's pass in `encoder`: colour cleared to `background`, depth to the far
    /// plane, stencil to 0; depth is stored for the techniques that read it after the pass.
    pub fn begin_pass<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        background: [f64; 4],
    ) -> wgpu::RenderPass<'e> {
        let (view, resolve_target) = match &self.multisampled {
            Some(msaa) => (msaa, Some(&self.color_view)),
            None => (&self.color_view, None),
        };
        let [r, g, b, a] = background;
        let stencil = self.formats.has_stencil().then_some(wgpu::Operations {
            load: wgpu::LoadOp::Clear(0),
            store: wgpu::StoreOp::Store,
        });
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("offscreen pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(self.formats.far_depth()),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: stencil,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        })
    }

    /// The finished colour and the depth, for [`Prepared::finish`](super::Prepared::finish).
    pub fn views(&self) -> FrameViews<'_> {
        FrameViews {
            color: &self.color_view,
            depth: &self.depth_sampled,
        }
    }

    /// Records `before` (compute work), then a pass cleared to `background` in which `inside`
    /// draws; submits and waits until the GPU is done. (For frames with no work after the pass.)
    pub fn draw(
        &self,
        gpu: &Offscreen,
        background: [f64; 4],
        before: impl FnOnce(&mut wgpu::CommandEncoder),
        inside: impl FnOnce(&mut wgpu::RenderPass<'_>),
    ) -> Result<(), RenderError> {
        let mut encoder = gpu.encoder();
        before(&mut encoder);
        inside(&mut self.begin_pass(&mut encoder, background));
        gpu.submit(encoder)
    }

    /// Copies the colour attachment back to the CPU.
    pub fn read(&self, gpu: &Offscreen) -> Result<Image, RenderError> {
        let row = 4 * self.width;
        let padded_row =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = checked(&gpu.device, "the readback buffer", || {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("offscreen readback"),
                size: u64::from(padded_row) * u64::from(self.height),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            })
        })?;
        let mut encoder = gpu.encoder();
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &self.color,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
        gpu.queue.submit([encoder.finish()]);
        let mapped = map_read(&gpu.device, &buffer)?;
        let mut rgba = Vec::with_capacity((row * self.height) as usize);
        for y in 0..self.height as usize {
            let start = y * padded_row as usize;
            rgba.extend_from_slice(&mapped[start..start + row as usize]);
        }
        Ok(Image {
            width: self.width,
            height: self.height,
            rgba,
        })
    }
}

/// An RGBA8 image read back from the GPU, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Four bytes per pixel.
    pub rgba: Vec<u8>,
}

impl Image {
    /// The pixel at column `x`, row `y` (0 at the top).
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        let i = 4 * (y as usize * self.width as usize + x as usize);
        [
            self.rgba[i],
            self.rgba[i + 1],
            self.rgba[i + 2],
            self.rgba[i + 3],
        ]
    }
}

/// Maps `buffer` (MAP_READ, its copy already submitted) for reading, blocking until the GPU is done.
pub(crate) fn map_read(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
) -> Result<wgpu::BufferView, RenderError> {
    let failed = |e: String| RenderError::Readback(e);
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |result| {
        let _ = sender.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| failed(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| failed(e.to_string()))?
        .map_err(|e| failed(e.to_string()))?;
    buffer
        .get_mapped_range(..)
        .map_err(|e| failed(e.to_string()))
}

/// The first `size` bytes of `buffer` (which must have `COPY_SRC` usage), read back to the CPU.
/// Blocks until the GPU is done.
pub(crate) fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    size: u64,
) -> Result<Vec<u8>, RenderError> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("readback"),
    });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    queue.submit([encoder.finish()]);
    Ok(map_read(device, &staging)?.to_vec())
}
