//! Per device and target: the compiled pipelines and bind-group layouts of every technique, created
//! once and shared by every asset and renderer drawn into that target (glyphon's `Cache`).
//!
//! A technique's pipelines are compiled the first time a frame uses it, then kept; every creation goes
//! through [`Pipelines::render_pipeline`] or [`Pipelines::compute_pipeline`], which count it (so a test
//! can tell two assets share one set) and turn a device error into a [`RenderError`].

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

use super::layout::{MAX_GROUPS, WORKGROUP};
use super::target::checked;
use super::{RenderError, Target, mesh, techniques};

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
    joined: OnceLock<Arc<techniques::joined::Pipelines>>,
    mesh: OnceLock<Arc<mesh::Pipeline>>,
    mcguire_hughes: OnceLock<Arc<techniques::mcguire_hughes::Pipelines>>,
    alternate: OnceLock<Arc<techniques::alternate::Pipelines>>,
    fins: OnceLock<Arc<techniques::fins::Pipelines>>,
    wireframe: OnceLock<Arc<techniques::wireframe::Pipelines>>,
    hardware: OnceLock<Arc<techniques::hardware::Pipelines>>,
    surface_angle: OnceLock<Arc<techniques::surface_angle::Pipelines>>,
    inverted_hull: OnceLock<Arc<techniques::inverted_hull::Pipelines>>,
    hybrid: OnceLock<Arc<techniques::hybrid::Pipelines>>,
    image_space: OnceLock<Arc<techniques::image_space::Pipelines>>,
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
                joined: OnceLock::new(),
                mesh: OnceLock::new(),
                mcguire_hughes: OnceLock::new(),
                alternate: OnceLock::new(),
                fins: OnceLock::new(),
                wireframe: OnceLock::new(),
                hardware: OnceLock::new(),
                surface_angle: OnceLock::new(),
                inverted_hull: OnceLock::new(),
                hybrid: OnceLock::new(),
                image_space: OnceLock::new(),
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

    pub(crate) fn joined(&self) -> Result<Arc<techniques::joined::Pipelines>, RenderError> {
        get_or_create(&self.inner.joined, || {
            techniques::joined::Pipelines::new(self)
        })
    }

    pub(crate) fn mcguire_hughes(
        &self,
    ) -> Result<Arc<techniques::mcguire_hughes::Pipelines>, RenderError> {
        get_or_create(&self.inner.mcguire_hughes, || {
            techniques::mcguire_hughes::Pipelines::new(self)
        })
    }

    pub(crate) fn alternate(&self) -> Result<Arc<techniques::alternate::Pipelines>, RenderError> {
        get_or_create(&self.inner.alternate, || {
            techniques::alternate::Pipelines::new(self)
        })
    }

    pub(crate) fn fins(&self) -> Result<Arc<techniques::fins::Pipelines>, RenderError> {
        get_or_create(&self.inner.fins, || techniques::fins::Pipelines::new(self))
    }

    pub(crate) fn wireframe(&self) -> Result<Arc<techniques::wireframe::Pipelines>, RenderError> {
        get_or_create(&self.inner.wireframe, || {
            techniques::wireframe::Pipelines::new(self)
        })
    }

    pub(crate) fn hardware(&self) -> Result<Arc<techniques::hardware::Pipelines>, RenderError> {
        get_or_create(&self.inner.hardware, || {
            techniques::hardware::Pipelines::new(self)
        })
    }

    pub(crate) fn surface_angle(
        &self,
    ) -> Result<Arc<techniques::surface_angle::Pipelines>, RenderError> {
        get_or_create(&self.inner.surface_angle, || {
            techniques::surface_angle::Pipelines::new(self)
        })
    }

    pub(crate) fn inverted_hull(
        &self,
    ) -> Result<Arc<techniques::inverted_hull::Pipelines>, RenderError> {
        get_or_create(&self.inner.inverted_hull, || {
            techniques::inverted_hull::Pipelines::new(self)
        })
    }

    pub(crate) fn hybrid(&self) -> Result<Arc<techniques::hybrid::Pipelines>, RenderError> {
        get_or_create(&self.inner.hybrid, || {
            techniques::hybrid::Pipelines::new(self)
        })
    }

    pub(crate) fn image_space(
        &self,
    ) -> Result<Arc<techniques::image_space::Pipelines>, RenderError> {
        get_or_create(&self.inner.image_space, || {
            techniques::image_space::Pipelines::new(self)
        })
    }

    pub(crate) fn mesh(&self) -> Result<Arc<mesh::Pipeline>, RenderError> {
        get_or_create(&self.inner.mesh, || mesh::Pipeline::new(self))
    }

    /// A shader module of `source`.
    pub(crate) fn module(
        &self,
        label: &str,
        source: &str,
    ) -> Result<wgpu::ShaderModule, RenderError> {
        checked(self.device(), label, || {
            self.device()
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(label),
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                })
        })
    }

    /// A bind-group layout of `set`.
    pub(crate) fn layout(&self, set: &BindingSet) -> wgpu::BindGroupLayout {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = set
            .entries
            .iter()
            .map(|&(binding, access)| access.entry(binding, set.stages))
            .collect();
        self.device()
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(set.label),
                entries: &entries,
            })
    }

    /// A compute pipeline of `entry` in `module` over one bind group of `layout`.
    pub(crate) fn compute_pipeline(
        &self,
        layout: &wgpu::BindGroupLayout,
        module: &wgpu::ShaderModule,
        entry: &str,
    ) -> Result<wgpu::ComputePipeline, RenderError> {
        let device = self.device();
        self.inner.compiled.fetch_add(1, Ordering::Relaxed);
        checked(device, entry, || {
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(entry),
                bind_group_layouts: &[Some(layout)],
                immediate_size: 0,
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        })
    }

    /// A render pipeline from `descriptor` (its layout made of `layouts`).
    pub(crate) fn render_pipeline(
        &self,
        layouts: &[&wgpu::BindGroupLayout],
        descriptor: RenderPipeline<'_>,
    ) -> Result<wgpu::RenderPipeline, RenderError> {
        let device = self.device();
        self.inner.compiled.fetch_add(1, Ordering::Relaxed);
        checked(device, descriptor.label, || {
            let layouts: Vec<Option<&wgpu::BindGroupLayout>> =
                layouts.iter().map(|&l| Some(l)).collect();
            let targets: Vec<Option<wgpu::ColorTargetState>> =
                descriptor.color.into_iter().map(Some).collect();
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(descriptor.label),
                bind_group_layouts: &layouts,
                immediate_size: 0,
            });
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(descriptor.label),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: descriptor.module,
                    entry_point: Some(descriptor.vertex),
                    compilation_options: Default::default(),
                    buffers: descriptor.buffers,
                },
                primitive: descriptor.primitive,
                depth_stencil: descriptor.depth_stencil,
                multisample: descriptor.multisample,
                fragment: descriptor.fragment.map(|entry| wgpu::FragmentState {
                    module: descriptor.module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        })
    }
}

/// What a render pipeline differs in; everything else is shared by all of the renderer's pipelines.
pub(crate) struct RenderPipeline<'a> {
    pub(crate) label: &'a str,
    pub(crate) module: &'a wgpu::ShaderModule,
    pub(crate) vertex: &'a str,
    /// `None`: a depth-only pipeline for a pass of the renderer's own without colour.
    pub(crate) fragment: Option<&'a str>,
    pub(crate) buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub(crate) primitive: wgpu::PrimitiveState,
    pub(crate) depth_stencil: Option<wgpu::DepthStencilState>,
    pub(crate) multisample: wgpu::MultisampleState,
    pub(crate) color: Option<wgpu::ColorTargetState>,
}

/// `cell`'s value, created by `create` the first time. (A race may create it twice; one is kept.)
fn get_or_create<T>(
    cell: &OnceLock<Arc<T>>,
    create: impl FnOnce() -> Result<T, RenderError>,
) -> Result<Arc<T>, RenderError> {
    if let Some(value) = cell.get() {
        return Ok(value.clone());
    }
    let value = Arc::new(create()?);
    Ok(cell.get_or_init(|| value).clone())
}

/// How a pass uses a binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Access {
    /// A read-only storage buffer.
    Read,
    /// A read-write storage buffer.
    Write,
    /// A uniform buffer.
    Uniform,
    /// A uniform buffer of per-instance blocks, bound at a dynamic offset.
    Instance,
}

impl Access {
    fn entry(self, binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
        let ty = match self {
            Self::Read => wgpu::BufferBindingType::Storage { read_only: true },
            Self::Write => wgpu::BufferBindingType::Storage { read_only: false },
            Self::Uniform | Self::Instance => wgpu::BufferBindingType::Uniform,
        };
        wgpu::BindGroupLayoutEntry {
            binding,
            visibility,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: self == Self::Instance,
                min_binding_size: None,
            },
            count: None,
        }
    }
}

/// The buffer bindings of one pass: the layout is made once per device ([`Pipelines::layout`]), the
/// group once per renderer ([`BindingSet::group`]) from buffers found by binding number.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BindingSet {
    pub(crate) label: &'static str,
    pub(crate) stages: wgpu::ShaderStages,
    pub(crate) entries: &'static [(u32, Access)],
}

impl BindingSet {
    /// The bind group of this set over `buffers` (binding number, buffer), which must hold every
    /// binding of the set.
    pub(crate) fn group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        buffers: &[(u32, &wgpu::Buffer)],
    ) -> wgpu::BindGroup {
        self.group_with_window(device, layout, buffers, None)
    }

    /// As [`group`](Self::group), with one binding bound to a window of its buffer.
    pub(crate) fn group_with_window(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        buffers: &[(u32, &wgpu::Buffer)],
        window: Option<(u32, wgpu::BufferBinding<'_>)>,
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = self
            .entries
            .iter()
            .filter_map(|&(binding, access)| {
                if let Some((windowed, part)) = &window
                    && *windowed == binding
                {
                    let resource = wgpu::BindingResource::Buffer(part.clone());
                    return Some(wgpu::BindGroupEntry { binding, resource });
                }
                let (_, buffer) = buffers.iter().find(|(b, _)| *b == binding)?;
                let resource = if access == Access::Instance {
                    // One block, placed by the dynamic offset.
                    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer,
                        offset: 0,
                        size: std::num::NonZeroU64::new(
                            std::mem::size_of::<super::layout::Frame>() as u64,
                        ),
                    })
                } else {
                    buffer.as_entire_binding()
                };
                Some(wgpu::BindGroupEntry { binding, resource })
            })
            .collect();
        debug_assert_eq!(entries.len(), self.entries.len(), "{}", self.label);
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.label),
            layout,
            entries: &entries,
        })
    }
}

/// Workgroups covering `items` threads, spread over two dimensions past [`MAX_GROUPS`].
pub(crate) fn workgroups(items: u32) -> [u32; 2] {
    let groups = items.div_ceil(WORKGROUP);
    let x = groups.min(MAX_GROUPS);
    [x, if x == 0 { 0 } else { groups.div_ceil(x) }]
}
