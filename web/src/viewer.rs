//! The page's canvas: an asset drawn on WebGPU by the runtime's renderers, as `chamfer render`
//! draws it. Frames are drawn into an [`OffscreenTarget`] (the command's own attachments, so the
//! post-process techniques read its depth and colour) and copied to the canvas, configured RGBA8:
//! the canvas shows the bytes the command writes to its PNG.

use std::sync::{Arc, Mutex};

use chamfer_runtime::asset::Asset;
use chamfer_runtime::render::{
    CutRenderer, GpuAsset, Instance, MeshRenderer, OffscreenTarget, Pipelines, PosedAsset,
    SceneRenderer, Target,
};
use wasm_bindgen::prelude::*;

use crate::settings::ViewSettings;

/// The canvas's format: the offscreen targets' own, so frames copy to it byte for byte.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// An asset drawn into a `<canvas>`.
#[wasm_bindgen]
pub struct Viewer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    surface: wgpu::Surface<'static>,
    adapter: String,
    /// The first error the device reported since the last frame (its handler cannot return one).
    device_error: Arc<Mutex<Option<String>>>,
    view: ViewSettings,
    frame: Option<Frame>,
    shown: Option<Shown>,
}

/// What depends on the canvas's size and the sample count.
struct Frame {
    size: [u32; 2],
    target: OffscreenTarget,
    mesh: MeshRenderer,
    cut: CutRenderer,
    edges: SceneRenderer,
    pipelines: Pipelines,
}

/// The asset on screen: decoded, and uploaded with what the techniques drawn so far need; posed
/// when the view asks for a pose (made at the first such frame, for this upload and frame).
struct Shown {
    asset: Asset,
    gpu: GpuAsset,
    posed: Option<PosedAsset>,
}

/// Opens WebGPU on `canvas`. Fails with the reason when the browser has no WebGPU adapter.
#[wasm_bindgen(js_name = createViewer)]
pub async fn create_viewer(canvas: web_sys::HtmlCanvasElement) -> Result<Viewer, JsError> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: wgpu::Backends::BROWSER_WEBGPU,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    let surface = instance
        .create_surface(wgpu::SurfaceTarget::Canvas(canvas))
        .map_err(|e| JsError::new(&format!("the canvas cannot show WebGPU: {e}")))?;
    let adapter = instance
        .request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        })
        .await
        .map_err(|e| JsError::new(&format!("this browser offers no WebGPU adapter: {e}")))?;
    let (device, queue) = adapter
        .request_device(&wgpu::DeviceDescriptor {
            label: Some("chamfer web"),
            required_features: adapter.features() & wgpu::Features::DEPTH32FLOAT_STENCIL8,
            required_limits: adapter.limits(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        })
        .await
        .map_err(|e| JsError::new(&format!("the WebGPU device was refused: {e}")))?;
    let device_error = Arc::new(Mutex::new(None));
    let sink = Arc::clone(&device_error);
    device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
        if let Ok(mut slot) = sink.lock() {
            slot.get_or_insert_with(|| error.to_string());
        }
    }));
    let info = adapter.get_info();
    let adapter = format!(
        "{} ({:?}, {:?}; depth {:?})",
        info.name,
        info.backend,
        info.device_type,
        OffscreenTarget::depth_format(&device)
    );
    Ok(Viewer {
        device,
        queue,
        surface,
        adapter,
        device_error,
        view: ViewSettings::default(),
        frame: None,
        shown: None,
    })
}

#[wasm_bindgen]
impl Viewer {
    /// The adapter's name, backend and kind.
    #[wasm_bindgen(getter)]
    pub fn adapter(&self) -> String {
        self.adapter.clone()
    }

    /// Shows the `.chamfer` file `bytes` (named `name` in errors).
    pub fn show(&mut self, name: &str, bytes: &[u8]) -> Result<(), JsError> {
        let asset = Asset::decode(bytes)
            .map_err(|e| JsError::new(&format!("{name}: not a valid .chamfer asset: {e}")))?;
        let technique = self.view.technique().map_err(|e| JsError::new(&e))?;
        let gpu = GpuAsset::for_techniques(&self.device, &asset, &[technique])
            .map_err(|e| JsError::new(&format!("{name}: cannot upload: {e}")))?;
        self.shown = Some(Shown {
            asset,
            gpu,
            posed: None,
        });
        Ok(())
    }

    /// The shown asset's animations as JSON, `[{"name", "duration"}]` (empty for a still asset
    /// or none shown): the page's animation panel lists them.
    pub fn animations(&self) -> String {
        let animations = self.shown.as_ref().map_or(Vec::new(), |shown| {
            shown
                .asset
                .motion
                .rig
                .animations
                .iter()
                .map(|a| serde_json::json!({"name": a.name, "duration": a.duration()}))
                .collect()
        });
        serde_json::Value::from(animations).to_string()
    }

    /// Changes the view (JSON, [`ViewSettings`]); refused settings leave it as it was.
    #[wasm_bindgen(js_name = setView)]
    pub fn set_view(&mut self, json: &str) -> Result<(), JsError> {
        let view = ViewSettings::from_json(json).map_err(|e| JsError::new(&e))?;
        if view.look.samples != self.view.look.samples {
            self.frame = None;
        }
        self.view = view;
        Ok(())
    }

    /// The camera's distance from the model's centre in the last view (what a wheel zooms from).
    pub fn distance(&self, width: u32, height: u32) -> f32 {
        let Some(shown) = &self.shown else {
            return 1.0;
        };
        let bounds = shown.gpu.bounds();
        let camera = self.view.camera(bounds, [width.max(1), height.max(1)]);
        let [lo, hi] = bounds.map(glam::Vec3::from);
        (camera.eye().truncate() - (lo + hi) * 0.5).length()
    }

    /// The asset's bounds, `[xmin, ymin, zmin, xmax, ymax, zmax]` (the section slider's range);
    /// empty when nothing is shown.
    pub fn bounds(&self) -> Vec<f32> {
        self.shown
            .as_ref()
            .map(|shown| shown.gpu.bounds().concat())
            .unwrap_or_default()
    }

    /// Draws a frame of `width` × `height` pixels (the canvas's size) and shows it.
    pub fn draw(&mut self, width: u32, height: u32) -> Result<(), JsError> {
        let size = [width.max(1), height.max(1)];
        if self.frame.as_ref().is_none_or(|f| f.size != size) {
            self.frame = Some(self.new_frame(size)?);
            // A pose is made for a frame's pipelines.
            if let Some(shown) = &mut self.shown {
                shown.posed = None;
            }
        }
        let (Some(frame), Some(shown)) = (&mut self.frame, &mut self.shown) else {
            return Ok(());
        };
        let fail = |what: &str, e: &dyn std::fmt::Display| JsError::new(&format!("{what}: {e}"));
        // A technique that needs more than the upload has (derived on the CPU) uploads again.
        let needs = self.view.technique().map_err(|e| JsError::new(&e))?.needs();
        if !shown.gpu.extras().contains(needs) {
            shown.gpu =
                GpuAsset::with_extras(&self.device, &shown.asset, shown.gpu.extras() | needs)
                    .map_err(|e| fail("cannot upload the asset", &e))?;
            shown.posed = None;
        }
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("chamfer web frame"),
            });
        // The pose the view asks for, as `chamfer render` takes it from the same keys.
        let moving = (!shown.asset.motion.rig.is_empty()).then_some(&shown.asset.motion.rig);
        let pose = self
            .view
            .animation
            .pose_of(moving)
            .map_err(|e| JsError::new(&e.to_string()))?;
        let drawn_asset = match pose {
            Some(pose) => {
                let posed = match &mut shown.posed {
                    Some(posed) => posed,
                    slot => slot.insert(
                        PosedAsset::new(&frame.pipelines, &shown.gpu)
                            .map_err(|e| fail("cannot pose the asset", &e))?,
                    ),
                };
                posed
                    .prepare(&self.queue, &mut encoder, &pose)
                    .map_err(|e| fail("cannot pose the asset", &e))?;
                posed.asset()
            }
            None => &shown.gpu,
        };
        let drawn = [Instance::new(drawn_asset)];
        let bounds = drawn_asset.bounds();
        let camera = self.view.camera(bounds, size);
        let faces = self.view.faces_style();
        if let Some(faces) = &faces {
            frame
                .mesh
                .prepare_scene(&self.queue, &camera, &drawn, faces);
        }
        let cut = self.view.cut_style();
        let cutting = !cut.section.is_empty();
        if cutting {
            frame.cut.prepare(&self.queue, &camera, &drawn, &cut);
        }
        let style = self.view.edge_style().map_err(|e| JsError::new(&e))?;
        let prepared = frame
            .edges
            .prepare(&self.queue, &mut encoder, &camera, &drawn, &style)
            .map_err(|e| fail("cannot draw the edges", &e))?;
        {
            let background = self.view.background.map(f64::from);
            let mut pass = frame.target.begin_pass(&mut encoder, background);
            if faces.is_some() {
                frame.mesh.render(&mut pass);
            }
            if cutting {
                frame.cut.render(&mut pass);
            }
            prepared.render(&mut pass);
        }
        prepared
            .finish(&mut encoder, &frame.target.views())
            .map_err(|e| fail("cannot finish the frame", &e))?;
        let output = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(texture)
            | wgpu::CurrentSurfaceTexture::Suboptimal(texture) => texture,
            other => {
                self.frame = None;
                return Err(JsError::new(&format!(
                    "the canvas gave no texture to draw into ({})",
                    surface_problem(&other)
                )));
            }
        };
        encoder.copy_texture_to_texture(
            frame.target.color_texture().as_image_copy(),
            output.texture.as_image_copy(),
            wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        self.queue.present(output);
        match self.device_error.lock().ok().and_then(|mut e| e.take()) {
            Some(error) => Err(JsError::new(&format!("WebGPU refused the frame: {error}"))),
            None => Ok(()),
        }
    }
}

impl Viewer {
    fn new_frame(&self, size: [u32; 2]) -> Result<Frame, JsError> {
        let fail = |what: &str, e: &dyn std::fmt::Display| JsError::new(&format!("{what}: {e}"));
        self.surface.configure(
            &self.device,
            &wgpu::SurfaceConfiguration {
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_DST,
                format: FORMAT,
                width: size[0],
                height: size[1],
                present_mode: wgpu::PresentMode::Fifo,
                desired_maximum_frame_latency: 2,
                alpha_mode: wgpu::CompositeAlphaMode::Opaque,
                view_formats: vec![],
                color_space: wgpu::SurfaceColorSpace::Auto,
            },
        );
        let formats = Target::new(
            FORMAT,
            Some(OffscreenTarget::depth_format(&self.device)),
            self.view.look.samples as u32,
        );
        let target = OffscreenTarget::new(&self.device, size[0], size[1], formats)
            .map_err(|e| fail("cannot make the frame's attachments", &e))?;
        let pipelines = Pipelines::new(&self.device, &formats)
            .map_err(|e| fail("cannot build the pipelines", &e))?;
        let mesh = MeshRenderer::for_scenes(&pipelines)
            .map_err(|e| fail("cannot build the mesh renderer", &e))?;
        let cut = CutRenderer::new(&pipelines)
            .map_err(|e| fail("cannot build the cut-face renderer", &e))?;
        let edges = SceneRenderer::new(&pipelines);
        Ok(Frame {
            size,
            target,
            mesh,
            cut,
            edges,
            pipelines,
        })
    }
}

fn surface_problem(status: &wgpu::CurrentSurfaceTexture) -> &'static str {
    match status {
        wgpu::CurrentSurfaceTexture::Timeout => "timed out",
        wgpu::CurrentSurfaceTexture::Occluded => "the page is hidden",
        wgpu::CurrentSurfaceTexture::Outdated => "its size changed",
        wgpu::CurrentSurfaceTexture::Lost => "the surface was lost",
        _ => "the device refused it",
    }
}
