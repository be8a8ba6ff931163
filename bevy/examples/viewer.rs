//! A window showing a mesh's edges drawn by the plugin over Bevy's own shading:
//!
//!     cargo run --release -p chamfer-bevy --features viewer --example viewer -- \
//!         [MESH_OR_ASSET] [--technique NAME] [--highlight] [--screenshot OUT.png]
//!
//! The mesh (default: the bundled fandisk; `.obj`, `.glb`, `.ply`, `.stl`, `.3mf` or a baked
//! `.chamfer`) is baked in the process with ridges rounded, so the highlight has strips to shade.
//! Drag to orbit, scroll to zoom; Space / Backspace cycle the techniques, H toggles the chamfer
//! highlight (lit by the scene's directional light), Escape quits. The window's title names the
//! technique. `--screenshot` saves the window's 60th frame and quits.
//!
//! Without the `viewer` feature (winit) the example builds, so CI checks it, but opens no window.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{anyhow, bail};
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::prelude::*;
use bevy::render::render_resource::TextureFormat;
use bevy::render::view::Tonemapping;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use chamfer_bevy::{
    BakeSettings, ChamferAsset, ChamferEdges, ChamferPlugin, EdgeStyle, Highlight, PbrMaterial,
    Shading, Technique, bake_to_asset, render_mesh,
};
use chamfer_runtime::asset::Asset as EdgeAsset;

/// What the command line asks for.
#[derive(Resource)]
struct Options {
    style: EdgeStyle,
    screenshot: Option<PathBuf>,
}

fn main() -> anyhow::Result<()> {
    if !cfg!(feature = "viewer") {
        bail!("built without a window: run with `--features viewer`");
    }
    let mut input = None;
    let mut options = Options {
        style: EdgeStyle::default(),
        screenshot: None,
    };
    let mut args = std::env::args_os().skip(1);
    while let Some(arg) = args.next() {
        match arg.to_str() {
            Some("--technique") => {
                let name = args
                    .next()
                    .and_then(|n| n.into_string().ok())
                    .unwrap_or_default();
                options.style.technique = Technique::from_name(&name).ok_or_else(|| {
                    anyhow!(
                        "no technique '{name}'; one of {}",
                        Technique::names().join(", ")
                    )
                })?;
            }
            Some("--highlight") => options.style.highlight = Some(pbr_highlight()),
            Some("--screenshot") => {
                let path = args
                    .next()
                    .ok_or_else(|| anyhow!("--screenshot needs a file"))?;
                options.screenshot = Some(PathBuf::from(path));
            }
            _ => input = Some(PathBuf::from(arg)),
        }
    }
    let input = input.unwrap_or_else(|| {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/meshes/fandisk.obj")
    });
    let asset = load(&input)?;
    App::new()
        .add_plugins(DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window {
                title: title(&options.style),
                ..default()
            }),
            ..default()
        }))
        .add_plugins(ChamferPlugin)
        .insert_resource(Part(Arc::new(asset)))
        .insert_resource(options)
        .add_systems(Startup, setup)
        .add_systems(Update, (orbit, switch, screenshot))
        .run();
    Ok(())
}

fn pbr_highlight() -> Highlight {
    Highlight {
        shading: Shading::Pbr(PbrMaterial::default()),
        ..Highlight::default()
    }
}

/// The baked asset given on the command line, or baked from the mesh given.
fn load(input: &Path) -> anyhow::Result<EdgeAsset> {
    let bytes =
        std::fs::read(input).map_err(|e| anyhow!("{}: cannot read: {e}", input.display()))?;
    let bytes = if input.extension().is_some_and(|e| e == "chamfer") {
        bytes
    } else {
        let settings = BakeSettings {
            radius_rel: Some(0.004),
            ..BakeSettings::default()
        };
        bake_to_asset(input, &bytes, &settings)?
    };
    EdgeAsset::decode(&bytes)
        .map_err(|e| anyhow!("{}: not a valid .chamfer asset: {e}", input.display()))
}

#[derive(Resource)]
struct Part(Arc<EdgeAsset>);

/// The orbit camera: where it looks, from how far, at which angles (radians).
#[derive(Component)]
struct Orbit {
    center: Vec3,
    distance: f32,
    yaw: f32,
    pitch: f32,
}

impl Orbit {
    fn transform(&self) -> Transform {
        let rotation = Quat::from_euler(EulerRot::YXZ, self.yaw, -self.pitch, 0.0);
        Transform::from_translation(self.center + rotation * Vec3::new(0.0, 0.0, self.distance))
            .looking_at(self.center, Vec3::Y)
    }
}

fn setup(
    mut commands: Commands,
    part: Res<Part>,
    options: Res<Options>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut assets: ResMut<Assets<ChamferAsset>>,
) {
    let asset = Arc::clone(&part.0);
    let [lo, hi] = [asset.header.bounds_min, asset.header.bounds_max].map(Vec3::from_array);
    let mesh = meshes.add(render_mesh(&asset));
    let handle = assets.add(ChamferAsset {
        asset,
        mesh: mesh.clone(),
    });
    commands.spawn((
        Mesh3d(mesh),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.8, 0.8, 0.78),
            perceptual_roughness: 0.5,
            ..default()
        })),
        ChamferEdges::new(handle).with_style(options.style),
    ));
    // A lamp rather than daylight at the camera's default exposure keeps the faces grey.
    commands.spawn((
        DirectionalLight {
            illuminance: 1500.0,
            ..default()
        },
        Transform::from_xyz(0.4, 0.8, 0.45).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 400.0,
        ..default()
    });
    let orbit = Orbit {
        center: (lo + hi) * 0.5,
        distance: (hi - lo).length() * 1.2,
        yaw: -0.9,
        pitch: 0.5,
    };
    // A tone mapper without lookup tables (the library leaves Bevy's `tonemapping_luts` off).
    commands.spawn((
        Camera3d::default(),
        Tonemapping::AcesFitted,
        orbit.transform(),
        orbit,
    ));
}

fn orbit(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut cameras: Query<(&mut Orbit, &mut Transform)>,
) {
    for (mut orbit, mut transform) in &mut cameras {
        if buttons.pressed(MouseButton::Left) {
            orbit.yaw -= motion.delta.x * 0.005;
            orbit.pitch = (orbit.pitch + motion.delta.y * 0.005).clamp(-1.5, 1.5);
        }
        orbit.distance *= (1.0 - scroll.delta.y * 0.1).clamp(0.5, 2.0);
        *transform = orbit.transform();
    }
}

fn switch(
    keys: Res<ButtonInput<KeyCode>>,
    mut edges: Query<&mut ChamferEdges>,
    mut windows: Query<&mut Window>,
    mut exit: MessageWriter<AppExit>,
) {
    if keys.just_pressed(KeyCode::Escape) {
        exit.write(AppExit::Success);
    }
    let step = if keys.just_pressed(KeyCode::Space) {
        1
    } else if keys.just_pressed(KeyCode::Backspace) {
        -1
    } else {
        0
    };
    let toggle = keys.just_pressed(KeyCode::KeyH);
    if step == 0 && !toggle {
        return;
    }
    let all = Technique::all();
    for mut edges in &mut edges {
        let style = &mut edges.style;
        if step != 0 {
            let at = all.iter().position(|t| *t == style.technique).unwrap_or(0);
            let next = (at as isize + step).rem_euclid(all.len() as isize) as usize;
            style.technique = all[next];
        }
        if toggle {
            style.highlight = match style.highlight {
                Some(_) => None,
                None => Some(pbr_highlight()),
            };
        }
        for mut window in &mut windows {
            window.title = title(style);
        }
    }
}

fn title(style: &EdgeStyle) -> String {
    let lit = if style.highlight.is_some() {
        ", highlight on"
    } else {
        ""
    };
    format!(
        "chamfer-bevy: {}{lit} (Space/Backspace: technique, H: highlight, drag: orbit)",
        style.technique.name()
    )
}

/// With `--screenshot`: saves the 60th frame as a PNG, then quits.
fn screenshot(mut commands: Commands, options: Res<Options>, mut frames: Local<u32>) {
    let Some(path) = options.screenshot.clone() else {
        return;
    };
    *frames += 1;
    if *frames != 60 {
        return;
    }
    commands.spawn(Screenshot::primary_window()).observe(
        move |captured: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| match write_png(
            &path,
            &captured.image,
        ) {
            Ok(()) => {
                println!("{}", path.display());
                exit.write(AppExit::Success);
            }
            Err(e) => {
                eprintln!("{}: {e}", path.display());
                exit.write(AppExit::error());
            }
        },
    );
}

fn write_png(path: &Path, image: &Image) -> anyhow::Result<()> {
    let size = image.texture_descriptor.size;
    let mut rgba = image
        .data
        .clone()
        .ok_or_else(|| anyhow!("an empty screenshot"))?;
    if matches!(
        image.texture_descriptor.format,
        TextureFormat::Bgra8Unorm | TextureFormat::Bgra8UnormSrgb
    ) {
        rgba.chunks_exact_mut(4).for_each(|p| p.swap(0, 2));
    }
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, size.width, size.height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.write_header()?.write_image_data(&rgba)?;
    Ok(())
}
