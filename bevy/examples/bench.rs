//! The cost of the plugin in a Bevy scene (BENCHMARKS.md, "Bevy"): 100 entities, bunnies and
//! fandisks, drawn by a 1280×720 camera with 4× MSAA into an image, without edges, with edges
//! (the joined technique) and with edges and the PBR highlight lit by the scene's light.
//!
//!     cargo run --release -p chamfer-bevy --example bench -- [FRAMES]
//!
//! Pipelined rendering is off and every frame waits for the GPU, so a frame's time is its whole
//! cost; the modes alternate (mesh, edges, highlight, twice) so drift on a shared machine hits all.

use std::path::Path;
use std::time::{Duration, Instant};

use bevy::asset::AssetPlugin;
use bevy::camera::RenderTarget;
use bevy::prelude::*;
use bevy::render::pipelined_rendering::PipelinedRenderingPlugin;
use bevy::render::render_resource::{TextureFormat, TextureUsages};
use bevy::render::renderer::RenderDevice;
use bevy::render::view::Tonemapping;
use bevy::render::{RenderApp, RenderPlugin};
use bevy::window::{ExitCondition, WindowPlugin};
use chamfer_bevy::{
    BakeSettings, ChamferAsset, ChamferEdges, ChamferPlugin, ChamferTimings, EdgeStyle, Highlight,
    PbrMaterial, Shading, bake_to_asset, render_mesh,
};
use chamfer_runtime::asset::Asset as EdgeAsset;

const SIZE: [u32; 2] = [1280, 720];
const SIDE: usize = 10;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Mesh,
    Edges,
    Highlight,
}

fn main() -> anyhow::Result<()> {
    let frames: usize = std::env::args().nth(1).map_or(Ok(20), |n| n.parse())?;
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/meshes");
    let settings = BakeSettings {
        radius_rel: Some(0.004),
        ..BakeSettings::default()
    };
    let mut parts = Vec::new();
    for name in ["stanford-bunny.obj", "fandisk.obj"] {
        let path = fixtures.join(name);
        let bytes = std::fs::read(&path)?;
        parts.push(EdgeAsset::decode(&bake_to_asset(
            &path, &bytes, &settings,
        )?)?);
    }

    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            })
            .set(AssetPlugin::default())
            .disable::<PipelinedRenderingPlugin>(),
    )
    .add_plugins(ChamferPlugin);
    app.finish();
    app.cleanup();

    let world = app.world_mut();
    let mut target =
        Image::new_target_texture(SIZE[0], SIZE[1], TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let image = world.resource_mut::<Assets<Image>>().add(target);
    let material = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial::from(Color::srgb(0.82, 0.82, 0.8)));
    let mut kinds = Vec::new();
    let mut triangles = 0;
    for part in parts {
        let [lo, hi] = [part.header.bounds_min, part.header.bounds_max].map(Vec3::from_array);
        // Each part scaled to a unit diagonal and centred on its place.
        let scale = 1.0 / (hi - lo).length();
        let center = (lo + hi) * 0.5;
        triangles += part.mesh_indices.len() / 3;
        let mesh = world.resource_mut::<Assets<Mesh>>().add(render_mesh(&part));
        let asset = world
            .resource_mut::<Assets<ChamferAsset>>()
            .add(ChamferAsset {
                asset: part.into(),
                mesh: mesh.clone(),
            });
        kinds.push((mesh, asset, scale, center));
    }
    let mut entities = Vec::new();
    for i in 0..SIDE * SIDE {
        let (mesh, asset, scale, center) = &kinds[i % kinds.len()];
        let place = Vec3::new((i % SIDE) as f32, 0.0, (i / SIDE) as f32) - Vec3::splat(4.5);
        let rotation = Quat::from_rotation_y((i as f32 * 37.0).to_radians());
        let transform = Transform::from_translation(place * Vec3::new(1.0, 0.0, 1.0))
            .with_rotation(rotation)
            .with_scale(Vec3::splat(*scale))
            * Transform::from_translation(-*center);
        let entity = world
            .spawn((
                Mesh3d(mesh.clone()),
                MeshMaterial3d(material.clone()),
                transform,
            ))
            .id();
        entities.push((entity, asset.clone()));
    }
    world.spawn((
        DirectionalLight {
            illuminance: 1500.0,
            ..default()
        },
        Transform::from_xyz(0.4, 0.8, 0.45).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.spawn((
        Camera3d::default(),
        RenderTarget::Image(image.into()),
        Tonemapping::None,
        Transform::from_xyz(0.0, 7.0, 9.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));

    println!(
        "{} entities ({triangles} triangles for one bunny and one fandisk), {}x{}, MSAA 4, {frames} frames per run",
        SIDE * SIDE,
        SIZE[0],
        SIZE[1]
    );
    let mut results: Vec<(Mode, Vec<Duration>, Vec<ChamferTimings>)> = Vec::new();
    for round in 0..2 {
        for mode in [Mode::Mesh, Mode::Edges, Mode::Highlight] {
            let world = app.world_mut();
            for (entity, asset) in &entities {
                let mut entity = world.entity_mut(*entity);
                match mode {
                    Mode::Mesh => {
                        entity.remove::<ChamferEdges>();
                    }
                    Mode::Edges | Mode::Highlight => {
                        let highlight = (mode == Mode::Highlight).then(|| Highlight {
                            shading: Shading::Pbr(PbrMaterial::default()),
                            ..Highlight::default()
                        });
                        entity.insert(ChamferEdges::new(asset.clone()).with_style(EdgeStyle {
                            highlight,
                            ..EdgeStyle::default()
                        }));
                    }
                }
            }
            for _ in 0..5 {
                frame(&mut app);
            }
            let mut times = Vec::new();
            let mut plugin = Vec::new();
            for _ in 0..frames {
                times.push(frame(&mut app));
                plugin.push(*app.sub_app(RenderApp).world().resource::<ChamferTimings>());
            }
            println!(
                "round {round} {mode:?}: median {:.1} ms",
                ms(median(&mut times.clone()))
            );
            results.push((mode, times, plugin));
        }
    }
    let of = |mode: Mode| -> (Vec<Duration>, Vec<ChamferTimings>) {
        results.iter().filter(|(m, _, _)| *m == mode).fold(
            (Vec::new(), Vec::new()),
            |(mut t, mut p), (_, times, plugin)| {
                t.extend(times);
                p.extend(plugin);
                (t, p)
            },
        )
    };
    let (mut mesh, _) = of(Mode::Mesh);
    let mesh_ms = ms(median(&mut mesh));
    println!("| mode | frame (median) | × mesh only | plugin CPU: extract | prepare | draw |");
    println!("|---|---|---|---|---|---|");
    println!("| mesh only | {mesh_ms:.1} ms | 1.00 | | | |");
    for (mode, label) in [
        (Mode::Edges, "edges (joined)"),
        (Mode::Highlight, "edges + PBR highlight"),
    ] {
        let (mut times, plugin) = of(mode);
        let frame_ms = ms(median(&mut times));
        let part = |f: fn(&ChamferTimings) -> Duration| {
            ms(median(&mut plugin.iter().map(f).collect::<Vec<_>>()))
        };
        println!(
            "| {label} | {frame_ms:.1} ms | {:.2} | {:.3} ms | {:.3} ms | {:.3} ms |",
            frame_ms / mesh_ms,
            part(|t| t.extract),
            part(|t| t.prepare),
            part(|t| t.draw),
        );
    }
    Ok(())
}

/// One frame, waited for on the GPU.
fn frame(app: &mut App) -> Duration {
    let start = Instant::now();
    app.update();
    let device = app.world().resource::<RenderDevice>().wgpu_device().clone();
    let _ = device.poll(wgpu::PollType::wait_indefinitely());
    start.elapsed()
}

fn median(values: &mut [Duration]) -> Duration {
    values.sort();
    values.get(values.len() / 2).copied().unwrap_or_default()
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
