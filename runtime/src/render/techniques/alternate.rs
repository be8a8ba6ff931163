//! The thesis' alternate drawable edge types (§9.3, `shaders/alternate.wgsl`):
//! [`Technique::HalfHex`], [`Technique::Plug`], [`Technique::HalfHexPlug`] and [`Technique::House`].
//! Each draws an edge and its caps in one pass of six points (four indexed triangles) per edge,
//! classified in the vertex shader like McGuire–Hughes (they share `shaders/vertex_edges.wgsl`); one
//! pipeline serves all four shapes, chosen by the frame uniform.
//!
//! [`Technique::HalfHex`]: crate::render::Technique::HalfHex
//! [`Technique::Plug`]: crate::render::Technique::Plug
//! [`Technique::HalfHexPlug`]: crate::render::Technique::HalfHexPlug
//! [`Technique::House`]: crate::render::Technique::House

use std::sync::Arc;

use super::mcguire_hughes::{SET, buffers};
use super::{FrameContext, Pulled, TechniqueFrame, pulled_pipeline};
use crate::render::{Pipelines as Cache, RenderError, Technique, modules};

/// The one pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    shapes: wgpu::RenderPipeline,
    /// The four triangles of the half hex and the plug over their six points.
    hex_plug: wgpu::Buffer,
    /// The house's fan.
    house: wgpu::Buffer,
}

impl Pipelines {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        let layout = cache.layout(&SET);
        let module = cache.module("alternate.wgsl", &modules::alternate())?;
        let shapes = pulled_pipeline(
            cache,
            &layout,
            "alternate edges",
            &module,
            "alternate_vertex",
            "flat_fragment",
        )?;
        Ok(Self {
            layout,
            shapes,
            hex_plug: super::corner_indices(
                cache,
                "half hex, plug",
                &[0, 1, 2, 0, 2, 3, 0, 3, 4, 1, 5, 2],
            ),
            house: super::corner_indices(cache, "house", &[0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5]),
        })
    }
}

/// The shape number `alternate.wgsl` switches on.
fn shape(technique: &Technique) -> u32 {
    match technique {
        Technique::HalfHex => 1,
        Technique::Plug => 2,
        Technique::HalfHexPlug => 3,
        _ => 4,
    }
}

/// A frame.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
    house: bool,
}

impl Frame {
    pub(crate) fn new(cache: &Cache) -> Result<Self, RenderError> {
        Ok(Self {
            pipelines: cache.alternate()?,
            pulled: Pulled::new(cache, "alternate edges"),
            house: false,
        })
    }
}

impl TechniqueFrame for Frame {
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        _encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError> {
        let technique = cx.style.technique;
        self.house = technique == Technique::House;
        let shape = shape(&technique);
        self.pulled.prepare(
            cx,
            &self.pipelines.layout,
            &SET,
            |d, i| super::frame_uniform(cx, d, i, shape),
            |asset| buffers(asset, &technique),
        )
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let p = &self.pipelines;
        let indices = if self.house { &p.house } else { &p.hex_plug };
        self.pulled.each(pass, |pass, asset| {
            pass.set_pipeline(&p.shapes);
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint16);
            pass.draw_indexed(0..12, 0, 0..asset.edge_count);
        });
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
