//! [`Technique::Wireframe`](crate::render::Technique::Wireframe): the barycentric thick wireframe of
//! seed 001 (`shaders/wireframe.wgsl`). The article's geometry shader computed per-corner edge
//! coordinates from its triangle; here the vertex shader pulls the triangle's three corners from the
//! asset's render sections (instance = triangle, vertex = corner) and does the same.

use super::pulled::{Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Binding, Bindings, FRAME, PARAMS, asset};
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::{PipelineSet, Raster};
use crate::render::{AssetExtras, GpuAsset, Pipelines, RenderError, Target, Technique};

pub(crate) static MODULE: PullModule<Wireframe> = PullModule::new();

const BINDINGS: Bindings = Bindings::draw(
    "wireframe",
    &[
        FRAME,
        PARAMS,
        asset::RENDER_POSITIONS,
        asset::MESH_INDICES,
        asset::TRIANGLE_EDGES,
    ],
);

/// `WireParams` in `shaders/wireframe.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct WireParams {
    naive: u32,
    smooth_border: u32,
    feature_only: u32,
    naive_threshold: f32,
}

pub(crate) struct Wireframe;

fn shader() -> Shader {
    use chamfer_shaders as wgsl;
    Shader::new(
        "wireframe.wgsl",
        &[wgsl::COMMON, wgsl::TRIANGLES, wgsl::WIREFRAME],
        vec![Program::draw("wire_vertex", "wire_fragment", &BINDINGS)],
    )
}

/// The wireframe pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct WirePipelines {
    wire: wgpu::RenderPipeline,
}

impl PipelineSet for WirePipelines {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let compiled = cache.compile(&shader)?;
        Ok(Self {
            wire: compiled.render(
                "wire_vertex",
                Some("wire_fragment"),
                Raster::over_mesh(cache.target()),
            )?,
        })
    }
}

fn feature_only(technique: &Technique) -> bool {
    matches!(
        technique,
        Technique::Wireframe {
            feature_only: true,
            ..
        }
    )
}

impl Pull for Wireframe {
    type Params = WireParams;
    type Pipelines = WirePipelines;
    type Draw = ();
    const BINDINGS: &'static Bindings = &BINDINGS;

    fn shaders(_target: &Target) -> Vec<Shader> {
        vec![shader()]
    }

    fn structs() -> Vec<Layout> {
        vec![layout!(
            "WireParams",
            WireParams,
            [naive, smooth_border, feature_only, naive_threshold]
        )]
    }

    fn needs(technique: &Technique) -> AssetExtras {
        if feature_only(technique) {
            AssetExtras::TRIANGLE_EDGES
        } else {
            AssetExtras::NONE
        }
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<WireParams> {
        let Technique::Wireframe {
            feature_only,
            smooth,
            naive_threshold,
        } = cx.style.technique
        else {
            return None;
        };
        Some(WireParams {
            naive: u32::from(naive_threshold.is_some()),
            smooth_border: u32::from(smooth),
            feature_only: u32::from(feature_only),
            naive_threshold: naive_threshold.unwrap_or(0.0),
        })
    }

    fn resource<'a>(
        asset: &'a GpuAsset,
        binding: Binding,
        technique: &Technique,
    ) -> Result<wgpu::BindingResource<'a>, RenderError> {
        // The masks are read only in feature-only mode; otherwise any buffer fills the binding.
        if binding == asset::TRIANGLE_EDGES && !feature_only(technique) {
            return asset
                .resource(binding, technique.name())
                .or_else(|_| asset.resource(asset::MESH_INDICES, technique.name()));
        }
        asset.resource(binding, technique.name())
    }

    fn draw(set: &WirePipelines, _: (), pass: &mut wgpu::RenderPass<'_>, asset: &GpuAsset) {
        pass.set_pipeline(&set.wire);
        pass.draw(0..3, 0..asset.index_count / 3);
    }
}
