//! One module per edge technique. Each has its per-device pipelines (kept in [`Pipelines`]) and its
//! per-frame state, a [`TechniqueFrame`] that an [`EdgeRenderer`](super::EdgeRenderer) owns for the
//! technique its style names.

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

use super::{
    Camera, DrawCounts, EdgeStyle, FrameViews, GpuAsset, Pipelines, RenderError, Technique,
};

/// The per-frame state of `technique` for `asset`.
pub(crate) fn new_frame(
    pipelines: &Pipelines,
    asset: &GpuAsset,
    technique: &Technique,
) -> Result<Box<dyn TechniqueFrame>, RenderError> {
    Ok(match technique {
        Technique::Joined => Box::new(joined::Frame::new(pipelines, asset)?),
        Technique::McGuireHughes => Box::new(mcguire_hughes::Frame::new(pipelines, asset)?),
        Technique::HalfHex | Technique::Plug | Technique::HalfHexPlug | Technique::House => {
            Box::new(alternate::Frame::new(pipelines, asset, technique)?)
        }
        Technique::Fins { .. } => Box::new(fins::Frame::new(pipelines, asset, technique)?),
        Technique::Wireframe { .. } => {
            Box::new(wireframe::Frame::new(pipelines, asset, technique)?)
        }
        Technique::Hardware(method) => Box::new(hardware::Frame::new(pipelines, asset, *method)?),
        Technique::SurfaceAngle { .. } => Box::new(surface_angle::Frame::new(pipelines, asset)?),
        Technique::InvertedHull { .. } => {
            Box::new(inverted_hull::Frame::new(pipelines, asset, technique)?)
        }
        Technique::Hybrid(_) => Box::new(hybrid::Frame::new(pipelines, asset)?),
        Technique::ImageSpace(_) => Box::new(image_space::Frame::new(pipelines, asset)?),
    })
}

/// What a technique's frame is prepared from.
pub(crate) struct FrameContext<'a> {
    pub(crate) pipelines: &'a Pipelines,
    pub(crate) queue: &'a wgpu::Queue,
    pub(crate) asset: &'a GpuAsset,
    pub(crate) camera: &'a Camera,
    pub(crate) style: &'a EdgeStyle,
}

/// Per-frame GPU state of one technique drawing one asset.
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

/// The `Frame` uniform of the object-space edge passes for this frame; `technique` selects a
/// technique's variant of a shared pass.
pub(crate) fn frame_uniform(cx: &FrameContext<'_>, technique: u32) -> super::layout::Frame {
    let (camera, style, asset) = (cx.camera, cx.style, cx.asset);
    let mvp = camera.view_projection();
    let depth_ref = if style.depth_scaled && !camera.is_orthographic() {
        (mvp * asset.center().extend(1.0)).w.max(1e-6)
    } else {
        0.0
    };
    super::layout::Frame {
        mvp: mvp.to_cols_array_2d(),
        eye: camera.eye().to_array(),
        proj_z: camera.projection.z_axis.to_array(),
        colors: style.colors.array(),
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
        heads_offset: asset.heads_offset,
        half_quads: u32::from(style.half_quad_contours),
        cap_capacity: 0,
        highlight: 0,
        radius_scale: asset.radius_scale,
        reverse_z: u32::from(cx.pipelines.target().reverse_z),
        technique,
        params: [0.0; 4],
        indices_u16: u32::from(asset.index_format == wgpu::IndexFormat::Uint16),
        triangle_count: asset.index_count / 3,
        _pad0: 0,
        _pad1: 0,
    }
}

/// The per-frame state of a technique that pulls its geometry in the vertex shader from the
/// asset's buffers: its frame uniform and one bind group over it and the asset.
#[derive(Debug)]
pub(crate) struct Pulled {
    uniform: wgpu::Buffer,
    pub(crate) group: wgpu::BindGroup,
}

impl Pulled {
    /// The uniform (binding 0) and the group of `set` over it and `buffers`.
    pub(crate) fn new(
        pipelines: &Pipelines,
        layout: &wgpu::BindGroupLayout,
        set: &super::pipelines::BindingSet,
        buffers: &[(u32, &wgpu::Buffer)],
    ) -> Self {
        let device = pipelines.device();
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(set.label),
            size: std::mem::size_of::<super::layout::Frame>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut all = vec![(0, &uniform)];
        all.extend_from_slice(buffers);
        let group = set.group(device, layout, &all);
        Self { uniform, group }
    }

    pub(crate) fn write(&self, queue: &wgpu::Queue, frame: &super::layout::Frame) {
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(frame));
    }

    pub(crate) fn gpu_bytes(&self) -> u64 {
        self.uniform.size()
    }

    pub(crate) fn uniform(&self) -> &wgpu::Buffer {
        &self.uniform
    }
}

/// `buffer`, or the error that says the asset was uploaded without `extra`.
pub(crate) fn extra<'a>(
    buffer: &'a Option<wgpu::Buffer>,
    technique: &Technique,
    needs: &'static str,
) -> Result<&'a wgpu::Buffer, RenderError> {
    buffer.as_ref().ok_or(RenderError::MissingAssetData {
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
