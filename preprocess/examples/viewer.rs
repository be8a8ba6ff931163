//! An interactive window on an asset, a mesh (baked on the fly) or a scene file (`chamfer bake
//! --scene`): `cargo run --release --example viewer -- INPUT`.
//!
//! Drag to orbit, scroll to zoom. Keys: 1 contours, 2 ridges, 3 valleys, 4 boundaries, 5 marked
//! (toggle each class); + / - edge width; C cycles the cap method; D depth-scaled width; E edges on
//! or off; O orthographic; T cycles the edge technique (its name is in the title); H cycles the chamfer
//! highlight under a light circling the model: off, seed 000's Blinn model, glTF's metallic-roughness; X explodes a scene (each instance moved
//! away from the centre, every frame's transforms given anew); S cycles a section plane across x,
//! y, z or none, and a right-button drag moves it along its axis (the cut capped and outlined);
//! V cycles the display mode: shaded, shaded with hidden edges dashed, hidden-line, X-ray,
//! wireframe (the display schema's modes, as `chamfer render --hidden-line` and the others); A
//! plays or pauses an animated asset's animations (each asset its first, looping; a
//! `PosedAsset` posed every frame, on by default); Esc quits. Meshes are baked with a chamfer radius of 0.4 % of their diagonal on ridges. It is also the smallest example of hosting the renderers in an
//! application's own wgpu setup: the window, device and frame belong to this file.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use chamfer_runtime::asset::Asset;
use chamfer_runtime::highlight::ggx::PbrMaterial;
use chamfer_runtime::highlight::strip::Material;
use chamfer_runtime::render::{
    Camera, CapMethod, CutRenderer, CutStyle, DisplaySettings, EdgeClasses, EdgeStyle, FrameViews,
    GpuAsset, Highlight, Instance, Light, MeshLight, MeshRenderer, MeshStyle, Orbit, Pipelines,
    PosedAsset, SceneRenderer, Shading, Target, Technique,
};
use chamfer_runtime::rig::Pose;
use chamfer_runtime::section::{ClipPlanes, Plane};
use glam::{Mat4, Vec3};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

// With stencil, for the stencil techniques; every format with depth can be sampled after the pass.
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth24PlusStencil8;

fn main() -> anyhow::Result<()> {
    let input: PathBuf = std::env::args_os()
        .nth(1)
        .context(
            "usage: viewer INPUT (a .chamfer asset, a .scene.json scene or an OBJ, glTF/GLB or PLY mesh)",
        )?
        .into();
    let name = input.to_string_lossy().to_ascii_lowercase();
    let limits = chamfer_preprocess::Limits::DEFAULT;
    let (assets, instances) = if name.ends_with(".scene.json") {
        let scene = chamfer_preprocess::scene::read_scene(&input, &limits)?;
        (scene.assets, scene.instances)
    } else if name.ends_with(".chamfer") {
        let bytes = chamfer_preprocess::load::read(&input, &limits)?;
        let asset = Asset::decode(&bytes).with_context(|| format!("{}", input.display()))?;
        (vec![asset], vec![(0, Mat4::IDENTITY)])
    } else {
        let options = chamfer_preprocess::BakeOptions::DEFAULT
            .with_radius(chamfer_preprocess::Radius::Relative(0.004));
        let asset = chamfer_preprocess::bake_file(&input, &options)?.asset;
        (vec![asset], vec![(0, Mat4::IDENTITY)])
    };
    let event_loop = EventLoop::new()?;
    let mut viewer = Viewer {
        assets,
        instances,
        explode: false,
        title: input.display().to_string(),
        window: None,
        orbit: Orbit::default(),
        style: EdgeStyle::default(),
        draw_edges: true,
        highlight: Lit::Off,
        started: std::time::Instant::now(),
        dragging: false,
        section: None,
        moving_section: false,
        display: 0,
        playing: true,
        cursor: None,
        error: None,
    };
    event_loop.run_app(&mut viewer)?;
    viewer.error.map_or(Ok(()), Err)
}

/// How chamfer edges are lit (key H).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Lit {
    Off,
    Blinn,
    Pbr,
}

struct Viewer {
    assets: Vec<Asset>,
    /// Each instance's asset and model-to-world transform, as the input gave them.
    instances: Vec<(usize, Mat4)>,
    explode: bool,
    title: String,
    window: Option<Gpu>,
    orbit: Orbit,
    style: EdgeStyle,
    draw_edges: bool,
    highlight: Lit,
    started: std::time::Instant,
    dragging: bool,
    /// The section plane: across which axis, and where along the scene's box (0 to 1).
    section: Option<(usize, f32)>,
    moving_section: bool,
    /// The display mode: an index into [`display_modes`].
    display: usize,
    /// Animated assets play their first animation (key A).
    playing: bool,
    cursor: Option<(f64, f64)>,
    error: Option<anyhow::Error>,
}

/// The display modes V cycles through, by name.
fn display_modes() -> [(&'static str, DisplaySettings); 5] {
    let hidden = DisplaySettings {
        hidden_edges: true,
        ..DisplaySettings::default()
    };
    [
        ("shaded", DisplaySettings::default()),
        ("shaded, hidden edges", hidden),
        (
            "hidden-line",
            DisplaySettings {
                hidden_line: true,
                ..hidden
            },
        ),
        (
            "x-ray",
            DisplaySettings {
                xray: Some(0.3),
                ..DisplaySettings::default()
            },
        ),
        (
            "wireframe",
            DisplaySettings {
                wireframe: true,
                ..DisplaySettings::default()
            },
        ),
    ]
}

/// Everything that belongs to the application, not to the renderers.
struct Gpu {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    depth: wgpu::TextureView,
    depth_sampled: wgpu::TextureView,
    assets: Vec<GpuAsset>,
    /// Per asset with an animation, its pose.
    posed: Vec<Option<PosedAsset>>,
    mesh: MeshRenderer,
    edges: SceneRenderer,
    cut: CutRenderer,
}

impl Gpu {
    fn new(event_loop: &ActiveEventLoop, assets: &[Asset]) -> anyhow::Result<Self> {
        let window = Arc::new(
            event_loop.create_window(Window::default_attributes().with_title("chamfer viewer"))?,
        );
        let instance = wgpu::Instance::new(
            wgpu::InstanceDescriptor::new_with_display_handle(Box::new(
                event_loop.owned_display_handle(),
            ))
            .with_env(),
        );
        let surface = instance.create_surface(window.clone())?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        }))?;
        let (device, queue) =
            pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("viewer"),
                required_features: wgpu::Features::empty(),
                required_limits: adapter.limits(),
                experimental_features: wgpu::ExperimentalFeatures::disabled(),
                memory_hints: wgpu::MemoryHints::Performance,
                trace: wgpu::Trace::Off,
            }))?;
        let size = window.inner_size();
        let config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .context("the surface does not work with this adapter")?;
        surface.configure(&device, &config);
        let target = Target::new(config.format, Some(DEPTH), 1);
        let pipelines = Pipelines::new(&device, &target)?;
        let uploaded = assets
            .iter()
            .map(|asset| GpuAsset::for_techniques(&device, asset, &Technique::all()))
            .collect::<Result<Vec<_>, _>>()?;
        let posed = uploaded
            .iter()
            .map(|asset| match asset.rig() {
                Some(rig) if !rig.animations.is_empty() => {
                    PosedAsset::new(&pipelines, asset).map(Some)
                }
                _ => Ok(None),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mesh = MeshRenderer::for_scenes(&pipelines)?;
        let edges = SceneRenderer::new(&pipelines);
        let cut = CutRenderer::new(&pipelines)?;
        let (depth, depth_sampled) = depth_views(&device, &config);
        Ok(Self {
            window,
            surface,
            device,
            queue,
            config,
            depth,
            depth_sampled,
            assets: uploaded,
            posed,
            mesh,
            edges,
            cut,
        })
    }

    fn resize(&mut self, width: u32, height: u32) {
        self.config.width = width.max(1);
        self.config.height = height.max(1);
        self.surface.configure(&self.device, &self.config);
        (self.depth, self.depth_sampled) = depth_views(&self.device, &self.config);
    }

    /// What the camera frames: the scene as placed, so that it stays put while the scene explodes.
    fn bounds(&self, placed: &[(usize, Mat4)]) -> [[f32; 3]; 2] {
        let still: Vec<&GpuAsset> = self.assets.iter().collect();
        Instance::scene_bounds(&instances(&still, placed, false)).unwrap_or_default()
    }

    fn draw(
        &mut self,
        placed: &[(usize, Mat4)],
        explode: bool,
        orbit: &Orbit,
        style: &EdgeStyle,
        mesh_style: Option<&MeshStyle>,
        draw_edges: bool,
        section: Option<(usize, f32)>,
        time: Option<f32>,
    ) -> anyhow::Result<()> {
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame)
            | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                return Ok(());
            }
            _ => return Ok(()),
        };
        let view = frame.texture.create_view(&Default::default());
        // The camera frames the scene as placed, so it stays put while the scene explodes.
        let bounds = self.bounds(placed);
        let camera = Camera::orbit(bounds, orbit, [self.config.width, self.config.height]);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        // Playing: each animated asset at its first animation's time, looping; paused, at rest.
        for posed in self.posed.iter_mut().flatten() {
            let rig = posed.rig();
            let duration = rig.animations[0].duration().max(1e-3);
            let pose = match time {
                Some(t) => Pose::sampled(rig, 0, t % duration),
                None => Some(Pose::rest(rig)),
            };
            if let Some(pose) = pose {
                posed.prepare(&self.queue, &mut encoder, &pose)?;
            }
        }
        let shown: Vec<&GpuAsset> = self
            .assets
            .iter()
            .zip(&self.posed)
            .map(|(still, posed)| posed.as_ref().map_or(still, PosedAsset::asset))
            .collect();
        let instances = instances(&shown, placed, explode);
        let cut = CutStyle {
            section: section_plane(bounds, section),
            ..CutStyle::default()
        };
        let style = &EdgeStyle {
            section: cut.section,
            ..*style
        };
        let mesh_style = mesh_style.map(|style| MeshStyle {
            section: cut.section,
            ..*style
        });
        if let Some(mesh_style) = &mesh_style {
            self.mesh
                .prepare_scene(&self.queue, &camera, &instances, mesh_style);
        }
        self.cut.prepare(&self.queue, &camera, &instances, &cut);
        let prepared = if draw_edges {
            Some(
                self.edges
                    .prepare(&self.queue, &mut encoder, &camera, &instances, style)?,
            )
        } else {
            None
        };
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("viewer"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::WHITE),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0),
                        store: wgpu::StoreOp::Store,
                    }),
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if mesh_style.is_some() {
                self.mesh.render(&mut pass);
            }
            self.cut.render(&mut pass);
            if let Some(prepared) = &prepared {
                prepared.render(&mut pass);
            }
        }
        if let Some(prepared) = &prepared {
            let views = FrameViews {
                color: &view,
                depth: &self.depth_sampled,
            };
            prepared.finish(&mut encoder, &views)?;
        }
        self.queue.submit([encoder.finish()]);
        self.window.pre_present_notify();
        self.queue.present(frame);
        Ok(())
    }
}

/// The section plane across `axis` at `at` (0 to 1) of `bounds`, its normal along the axis (the
/// part beyond it is cut away); none without a section.
fn section_plane(bounds: [[f32; 3]; 2], section: Option<(usize, f32)>) -> ClipPlanes {
    let Some((axis, at)) = section else {
        return ClipPlanes::NONE;
    };
    let [lo, hi] = bounds;
    let mut normal = [0.0; 3];
    normal[axis] = 1.0;
    let offset = f64::from(lo[axis] + at * (hi[axis] - lo[axis]));
    ClipPlanes::new(&[Plane { normal, offset }])
}

/// The instances to draw this frame; exploded: each moved away from the scene's centre to twice
/// its distance.
fn instances<'a>(
    assets: &[&'a GpuAsset],
    placed: &[(usize, Mat4)],
    explode: bool,
) -> Vec<Instance<'a>> {
    let instances: Vec<Instance<'a>> = placed
        .iter()
        .map(|&(asset, transform)| Instance::new(assets[asset]).with_transform(transform))
        .collect();
    let Some(bounds) = Instance::scene_bounds(&instances).filter(|_| explode) else {
        return instances;
    };
    let centre = |[lo, hi]: [[f32; 3]; 2]| (Vec3::from(lo) + Vec3::from(hi)) * 0.5;
    let scene_centre = centre(bounds);
    instances
        .into_iter()
        .map(|instance| {
            let away = centre(instance.world_bounds()) - scene_centre;
            instance.with_transform(Mat4::from_translation(away) * instance.transform)
        })
        .collect()
}

/// The depth attachment, and a depth-only view of it for the techniques that read it after the pass.
fn depth_views(
    device: &wgpu::Device,
    config: &wgpu::SurfaceConfiguration,
) -> (wgpu::TextureView, wgpu::TextureView) {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("viewer depth"),
        size: wgpu::Extent3d {
            width: config.width,
            height: config.height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: DEPTH,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let sampled = texture.create_view(&wgpu::TextureViewDescriptor {
        aspect: wgpu::TextureAspect::DepthOnly,
        ..Default::default()
    });
    (texture.create_view(&Default::default()), sampled)
}

/// Applies a key press; true if the picture changed.
fn apply_key(key: &Key, style: &mut EdgeStyle, orbit: &mut Orbit, draw_edges: &mut bool) -> bool {
    {
        let toggle = |classes: &mut EdgeClasses, class: EdgeClasses| {
            *classes = if classes.contains(class) {
                EdgeClasses(classes.0 & !class.0)
            } else {
                *classes | class
            };
        };
        match key {
            Key::Character(c) => match c.as_str() {
                "1" => toggle(&mut style.classes, EdgeClasses::CONTOUR),
                "2" => toggle(&mut style.classes, EdgeClasses::RIDGE),
                "3" => toggle(&mut style.classes, EdgeClasses::VALLEY),
                "4" => toggle(&mut style.classes, EdgeClasses::BOUNDARY),
                "5" => toggle(&mut style.classes, EdgeClasses::MARKED),
                "+" | "=" => style.width_px = (style.width_px * 1.25).min(64.0),
                "-" => style.width_px = (style.width_px / 1.25).max(0.5),
                "c" => {
                    style.caps = match style.caps {
                        CapMethod::NextIndex => CapMethod::CapBuffer,
                        CapMethod::CapBuffer => CapMethod::None,
                        CapMethod::None => CapMethod::NextIndex,
                    }
                }
                "d" => style.depth_scaled = !style.depth_scaled,
                "e" => *draw_edges = !*draw_edges,
                "o" => orbit.ortho = !orbit.ortho,
                "t" => {
                    let all = Technique::all();
                    let now = all
                        .iter()
                        .position(|t| t.name() == style.technique.name())
                        .unwrap_or(0);
                    style.technique = all[(now + 1) % all.len()];
                }
                _ => return false,
            },
            _ => return false,
        }
        true
    }
}

impl ApplicationHandler for Viewer {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        match Gpu::new(event_loop, &self.assets) {
            Ok(gpu) => {
                gpu.window
                    .set_title(&format!("chamfer viewer: {}", self.title));
                self.window = Some(gpu);
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(gpu) = self.window.as_mut() else {
            return;
        };
        let changed = match event {
            WindowEvent::CloseRequested => {
                event_loop.exit();
                false
            }
            WindowEvent::Resized(size) => {
                gpu.resize(size.width, size.height);
                true
            }
            WindowEvent::RedrawRequested => {
                let (style, mesh_style) = if self.highlight != Lit::Off {
                    // The light circles the model once every eight seconds, above it.
                    let angle = self.started.elapsed().as_secs_f32() * std::f32::consts::TAU / 8.0;
                    let light = Light::Directional([angle.cos(), 0.8, angle.sin()]);
                    let material = Material {
                        diffuse: 0.7,
                        specular: 0.5,
                        shininess: 32.0,
                    };
                    let pbr = PbrMaterial {
                        base_color: [0.62, 0.64, 0.68],
                        metallic: 0.0,
                        roughness: 0.35,
                    };
                    let (shading, intensity) = match self.highlight {
                        Lit::Pbr => (Shading::Pbr(pbr), std::f32::consts::PI),
                        _ => (Shading::Blinn(material), 1.0),
                    };
                    let highlight = Highlight {
                        light,
                        color: [intensity; 3],
                        shading,
                        ambient: 0.2,
                        k: None,
                        ..Highlight::default()
                    };
                    let mesh_style = MeshStyle {
                        color: [material.diffuse, material.diffuse, material.diffuse, 1.0],
                        light: MeshLight::Model(light),
                        light_color: [intensity; 3],
                        ambient: 0.2,
                        specular: material.specular,
                        shininess: material.shininess,
                        pbr: (self.highlight == Lit::Pbr).then_some(pbr),
                        ..MeshStyle::default()
                    };
                    (
                        EdgeStyle {
                            highlight: Some(highlight),
                            ..self.style
                        },
                        mesh_style,
                    )
                } else {
                    (self.style, MeshStyle::default())
                };
                let (mode, display) = display_modes()[self.display];
                // A technique without hidden edges draws the mode's faces and its visible edges.
                let style = EdgeStyle {
                    display: if style.technique.draws_hidden_edges() {
                        display.display()
                    } else {
                        Default::default()
                    },
                    ..style
                };
                let mesh_style = display.faces().mesh_style(mesh_style, [1.0; 4]);
                if let Err(e) = gpu.draw(
                    &self.instances,
                    self.explode,
                    &self.orbit,
                    &style,
                    mesh_style.as_ref(),
                    self.draw_edges,
                    self.section,
                    self.playing.then(|| self.started.elapsed().as_secs_f32()),
                ) {
                    self.error = Some(e);
                    event_loop.exit();
                }
                gpu.window.set_title(&format!(
                    "chamfer viewer: {} ({}, {mode})",
                    self.title,
                    style.technique.name()
                ));
                let animated = gpu.posed.iter().any(Option::is_some);
                if self.highlight != Lit::Off || (self.playing && animated) {
                    gpu.window.request_redraw();
                }
                false
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                self.dragging = state == ElementState::Pressed;
                false
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Right,
                ..
            } => {
                self.moving_section = state == ElementState::Pressed;
                false
            }
            WindowEvent::CursorMoved { position, .. }
                if self.moving_section && self.section.is_some() =>
            {
                let dy = self.cursor.map_or(0.0, |(_, y)| position.y - y);
                self.cursor = Some((position.x, position.y));
                if let Some((_, at)) = &mut self.section {
                    // Up moves the plane towards the axis' end: a window's height is the box.
                    *at = (*at - dy as f32 / gpu.config.height.max(1) as f32).clamp(0.0, 1.0);
                }
                true
            }
            WindowEvent::CursorMoved { position, .. } => {
                let moved = self
                    .cursor
                    .filter(|_| self.dragging)
                    .map(|(x, y)| (position.x - x, position.y - y));
                self.cursor = Some((position.x, position.y));
                if let Some((dx, dy)) = moved {
                    self.orbit.azimuth -= dx as f32 * 0.4;
                    self.orbit.elevation =
                        (self.orbit.elevation + dy as f32 * 0.4).clamp(-89.0, 89.0);
                }
                moved.is_some()
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                let fitted = self.orbit.distance.unwrap_or_else(|| {
                    let bounds = gpu.bounds(&self.instances);
                    let camera =
                        Camera::orbit(bounds, &self.orbit, [gpu.config.width, gpu.config.height]);
                    let [lo, hi] = bounds.map(Vec3::from);
                    camera.eye().truncate().distance((lo + hi) * 0.5)
                });
                self.orbit.distance = Some(fitted * 0.9f32.powf(steps));
                true
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                if event.logical_key == Key::Named(NamedKey::Escape) {
                    event_loop.exit();
                }
                if event.logical_key == Key::Character("h".into()) {
                    self.highlight = match self.highlight {
                        Lit::Off => Lit::Blinn,
                        Lit::Blinn => Lit::Pbr,
                        Lit::Pbr => Lit::Off,
                    };
                    true
                } else if event.logical_key == Key::Character("x".into()) {
                    self.explode = !self.explode;
                    true
                } else if event.logical_key == Key::Character("a".into()) {
                    self.playing = !self.playing;
                    true
                } else if event.logical_key == Key::Character("v".into()) {
                    self.display = (self.display + 1) % display_modes().len();
                    true
                } else if event.logical_key == Key::Character("s".into()) {
                    self.section = match self.section {
                        None => Some((0, 0.5)),
                        Some((axis, at)) if axis < 2 => Some((axis + 1, at)),
                        Some(_) => None,
                    };
                    true
                } else {
                    apply_key(
                        &event.logical_key,
                        &mut self.style,
                        &mut self.orbit,
                        &mut self.draw_edges,
                    )
                }
            }
            _ => false,
        };
        if changed {
            gpu.window.request_redraw();
        }
    }
}
