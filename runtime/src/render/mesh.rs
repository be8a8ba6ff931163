//! The runtime's simple lit mesh pass, for applications without their own (and for `chamfer render`).

use glam::Vec3;

use super::{Camera, GpuAsset, Light, Target, shaders};

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

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct MeshUniform {
    mvp: [[f32; 4]; 4],
    light: [f32; 4],
    color: [f32; 4],
    params: [f32; 4],
    eye: [f32; 4],
}

/// Draws a [`GpuAsset`]'s triangles with its crease-split normals, writing depth for the edges.
#[derive(Debug)]
pub struct MeshRenderer {
    uniform: wgpu::Buffer,
    group: wgpu::BindGroup,
    pipeline: wgpu::RenderPipeline,
    positions: wgpu::Buffer,
    normals: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_format: wgpu::IndexFormat,
    index_count: u32,
}

impl MeshRenderer {
    /// Builds the pipeline for `target`.
    pub fn new(device: &wgpu::Device, target: &Target, asset: &GpuAsset) -> Self {
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("mesh frame"),
            size: std::mem::size_of::<MeshUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("mesh"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mesh"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            }],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("mesh.wgsl"),
            source: wgpu::ShaderSource::Wgsl(shaders::MESH.into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mesh"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let vertex_buffer = |location| wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: if location == 0 {
                &wgpu::vertex_attr_array![0 => Float32x3]
            } else {
                &wgpu::vertex_attr_array![1 => Float32x3]
            },
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("mesh"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("mesh_vertex"),
                compilation_options: Default::default(),
                buffers: &[Some(vertex_buffer(0)), Some(vertex_buffer(1))],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: target.depth(true, wgpu::CompareFunction::Less),
            multisample: target.multisample(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("mesh_fragment"),
                compilation_options: Default::default(),
                targets: &[Some(target.blended_color())],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self {
            uniform,
            group,
            pipeline,
            positions: asset.render_positions.clone(),
            normals: asset.render_normals.clone(),
            indices: asset.mesh_indices.clone(),
            index_format: asset.index_format,
            index_count: asset.index_count,
        }
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
        let uniform = MeshUniform {
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
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        pass.set_vertex_buffer(0, self.positions.slice(..));
        pass.set_vertex_buffer(1, self.normals.slice(..));
        pass.set_index_buffer(self.indices.slice(..), self.index_format);
        pass.draw_indexed(0..self.index_count, 0, 0..1);
    }
}
