//! The runtime's simple lit mesh pass, for applications without their own (and for `chamfer render`).

use std::sync::Arc;

use glam::Vec3;

use super::bindings::{Binding, Bindings, Kind};
use super::environment::EnvironmentBuffer;
use super::gpu_asset::VERTEX_LAYOUTS;
use super::layout::{MeshFrame, SHADE_ENVIRONMENT, SHADE_PBR};
use super::lighting::punctual;
use super::modules::{Program, Shader};
use super::pipelines::{PipelineSet, Raster};
use super::techniques::Blocks;
use super::{Camera, GpuAsset, Instance, Light, Pipelines, RenderError};
use crate::highlight::environment::Environment;
use crate::highlight::ggx::PbrMaterial;
use crate::section::ClipPlanes;

/// Where the mesh's light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeshLight {
    /// A headlight: towards the light in view space (x right, y up, z towards the viewer).
    View([f32; 3]),
    /// A light fixed to the model (the chamfer highlight's light, for matching shading).
    Model(Light),
}

/// How the mesh looks: `color × (ambient + (1 − ambient) E (N·L)₊) + specular E (N·H)₊^shininess`
/// with `E` the light's colour (Blinn; with `ambient` 0, `color` = R_d and `specular` = R_s it is the
/// highlight's model exactly), or with `pbr` glTF's metallic-roughness model as
/// [`Shading::Pbr`](super::lighting::Shading::Pbr) shades chamfer strips.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshStyle {
    /// Straight-alpha RGBA base colour.
    pub color: [f32; 4],
    /// The light.
    pub light: MeshLight,
    /// The light's colour × intensity (linear RGB), as [`Highlight::color`](super::Highlight::color).
    pub light_color: [f32; 3],
    /// Share of the colour lit regardless of the light, 0..1 (with `pbr`: the radiance of a uniform
    /// white environment, reflected diffusely and by the specular lobe's directional albedo).
    pub ambient: f32,
    /// Specular reflectance `R_s` (white), 0 for none.
    pub specular: f32,
    /// Specular exponent.
    pub shininess: f32,
    /// Shade with glTF's metallic-roughness model and this material instead of Blinn's: its base
    /// colour replaces `color`'s RGB (the alpha stays), `specular` and `shininess` are unused, and
    /// point and spot lights fall off as 1/d².
    pub pbr: Option<PbrMaterial>,
    /// Section planes in world space (issue 43): what they cut away is not drawn. Give the edges'
    /// style the same ([`EdgeStyle::section`](super::EdgeStyle::section)); an
    /// [`Instance`] may have its own.
    pub section: ClipPlanes,
}

impl Default for MeshStyle {
    fn default() -> Self {
        Self {
            color: [0.86, 0.86, 0.84, 1.0],
            light: MeshLight::View([-0.4, 0.6, 0.7]),
            light_color: [1.0; 3],
            ambient: 0.35,
            specular: 0.0,
            shininess: 32.0,
            pbr: None,
            section: ClipPlanes::NONE,
        }
    }
}

const MESH: Bindings = Bindings::draw(
    "mesh",
    &[
        Binding::new(0, "mesh", Kind::Block),
        Binding::new(1, "environment", Kind::Read),
    ],
);

/// The mesh pass's module.
pub(crate) fn shader() -> Shader {
    Shader::new(
        "mesh.wgsl",
        &[
            chamfer_shaders::BRDF,
            chamfer_shaders::ENVIRONMENT,
            chamfer_shaders::SECTION,
            chamfer_shaders::MESH,
        ],
        vec![Program::draw("mesh_vertex", "mesh_fragment", &MESH)],
    )
}

/// The mesh pipeline, per device and target.
#[derive(Debug)]
pub(crate) struct Pipeline {
    pipeline: wgpu::RenderPipeline,
}

impl PipelineSet for Pipeline {
    fn new(cache: &Pipelines) -> Result<Self, RenderError> {
        let shader = shader();
        let target = cache.target();
        let pipeline = cache.compile(&shader)?.render(
            "mesh_vertex",
            Some("mesh_fragment"),
            Raster {
                buffers: &VERTEX_LAYOUTS,
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: target.depth(true, wgpu::CompareFunction::Less),
                multisample: target.multisample(),
                color: Some(target.blended_color()),
            },
        )?;
        Ok(Self { pipeline })
    }
}

/// Draws assets' triangles with their crease-split normals, writing depth for the edges: one asset
/// ([`MeshRenderer::new`]) or the instances of a scene ([`MeshRenderer::prepare_scene`]).
#[derive(Debug)]
pub struct MeshRenderer {
    pipeline: Arc<Pipeline>,
    cache: Pipelines,
    blocks: Blocks,
    group: Option<wgpu::BindGroup>,
    asset: Option<GpuAsset>,
    /// Per instance of this frame: its block and asset.
    draws: Vec<(u32, GpuAsset)>,
    /// The image-based light, when one is set.
    environment: Option<Arc<Environment>>,
    environment_maps: EnvironmentBuffer,
}

impl MeshRenderer {
    /// A mesh pass for `asset` with the pipeline of `pipelines` (compiled once per target).
    pub fn new(pipelines: &Pipelines, asset: &GpuAsset) -> Result<Self, RenderError> {
        let mut renderer = Self::for_scenes(pipelines)?;
        renderer.asset = Some(asset.clone());
        Ok(renderer)
    }

    /// A mesh pass for the instances given to [`prepare_scene`](Self::prepare_scene).
    pub fn for_scenes(pipelines: &Pipelines) -> Result<Self, RenderError> {
        Ok(Self {
            pipeline: pipelines.get::<Pipeline>()?,
            cache: pipelines.clone(),
            blocks: Blocks::new(pipelines, "mesh frame", std::mem::size_of::<MeshFrame>()),
            group: None,
            asset: None,
            draws: Vec::new(),
            environment: None,
            environment_maps: EnvironmentBuffer::new(pipelines.device()),
        })
    }

    /// Lights physically based meshes ([`MeshStyle::pbr`]) by `environment` too (its directions in
    /// model space, as [`Light`]'s), from the next `prepare` on; `None` removes it.
    pub fn set_environment(&mut self, environment: Option<Arc<Environment>>) {
        self.environment = environment;
    }

    /// Sets this frame's camera and style for the asset given to [`new`](Self::new) (nothing is
    /// drawn for a renderer made [`for_scenes`](Self::for_scenes)).
    pub fn prepare(&mut self, queue: &wgpu::Queue, camera: &Camera, style: &MeshStyle) {
        match self.asset.clone() {
            Some(asset) => self.prepare_scene(queue, camera, &[Instance::new(&asset)], style),
            None => self.prepare_scene(queue, camera, &[], style),
        }
    }

    /// Sets this frame's camera, instances and style.
    pub fn prepare_scene(
        &mut self,
        queue: &wgpu::Queue,
        camera: &Camera,
        instances: &[Instance<'_>],
        style: &MeshStyle,
    ) {
        let lit_by_environment = style.pbr.is_some_and(|material| {
            self.environment_maps
                .update(queue, self.environment.as_ref(), material.alpha())
        });
        let frames: Vec<MeshFrame> = instances
            .iter()
            .map(|instance| {
                let camera = Camera {
                    model_view: camera.model_view * instance.transform,
                    ..*camera
                };
                // A light fixed to the model is the instance's own where it has one, as the
                // highlight's is.
                let style = match (style.light, instance.light) {
                    (MeshLight::Model(_), Some(own)) => MeshStyle {
                        light: MeshLight::Model(own),
                        ..*style
                    },
                    _ => *style,
                };
                let mut frame = mesh_frame(&camera, &style);
                frame.section = instance.model_section(&style.section).rows();
                if lit_by_environment {
                    frame.pbr |= SHADE_ENVIRONMENT;
                }
                frame
            })
            .collect();
        if self.blocks.write(&self.cache, queue, &frames) {
            self.group = None;
        }
        if self.group.is_none() {
            let layout = self.cache.layout(&MESH);
            let (blocks, maps) = (&self.blocks, &self.environment_maps.buffer);
            // A group of a block and a buffer cannot fail to be made.
            self.group = MESH
                .group(self.cache.device(), &layout, |binding| {
                    Ok(match binding.index {
                        0 => blocks.binding(),
                        _ => maps.as_entire_binding(),
                    })
                })
                .ok();
        }
        self.draws = instances
            .iter()
            .enumerate()
            .map(|(i, instance)| (self.blocks.offset(i), instance.asset.clone()))
            .collect();
    }

    /// Draws the mesh (or the scene's meshes) into `pass`.
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(group) = &self.group else {
            return;
        };
        pass.set_pipeline(&self.pipeline.pipeline);
        for (offset, asset) in &self.draws {
            pass.set_bind_group(0, group, &[*offset]);
            super::techniques::draw_mesh(pass, asset);
        }
    }
}

/// The mesh pass's uniform for `camera` (already in the instance's model space).
fn mesh_frame(camera: &Camera, style: &MeshStyle) -> MeshFrame {
    let light = match style.light {
        MeshLight::View(towards) => Light::Directional(
            camera
                .model_view
                .inverse()
                .transform_vector3(Vec3::from(towards))
                .to_array(),
        ),
        MeshLight::Model(light) => light,
    };
    let mut color = style.color;
    let (pbr, surface) = match &style.pbr {
        Some(material) => {
            let [r, g, b] = material.clamped_base().to_array();
            color = [r, g, b, color[3]];
            (
                SHADE_PBR,
                [material.clamped_metallic(), material.alpha(), 0.0, 0.0],
            )
        }
        None => (0, [0.0; 4]),
    };
    MeshFrame {
        mvp: camera.view_projection().to_cols_array_2d(),
        light: punctual(&light, style.light_color, style.pbr.is_some()),
        color,
        ambient: style.ambient.clamp(0.0, 1.0),
        specular: style.specular.max(0.0),
        shininess: style.shininess.max(0.0),
        pbr,
        eye: camera.eye().to_array(),
        surface,
        section: style.section.rows(),
    }
}
