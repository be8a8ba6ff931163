//! One module per edge technique. Each has its per-device pipelines (kept in [`Pipelines`]) and its
//! per-frame state, a [`TechniqueFrame`] that an [`EdgeRenderer`](super::EdgeRenderer) owns for the
//! technique its style names.

pub(crate) mod joined;

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
    }
}
