//! The runtime's simple lit mesh pass, for applications without their own (and for `chamfer render`).

use std::sync::Arc;

use glam::Vec3;

use super::layout::MeshFrame;
use super::pipelines::{Access, BindingSet, RenderPipeline};
use super::{Camera, GpuAsset, Light, Pipelines, RenderError, modules};

/// Where the mesh's light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeshLight {
    /// A headlight: towards the light in view space (x right, y up, z towards the viewer).
    View([f32; 3]),
    /// A light fixed to the model (the chamfer highlight's light, for matching shading).
    Model(Light),
}

/// How the mesh looks: `color × (ambient + (1 − ambient) (N·L)₊) + specular (N·H)₊^shininess`
/// (Blinn; with `ambient` 0, `color` = R_d and `specular` = R_s it is the highlight's model exactly).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshStyle {
    /// Straight-alpha RGBA base colour.
    pub color: [f32; 4],
    /// The light.
    pub light: MeshLight,
    /// Share of the colour lit regardless of the light, 0..1.
    pub ambient: f32,
    /// Specular reflectance `R_s` (white), 0 for none.
    pub specular: f32,
    /// Specular exponent.
    pub shininess: f32,
}

impl Default for MeshStyle {
    fn default() -> Self {
        Self {
            color: [0.86, 0.86, 0.84, 1.0],
            light: MeshLight::View([-0.4, 0.6, 0.7]),
            ambient: 0.35,
            specular: 0.0,
            shininess: 32.0,
        }
    }
}

const MESH: BindingSet = BindingSet {
    label: "mesh",
    stages: wgpu::ShaderStages::VERTEX_FRAGMENT,
    entries: &[(0, Access::Uniform)],
};

/// The mesh pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct Pipeline {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl Pipeline {
    pub(crate) fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let layout = cache.layout(&MESH);
        let module = cache.module("mesh.wgsl", &modules::mesh())?;
        let vertex_buffer = |attributes| {
            Some(wgpu::VertexBufferLayout {
                array_stride: 12,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes,
            })
        };
        let target = cache.target();
        let pipeline = cache.render_pipeline(
            &[&layout],
            RenderPipeline {
                label: "mesh",
                module: &module,
                vertex: "mesh_vertex",
                fragment: Some("mesh_fragment"),
                buffers: &[
                    vertex_buffer(&wgpu::vertex_attr_array![0 => Float32x3]),
                    vertex_buffer(&wgpu::vertex_attr_array![1 => Float32x3]),
                ],
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: target.depth(true, wgpu::CompareFunction::Less),
                multisample: target.multisample(),
                color: Some(target.blended_color()),
            },
        )?;
        Ok(Self { layout, pipeline })
    }
}

/// Draws a [`GpuAsset`]'s triangles with its crease-split normals, writing depth for the edges.
#[derive(Debug)]
pub struct MeshRenderer {
    pipeline: Arc<Pipeline>,
    uniform: wgpu::Buffer,
    group: wgpu::BindGroup,
    asset: GpuAsset,
}

impl MeshRenderer {
    /// A mesh pass for `asset` with the pipeline of `pipelines` (compiled once per target).
    pub fn new(pipelines: &Pipelines, asset: &GpuAsset) -> Result<Self, RenderError> {
        let pipeline = pipelines.mesh()?;
        let device = pipelines.device();
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("mesh frame"),
            size: std::mem::size_of::<MeshFrame>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let group = MESH.group(device, &pipeline.layout, &[(0, &uniform)]);
        Ok(Self {
            pipeline,
            uniform,
            group,
            asset: asset.clone(),
        })
    }

    /// Sets this frame's camera and style.
    pub fn prepare(&mut self, queue: &wgpu::Queue, camera: &Camera, style: &MeshStyle) {
        let light = match style.light {
            MeshLight::View(towards) => camera
                .model_view
                .inverse()
                .transform_vector3(Vec3::from(towards))
                .normalize_or(Vec3::Z)
                .extend(0.0),
            MeshLight::Model(Light::Directional(towards)) => {
                Vec3::from(towards).normalize_or(Vec3::Z).extend(0.0)
            }
            MeshLight::Model(Light::Point(position)) => Vec3::from(position).extend(1.0),
        };
        let uniform = MeshFrame {
            mvp: camera.view_projection().to_cols_array_2d(),
            light: light.to_array(),
            color: style.color,
            params: [
                style.ambient.clamp(0.0, 1.0),
                style.specular.max(0.0),
                style.shininess.max(0.0),
                0.0,
            ],
            eye: camera.eye().to_array(),
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
    }

    /// Draws the mesh into `pass`.
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let asset = &self.asset;
        pass.set_pipeline(&self.pipeline.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        pass.set_vertex_buffer(0, asset.render_positions.slice(..));
        pass.set_vertex_buffer(1, asset.render_normals.slice(..));
        pass.set_index_buffer(asset.mesh_indices.slice(..), asset.index_format);
        pass.draw_indexed(0..asset.index_count, 0, 0..1);
    }
}
