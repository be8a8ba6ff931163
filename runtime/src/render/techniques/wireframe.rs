//! [`Technique::Wireframe`](crate::render::Technique::Wireframe): the barycentric thick wireframe of
//! seed 001 (`shaders/wireframe.wgsl`). The article's geometry shader computed per-corner edge
//! coordinates from its triangle; here the vertex shader pulls the triangle's three corners from the
//! asset's render sections (instance = triangle, vertex = corner) and does the same.

use chamfer_shaders as wgsl;

use super::pulled::{Draws, Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Binding, Bindings, FRAME, PARAMS, asset};
use crate::render::layout::{Layout, layout};
use crate::render::modules::Program;
use crate::render::{AssetExtras, GpuAsset, RenderError, Technique};

pub(crate) static MODULE: PullModule<Wireframe> = PullModule::new();

#[derive(Debug)]
pub(crate) struct Wireframe;

/// `WireParams` in `shaders/wireframe.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct WireParams {
    naive: u32,
    smooth_border: u32,
    feature_only: u32,
    naive_threshold: f32,
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
    const PRESETS: &'static [crate::render::Preset] = &[
        crate::render::Preset {
            name: "wireframe",
            summary: "barycentric thick wireframe of every triangle (seed 001)",
            technique: crate::render::Technique::Wireframe {
                feature_only: false,
                smooth: true,
                naive_threshold: None,
            },
        },
        crate::render::Preset {
            name: "wireframe-features",
            summary: "barycentric thick wireframe of the feature edges (seed 001)",
            technique: crate::render::Technique::Wireframe {
                feature_only: true,
                smooth: true,
                naive_threshold: None,
            },
        },
    ];

    /// By `feature_only`, whatever the other parameters.
    fn preset(technique: &crate::render::Technique) -> &'static crate::render::Preset {
        let features = matches!(
            technique,
            crate::render::Technique::Wireframe {
                feature_only: true,
                ..
            }
        );
        &Self::PRESETS[usize::from(features)]
    }

    type Params = WireParams;
    type Draw = ();
    const BINDINGS: &'static Bindings = &Bindings::draw(
        "wireframe",
        &[
            FRAME,
            PARAMS,
            asset::RENDER_POSITIONS,
            asset::MESH_INDICES,
            asset::TRIANGLE_EDGES,
        ],
    );
    const SHADER: (&'static str, &'static [&'static str]) = (
        "wireframe.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::TRIANGLES,
            wgsl::WIREFRAME,
        ],
    );
    const DRAWS: Draws = Draws::PerTriangle(3);
    const PROGRAMS: &'static [Program] = &[Program::draw(
        "wire_vertex",
        "wire_fragment",
        Self::BINDINGS,
    )];
    const STRUCTS: &'static [Layout] = &[layout!(
        "WireParams",
        WireParams,
        [naive, smooth_border, feature_only, naive_threshold]
    )];

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
}
