//! [`Technique::Hybrid`](crate::render::Technique::Hybrid): seed 004's hybrid shader for edges and
//! ambient shading (`shaders/hybrid.wgsl`), a post-process of the application's depth, multiplied
//! over its colour in [`Prepared::finish`](crate::render::Prepared::finish). With `object_only` the
//! frame first draws this asset white into a mask of its own (§3.1), whose Laplacian outlines it.

use super::FrameContext;
use super::post::{self, Blend, DEPTH, MESH_PASS, PARAMS, POST, PostModule, PostProcess};
use crate::render::bindings::{Binding, Bindings, Kind};
use crate::render::layout::{Layout, layout};
use crate::render::modules::{Program, Shader};
use crate::render::{Target, Technique};
use crate::schema::FINITE;

crate::schema! {
    /// Parameters of the hybrid depth shader (seed 004, §3.3–3.4, §4): `chamfer render
    /// --hybrid-step` and the others, the page's technique panel. The default is
    /// [`HybridDepth::EDGES`]; each `hybrid-*` preset has its own.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct HybridDepth {
        /// `r`: the neighbours' distance in pixels (1 to 10 in the paper): thin lines at 1, broad
        /// shading at 5 or more.
        step: f32 = 2.0, { group: "hybrid", value: "PX", range: Some((1.0, 64.0)), example: 3.0,
            conflicts: [], requires: [] },
        /// `L`, the bleach factor of eq. 5: low values lighten the dark halos of large depth
        /// differences, 1 keeps them.
        bleach: f32 = 1.0, { group: "hybrid", value: "L", range: Some((1e-4, 1.0)), example: 0.6,
            conflicts: [], requires: [] },
        /// The exponent the averaged shade is raised to.
        contrast: f32 = 100.0, { group: "hybrid", value: "EXP", range: Some((0.0, 1000.0)),
            example: 12.0, conflicts: [], requires: [] },
        /// Inverted brightness: 0 leaves flat regions white, higher values darken everything.
        brightness: f32 = 0.0, { group: "hybrid", value: "B", range: Some((0.0, 2.0)),
            example: 0.4, conflicts: [], requires: [] },
        /// What a depth difference is divided by, as a share of the far plane's distance (the
        /// paper advises 0.8; an infinite far plane counts as twice the model's far side): smaller
        /// values bring out smaller depth differences.
        range: f32 = 0.8, { group: "hybrid", value: "SHARE", range: Some((1e-6, FINITE)),
            example: 0.05, conflicts: [], requires: [] },
        /// Apply to this asset's pixels and outline only (the Laplacian mask steps of §3.1), not
        /// to the whole scene.
        object_only: bool = false, { group: "hybrid", value: "", range: None, example: true,
            conflicts: [], requires: [] },
    }
}

impl HybridDepth {
    /// Edge detection (§4, Fig. 3 right: a small step, bleach 1, brightness 0), with the range the
    /// paper advises.
    pub const EDGES: Self = Self {
        step: 2.0,
        bleach: 1.0,
        contrast: 100.0,
        brightness: 0.0,
        range: 0.8,
        object_only: false,
    };
    /// Ambient shading (§4, Fig. 5: a wide step, low bleach), with a shorter range so that the
    /// gentle depth changes of corners count.
    pub const AMBIENT: Self = Self {
        step: 10.0,
        bleach: 0.3,
        contrast: 30.0,
        brightness: 0.0,
        range: 0.2,
        object_only: false,
    };
    /// Both at once (§4, Fig. 6): a step between the two, bleach 1 so silhouettes stay dark, and a
    /// range between the two.
    pub const BOTH: Self = Self {
        step: 5.0,
        bleach: 1.0,
        contrast: 30.0,
        brightness: 0.0,
        range: 0.3,
        object_only: false,
    };
}

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
            &[
                post::depth_source(target),
                wgsl::POST,
                wgsl::SECTION,
                wgsl::HYBRID,
            ],
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
            step_px: finite(p.step, defaults.step).clamp(1.0, 64.0),
            bleach: finite(p.bleach, defaults.bleach).clamp(1e-4, 1.0),
            contrast: finite(p.contrast, defaults.contrast).clamp(0.0, 1000.0),
            brightness: finite(p.brightness, 0.0).clamp(0.0, 2.0),
            range: share * post::far_distance(cx),
            object_only: u32::from(p.object_only),
        };
        Some((params, p.object_only))
    }
}
