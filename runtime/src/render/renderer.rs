//! Per frame: [`EdgeRenderer`] holds one asset's per-frame state for the technique its style names,
//! and [`EdgeRenderer::prepare`] hands back the [`Prepared`] frame that alone can draw it.
//!
//! The order of a frame is in the types: `prepare` records the frame's compute work into the encoder
//! it is given (so it happens before any pass that draws), and only the `Prepared` value it returns
//! can `render` into a pass or `finish` after it. A frame whose encoder is dropped unsubmitted leaves
//! nothing behind: every frame writes all it reads.

use super::techniques::{self, FrameContext, TechniqueFrame};
use super::{Camera, EdgeStyle, GpuAsset, Pipelines, RenderError, Technique};

/// Draws one [`GpuAsset`]'s edges with the pipelines of a [`Pipelines`] cache. Create one per asset
/// you draw (it holds that asset's per-frame state); the pipelines and the asset's buffers are shared.
#[derive(Debug)]
pub struct EdgeRenderer {
    pipelines: Pipelines,
    asset: GpuAsset,
    frame: Option<(Technique, Box<dyn TechniqueFrame>)>,
}

/// What the last computed frame drew, read back from the GPU (see [`EdgeRenderer::read_counts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawCounts {
    /// Edges that passed classification.
    pub edges: u32,
    /// Caps the joins emitted.
    pub caps: u32,
}

/// The application's finished attachments, for the techniques that work after its pass
/// (post-processes): see [`Prepared::finish`].
#[derive(Clone, Copy, Debug)]
pub struct FrameViews<'a> {
    /// The single-sample colour the frame ends in (the resolve target under MSAA); drawn into.
    pub color: &'a wgpu::TextureView,
    /// The depth attachment of the pass (multisampled under MSAA), created with
    /// `TEXTURE_BINDING` usage and stored (`StoreOp::Store`); read.
    pub depth: &'a wgpu::TextureView,
}

impl EdgeRenderer {
    /// A renderer for `asset`; allocates nothing until the first [`prepare`](Self::prepare), which
    /// sizes the state for the technique in use.
    pub fn new(pipelines: &Pipelines, asset: &GpuAsset) -> Self {
        Self {
            pipelines: pipelines.clone(),
            asset: asset.clone(),
            frame: None,
        }
    }

    /// Sets this frame's camera and style and records the frame's compute work into `encoder`
    /// (submit it before, or with, the pass that draws). Returns the frame to draw.
    ///
    /// Fails if the style's technique needs what the target or the asset lacks, or if a list does
    /// not fit the device (typed [`RenderError`]s; nothing is recorded then).
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        style: &EdgeStyle,
    ) -> Result<Prepared<'_>, RenderError> {
        // A frame serves every parameter of its technique that needs the same per-asset data.
        let same_kind = self.frame.as_ref().is_some_and(|(t, _)| {
            std::mem::discriminant(t) == std::mem::discriminant(&style.technique)
                && t.needs() == style.technique.needs()
        });
        if !same_kind {
            // Free the old technique's state before making the new one.
            self.frame = None;
            let frame = techniques::new_frame(&self.pipelines, &self.asset, &style.technique)?;
            self.frame = Some((style.technique, frame));
        }
        let Some((technique, frame)) = self.frame.as_mut() else {
            return Err(RenderError::Unsupported {
                technique: style.technique.name(),
                why: "its frame state could not be made".into(),
            });
        };
        *technique = style.technique;
        let cx = FrameContext {
            pipelines: &self.pipelines,
            queue,
            asset: &self.asset,
            camera,
            style,
        };
        frame.prepare(&cx, encoder)?;
        Ok(Prepared { frame: &**frame })
    }

    /// Reads back how many edges and caps the last submitted frame produced. Blocks until the GPU
    /// is idle: for statistics, tests and benchmarks, not for every frame.
    ///
    /// Fails with [`RenderError::Unsupported`] before any frame, or for techniques that do not
    /// count what they draw (they classify in the vertex shader, with nothing to read back).
    pub fn read_counts(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<DrawCounts, RenderError> {
        let Some((technique, frame)) = &self.frame else {
            return Err(RenderError::Unsupported {
                technique: "EdgeRenderer::read_counts",
                why: "no frame was prepared yet".into(),
            });
        };
        frame.read_counts(device, queue).unwrap_or_else(|| {
            Err(RenderError::Unsupported {
                technique: technique.name(),
                why: "it does not count its edges".into(),
            })
        })
    }

    /// GPU bytes of this renderer's per-frame state (the asset's buffers are counted by
    /// [`GpuAsset::gpu_bytes`]).
    pub fn gpu_bytes(&self) -> u64 {
        self.frame.as_ref().map_or(0, |(_, f)| f.gpu_bytes())
    }
}

/// A frame whose compute work is recorded: draw it with [`render`](Self::render) inside the
/// application's pass, after its mesh, then [`finish`](Self::finish) after that pass.
#[derive(Debug)]
pub struct Prepared<'a> {
    frame: &'a dyn TechniqueFrame,
}

impl Prepared<'_> {
    /// Draws this frame's edges into `pass` (after the mesh, against its depth).
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.frame.render(pass);
    }

    /// Records what the technique does after the application's pass (post-processes over its
    /// colour, reading its depth); nothing for the others. Call it once the pass has ended.
    pub fn finish(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        views: &FrameViews<'_>,
    ) -> Result<(), RenderError> {
        self.frame.finish(encoder, views)
    }
}
