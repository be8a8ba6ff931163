//! Per frame: [`SceneRenderer`] draws any number of [`Instance`]s of any number of assets with the
//! technique its style names; [`EdgeRenderer`] is the one-asset case. [`SceneRenderer::prepare`]
//! hands back the [`Prepared`] frame that alone can draw it.
//!
//! The order of a frame is in the types: `prepare` records the frame's compute work into the encoder
//! it is given (so it happens before any pass that draws), and only the `Prepared` value it returns
//! can `render` into a pass or `finish` after it. A frame whose encoder is dropped unsubmitted leaves
//! nothing behind: every frame writes all it reads.
//!
//! Instances share everything but one uniform block each: the assets' sections and the pipelines
//! are never copied, and the per-frame lists are sized by the edges drawn, not by instances × edges.
//! An instance whose bounding box lies outside the view costs no edge work at all; each instance's
//! contours are found with the camera in its own model space, so any affine transform works,
//! non-uniform scales and mirrors included.

use std::sync::Arc;

use glam::{Mat4, Vec3};

use super::layout::MAX_INSTANCES;
use super::techniques::{self, Drawn, FrameContext, FrameOptions, Module, TechniqueFrame};
use super::{Camera, EdgeColors, EdgeStyle, GpuAsset, Light, Pipelines, RenderError, Technique};
use crate::highlight::environment::Environment;
use crate::section::ClipPlanes;

/// One drawn copy of an asset: where it is and, optionally, its own colours.
#[derive(Clone, Copy, Debug)]
pub struct Instance<'a> {
    /// The asset (its buffers are shared by all its instances).
    pub asset: &'a GpuAsset,
    /// Model to world: the scene camera's `model_view` takes world to view.
    pub transform: Mat4,
    /// This instance's class colours; `None`: the style's.
    pub colors: Option<EdgeColors>,
    /// The chamfer highlight's light for this instance, in its model space; `None`: the style's
    /// (`Highlight::light`, also in model space). It also replaces a mesh pass's
    /// `MeshLight::Model`. A scene light reaches differently turned instances from different
    /// model-space directions: give each its own and draw them together.
    pub light: Option<Light>,
    /// This instance's section planes in world space; `None`: the style's
    /// ([`EdgeStyle::section`], [`MeshStyle::section`](super::MeshStyle::section)).
    pub section: Option<ClipPlanes>,
    /// This instance's cut faces; `None`: the [`CutStyle`](super::CutStyle)'s.
    pub cap: Option<super::CapStyle>,
}

impl<'a> Instance<'a> {
    /// `asset` at the origin, in the style's colours.
    pub fn new(asset: &'a GpuAsset) -> Self {
        Self {
            asset,
            transform: Mat4::IDENTITY,
            colors: None,
            light: None,
            section: None,
            cap: None,
        }
    }

    /// The same instance with its own cut faces.
    pub fn with_cap(self, cap: super::CapStyle) -> Self {
        Self {
            cap: Some(cap),
            ..self
        }
    }

    /// The same instance cut by its own section planes (world space).
    pub fn with_section(self, section: ClipPlanes) -> Self {
        Self {
            section: Some(section),
            ..self
        }
    }

    /// This instance's section planes in its model space, given the style's (world space).
    pub fn model_section(&self, style: &ClipPlanes) -> ClipPlanes {
        self.section
            .as_ref()
            .unwrap_or(style)
            .to_model(self.transform)
    }

    /// The same instance at `transform`.
    pub fn with_transform(self, transform: Mat4) -> Self {
        Self { transform, ..self }
    }

    /// The same instance lit (by the highlight) with `light`, in its model space.
    pub fn with_light(self, light: Light) -> Self {
        Self {
            light: Some(light),
            ..self
        }
    }

    /// The same instance in `colors`.
    pub fn with_colors(self, colors: EdgeColors) -> Self {
        Self {
            colors: Some(colors),
            ..self
        }
    }

    /// The world-space box around the asset's bounds moved by the transform.
    pub fn world_bounds(&self) -> [[f32; 3]; 2] {
        let [lo, hi] = self.asset.bounds().map(Vec3::from);
        let mut world = [Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)];
        for k in 0..8 {
            let corner = Vec3::select(glam::BVec3::new(k & 1 == 0, k & 2 == 0, k & 4 == 0), lo, hi);
            let p = self.transform.transform_point3(corner);
            world = [world[0].min(p), world[1].max(p)];
        }
        world.map(|v| v.to_array())
    }

    /// The box around every instance's [`world_bounds`](Self::world_bounds), to frame a scene with
    /// [`Camera::orbit`]; `None` when there are none.
    pub fn scene_bounds(instances: &[Instance<'_>]) -> Option<[[f32; 3]; 2]> {
        instances.iter().map(Instance::world_bounds).reduce(|a, b| {
            [
                Vec3::from(a[0]).min(Vec3::from(b[0])).to_array(),
                Vec3::from(a[1]).max(Vec3::from(b[1])).to_array(),
            ]
        })
    }
}

/// What the last [`SceneRenderer::prepare`] did with its instances.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneStats {
    /// Instances given.
    pub instances: u32,
    /// Instances outside the view, skipped on the host before any edge work. The joined technique
    /// culls instances on the GPU instead (0 here; see [`DrawCounts::instances_in_view`]).
    pub culled: u32,
}

/// What the last computed frame drew, read back from the GPU (see [`SceneRenderer::read_counts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawCounts {
    /// Edges that passed classification.
    pub edges: u32,
    /// Caps the joins emitted.
    pub caps: u32,
    /// Edges the frame wanted to draw; more than `edges` when the lists were full (they grow for
    /// later frames).
    pub wanted: u32,
    /// Edge clusters the cull pass kept for classification, all instances together (0 with
    /// [`EdgeStyle::cluster_culling`] off).
    pub clusters_kept: u32,
    /// Instances the GPU found in view, for the techniques that cull instances there
    /// ([`Technique::Joined`]; 0 for the others, which cull on the host: see [`SceneStats`]).
    pub instances_in_view: u32,
}

/// The application's finished attachments, for the techniques that work after its pass
/// (post-processes): see [`Prepared::finish`].
#[derive(Clone, Copy, Debug)]
pub struct FrameViews<'a> {
    /// The single-sample colour the frame ends in (the resolve target under MSAA); drawn into.
    pub color: &'a wgpu::TextureView,
    /// The depth attachment of the pass (multisampled under MSAA), created with
    /// `TEXTURE_BINDING` usage and stored (`StoreOp::Store`); read.
    pub depth: &'a wgpu::TextureView,
}

/// Draws instances of assets with the pipelines of a [`Pipelines`] cache. It holds the per-frame
/// state of the technique in use (uniform blocks, lists); the assets' buffers are shared.
#[derive(Debug)]
pub struct SceneRenderer {
    pipelines: Pipelines,
    /// The frame state of the module in use (by its id).
    frame: Option<(std::any::TypeId, Box<dyn TechniqueFrame>)>,
    /// The technique of the last frame prepared.
    technique: Option<Technique>,
    first_slots: u64,
    stats: SceneStats,
    /// The highlight's image-based light, when one is set.
    environment: Option<Arc<Environment>>,
}

impl SceneRenderer {
    /// A renderer; allocates nothing until the first [`prepare`](Self::prepare), which sizes the
    /// state for the technique in use and the instances drawn.
    pub fn new(pipelines: &Pipelines) -> Self {
        Self::with_first_slots(pipelines, 0)
    }

    /// A renderer whose edge lists ([`Technique::Joined`]) start with `slots` slots (at least 64);
    /// by default they hold every edge of the first frame's instances up to 16 384, then a
    /// sixteenth of them. Either way they grow when a frame wants more: that frame drops what does not fit,
    /// and a later one (once the count is read back, without waiting) gets lists a quarter larger
    /// than it wanted.
    pub fn with_first_slots(pipelines: &Pipelines, slots: u64) -> Self {
        Self {
            pipelines: pipelines.clone(),
            frame: None,
            technique: None,
            first_slots: slots,
            stats: SceneStats::default(),
            environment: None,
        }
    }

    /// Lights physically based chamfer strips ([`Shading::Pbr`](super::Shading::Pbr)) by
    /// `environment` too (its directions in model space, as [`Light`](super::Light)'s), from the next
    /// `prepare` on; `None` removes it. Give the mesh pass the same
    /// ([`MeshRenderer::set_environment`](super::MeshRenderer::set_environment)).
    pub fn set_environment(&mut self, environment: Option<Arc<Environment>>) {
        self.environment = environment;
    }

    /// Sets this frame's camera, instances and style, and records the frame's compute work into
    /// `encoder` (submit it before, or with, the pass that draws). Returns the frame to draw.
    ///
    /// Fails if the style's technique needs what the target or an asset lacks, if a list does not
    /// fit the device, or past 262 143 instances in view (typed [`RenderError`]s; nothing is
    /// recorded then).
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        instances: &[Instance<'_>],
        style: &EdgeStyle,
    ) -> Result<Prepared<'_>, RenderError> {
        let module = techniques::module(&style.technique);
        self.prepare_module(module, queue, encoder, camera, instances, style)
    }

    /// [`prepare`](Self::prepare) with the technique of `module`: the one path every technique
    /// takes, and the extension point a technique outside [`Technique`]'s list uses.
    pub(crate) fn prepare_module(
        &mut self,
        module: &'static dyn Module,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        instances: &[Instance<'_>],
        style: &EdgeStyle,
    ) -> Result<Prepared<'_>, RenderError> {
        // What the technique needs of the target is checked every frame, whether its state is
        // made or kept: a frame kept from another technique of the module proves nothing.
        techniques::check_target(module, &style.technique, self.pipelines.target())?;
        let view_projection = camera.view_projection();
        let on_gpu = module.culls_on_gpu();
        let drawn: Vec<Drawn<'_>> = instances
            .iter()
            .filter(|i| on_gpu || in_view(view_projection * i.transform, i.asset.bounds()))
            .map(|i| (i, i.model_section(&style.section)))
            // An instance wholly cut away draws nothing.
            .filter(|(i, section)| {
                let [lo, hi] = i.asset.bounds();
                !section.against_box(lo, hi).0
            })
            .map(|(i, section)| Drawn {
                section,
                asset: i.asset,
                camera: Camera {
                    model_view: camera.model_view * i.transform,
                    ..*camera
                },
                colors: i.colors.unwrap_or(style.colors),
                light: i.light,
            })
            .collect();
        if drawn.len() > MAX_INSTANCES as usize - 1 {
            return Err(RenderError::Unsupported {
                technique: style.technique.name(),
                why: format!(
                    "{} instances in view; a frame numbers at most {}",
                    drawn.len(),
                    MAX_INSTANCES - 1
                ),
            });
        }
        self.stats = SceneStats {
            instances: instances.len() as u32,
            culled: (instances.len() - drawn.len()) as u32,
        };
        // A module's frame serves every technique of the module.
        if self.frame.as_ref().is_none_or(|(id, _)| *id != module.id()) {
            // Free the old technique's state before making the new one.
            self.frame = None;
            let options = FrameOptions {
                first_slots: self.first_slots,
            };
            self.frame = Some((module.id(), module.new_frame(&self.pipelines, &options)?));
        }
        let Some((_, frame)) = self.frame.as_mut() else {
            return Err(RenderError::Internal("the frame state was not made".into()));
        };
        self.technique = Some(style.technique);
        let cx = FrameContext {
            pipelines: &self.pipelines,
            queue,
            camera,
            style,
            instances: &drawn,
            environment: self.environment.as_ref(),
        };
        frame.prepare(&cx, encoder)?;
        Ok(Prepared { frame: &**frame })
    }

    /// What the last `prepare` did with its instances.
    pub fn stats(&self) -> SceneStats {
        self.stats
    }

    /// Reads back how many edges and caps the last submitted frame produced. Blocks until the GPU
    /// is idle: for statistics, tests and benchmarks, not for every frame.
    ///
    /// Fails with [`RenderError::Unsupported`] before any frame, or for techniques that do not
    /// count what they draw (they classify in the vertex shader, with nothing to read back).
    pub fn read_counts(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<DrawCounts, RenderError> {
        let (Some((_, frame)), Some(technique)) = (&self.frame, &self.technique) else {
            return Err(RenderError::Unsupported {
                technique: "SceneRenderer::read_counts",
                why: "no frame was prepared yet".into(),
            });
        };
        frame.read_counts(device, queue).unwrap_or_else(|| {
            Err(RenderError::Unsupported {
                technique: technique.name(),
                why: "it does not count its edges".into(),
            })
        })
    }

    /// GPU bytes of this renderer's per-frame state (the assets' buffers are counted by
    /// [`GpuAsset::gpu_bytes`]).
    pub fn gpu_bytes(&self) -> u64 {
        self.frame.as_ref().map_or(0, |(_, f)| f.gpu_bytes())
    }
}

/// True unless the box `bounds`, through `mvp`, lies wholly outside one plane of the clip volume.
fn in_view(mvp: Mat4, bounds: [[f32; 3]; 2]) -> bool {
    let [lo, hi] = bounds.map(Vec3::from);
    let corners: [glam::Vec4; 8] = std::array::from_fn(|i| {
        let p = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        mvp * p.extend(1.0)
    });
    let outside = |test: fn(glam::Vec4) -> bool| corners.iter().all(|&c| test(c));
    !(outside(|c| c.x < -c.w)
        || outside(|c| c.x > c.w)
        || outside(|c| c.y < -c.w)
        || outside(|c| c.y > c.w)
        || outside(|c| c.z < 0.0)
        || outside(|c| c.z > c.w))
}

/// Draws one [`GpuAsset`]'s edges: a [`SceneRenderer`] with the asset as its one instance. Create one
/// per asset you draw; the pipelines and the asset's buffers are shared.
#[derive(Debug)]
pub struct EdgeRenderer {
    scene: SceneRenderer,
    asset: GpuAsset,
}

impl EdgeRenderer {
    /// A renderer for `asset`; allocates nothing until the first [`prepare`](Self::prepare), which
    /// sizes the state for the technique in use.
    pub fn new(pipelines: &Pipelines, asset: &GpuAsset) -> Self {
        Self {
            scene: SceneRenderer::new(pipelines),
            asset: asset.clone(),
        }
    }

    /// See [`SceneRenderer::set_environment`].
    pub fn set_environment(&mut self, environment: Option<Arc<Environment>>) {
        self.scene.set_environment(environment);
    }

    /// Sets this frame's camera and style and records the frame's compute work into `encoder`
    /// (submit it before, or with, the pass that draws). Returns the frame to draw.
    ///
    /// Fails if the style's technique needs what the target or the asset lacks, or if a list does
    /// not fit the device (typed [`RenderError`]s; nothing is recorded then).
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        style: &EdgeStyle,
    ) -> Result<Prepared<'_>, RenderError> {
        let instance = [Instance::new(&self.asset)];
        self.scene.prepare(queue, encoder, camera, &instance, style)
    }

    /// See [`SceneRenderer::read_counts`].
    pub fn read_counts(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<DrawCounts, RenderError> {
        self.scene.read_counts(device, queue)
    }

    /// GPU bytes of this renderer's per-frame state.
    pub fn gpu_bytes(&self) -> u64 {
        self.scene.gpu_bytes()
    }
}

/// A frame whose compute work is recorded: draw it with [`render`](Self::render) inside the
/// application's pass, after its mesh, then [`finish`](Self::finish) after that pass.
#[derive(Debug)]
pub struct Prepared<'a> {
    frame: &'a dyn TechniqueFrame,
}

impl Prepared<'_> {
    /// Draws this frame's edges into `pass` (after the mesh, against its depth).
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.frame.render(pass);
    }

    /// Records what the technique does after the application's pass (post-processes over its
    /// colour, reading its depth); nothing for the others. Call it once the pass has ended.
    pub fn finish(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        views: &FrameViews<'_>,
    ) -> Result<(), RenderError> {
        self.frame.finish(encoder, views)
    }
}
