//! [`Technique::ImageSpace`](crate::render::Technique::ImageSpace): gradient operators over the
//! application's depth and a normal buffer (thesis §5, `shaders/image_space.wgsl`). The frame draws
//! this asset's normals into a buffer of its own before the application's pass (§5.4's first pass),
//! and runs the operator over both in [`Prepared::finish`](crate::render::Prepared::finish).

use super::FrameContext;
use super::post::{self, Blend, DEPTH, MESH_PASS, PARAMS, POST, PostModule, PostProcess};
use crate::render::bindings::{Binding, Bindings, Kind};
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::{Operator, Target, Technique};

pub(crate) static MODULE: PostModule<ImageSpace> = PostModule::new();

/// `ImageParams` in `shaders/image_space.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ImageParams {
    kernel: u32,
    depth_threshold: f32,
    normal_threshold: f32,
    step_px: f32,
    depth_scaled: u32,
}

#[derive(Debug)]
pub(crate) struct ImageSpace;

/// The normal buffer the frame draws.
const NORMALS: Binding = Binding::new(17, "normals", Kind::Texture);
const BINDINGS: Bindings = Bindings::draw("image-space edges", &[POST, PARAMS, DEPTH, NORMALS]);

impl PostProcess for ImageSpace {
    const PRESETS: &'static [crate::render::Preset] = &[
        crate::render::Preset {
            name: "image-sobel",
            summary: "gradient operator over depth and normal buffers, thresholded (thesis §5)",
            technique: crate::render::Technique::ImageSpace(crate::render::ImageSpace::new(
                crate::render::Operator::Sobel,
            )),
        },
        crate::render::Preset {
            name: "image-prewitt",
            summary: "gradient operator over depth and normal buffers, thresholded (thesis §5)",
            technique: crate::render::Technique::ImageSpace(crate::render::ImageSpace::new(
                crate::render::Operator::Prewitt,
            )),
        },
        crate::render::Preset {
            name: "image-scharr",
            summary: "gradient operator over depth and normal buffers, thresholded (thesis §5)",
            technique: crate::render::Technique::ImageSpace(crate::render::ImageSpace::new(
                crate::render::Operator::Scharr,
            )),
        },
        crate::render::Preset {
            name: "image-roberts",
            summary: "gradient operator over depth and normal buffers, thresholded (thesis §5)",
            technique: crate::render::Technique::ImageSpace(crate::render::ImageSpace::new(
                crate::render::Operator::Roberts,
            )),
        },
    ];

    /// By the operator, whatever the thresholds (the presets are in [`Operator::ALL`]'s order).
    ///
    /// [`Operator::ALL`]: crate::render::Operator::ALL
    fn preset(technique: &crate::render::Technique) -> &'static crate::render::Preset {
        let index = match technique {
            crate::render::Technique::ImageSpace(p) => crate::render::Operator::ALL
                .iter()
                .position(|o| *o == p.operator),
            _ => None,
        };
        &Self::PRESETS[index.unwrap_or(0)]
    }

    type Params = ImageParams;
    const BINDINGS: &'static Bindings = &BINDINGS;
    const OWN: Binding = NORMALS;
    const OWN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
    const OWN_DEPTH: bool = true;
    const BLEND: Blend = Blend::Alpha;

    fn shader(target: &Target) -> Shader {
        use chamfer_shaders as wgsl;
        Shader::new(
            "image_space.wgsl",
            &[
                post::depth_source(target),
                wgsl::POST,
                wgsl::SECTION,
                wgsl::IMAGE_SPACE,
            ],
            vec![
                Program::draw("post_vertex", "image_fragment", &BINDINGS),
                Program::draw("normal_vertex", "normal_fragment", &MESH_PASS),
            ],
        )
    }

    fn structs() -> Vec<Layout> {
        vec![layout!(
            "ImageParams",
            ImageParams,
            [
                kernel,
                depth_threshold,
                normal_threshold,
                step_px,
                depth_scaled
            ]
        )]
    }

    fn params(cx: &FrameContext<'_>) -> Option<(ImageParams, bool)> {
        let Technique::ImageSpace(p) = cx.style.technique else {
            return None;
        };
        let threshold = |t: f32| if t.is_finite() { t.max(0.0) } else { 0.0 };
        let params = ImageParams {
            kernel: match p.operator {
                Operator::Sobel => 0,
                Operator::Prewitt => 1,
                Operator::Scharr => 2,
                Operator::Roberts => 3,
            },
            depth_threshold: threshold(p.depth_threshold),
            normal_threshold: threshold(p.normal_threshold),
            step_px: (0.5 * cx.style.width()).max(1.0),
            depth_scaled: u32::from(cx.style.depth_scaled),
        };
        // The normal buffer is drawn every frame (§5.4's first pass).
        Some((params, true))
    }
}
