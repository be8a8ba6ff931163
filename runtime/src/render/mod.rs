//! The wgpu renderer: draws an asset's feature edges inside the user's own frame.
//!
//! Like `glyphon` or `egui-wgpu`, it is a guest in the application's wgpu setup: it never owns the
//! window, the device or the frame. Its GPU state is split by lifetime:
//!
//! - **per device and target**, [`Pipelines`]: every technique's compiled pipelines and layouts,
//!   created once per target format and shared by all assets (cheap to clone);
//! - **per asset**, [`GpuAsset`]: the asset's sections as uploaded (its edge clusters included, which
//!   every frame's cull pass reads) and what a technique derives from them at upload;
//! - **per frame**, [`EdgeRenderer`] (one per asset drawn): uniforms and lists, sized for the
//!   technique its [`EdgeStyle`] names. [`EdgeRenderer::prepare`] records the frame's compute work
//!   into the encoder it is given and returns the [`Prepared`] frame, the only thing that can draw it.
//!
//! ```no_run
//! # use chamfer_runtime::render::*;
//! # fn frame(device: &wgpu::Device, queue: &wgpu::Queue, asset: &chamfer_runtime::asset::Asset,
//! #          camera: &Camera, color: &wgpu::TextureView,
//! #          depth: &wgpu::TextureView) -> Result<(), RenderError> {
//! let target = Target::new(wgpu::TextureFormat::Rgba8Unorm,
//!                          Some(wgpu::TextureFormat::Depth32Float), 1);
//! let pipelines = Pipelines::new(device, &target)?;           // once per target format
//! let gpu = GpuAsset::new(device, asset)?;                    // once per asset
//! let mut mesh = MeshRenderer::new(&pipelines, &gpu)?;       // optional: a simple lit mesh pass
//! let mut edges = EdgeRenderer::new(&pipelines, &gpu);
//!
//! let mut encoder = device.create_command_encoder(&Default::default()); // each frame
//! mesh.prepare(queue, camera, &MeshStyle::default());
//! let prepared = edges.prepare(queue, &mut encoder, camera, &EdgeStyle::default())?;
//! {
//!     let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
//!         // ... the application's color and depth attachments ...
//! #       label: None, color_attachments: &[], depth_stencil_attachment: None,
//! #       timestamp_writes: None, occlusion_query_set: None, multiview_mask: None,
//!     });
//!     mesh.render(&mut pass);
//!     prepared.render(&mut pass);
//! }
//! prepared.finish(&mut encoder, &FrameViews { color, depth })?; // post-process techniques only
//! queue.submit([encoder.finish()]);
//! # Ok(()) }
//! ```
//!
//! Techniques ([`Technique`], one switch in [`EdgeStyle::technique`]) are one module each under
//! `techniques/` with their own shader files. [`Offscreen`] renders without a window (tests,
//! thumbnails, the `chamfer render` command).

mod bindings;
mod cut;
mod derived;
mod display;
mod environment;
mod error;
mod gpu_asset;
pub(crate) mod layout;
mod lighting;
mod mesh;
mod modules;
mod offscreen;
mod pipelines;
mod pose;
mod renderer;
mod style;
mod style_settings;
mod target;
mod technique;
mod techniques;

pub use crate::camera::{Camera, Orbit};
pub use cut::{CapHatch, CapStyle, CutOutline, CutRenderer, CutStyle, section_wgsl};
pub use derived::AssetExtras;
pub use display::{
    Display, DisplaySettings, DistanceFade, FaceMode, HiddenStyle, LinePattern, MAX_DASHES,
};
pub use error::RenderError;
pub use gpu_asset::GpuAsset;
pub use lighting::{DEFAULT_LIGHT_DIRECTION, Highlight, Light, Shading};
pub use mesh::{MeshLight, MeshRenderer, MeshStyle};
pub use offscreen::{Image, Offscreen, OffscreenTarget};
pub use pipelines::Pipelines;
pub use pose::PosedAsset;
pub use renderer::{
    DrawCounts, EdgeRenderer, FrameViews, Instance, Prepared, SceneRenderer, SceneStats,
};
pub use style::{CapMethod, EdgeClasses, EdgeColors, EdgeStyle};
pub use style_settings::StyleSettings;
pub use target::Target;
pub use technique::{
    FinSettings, HardwareContour, HybridDepth, ImageSpace, Operator, Parameters, Preset,
    SurfaceAngleSettings, Technique,
};
