//! The technique layer's extension point, proved from outside the core's lists: a technique that no
//! list names (not [`Technique`], not [`module`](super::module)) is declared here with the crate's
//! [`Pull`] skeleton alone, passes the same CPU checks of its WGSL, and draws; and a frame kept from
//! one technique of a module does not skip the checks another technique of it needs.

use super::pulled::{Draws, Pull, PullModule};
use super::{Drawn, FrameContext};
use crate::asset::Asset;
use crate::render::bindings::{Bindings, FRAME, PARAMS};
use crate::render::gpu_asset::VERTEX_LAYOUTS;
use crate::render::layout::{Layout, layout};
use crate::render::modules::tests::{binding_mismatches, parse, struct_mismatches};
use crate::render::modules::{Program, Shader};
use crate::render::pipelines::Raster;
use crate::render::{
    Camera, EdgeStyle, GpuAsset, HardwareContour, Instance, Offscreen, Orbit, Pipelines,
    RenderError, SceneRenderer, Target, Technique,
};

/// The technique's own WGSL: the mesh filled in one colour over its own depth.
const SILHOUETTE_WGSL: &str = "
struct SilhouetteParams {
    color: vec4<f32>,
}

@group(0) @binding(15) var<uniform> params: SilhouetteParams;

@vertex
fn silhouette_vertex(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return frame.mvp * vec4<f32>(position, 1.0);
}

@fragment
fn silhouette_fragment() -> @location(0) vec4<f32> {
    return params.color;
}
";

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct SilhouetteParams {
    color: [f32; 4],
}

/// A flat-colour silhouette, declared outside the core's lists.
#[derive(Debug)]
struct Silhouette;

static SILHOUETTE: PullModule<Silhouette> = PullModule::new();

impl Pull for Silhouette {
    // Not offered to the front ends (it is in no list); a preset only names it.
    const PRESETS: &'static [crate::render::Preset] = &[crate::render::Preset {
        name: "silhouette",
        summary: "a flat-colour silhouette (test)",
        technique: crate::render::Technique::Joined,
    }];
    type Params = SilhouetteParams;
    type Draw = ();
    const BINDINGS: &'static Bindings = &Bindings::draw("silhouette", &[FRAME, PARAMS]);
    const SHADER: (&'static str, &'static [&'static str]) = (
        "silhouette (test)",
        &[
            chamfer_shaders::COMMON,
            chamfer_shaders::SECTION,
            chamfer_shaders::FRAME,
            SILHOUETTE_WGSL,
        ],
    );
    const DRAWS: Draws = Draws::Mesh;
    const PROGRAMS: &'static [Program] = &[Program::draw(
        "silhouette_vertex",
        "silhouette_fragment",
        Self::BINDINGS,
    )];
    const STRUCTS: &'static [Layout] = &[layout!("SilhouetteParams", SilhouetteParams, [color])];

    fn raster(target: &Target) -> Raster<'static> {
        Raster {
            buffers: &VERTEX_LAYOUTS,
            ..Raster::over_mesh(target)
        }
    }

    fn params(cx: &FrameContext<'_>, _: &Drawn<'_>) -> Option<SilhouetteParams> {
        Some(SilhouetteParams {
            color: cx.style.colors.contour,
        })
    }
}

fn gpu() -> &'static Offscreen {
    static GPU: std::sync::OnceLock<Offscreen> = std::sync::OnceLock::new();
    GPU.get_or_init(|| {
        Offscreen::new().unwrap_or_else(|e| panic!("these tests need a GPU adapter: {e}"))
    })
}

/// The cube of the fixtures (baked by an earlier format; decoded as any file is).
fn cube() -> Asset {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../fixtures/assets/cube-v3.chamfer"
    );
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    Asset::decode(&bytes).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn a_technique_outside_the_core_lists_is_checked_like_the_others() {
    let target = Target::new(
        wgpu::TextureFormat::Rgba8Unorm,
        Some(wgpu::TextureFormat::Depth32Float),
        1,
    );
    let shader = Silhouette::shader();
    assert!(binding_mismatches(&shader, &target).is_empty());
    let (module, _) = parse(shader.label, &shader.source);
    assert!(
        struct_mismatches(shader.label, &module, Silhouette::STRUCTS)
            .0
            .is_empty()
    );
    // Control: the check sees its parameters at a binding its layout does not declare.
    let moved = Shader {
        source: shader.source.replace("@binding(15)", "@binding(14)"),
        ..shader
    };
    assert!(!binding_mismatches(&moved, &target).is_empty());
}

#[test]
fn a_technique_outside_the_core_lists_draws() {
    let gpu = gpu();
    let (width, height) = (96, 80);
    let target = gpu.target(width, height, 1).expect("a target");
    let pipelines = Pipelines::new(&gpu.device, &target.formats()).expect("pipelines");
    let asset = GpuAsset::new(&gpu.device, &cube()).expect("upload");
    let camera = Camera::orbit(asset.bounds(), &Orbit::default(), [width, height]);
    let mut style = EdgeStyle::default();
    style.colors.contour = [1.0, 0.0, 0.0, 1.0];
    let mut renderer = SceneRenderer::new(&pipelines);
    let mut encoder = gpu.encoder();
    let prepared = renderer
        .prepare_module(
            &SILHOUETTE,
            &gpu.queue,
            &mut encoder,
            &camera,
            &[Instance::new(&asset)],
            &style,
        )
        .expect("the technique prepares");
    {
        let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
        prepared.render(&mut pass);
    }
    gpu.submit(encoder).expect("submit");
    let image = target.read(gpu).expect("read back");
    let red = |p: [u8; 4]| p[0] > 200 && p[1] < 50 && p[2] < 50;
    let filled = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .filter(|&(x, y)| red(image.pixel(x, y)))
        .count();
    // The cube framed by the default orbit covers a good share of the picture, and its middle is
    // inside the silhouette while the corners are background.
    let share = filled as f64 / f64::from(width * height);
    assert!((0.1..0.9).contains(&share), "{share}");
    assert!(red(image.pixel(width / 2, height / 2)));
    assert_eq!(image.pixel(0, 0), [255, 255, 255, 255]);
}

#[test]
fn a_frame_kept_from_another_technique_still_checks_the_target() {
    let gpu = gpu();
    let asset = GpuAsset::new(&gpu.device, &cube()).expect("upload");
    let camera = Camera::orbit(asset.bounds(), &Orbit::default(), [32, 32]);
    // A target without a stencil aspect.
    let target = Target::new(
        wgpu::TextureFormat::Rgba8Unorm,
        Some(wgpu::TextureFormat::Depth32Float),
        1,
    );
    let pipelines = Pipelines::new(&gpu.device, &target).expect("pipelines");
    let style = |method| EdgeStyle {
        technique: Technique::Hardware(method),
        ..EdgeStyle::default()
    };
    let instances = [Instance::new(&asset)];
    let prepare = |renderer: &mut SceneRenderer, method| {
        let mut encoder = gpu.encoder();
        renderer
            .prepare(
                &gpu.queue,
                &mut encoder,
                &camera,
                &instances,
                &style(method),
            )
            .map(|_| ())
    };
    let lacks_stencil = |result: Result<(), RenderError>| {
        matches!(
            result,
            Err(RenderError::TargetLacks {
                technique: "stencil-shifted",
                needs: "a depth format with a stencil aspect"
            })
        )
    };
    // A fresh renderer refuses the stencil method...
    assert!(lacks_stencil(prepare(
        &mut SceneRenderer::new(&pipelines),
        HardwareContour::StencilShifted
    )));
    // ...and so does one whose frame was made for another method of the same module.
    let mut renderer = SceneRenderer::new(&pipelines);
    assert!(prepare(&mut renderer, HardwareContour::BackFaces).is_ok());
    assert!(lacks_stencil(prepare(
        &mut renderer,
        HardwareContour::StencilShifted
    )));
    // The refusal leaves the renderer usable.
    assert!(prepare(&mut renderer, HardwareContour::BackFaces).is_ok());
}
