//! Per device and target: the compiled pipelines and bind-group layouts of every technique, created
//! once and shared by every asset and renderer drawn into that target (glyphon's `Cache`).
//!
//! The cache knows no technique: each keeps its pipelines in a [`PipelineSet`] of its own, made the
//! first time a frame asks for it ([`Pipelines::get`], keyed by type). Every pipeline is compiled from
//! a declared [`Shader`] through [`Compiled`], which builds its layout from the bindings the
//! declaration names, counts it (so a test can tell two assets share one set) and turns a device
//! error into a [`RenderError`].

use std::any::{Any, TypeId};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use super::bindings::Bindings;
use super::layout::{MAX_GROUPS, WORKGROUP};
use super::modules::{Program, Shader};
use super::target::checked;
use super::{RenderError, Target};

/// The compiled pipelines of every technique for one device and one [`Target`]. Cheap to clone
/// (a shared handle); create one per target format and share it between all assets.
#[derive(Clone, Debug)]
pub struct Pipelines {
    inner: Arc<Inner>,
}

#[derive(Debug)]
struct Inner {
    device: wgpu::Device,
    target: Target,
    compiled: AtomicUsize,
    /// Each technique's pipeline set, by its type.
    sets: Mutex<Vec<(TypeId, Arc<dyn Any + Send + Sync>)>>,
    /// One layout per binding set, shared by every pipeline declared with it.
    layouts: Mutex<Vec<(&'static Bindings, wgpu::BindGroupLayout)>>,
}

/// The pipelines a technique (or the mesh pass) keeps per device and target.
pub(crate) trait PipelineSet: Send + Sync + std::fmt::Debug + Sized + 'static {
    /// Compiles the set for `cache`'s device and target.
    fn new(cache: &Pipelines) -> Result<Self, RenderError>;
}

impl Pipelines {
    /// The pipeline cache for drawing into `target` with `device`. Compiles nothing yet.
    ///
    /// Fails with [`RenderError::Target`] for a target the renderer would draw wrongly (a depth
    /// format without depth, reverse Z without depth, an invalid sample count).
    pub fn new(device: &wgpu::Device, target: &Target) -> Result<Self, RenderError> {
        target.check()?;
        Ok(Self {
            inner: Arc::new(Inner {
                device: device.clone(),
                target: *target,
                compiled: AtomicUsize::new(0),
                sets: Mutex::new(Vec::new()),
                layouts: Mutex::new(Vec::new()),
            }),
        })
    }

    /// The device.
    pub fn device(&self) -> &wgpu::Device {
        &self.inner.device
    }

    /// The target these pipelines draw into.
    pub fn target(&self) -> &Target {
        &self.inner.target
    }

    /// How many pipelines have been compiled so far (for tests and statistics).
    pub fn compiled_pipelines(&self) -> usize {
        self.inner.compiled.load(Ordering::Relaxed)
    }

    /// True if both handles share one cache.
    pub fn same_cache(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.inner, &other.inner)
    }

    /// The pipeline set `T`, compiled the first time it is asked for. (Two threads asking at once
    /// may both compile it; one is kept. No lock is held while compiling, so a set may ask for
    /// another.)
    pub(crate) fn get<T: PipelineSet>(&self) -> Result<Arc<T>, RenderError> {
        let find = |sets: &[(TypeId, Arc<dyn Any + Send + Sync>)]| {
            sets.iter()
                .find(|(id, _)| *id == TypeId::of::<T>())
                .and_then(|(_, set)| set.clone().downcast::<T>().ok())
        };
        let sets = || {
            self.inner
                .sets
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
        };
        if let Some(set) = find(&sets()) {
            return Ok(set);
        }
        let made = Arc::new(T::new(self)?);
        let mut sets = sets();
        if let Some(set) = find(&sets) {
            return Ok(set);
        }
        sets.push((TypeId::of::<T>(), made.clone()));
        Ok(made)
    }

    /// The layout of `bindings` (one per set and cache).
    pub(crate) fn layout(&self, bindings: &'static Bindings) -> wgpu::BindGroupLayout {
        let mut layouts = self
            .inner
            .layouts
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        if let Some((_, layout)) = layouts.iter().find(|(b, _)| std::ptr::eq(*b, bindings)) {
            return layout.clone();
        }
        let layout = bindings.layout(self.device(), self.target());
        layouts.push((bindings, layout.clone()));
        layout
    }

    /// Compiles `shader`'s module; its declared programs become pipelines through [`Compiled`].
    pub(crate) fn compile<'s>(&self, shader: &'s Shader) -> Result<Compiled<'s>, RenderError> {
        let device = self.device();
        let module = checked(device, shader.label, || {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(shader.label),
                source: wgpu::ShaderSource::Wgsl(shader.source.as_str().into()),
            })
        })?;
        Ok(Compiled {
            cache: self.clone(),
            shader,
            module,
        })
    }
}

/// How a render pipeline draws; its shader side (entry points, bindings) is the declared
/// [`Program`]'s.
pub(crate) struct Raster<'a> {
    pub(crate) buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub(crate) primitive: wgpu::PrimitiveState,
    pub(crate) depth_stencil: Option<wgpu::DepthStencilState>,
    pub(crate) multisample: wgpu::MultisampleState,
    /// `None`: no colour attachment (a depth-only pass of the renderer's own).
    pub(crate) color: Option<wgpu::ColorTargetState>,
}

impl Raster<'_> {
    /// Triangles pulled in the vertex shader (no vertex buffers), depth-tested with LessEqual
    /// without writes and alpha-blended into the target: how every edge is drawn over the mesh.
    pub(crate) fn over_mesh(target: &Target) -> Self {
        Raster {
            buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: target.depth(false, wgpu::CompareFunction::LessEqual),
            multisample: target.multisample(),
            color: Some(target.blended_color()),
        }
    }
}

/// A compiled shader module and its declaration: pipelines are made of its declared programs only.
pub(crate) struct Compiled<'s> {
    cache: Pipelines,
    shader: &'s Shader,
    module: wgpu::ShaderModule,
}

impl Compiled<'_> {
    fn program(&self, entry: &str, fragment: Option<&str>) -> Result<&Program, RenderError> {
        self.shader
            .programs
            .iter()
            .find(|p| p.entry == entry && p.fragment == fragment)
            .ok_or_else(|| {
                RenderError::Internal(format!(
                    "{} declares no program {entry} {fragment:?}",
                    self.shader.label
                ))
            })
    }

    fn pipeline_layout(&self, program: &Program) -> wgpu::PipelineLayout {
        let layout = self.cache.layout(program.bindings);
        self.cache.inner.compiled.fetch_add(1, Ordering::Relaxed);
        self.cache
            .device()
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(program.entry),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            })
    }

    /// The compute pipeline of the declared program `entry`.
    pub(crate) fn compute(&self, entry: &str) -> Result<wgpu::ComputePipeline, RenderError> {
        let program = self.program(entry, None)?;
        let device = self.cache.device();
        checked(device, entry, || {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&self.pipeline_layout(program)),
                module: &self.module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        })
    }

    /// The render pipeline of the declared program `vertex` + `fragment`, drawn as `raster` says.
    pub(crate) fn render(
        &self,
        vertex: &str,
        fragment: Option<&str>,
        raster: Raster<'_>,
    ) -> Result<wgpu::RenderPipeline, RenderError> {
        self.render_with(vertex, fragment, raster, &[])
    }

    /// The hidden pass's pipeline of `vertex` + `fragment` (a module with `display.wgsl`): drawn as
    /// `raster` says but only where the target's depth is nearer (the depth test reversed), the
    /// shaders compiled with `HIDDEN`. `None` on a target without depth, where nothing hides.
    pub(crate) fn render_hidden(
        &self,
        vertex: &str,
        fragment: Option<&str>,
        mut raster: Raster<'_>,
    ) -> Result<Option<wgpu::RenderPipeline>, RenderError> {
        let Some(depth) = raster.depth_stencil.as_mut() else {
            return Ok(None);
        };
        depth.depth_compare = Some(self.cache.target().nearer(wgpu::CompareFunction::Greater));
        self.render_with(vertex, fragment, raster, &[("HIDDEN", 1.0)])
            .map(Some)
    }

    fn render_with(
        &self,
        vertex: &str,
        fragment: Option<&str>,
        raster: Raster<'_>,
        constants: &[(&str, f64)],
    ) -> Result<wgpu::RenderPipeline, RenderError> {
        let program = self.program(vertex, fragment)?;
        let device = self.cache.device();
        let targets: Vec<Option<wgpu::ColorTargetState>> =
            raster.color.into_iter().map(Some).collect();
        checked(device, vertex, || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(vertex),
                layout: Some(&self.pipeline_layout(program)),
                vertex: wgpu::VertexState {
                    module: &self.module,
                    entry_point: Some(vertex),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants,
                        ..Default::default()
                    },
                    buffers: raster.buffers,
                },
                primitive: raster.primitive,
                depth_stencil: raster.depth_stencil,
                multisample: raster.multisample,
                fragment: fragment.map(|entry| wgpu::FragmentState {
                    module: &self.module,
                    entry_point: Some(entry),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants,
                        ..Default::default()
                    },
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        })
    }
}

/// Workgroups covering `items` threads, spread over two dimensions past [`MAX_GROUPS`].
pub(crate) fn workgroups(items: u32) -> [u32; 2] {
    let groups = items.div_ceil(WORKGROUP);
    let x = groups.min(MAX_GROUPS);
    [x, if x == 0 { 0 } else { groups.div_ceil(x) }]
}
