//! The wgpu renderer: draws an asset's feature edges inside the user's own frame.
//!
//! Like `glyphon` or `egui-wgpu`, it is a guest in the application's wgpu setup: it is created from
//! the application's device and target formats, is told the camera each frame, records its compute
//! work into the application's encoder and draws into the application's render pass. It never owns
//! the window, the device or the frame.
//!
//! ```no_run
//! # use chamfer_runtime::render::*;
//! # fn frame(device: &wgpu::Device, queue: &wgpu::Queue, asset: &chamfer_runtime::asset::Asset,
//! #          camera: &Camera, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView,
//! #          depth: &wgpu::TextureView) -> Result<(), RenderError> {
//! let target = Target { color_format: wgpu::TextureFormat::Rgba8Unorm,
//!                       depth_format: Some(wgpu::TextureFormat::Depth32Float), sample_count: 1 };
//! let gpu = GpuAsset::new(device, asset)?;                 // once: uploads the sections as they are
//! let mut mesh = MeshRenderer::new(device, &target, &gpu); // optional: the runtime's lit mesh pass
//! let mut edges = EdgeRenderer::new(device, &target, &gpu)?;
//!
//! mesh.prepare(queue, camera, &MeshStyle::default());      // each frame
//! edges.prepare(queue, camera, &EdgeStyle::default());
//! edges.compute(encoder);                                  // classify edges and joins on the GPU
//! let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
//!     // ... the application's color and depth attachments ...
//! #   label: None, color_attachments: &[], depth_stencil_attachment: None,
//! #   timestamp_writes: None, occlusion_query_set: None, multiview_mask: None,
//! });
//! mesh.render(&mut pass);
//! edges.render(&mut pass);
//! # Ok(()) }
//! ```
//!
//! Per frame on the GPU (shaders in `shaders/`, one file per pass): `classify` tests every edge
//! (contours by the front/back test against the camera, thesis §6.1; baked crease, boundary and marked
//! classes) and appends the drawable ones to a compact list that is the instance count of an indirect
//! draw; `joins` finds, at each drawn edge end, the neighbouring drawn edges by walking the next-index
//! ring (thesis §13) or the cap buffer (§10.5), cuts overlapping quads apart and emits round caps for
//! the gaps; then the edges are drawn as screen-space quads (half quads outside the silhouette for
//! contours, §8.3) and the caps as sectors. No pixel is covered twice, so translucent colours blend once.
//! [`Offscreen`] renders without a window (tests, thumbnails, the `chamfer render` command).

mod camera;
mod edges;
mod error;
mod gpu_asset;
mod lighting;
mod mesh;
mod offscreen;
mod shaders;

pub use camera::{Camera, Orbit};
pub use edges::{CapMethod, DrawCounts, EdgeClasses, EdgeColors, EdgeRenderer, EdgeStyle};
pub use error::RenderError;
pub use gpu_asset::GpuAsset;
pub use lighting::{Highlight, Light};
pub use mesh::{MeshLight, MeshRenderer, MeshStyle};
pub use offscreen::{Image, Offscreen, OffscreenTarget};

/// The formats of the render pass the renderers draw into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Target {
    /// Format of the color attachment.
    pub color_format: wgpu::TextureFormat,
    /// Format of the depth attachment; `None` draws without a depth test.
    pub depth_format: Option<wgpu::TextureFormat>,
    /// MSAA sample count of the attachments.
    pub sample_count: u32,
}

impl Target {
    /// The depth state of a pass that tests with `compare` and writes depth if `write`.
    pub(crate) fn depth(
        &self,
        write: bool,
        compare: wgpu::CompareFunction,
    ) -> Option<wgpu::DepthStencilState> {
        self.depth_format.map(|format| wgpu::DepthStencilState {
            format,
            depth_write_enabled: Some(write),
            depth_compare: Some(compare),
            stencil: wgpu::StencilState::default(),
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
        wgpu::ColorTargetState {
            format: self.color_format,
            blend: Some(wgpu::BlendState::ALPHA_BLENDING),
            write_mask: wgpu::ColorWrites::ALL,
        }
    }
}
