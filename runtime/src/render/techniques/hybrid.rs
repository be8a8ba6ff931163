//! [`Technique::Hybrid`](crate::render::Technique::Hybrid): seed 004's hybrid shader for edges and
//! ambient shading (`shaders/hybrid.wgsl`), a post-process of the application's depth, multiplied
//! over its colour in [`Prepared::finish`](crate::render::Prepared::finish). With `object_only` the
//! frame first draws this asset white into a mask of its own (§3.1), whose Laplacian outlines it.

use super::FrameContext;
use super::post::{self, Blend, DEPTH, MESH_PASS, PARAMS, POST, PostModule, PostProcess};
use crate::render::bindings::{Binding, Bindings, Kind};
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::{HybridDepth, Target, Technique};

pub(crate) static MODULE: PostModule<Hybrid> = PostModule::new();

/// The name and summary of the hybrid shader with parameters of the caller's own (not offered as a
/// preset: it has no default parameters of its own).
static OWN_PARAMETERS: crate::render::Preset = crate::render::Preset {
    name: "hybrid",
    summary: "hybrid depth shader, own parameters (seed 004)",
    technique: crate::render::Technique::Hybrid(crate::render::HybridDepth::EDGES),
};

/// `HybridParams` in `shaders/hybrid.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct HybridParams {
    step_px: f32,
    bleach: f32,
    contrast: f32,
    brightness: f32,
    range: f32,
    object_only: u32,
}

#[derive(Debug)]
pub(crate) struct Hybrid;

/// The object mask of `object_only`.
const MASK: Binding = Binding::new(17, "mask", Kind::Texture);
const BINDINGS: Bindings = Bindings::draw("hybrid", &[POST, PARAMS, DEPTH, MASK]);

fn finite(value: f32, fallback: f32) -> f32 {
    if value.is_finite() { value } else { fallback }
}

impl PostProcess for Hybrid {
    const PRESETS: &'static [crate::render::Preset] = &[
        crate::render::Preset {
            name: "hybrid-edges",
            summary: "hybrid depth shader, edge setting: post-process of the depth alone (seed 004)",
            technique: crate::render::Technique::Hybrid(crate::render::HybridDepth::EDGES),
        },
        crate::render::Preset {
            name: "hybrid-ambient",
            summary: "hybrid depth shader, ambient-shading setting (seed 004)",
            technique: crate::render::Technique::Hybrid(crate::render::HybridDepth::AMBIENT),
        },
        crate::render::Preset {
            name: "hybrid-both",
            summary: "hybrid depth shader, edges and ambient shading at once (seed 004)",
            technique: crate::render::Technique::Hybrid(crate::render::HybridDepth::BOTH),
        },
    ];

    /// A preset's parameters, or [`OWN_PARAMETERS`] for any others.
    fn preset(technique: &crate::render::Technique) -> &'static crate::render::Preset {
        Self::PRESETS
            .iter()
            .find(|p| p.technique == *technique)
            .unwrap_or(&OWN_PARAMETERS)
    }

    type Params = HybridParams;
    const BINDINGS: &'static Bindings = &BINDINGS;
    const OWN: Binding = MASK;
    const OWN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;
    const OWN_DEPTH: bool = false;
    const BLEND: Blend = Blend::Multiply;

    fn shader(target: &Target) -> Shader {
        use chamfer_shaders as wgsl;
        Shader::new(
            "hybrid.wgsl",
            &[post::depth_source(target), wgsl::POST, wgsl::HYBRID],
            vec![
                Program::draw("post_vertex", "hybrid_fragment", &BINDINGS),
                Program::draw("mask_vertex", "mask_fragment", &MESH_PASS),
            ],
        )
    }

    fn structs() -> Vec<Layout> {
        vec![layout!(
            "HybridParams",
            HybridParams,
            [step_px, bleach, contrast, brightness, range, object_only]
        )]
    }

    fn params(cx: &FrameContext<'_>) -> Option<(HybridParams, bool)> {
        let Technique::Hybrid(p) = cx.style.technique else {
            return None;
        };
        let defaults = HybridDepth::EDGES;
        let share = if p.range.is_finite() && p.range > 0.0 {
            p.range
        } else {
            defaults.range
        };
        let params = HybridParams {
            step_px: finite(p.step_px, defaults.step_px).clamp(1.0, 64.0),
            bleach: finite(p.bleach, defaults.bleach).clamp(1e-4, 1.0),
            contrast: finite(p.contrast, defaults.contrast).clamp(0.0, 1000.0),
            brightness: finite(p.brightness, 0.0).clamp(0.0, 2.0),
            range: share * post::far_distance(cx),
            object_only: u32::from(p.object_only),
        };
        Some((params, p.object_only))
    }
}
