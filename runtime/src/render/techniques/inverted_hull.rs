//! [`Technique::InvertedHull`](crate::render::Technique::InvertedHull): the expanded inverted hull
//! (thesis §7.2, `shaders/inverted_hull.wgsl`): the mesh pushed out along its normals, front faces
//! culled, in the contour colour.

use chamfer_shaders as wgsl;

use super::pulled::{Draws, Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::render::bindings::{Bindings, FRAME, PARAMS, asset};
use crate::render::gpu_asset::VERTEX_LAYOUTS;
use crate::render::layout::{Layout, layout};
use crate::render::modules::Program;
use crate::render::pipelines::Raster;
use crate::render::{Target, Technique};

pub(crate) static MODULE: PullModule<InvertedHull> = PullModule::new();

#[derive(Debug)]
pub(crate) struct InvertedHull;

/// `HullParams` in `shaders/inverted_hull.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct HullParams {
    smooth_normals: u32,
}

impl Pull for InvertedHull {
    const PRESETS: &'static [crate::render::Preset] = &[
        crate::render::Preset {
            name: "inverted-hull",
            summary: "the mesh pushed out along its normals, front faces culled (thesis §7.2)",
            technique: crate::render::Technique::InvertedHull {
                smooth_normals: false,
            },
        },
        crate::render::Preset {
            name: "inverted-hull-smooth",
            summary: "inverted hull along smooth normals (thesis §7.2)",
            technique: crate::render::Technique::InvertedHull {
                smooth_normals: true,
            },
        },
    ];

    /// By `smooth_normals`.
    fn preset(technique: &crate::render::Technique) -> &'static crate::render::Preset {
        let smooth = matches!(
            technique,
            crate::render::Technique::InvertedHull {
                smooth_normals: true
            }
        );
        &Self::PRESETS[usize::from(smooth)]
    }

    type Params = HullParams;
    type Draw = ();
    const BINDINGS: &'static Bindings = &Bindings::draw(
        "inverted hull",
        &[
            FRAME,
            PARAMS,
            asset::VERTEX_NORMALS,
            asset::RENDER_TO_TOPOLOGY,
        ],
    );
    const SHADER: (&'static str, &'static [&'static str]) = (
        "inverted_hull.wgsl",
        &[
            wgsl::COMMON,
            wgsl::SECTION,
            wgsl::FRAME,
            wgsl::FLAT,
            wgsl::INVERTED_HULL,
        ],
    );
    const DRAWS: Draws = Draws::Mesh;
    const PROGRAMS: &'static [Program] = &[Program::draw(
        "hull_vertex",
        "flat_fragment",
        Self::BINDINGS,
    )];
    const STRUCTS: &'static [Layout] = &[layout!("HullParams", HullParams, [smooth_normals])];

    /// The mesh's vertex buffers, front faces culled: the hull's far side.
    fn raster(target: &Target) -> Raster<'static> {
        Raster {
            buffers: &VERTEX_LAYOUTS,
            primitive: wgpu::PrimitiveState {
                cull_mode: Some(wgpu::Face::Front),
                ..Default::default()
            },
            ..Raster::over_mesh(target)
        }
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<HullParams> {
        let Technique::InvertedHull { smooth_normals } = cx.style.technique else {
            return None;
        };
        Some(HullParams {
            smooth_normals: u32::from(smooth_normals),
        })
    }
}
