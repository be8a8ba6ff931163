//! One module per edge technique, behind the one switch [`Technique`]. A technique module declares
//! everything the core needs of it in one [`Module`] value: its shaders with the bindings and
//! parameters of each pipeline (checked against the WGSL on the CPU by `modules.rs`), its per-asset
//! needs, what it needs of the target, and its per-frame state, a [`TechniqueFrame`] that a
//! [`SceneRenderer`](super::SceneRenderer) owns while its style names the technique. Its pipelines
//! are a [`PipelineSet`](super::pipelines::PipelineSet) of its own, made on first use; the core
//! keeps no list of techniques but [`module`], the enum's one dispatch.
//!
//! A frame draws any number of instances of any number of assets: what is per instance (the camera
//! in the instance's model space, its colours, its parameters) is a block of a dynamic uniform buffer
//! ([`Blocks`]), what is per asset (bind groups over its sections) is kept per asset ([`PerAsset`]).
//! The techniques that pull their geometry in the vertex shader share one skeleton, [`pulled`].

mod alternate;
mod fins;
mod hardware;
mod hybrid;
mod image_space;
mod inverted_hull;
mod joined;
mod mcguire_hughes;
mod post;
pub(crate) mod pulled;
mod surface_angle;
#[cfg(test)]
mod tests;
mod wireframe;

pub use fins::FinSettings;
pub use hybrid::HybridDepth;
pub use surface_angle::SurfaceAngleSettings;

use std::sync::Arc;

use super::layout::{Frame, InstanceFrame, Layout};
use super::modules::Shader;
use super::technique::{Preset, preset_of};
use super::{
    AssetExtras, Camera, DrawCounts, EdgeColors, EdgeStyle, FrameViews, GpuAsset, Pipelines,
    RenderError, Target, Technique,
};

/// The module that draws `technique`: the one place the enum meets the modules.
pub(crate) fn module(technique: &Technique) -> &'static dyn Module {
    match technique {
        Technique::Joined => &joined::MODULE,
        Technique::McGuireHughes => &mcguire_hughes::MODULE,
        Technique::HalfHex | Technique::Plug | Technique::HalfHexPlug | Technique::House => {
            &alternate::MODULE
        }
        Technique::Fins(_) => &fins::MODULE,
        Technique::Wireframe { .. } => &wireframe::MODULE,
        Technique::Hardware(_) => &hardware::MODULE,
        Technique::SurfaceAngle(_) => &surface_angle::MODULE,
        Technique::InvertedHull { .. } => &inverted_hull::MODULE,
        Technique::Hybrid(_) => &hybrid::MODULE,
        Technique::ImageSpace(_) => &image_space::MODULE,
    }
}

/// Every technique module, in the order their presets are offered: [`Technique::all`], names and
/// summaries come from here (each module lists its presets), so this list and [`module`] are the
/// only places the core names a technique.
pub(crate) static MODULES: [&'static dyn Module; 10] = [
    &joined::MODULE,
    &mcguire_hughes::MODULE,
    &alternate::MODULE,
    &fins::MODULE,
    &wireframe::MODULE,
    &hardware::MODULE,
    &surface_angle::MODULE,
    &inverted_hull::MODULE,
    &hybrid::MODULE,
    &image_space::MODULE,
];

/// Every technique module, once each.
#[cfg(test)]
pub(crate) fn modules() -> Vec<&'static dyn Module> {
    MODULES.to_vec()
}

/// What a technique module declares. One `static` value per module implements it.
pub(crate) trait Module: Sync + 'static {
    /// The techniques this module draws, named and summarized, with their default parameters.
    fn presets(&self) -> &'static [Preset];

    /// The preset `technique` (one of this module's) is, or is a variant of: the one equal to it,
    /// else the first. Modules whose presets differ by a parameter pick by that parameter.
    fn preset(&self, technique: &Technique) -> &'static Preset {
        preset_of(self.presets(), technique)
    }

    /// The WGSL modules the technique compiles for `target` and the pipelines made of each (the
    /// same declarations its [`PipelineSet`](super::pipelines::PipelineSet) compiles; the CPU tests
    /// of `modules.rs` read them).
    #[cfg_attr(not(test), allow(dead_code))]
    fn shaders(&self, target: &Target) -> Vec<Shader>;

    /// The Rust twins of the structs its own WGSL declares (its parameters).
    #[cfg_attr(not(test), allow(dead_code))]
    fn structs(&self) -> Vec<Layout> {
        Vec::new()
    }

    /// What an asset must be uploaded with for `technique`.
    fn needs(&self, _technique: &Technique) -> AssetExtras {
        AssetExtras::NONE
    }

    /// True if `technique` draws through the target's stencil.
    fn needs_stencil(&self, _technique: &Technique) -> bool {
        false
    }

    /// True if the technique works after the application's pass ([`TechniqueFrame::finish`]).
    fn is_post_process(&self) -> bool {
        false
    }

    /// True if the technique draws the hidden part of drawn edges in their own style
    /// ([`EdgeStyle::display`](super::EdgeStyle::display)); the others ignore it.
    fn draws_hidden(&self) -> bool {
        false
    }

    /// True if the technique's frame culls whole instances out of view on the GPU: the renderer
    /// then hands it every instance instead of culling on the host.
    fn culls_on_gpu(&self) -> bool {
        false
    }

    /// Fresh per-frame state (compiling the technique's pipelines if they are not yet).
    fn new_frame(
        &self,
        pipelines: &Pipelines,
        options: &FrameOptions,
    ) -> Result<Box<dyn TechniqueFrame>, RenderError>;

    /// The module's identity: a renderer keeps its frame while the module stays the same.
    fn id(&self) -> std::any::TypeId {
        std::any::TypeId::of::<Self>()
    }
}

/// What a renderer asks of the frames it makes.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct FrameOptions {
    /// Slots of the first edge lists (0: sized from the first frame), where a technique has lists.
    pub(crate) first_slots: u64,
}

/// Checks what `technique` needs of `target`, before any frame is made or reused for it.
pub(crate) fn check_target(
    module: &dyn Module,
    technique: &Technique,
    target: &Target,
) -> Result<(), RenderError> {
    if module.needs_stencil(technique) && !target.has_stencil() {
        return Err(RenderError::TargetLacks {
            technique: technique.name(),
            needs: "a depth format with a stencil aspect",
        });
    }
    Ok(())
}

/// The error for a frame asked to draw a technique other than the one its module draws (the
/// renderer dispatches by module, so this is a bug).
pub(crate) fn mismatch(cx: &FrameContext<'_>) -> RenderError {
    RenderError::Internal(format!(
        "a frame was asked to draw {}, which its module does not draw",
        cx.style.technique.name()
    ))
}

/// One instance the frame draws: its asset, the camera as its model space sees it (the scene
/// camera's model-view times the instance's transform) and its colours.
#[derive(Clone, Debug)]
pub(crate) struct Drawn<'a> {
    pub(crate) asset: &'a GpuAsset,
    pub(crate) camera: Camera,
    pub(crate) colors: EdgeColors,
    /// The highlight's light for this instance (model space); `None`: the style's.
    pub(crate) light: Option<super::Light>,
    /// The section planes in the instance's model space.
    pub(crate) section: crate::section::ClipPlanes,
}

/// What a technique's frame is prepared from.
pub(crate) struct FrameContext<'a> {
    pub(crate) pipelines: &'a Pipelines,
    pub(crate) queue: &'a wgpu::Queue,
    /// The scene's camera (world space).
    pub(crate) camera: &'a Camera,
    pub(crate) style: &'a EdgeStyle,
    /// The instances in view, in the order their blocks are numbered.
    pub(crate) instances: &'a [Drawn<'a>],
    /// The highlight's image-based light.
    pub(crate) environment: Option<&'a std::sync::Arc<crate::highlight::environment::Environment>>,
}

/// Per-frame GPU state of one technique drawing a frame's instances.
pub(crate) trait TechniqueFrame: std::fmt::Debug + Send + Sync {
    /// Writes this frame's uniforms and records its compute work (and any passes of its own) into
    /// `encoder`.
    fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), RenderError>;

    /// Draws into the application's pass, after its mesh.
    fn render(&self, pass: &mut wgpu::RenderPass<'_>);

    /// After the application's pass: work over its finished colour and depth (post-processes).
    fn finish(
        &self,
        _encoder: &mut wgpu::CommandEncoder,
        _views: &FrameViews<'_>,
    ) -> Result<(), RenderError> {
        Ok(())
    }

    /// What the last submitted frame drew, if the technique counts it.
    fn read_counts(
        &self,
        _device: &wgpu::Device,
        _queue: &wgpu::Queue,
    ) -> Option<Result<DrawCounts, RenderError>> {
        None
    }

    /// GPU bytes this frame state holds (lists, uniforms, textures).
    fn gpu_bytes(&self) -> u64;
}

/// The `Frame` uniform of the object-space edge passes for instance `index`.
pub(crate) fn frame_uniform(cx: &FrameContext<'_>, drawn: &Drawn<'_>, index: usize) -> Frame {
    let (camera, style, asset) = (&drawn.camera, cx.style, drawn.asset);
    let mvp = camera.view_projection();
    let depth_ref = if style.depth_scaled && !camera.is_orthographic() {
        (mvp * asset.center().extend(1.0)).w.max(1e-6)
    } else {
        0.0
    };
    // Where the highlight's light is for this instance; its colour is the style's (`Lighting`).
    let light = drawn
        .light
        .or(style.highlight.map(|h| h.light))
        .map(|light| super::lighting::punctual(&light, [0.0; 3], false))
        .unwrap_or_default();
    Frame {
        mvp: mvp.to_cols_array_2d(),
        eye: camera.eye().to_array(),
        proj_z: camera.projection.z_axis.to_array(),
        colors: drawn.colors.array(),
        viewport: camera.viewport.map(|v| v.max(1) as f32),
        pixel_scale: camera.pixel_scale(),
        width: style.width(),
        min_width: style.min_width_px.clamp(0.0, 4096.0),
        depth_ref,
        bias_px: style.bias_px(),
        classes: style.classes.0,
        // Back-facing creases are hidden edges: drawn when hidden edges are.
        cull_back: u32::from(style.cull_back_facing && style.display.hidden.is_none()),
        edges_u16: u32::from(asset.edges_u16),
        rings_u16: u32::from(asset.rings_u16),
        edge_count: asset.edge_count,
        head_count: asset.head_count,
        first_edge: 0,
        half_quads: u32::from(style.half_quad_contours),
        cap_capacity: 0,
        highlight: 0,
        radius_scale: asset.radius_scale,
        reverse_z: u32::from(cx.pipelines.target().reverse_z),
        _pad: 0,
        frustum: [[0.0; 4]; 4],
        light_position: light.position,
        light_axis: light.spot,
        indices_u16: u32::from(asset.index_format == wgpu::IndexFormat::Uint16),
        triangle_count: asset.index_count / 3,
        instance: index as u32,
        capacity: 0,
        batch: 0,
        batch_instances: 0,
        table_mask: 0,
        survivor_capacity: 0,
        section: drawn.section.rows(),
        display: style.display.frame(camera),
    }
}

/// The frame's instances grouped by asset (assets in the order they first appear, instances in
/// theirs): the order batches number them in.
pub(crate) fn by_asset(instances: &[Drawn<'_>]) -> Vec<usize> {
    let mut keys: Vec<&Arc<()>> = Vec::new();
    let asset_of: Vec<usize> = instances
        .iter()
        .map(
            |d| match keys.iter().position(|k| Arc::ptr_eq(k, &d.asset.key)) {
                Some(k) => k,
                None => {
                    keys.push(&d.asset.key);
                    keys.len() - 1
                }
            },
        )
        .collect();
    let mut order: Vec<usize> = (0..instances.len()).collect();
    order.sort_by_key(|&i| (asset_of[i], i));
    order
}

/// The batches of `order` (from [`by_asset`]): runs of one asset's instances, each at most
/// `most(asset)` long. Returns (first position in `order`, instances) per batch.
pub(crate) fn batches(
    instances: &[Drawn<'_>],
    order: &[usize],
    most: impl Fn(&GpuAsset) -> usize,
) -> Vec<(usize, usize)> {
    let mut runs = Vec::new();
    let mut start = 0;
    while start < order.len() {
        let asset = instances[order[start]].asset;
        let same = order[start..]
            .iter()
            .take_while(|&&d| Arc::ptr_eq(&instances[d].asset.key, &asset.key))
            .count();
        let count = same.min(most(asset).max(1));
        runs.push((start, count));
        start += count;
    }
    runs
}

/// Instance `drawn`'s view for the batched passes (numbered `index` in the frame), its frustum
/// planes `frustum` (zeros: none).
pub(crate) fn instance_view(
    cx: &FrameContext<'_>,
    drawn: &Drawn<'_>,
    index: usize,
    frustum: [[f32; 4]; 4],
) -> InstanceFrame {
    let uniform = frame_uniform(cx, drawn, index);
    let [lo, hi] = drawn.asset.bounds();
    InstanceFrame {
        mvp: uniform.mvp,
        eye: uniform.eye,
        frustum,
        lo: [lo[0], lo[1], lo[2], uniform.depth_ref],
        hi: [hi[0], hi[1], hi[2], 0.0],
        colors: uniform.colors,
        light_position: uniform.light_position,
        light_axis: uniform.light_axis,
        visible: 1,
        _pad0: 0,
        _pad1: 0,
        _pad2: 0,
        section: drawn.section.rows(),
    }
}

/// A storage buffer of [`InstanceFrame`]s, regrown when a frame has more instances.
#[derive(Debug)]
pub(crate) struct InstanceViews {
    pub(crate) buffer: wgpu::Buffer,
    capacity: usize,
}

impl InstanceViews {
    pub(crate) fn new(cache: &Pipelines) -> Self {
        Self {
            buffer: Self::make(cache, 1),
            capacity: 1,
        }
    }

    fn make(cache: &Pipelines, capacity: usize) -> wgpu::Buffer {
        cache.device().create_buffer(&wgpu::BufferDescriptor {
            label: Some("instance views"),
            size: (std::mem::size_of::<InstanceFrame>() * capacity) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Writes `views`; true if the buffer had to be remade (bind groups over it too).
    pub(crate) fn write(
        &mut self,
        cache: &Pipelines,
        queue: &wgpu::Queue,
        views: &[InstanceFrame],
    ) -> bool {
        let grown = views.len() > self.capacity;
        if grown {
            self.capacity = views.len().next_power_of_two();
            self.buffer = Self::make(cache, self.capacity);
        }
        if !views.is_empty() {
            queue.write_buffer(&self.buffer, 0, bytemuck::cast_slice(views));
        }
        grown
    }

    pub(crate) fn gpu_bytes(&self) -> u64 {
        self.buffer.size()
    }
}

/// A dynamic uniform buffer of one block per instance, regrown when a frame has more instances.
#[derive(Debug)]
pub(crate) struct Blocks {
    label: &'static str,
    buffer: wgpu::Buffer,
    /// Bytes of one block's contents.
    size: u64,
    /// Bytes from one block to the next (the device's dynamic-offset alignment).
    stride: u64,
    capacity: usize,
}

impl Blocks {
    /// Blocks of `size` bytes.
    pub(crate) fn new(cache: &Pipelines, label: &'static str, size: usize) -> Self {
        let align = u64::from(cache.device().limits().min_uniform_buffer_offset_alignment).max(1);
        let size = size as u64;
        let stride = size.div_ceil(align) * align;
        Self {
            label,
            buffer: Self::make(cache, label, stride, 1),
            size,
            stride,
            capacity: 1,
        }
    }

    fn make(cache: &Pipelines, label: &str, stride: u64, capacity: usize) -> wgpu::Buffer {
        cache.device().create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: stride * capacity as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Writes `blocks` (each `size` bytes); true if the buffer had to be remade, so bind groups over
    /// it must be remade too.
    pub(crate) fn write<T: bytemuck::Pod>(
        &mut self,
        cache: &Pipelines,
        queue: &wgpu::Queue,
        blocks: &[T],
    ) -> bool {
        debug_assert_eq!(std::mem::size_of::<T>() as u64, self.size);
        let grown = blocks.len() > self.capacity;
        if grown {
            self.capacity = blocks.len().next_power_of_two();
            self.buffer = Self::make(cache, self.label, self.stride, self.capacity);
        }
        let mut bytes = vec![0u8; (self.stride as usize) * blocks.len()];
        for (i, block) in blocks.iter().enumerate() {
            let start = i * self.stride as usize;
            bytes[start..start + self.size as usize].copy_from_slice(bytemuck::bytes_of(block));
        }
        if !bytes.is_empty() {
            queue.write_buffer(&self.buffer, 0, &bytes);
        }
        grown
    }

    /// The dynamic offset of block `i`.
    pub(crate) fn offset(&self, i: usize) -> u32 {
        (self.stride * i as u64) as u32
    }

    /// The binding of one block (the offset is given when the group is set).
    pub(crate) fn binding(&self) -> wgpu::BindingResource<'_> {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &self.buffer,
            offset: 0,
            size: std::num::NonZeroU64::new(self.size),
        })
    }

    pub(crate) fn gpu_bytes(&self) -> u64 {
        self.buffer.size()
    }
}

/// Per-asset state of a frame (bind groups over the asset's buffers), made the first time an asset
/// is drawn and dropped once a frame no longer draws it.
#[derive(Debug)]
pub(crate) struct PerAsset<T> {
    entries: Vec<(Arc<()>, GpuAsset, T)>,
}

impl<T> Default for PerAsset<T> {
    fn default() -> Self {
        Self {
            entries: Vec::new(),
        }
    }
}

impl<T> PerAsset<T> {
    /// Forgets every asset (when what their state refers to was remade).
    pub(crate) fn clear(&mut self) {
        self.entries.clear();
    }

    /// Keeps only the assets among `instances`.
    pub(crate) fn retain(&mut self, instances: &[Drawn<'_>]) {
        self.entries
            .retain(|(key, _, _)| instances.iter().any(|d| Arc::ptr_eq(key, &d.asset.key)));
    }

    /// The index of `asset`'s state, made by `make` the first time.
    pub(crate) fn index(
        &mut self,
        asset: &GpuAsset,
        make: impl FnOnce(&GpuAsset) -> Result<T, RenderError>,
    ) -> Result<usize, RenderError> {
        if let Some(i) = self
            .entries
            .iter()
            .position(|(key, _, _)| Arc::ptr_eq(key, &asset.key))
        {
            return Ok(i);
        }
        let state = make(asset)?;
        self.entries.push((asset.key.clone(), asset.clone(), state));
        Ok(self.entries.len() - 1)
    }

    pub(crate) fn get(&self, i: usize) -> (&GpuAsset, &T) {
        let (_, asset, state) = &self.entries[i];
        (asset, state)
    }
}

/// A single-sampled 2D texture of the frame's own, `size` pixels, and its view.
pub(crate) fn texture(
    cache: &Pipelines,
    label: &str,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> Result<wgpu::TextureView, RenderError> {
    let device = cache.device();
    let texture = super::target::checked(device, label, || {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    })?;
    Ok(texture.create_view(&Default::default()))
}

/// Draws `asset`'s triangles with its position and normal vertex buffers.
pub(crate) fn draw_mesh(pass: &mut wgpu::RenderPass<'_>, asset: &GpuAsset) {
    pass.set_vertex_buffer(0, asset.render_positions.slice(..));
    pass.set_vertex_buffer(1, asset.render_normals.slice(..));
    pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
    pass.draw_indexed(0..asset.index_count, 0, 0..1);
}

/// An index buffer of `indices` (`u16`), for drawing one instance's corners indexed.
pub(crate) fn corner_indices(cache: &Pipelines, label: &str, indices: &[u16]) -> wgpu::Buffer {
    use wgpu::util::DeviceExt;
    // Index buffers are padded to four bytes.
    let mut padded = indices.to_vec();
    if padded.len() % 2 == 1 {
        padded.push(0);
    }
    cache
        .device()
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(&padded),
            usage: wgpu::BufferUsages::INDEX,
        })
}
