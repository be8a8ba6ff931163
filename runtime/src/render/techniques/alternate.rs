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

use super::mcguire_hughes::SET;
use super::{FrameContext, Pulled, TechniqueFrame, extra, pulled_pipeline};
use crate::render::{GpuAsset, Pipelines as Cache, RenderError, Technique, modules};

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

/// One asset's frame.
#[derive(Debug)]
pub(crate) struct Frame {
    pipelines: Arc<Pipelines>,
    pulled: Pulled,
    edge_count: u32,
    house: bool,
}

impl Frame {
    pub(crate) fn new(
        cache: &Cache,
        asset: &GpuAsset,
        technique: &Technique,
    ) -> Result<Self, RenderError> {
        let pipelines = cache.alternate()?;
        let normals = extra(
            &asset.vertex_normals,
            technique,
            "AssetExtras::VERTEX_NORMALS",
        )?;
        let pulled = Pulled::new(
            cache,
            &pipelines.layout,
            &SET,
            &[
                (1, &asset.topology_positions),
                (2, &asset.edge_vertices),
                (3, &asset.edge_attributes),
                (4, normals),
            ],
        );
        Ok(Self {
            pipelines,
            pulled,
            edge_count: asset.edge_count,
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
        let uniform = super::frame_uniform(cx, shape(&cx.style.technique));
        self.house = cx.style.technique == Technique::House;
        self.pulled.write(cx.queue, &uniform);
        Ok(())
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(0, &self.pulled.group, &[]);
        pass.set_pipeline(&self.pipelines.shapes);
        let indices = if self.house {
            &self.pipelines.house
        } else {
            &self.pipelines.hex_plug
        };
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint16);
        pass.draw_indexed(0..12, 0, 0..self.edge_count);
    }

    fn gpu_bytes(&self) -> u64 {
        self.pulled.gpu_bytes()
    }
}
