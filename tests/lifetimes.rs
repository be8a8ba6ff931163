//! The renderer's split by lifetime, checked on the GPU: pipelines are compiled once per target and
//! shared by every asset; a frame whose encoder is dropped leaves nothing that poisons later frames.

use chamfer_runtime::render::{
    Camera, EdgeColors, EdgeRenderer, EdgeStyle, GpuAsset, MeshRenderer, MeshStyle, Orbit,
    Pipelines,
};
use chamfer_tests::{bake_fixture, draw_frame, gpu};

const BACKGROUND: [f64; 4] = [0.0, 0.0, 1.0, 1.0];

fn camera_for(asset: &chamfer_runtime::asset::Asset, size: u32) -> Camera {
    Camera::orbit(
        [asset.header.bounds_min, asset.header.bounds_max],
        &Orbit::default(),
        [size, size],
    )
}

#[test]
fn two_assets_share_one_set_of_pipelines() {
    let gpu = gpu();
    let target = gpu.target(96, 96, 1).expect("target");
    // A cache of its own, so the count is this test's.
    let pipelines = Pipelines::new(&gpu.device, &target.formats()).expect("pipelines");
    assert_eq!(
        pipelines.compiled_pipelines(),
        0,
        "nothing compiles before use"
    );
    let draw = |fixture: &str| {
        let asset = bake_fixture(fixture);
        let camera = camera_for(&asset, 96);
        let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
        let mut mesh = MeshRenderer::new(&pipelines, &uploaded).expect("mesh");
        let mut edges = EdgeRenderer::new(&pipelines, &uploaded);
        draw_frame(
            &target,
            &camera,
            BACKGROUND,
            Some((&mut mesh, &MeshStyle::default())),
            Some((&mut edges, &EdgeStyle::default())),
        )
    };
    draw("shapes/cube.obj");
    let after_first = pipelines.compiled_pipelines();
    assert!(
        after_first >= 3,
        "mesh, classify, edges at least: {after_first}"
    );
    draw("meshes/fandisk.obj");
    draw("shapes/cylinder-16.obj");
    assert_eq!(
        pipelines.compiled_pipelines(),
        after_first,
        "a second and third asset compiled pipelines again"
    );
    // The count is real: another cache for the same target compiles its own.
    let other = Pipelines::new(&gpu.device, &target.formats()).expect("pipelines");
    assert!(!other.same_cache(&pipelines));
    let asset = bake_fixture("shapes/cube.obj");
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    MeshRenderer::new(&other, &uploaded).expect("mesh");
    assert_eq!(other.compiled_pipelines(), 1);
}

#[test]
fn a_dropped_frame_does_not_poison_later_frames() {
    let gpu = gpu();
    let target = gpu.target(160, 160, 1).expect("target");
    let pipelines = chamfer_tests::pipelines(target.formats());
    let asset = bake_fixture("meshes/fandisk.obj");
    let camera = camera_for(&asset, 160);
    let uploaded = GpuAsset::new(&gpu.device, &asset).expect("upload");
    let mut mesh = MeshRenderer::new(&pipelines, &uploaded).expect("mesh");
    // One colour for every class: where edges of different classes cross on screen, the one drawn
    // last wins, and the compacted list's order follows the GPU's scheduling.
    let style = EdgeStyle {
        width_px: 4.0,
        colors: EdgeColors::all([1.0, 0.0, 0.0, 1.0]),
        ..EdgeStyle::default()
    };

    // The renderer's very first frame is recorded into an encoder that is never submitted.
    let mut dropped = EdgeRenderer::new(&pipelines, &uploaded);
    {
        let mut encoder = gpu.encoder();
        dropped
            .prepare(&gpu.queue, &mut encoder, &camera, &style)
            .expect("prepare");
        drop(encoder);
    }
    let after_drop = draw_frame(
        &target,
        &camera,
        BACKGROUND,
        Some((&mut mesh, &MeshStyle::default())),
        Some((&mut dropped, &style)),
    );
    let mut fresh = EdgeRenderer::new(&pipelines, &uploaded);
    let expected = draw_frame(
        &target,
        &camera,
        BACKGROUND,
        Some((&mut mesh, &MeshStyle::default())),
        Some((&mut fresh, &style)),
    );
    assert!(
        after_drop == expected,
        "a dropped frame changed the next one"
    );
    let counts = dropped
        .read_counts(&gpu.device, &gpu.queue)
        .expect("counts");
    assert!(counts.edges > 100, "{counts:?}");
}
