//! One module per edge technique. Each has its per-device pipelines (kept in [`Pipelines`]) and its
//! per-frame state, a [`TechniqueFrame`] that a [`SceneRenderer`](super::SceneRenderer) owns for the
//! technique its style names. A frame draws any number of instances of any number of assets: what
//! is per instance (the camera in the instance's model space, its colours) is a block of a dynamic
//! uniform buffer ([`Blocks`]), what is per asset (bind groups over its sections) is kept per asset
//! ([`PerAsset`]), and the pipelines are the device's.

pub(crate) mod alternate;
pub(crate) mod fins;
pub(crate) mod hardware;
pub(crate) mod hybrid;
pub(crate) mod image_space;
pub(crate) mod inverted_hull;
pub(crate) mod joined;
pub(crate) mod mcguire_hughes;
pub(crate) mod post;
pub(crate) mod surface_angle;
pub(crate) mod wireframe;

use std::sync::Arc;

use super::layout::Frame;
use super::pipelines::BindingSet;
use super::{
    Camera, DrawCounts, EdgeColors, EdgeStyle, FrameViews, GpuAsset, Pipelines, RenderError,
    Technique,
};

/// The per-frame state of `technique`.
pub(crate) fn new_frame(
    pipelines: &Pipelines,
    technique: &Technique,
) -> Result<Box<dyn TechniqueFrame>, RenderError> {
    Ok(match technique {
        Technique::Joined => Box::new(joined::Frame::new(pipelines)?),
        Technique::McGuireHughes => Box::new(mcguire_hughes::Frame::new(pipelines)?),
        Technique::HalfHex | Technique::Plug | Technique::HalfHexPlug | Technique::House => {
            Box::new(alternate::Frame::new(pipelines)?)
        }
        Technique::Fins { .. } => Box::new(fins::Frame::new(pipelines)?),
        Technique::Wireframe { .. } => Box::new(wireframe::Frame::new(pipelines)?),
        Technique::Hardware(method) => Box::new(hardware::Frame::new(pipelines, *method)?),
        Technique::SurfaceAngle { .. } => Box::new(surface_angle::Frame::new(pipelines)?),
        Technique::InvertedHull { .. } => Box::new(inverted_hull::Frame::new(pipelines)?),
        Technique::Hybrid(_) => Box::new(hybrid::Frame::new(pipelines)?),
        Technique::ImageSpace(_) => Box::new(image_space::Frame::new(pipelines)?),
    })
}

/// One instance the frame draws: its asset, the camera as its model space sees it (the scene
/// camera's model-view times the instance's transform) and its colours.
#[derive(Clone, Debug)]
pub(crate) struct Drawn<'a> {
    pub(crate) asset: &'a GpuAsset,
    pub(crate) camera: Camera,
    pub(crate) colors: EdgeColors,
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

/// The `Frame` uniform of the object-space edge passes for instance `index`; `technique` selects a
/// technique's variant of a shared pass.
pub(crate) fn frame_uniform(
    cx: &FrameContext<'_>,
    drawn: &Drawn<'_>,
    index: usize,
    technique: u32,
) -> Frame {
    let (camera, style, asset) = (&drawn.camera, cx.style, drawn.asset);
    let mvp = camera.view_projection();
    let depth_ref = if style.depth_scaled && !camera.is_orthographic() {
        (mvp * asset.center().extend(1.0)).w.max(1e-6)
    } else {
        0.0
    };
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
        cull_back: u32::from(style.cull_back_facing),
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
        technique,
        params: [0.0; 4],
        frustum: [[0.0; 4]; 4],
        indices_u16: u32::from(asset.index_format == wgpu::IndexFormat::Uint16),
        triangle_count: asset.index_count / 3,
        instance: index as u32,
        capacity: 0,
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

    pub(crate) fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
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

    pub(crate) fn iter(&self) -> impl Iterator<Item = &T> {
        self.entries.iter().map(|(_, _, t)| t)
    }
}

/// The per-frame state of a technique that pulls its geometry in the vertex shader from the
/// asset's buffers: one uniform block per instance and one bind group per asset over the block
/// buffer (binding 0, dynamic) and the asset's buffers; `draws` lists, per instance, its asset's
/// group and its block.
#[derive(Debug)]
pub(crate) struct Pulled {
    pub(crate) blocks: Blocks,
    groups: PerAsset<wgpu::BindGroup>,
    pub(crate) draws: Vec<(usize, u32)>,
}

impl Pulled {
    pub(crate) fn new(pipelines: &Pipelines, label: &'static str) -> Self {
        Self {
            blocks: Blocks::new(pipelines, label, std::mem::size_of::<Frame>()),
            groups: PerAsset::default(),
            draws: Vec::new(),
        }
    }

    /// Writes one `Frame` per instance (from `uniform`) and makes the group of each new asset with
    /// `buffers`, the asset's buffers beside the blocks at binding 0.
    pub(crate) fn prepare(
        &mut self,
        cx: &FrameContext<'_>,
        layout: &wgpu::BindGroupLayout,
        set: &BindingSet,
        uniform: impl Fn(&Drawn<'_>, usize) -> Frame,
        buffers: impl Fn(&GpuAsset) -> Result<Vec<(u32, wgpu::Buffer)>, RenderError>,
    ) -> Result<(), RenderError> {
        let frames: Vec<Frame> = cx
            .instances
            .iter()
            .enumerate()
            .map(|(i, d)| uniform(d, i))
            .collect();
        if self.blocks.write(cx.pipelines, cx.queue, &frames) {
            self.groups.clear();
        }
        self.groups.retain(cx.instances);
        self.draws.clear();
        for (i, drawn) in cx.instances.iter().enumerate() {
            let blocks = &self.blocks;
            let group = self.groups.index(drawn.asset, |asset| {
                let buffers = buffers(asset)?;
                let mut entries = vec![wgpu::BindGroupEntry {
                    binding: 0,
                    resource: blocks.binding(),
                }];
                entries.extend(
                    buffers
                        .iter()
                        .map(|(binding, buffer)| wgpu::BindGroupEntry {
                            binding: *binding,
                            resource: buffer.as_entire_binding(),
                        }),
                );
                debug_assert_eq!(entries.len(), set.entries.len(), "{}", set.label);
                Ok(cx
                    .pipelines
                    .device()
                    .create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some(set.label),
                        layout,
                        entries: &entries,
                    }))
            })?;
            self.draws.push((group, self.blocks.offset(i)));
        }
        Ok(())
    }

    /// For each instance: sets its group and block on `pass` and calls `draw` with its asset.
    pub(crate) fn each(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        mut draw: impl FnMut(&mut wgpu::RenderPass<'_>, &GpuAsset),
    ) {
        for &(group, offset) in &self.draws {
            let (asset, bind_group) = self.groups.get(group);
            pass.set_bind_group(0, bind_group, &[offset]);
            draw(pass, asset);
        }
    }

    pub(crate) fn gpu_bytes(&self) -> u64 {
        self.blocks.gpu_bytes()
    }
}

/// `buffer`, or the error that says the asset was uploaded without `extra`.
pub(crate) fn extra(
    buffer: &Option<wgpu::Buffer>,
    technique: &Technique,
    needs: &'static str,
) -> Result<wgpu::Buffer, RenderError> {
    buffer.clone().ok_or(RenderError::MissingAssetData {
        technique: technique.name(),
        needs,
    })
}

/// A render pipeline of the pulled kind: no vertex buffers, one bind group, `primitive` triangles,
/// depth tested (LessEqual, no writes) and alpha-blended like the default edges.
pub(crate) fn pulled_pipeline(
    cache: &Pipelines,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    module: &wgpu::ShaderModule,
    vertex: &str,
    fragment: &str,
) -> Result<wgpu::RenderPipeline, RenderError> {
    let target = cache.target();
    cache.render_pipeline(
        &[layout],
        super::pipelines::RenderPipeline {
            label,
            module,
            vertex,
            fragment: Some(fragment),
            buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: target.depth(false, wgpu::CompareFunction::LessEqual),
            multisample: target.multisample(),
            color: Some(target.blended_color()),
        },
    )
}

/// The error for a frame asked to draw a technique other than the one it was made for (the
/// renderer remakes frames when the technique changes, so this is a bug).
pub(crate) fn mismatch(cx: &FrameContext<'_>) -> RenderError {
    RenderError::Unsupported {
        technique: cx.style.technique.name(),
        why: "its frame state was made for another technique (a bug: please report it)".into(),
    }
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
