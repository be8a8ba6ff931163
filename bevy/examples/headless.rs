//! Renders a mesh's edges with the plugin in a Bevy app without a window and writes a PNG:
//!
//!     cargo run --release -p chamfer-bevy --example headless -- [MESH_OR_ASSET] [OUT.png]
//!
//! The mesh (default: the bundled fandisk) is baked into a temporary asset folder first (a
//! `.chamfer` file is used as it is); the camera orbits it like `chamfer render`'s default view.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use anyhow::{anyhow, bail};
use bevy::asset::AssetPlugin;
use bevy::camera::RenderTarget;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::render_resource::{TextureFormat, TextureUsages};
use bevy::render::view::Tonemapping;
use bevy::window::{ExitCondition, WindowPlugin};
use chamfer_bevy::{ChamferAsset, ChamferEdges, ChamferPlugin};
use chamfer_preprocess::{BakeOptions, bake_file};
use chamfer_runtime::render::{Camera as EdgeCamera, Orbit};

const SIZE: [u32; 2] = [800, 600];

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args_os().skip(1);
    let input = args.next().map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/meshes/fandisk.obj"),
        PathBuf::from,
    );
    let output = args
        .next()
        .map_or_else(|| PathBuf::from("chamfer-bevy.png"), PathBuf::from);
    let folder = tempfile::tempdir()?;
    let bytes = if input.extension().is_some_and(|e| e == "chamfer") {
        std::fs::read(&input).map_err(|e| anyhow!("{}: cannot read: {e}", input.display()))?
    } else {
        bake_file(&input, &BakeOptions::DEFAULT)?
            .asset
            .encode_to_vec()
    };
    let asset = chamfer_runtime::asset::Asset::decode(&bytes)
        .map_err(|e| anyhow!("{}: not a valid .chamfer asset: {e}", input.display()))?;
    std::fs::write(folder.path().join("part.chamfer"), &bytes)?;

    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(AssetPlugin {
                file_path: folder.path().to_string_lossy().into_owned(),
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            }),
    )
    .add_plugins(ChamferPlugin);
    app.finish();
    app.cleanup();

    let world = app.world_mut();
    let mut target =
        Image::new_target_texture(SIZE[0], SIZE[1], TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let image = world.resource_mut::<Assets<Image>>().add(target);
    let server = world.resource::<AssetServer>().clone();
    let part: Handle<ChamferAsset> = server.load("part.chamfer");
    let material = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial::from(Color::srgb(0.82, 0.82, 0.8)));
    world.spawn((
        Mesh3d(server.load("part.chamfer#mesh")),
        MeshMaterial3d(material),
        ChamferEdges::new(part),
    ));
    world.spawn((
        // Untonemapped at the camera's default exposure: a lamp, not daylight, keeps the faces grey.
        DirectionalLight {
            illuminance: 1500.0,
            ..default()
        },
        Transform::from_xyz(0.4, 0.8, 0.45).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    world.insert_resource(GlobalAmbientLight {
        brightness: 400.0,
        ..default()
    });
    let bounds = [asset.header.bounds_min, asset.header.bounds_max];
    let orbit = Orbit {
        azimuth: -120.0,
        elevation: 30.0,
        ..Orbit::default()
    };
    let camera = EdgeCamera::orbit(bounds, &orbit, SIZE);
    let eye = camera.model_view.inverse().w_axis.truncate().to_array();
    let [lo, hi] = bounds.map(Vec3::from_array);
    world.spawn((
        Camera3d::default(),
        RenderTarget::Image(image.clone().into()),
        Tonemapping::None,
        Transform::from_translation(Vec3::from_array(eye)).looking_at((lo + hi) * 0.5, Vec3::Y),
        Projection::Perspective(PerspectiveProjection {
            fov: orbit.fov_y.to_radians(),
            ..default()
        }),
    ));

    for _ in 0..300 {
        app.update();
        if !app.world().resource::<Assets<ChamferAsset>>().is_empty() {
            break;
        }
    }
    for _ in 0..4 {
        app.update();
    }
    let received: Arc<Mutex<Option<Vec<u8>>>> = Arc::default();
    let sink = Arc::clone(&received);
    app.world_mut()
        .spawn(Readback::texture(image))
        .observe(move |event: On<ReadbackComplete>| {
            if let Ok(mut slot) = sink.lock() {
                slot.get_or_insert_with(|| event.data.clone());
            }
        });
    for _ in 0..20 {
        app.update();
        let Some(padded) = received.lock().ok().and_then(|r| r.clone()) else {
            continue;
        };
        let row = 4 * SIZE[0] as usize;
        let stride = row.next_multiple_of(256);
        let rgba: Vec<u8> = (0..SIZE[1] as usize)
            .flat_map(|y| padded[y * stride..y * stride + row].iter().copied())
            .collect();
        let file = std::io::BufWriter::new(std::fs::File::create(&output)?);
        let mut encoder = png::Encoder::new(file, SIZE[0], SIZE[1]);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.write_header()?.write_image_data(&rgba)?;
        println!("{} -> {}", input.display(), output.display());
        return Ok(());
    }
    bail!("the frame was never read back")
}
