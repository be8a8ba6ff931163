//! The edge renderer: per-frame GPU classification, compaction, joins and caps, then quads.

use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec3;

use super::lighting::{Highlight, Light, LightingUniform};
use super::{Camera, GpuAsset, RenderError, Target, shaders};
use crate::asset::EdgeFlags;

/// Which edge classes to draw; combine with `|`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeClasses(pub u32);

impl EdgeClasses {
    /// Silhouette edges of this frame: one face towards the camera, one away (thesis §6.1).
    pub const CONTOUR: Self = Self(1 << 8);
    /// Edges with one face, and edges with more than two.
    pub const BOUNDARY: Self = Self((EdgeFlags::BOUNDARY.0 | EdgeFlags::NON_MANIFOLD.0) as u32);
    /// Convex creases.
    pub const RIDGE: Self = Self(EdgeFlags::RIDGE.0 as u32);
    /// Concave creases.
    pub const VALLEY: Self = Self(EdgeFlags::VALLEY.0 as u32);
    /// Edges marked in the source file, and material seams.
    pub const MARKED: Self = Self((EdgeFlags::MARKED.0 | EdgeFlags::MATERIAL.0) as u32);
    /// Both crease directions.
    pub const CREASE: Self = Self(Self::RIDGE.0 | Self::VALLEY.0);
    /// Every class.
    pub const ALL: Self =
        Self(Self::CONTOUR.0 | Self::BOUNDARY.0 | Self::CREASE.0 | Self::MARKED.0);
    /// No class: nothing is drawn.
    pub const NONE: Self = Self(0);

    /// True if every class of `other` is in `self`.
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }
}

impl std::ops::BitOr for EdgeClasses {
    type Output = Self;
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

/// Straight-alpha RGBA colour per class. An edge in several classes takes the first of: contour,
/// boundary, marked, ridge, valley.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeColors {
    /// Silhouettes.
    pub contour: [f32; 4],
    /// Boundary and non-manifold edges.
    pub boundary: [f32; 4],
    /// Marked edges and material seams.
    pub marked: [f32; 4],
    /// Convex creases.
    pub ridge: [f32; 4],
    /// Concave creases.
    pub valley: [f32; 4],
}

impl Default for EdgeColors {
    fn default() -> Self {
        Self {
            contour: [0.0, 0.0, 0.0, 1.0],
            boundary: [0.75, 0.1, 0.1, 1.0],
            marked: [0.95, 0.55, 0.05, 1.0],
            ridge: [0.08, 0.08, 0.1, 1.0],
            valley: [0.1, 0.25, 0.6, 1.0],
        }
    }
}

/// How the gaps and overlaps where drawn edges meet are resolved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CapMethod {
    /// One thread per drawn edge end walks its vertex's next-index ring (thesis §13): the work
    /// follows the drawn edges.
    #[default]
    NextIndex,
    /// One thread per vertex with two or more edges walks its ring from the cap buffer's head
    /// (thesis §10.5): the work follows the mesh. Up to 16 drawn edges per vertex are joined.
    CapBuffer,
    /// Plain quads: gaps at bends and double coverage where quads overlap (McGuire–Hughes
    /// without caps). For comparison.
    None,
}

/// How edges look; given to [`EdgeRenderer::prepare`] each frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeStyle {
    /// Classes to draw.
    pub classes: EdgeClasses,
    /// Colour per class.
    pub colors: EdgeColors,
    /// Line width in pixels.
    pub width_px: f32,
    /// Scale the width with depth (thesis §9.1): `width_px` at the model's centre, wider in front,
    /// narrower behind, never below `min_width_px`. Perspective cameras only.
    pub depth_scaled: bool,
    /// Lower bound of a depth-scaled width, pixels.
    pub min_width_px: f32,
    /// How far, in pixels' worth of world distance at the edge's depth, edges are pulled towards the
    /// camera for the depth test. `None`: `1 + 1.5 × width`, enough for faces up to about 55° from
    /// the view direction across the quad's half-width, far less than any real occluder's distance.
    pub depth_bias_px: Option<f32>,
    /// How edges join.
    pub caps: CapMethod,
    /// Draw contours as half quads outside the silhouette (thesis §8.3), full width.
    pub half_quad_contours: bool,
    /// Skip creases and marked edges whose two faces both look away (closed meshes hide them anyway).
    pub cull_back_facing: bool,
    /// Draw chamfer edges (those with a radius) as lit rounded strips (seed 000) instead of lines.
    pub highlight: Option<Highlight>,
}

impl Default for EdgeStyle {
    fn default() -> Self {
        Self {
            classes: EdgeClasses::ALL,
            colors: EdgeColors::default(),
            width_px: 2.0,
            depth_scaled: false,
            min_width_px: 1.0,
            depth_bias_px: None,
            caps: CapMethod::NextIndex,
            half_quad_contours: true,
            cull_back_facing: true,
            highlight: None,
        }
    }
}

/// The per-frame uniform; its layout is `Frame` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct FrameUniform {
    mvp: [[f32; 4]; 4],
    eye: [f32; 4],
    proj_z: [f32; 4],
    colors: [[f32; 4]; 5],
    viewport: [f32; 2],
    pixel_scale: f32,
    width: f32,
    min_width: f32,
    depth_ref: f32,
    bias_px: f32,
    classes: u32,
    cull_back: u32,
    edges_u16: u32,
    rings_u16: u32,
    edge_count: u32,
    head_count: u32,
    heads_offset: u32,
    half_quads: u32,
    cap_capacity: u32,
    highlight: u32,
    radius_scale: f32,
    _pad: [u32; 2],
}

/// Bytes of `Out` in the shaders before the cap list: two indirect draws and padding.
const OUT_HEADER: u64 = 48;
/// Bytes of one `Cap`.
const CAP_BYTES: u64 = 20;
/// Offset of the cap draw's arguments in the `out` buffer.
const CAP_DRAW_OFFSET: u64 = 16;
const WORKGROUP: u32 = 256;

/// Draws one [`GpuAsset`]'s edges. Create one per asset you draw (it holds that asset's per-frame
/// lists); each frame call [`prepare`](Self::prepare), [`compute`](Self::compute) before the render
/// pass, then [`render`](Self::render) inside it, after the mesh.
#[derive(Debug)]
pub struct EdgeRenderer {
    frame: wgpu::Buffer,
    out: wgpu::Buffer,
    dispatch: wgpu::Buffer,
    planes_group: wgpu::BindGroup,
    classify_group: wgpu::BindGroup,
    joins_group: wgpu::BindGroup,
    args_group: wgpu::BindGroup,
    draw_group: wgpu::BindGroup,
    /// The face planes are computed by the first [`EdgeRenderer::compute`].
    planes_ready: AtomicBool,
    face_planes: wgpu::ComputePipeline,
    chamfer_records: wgpu::ComputePipeline,
    records_group: wgpu::BindGroup,
    cos_power: wgpu::Buffer,
    lighting: wgpu::Buffer,
    /// The exponent the cos-power row holds now.
    row_exponent: Option<f32>,
    highlight: bool,
    reset: wgpu::ComputePipeline,
    classify: wgpu::ComputePipeline,
    args: wgpu::ComputePipeline,
    joins_next: wgpu::ComputePipeline,
    joins_heads: wgpu::ComputePipeline,
    clear_joins: wgpu::ComputePipeline,
    finish: wgpu::ComputePipeline,
    edge_pipeline: wgpu::RenderPipeline,
    cap_pipeline: wgpu::RenderPipeline,
    edge_count: u32,
    head_count: u32,
    has_rings: bool,
    center: Vec3,
    uniform: FrameUniform,
    caps: CapMethod,
}

impl EdgeRenderer {
    /// Builds the pipelines for `target` and the per-frame lists for `asset`.
    ///
    /// Fails with [`RenderError::TooLarge`] if a per-frame list exceeds the device's binding limit.
    pub fn new(
        device: &wgpu::Device,
        target: &Target,
        asset: &GpuAsset,
    ) -> Result<Self, RenderError> {
        let edges = u64::from(asset.edge_count);
        let cap_capacity = edges + 64;
        let limit = device.limits().max_storage_buffer_binding_size;
        let storage = |what: &'static str, bytes: u64, usage: wgpu::BufferUsages| {
            if bytes > limit {
                return Err(RenderError::TooLarge { what, bytes, limit });
            }
            Ok(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(what),
                size: bytes.max(64),
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            }))
        };
        let none = wgpu::BufferUsages::empty();
        let state = storage("edge state", 4 * edges, none)?;
        let drawn = storage("drawn edges", 8 * edges, none)?;
        let joins = storage("joins", 16 * edges, none)?;
        let indirect = wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_SRC;
        let out = storage(
            "edge draw lists",
            OUT_HEADER + CAP_BYTES * cap_capacity,
            indirect,
        )?;
        let dispatch = storage("joins dispatch", 16, indirect)?;
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("edge frame"),
            size: std::mem::size_of::<FrameUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });

        let planes = storage("face planes", 32 * edges, none)?;
        let screen = storage("screen quads", 48 * edges, none)?;
        // Highlight records, only where the asset has chamfer edges to highlight.
        let chamfer_slots = if asset.has_chamfers { edges } else { 0 };
        let chamfers = storage("chamfer records", 64 * chamfer_slots, none)?;
        let cos_power = storage(
            "cos power row",
            4 * (crate::highlight::table::SAMPLES as u64 + 1),
            wgpu::BufferUsages::COPY_DST,
        )?;
        let lighting = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("highlight lighting"),
            size: std::mem::size_of::<LightingUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });

        // Binding numbers are the shaders' (common.wgsl, compute.wgsl, draw.wgsl); each pass binds
        // only what it uses, which keeps every stage within the default limit of 8 storage buffers.
        let buffers: [(u32, &wgpu::Buffer); 14] = [
            (0, &frame),
            (1, &asset.topology_positions),
            (2, &asset.edge_vertices),
            (3, &asset.edge_attributes),
            (4, &asset.rings),
            (5, &state),
            (6, &drawn),
            (7, &joins),
            (8, &out),
            (9, &planes),
            (10, &screen),
            (11, &chamfers),
            (12, &cos_power),
            (13, &lighting),
        ];
        let bindings = |label, stages, storage: &[(u32, Access)]| {
            binding_set(device, label, stages, &buffers, storage)
        };
        let compute = wgpu::ShaderStages::COMPUTE;
        let (read, write, uniform) = (Access::Read, Access::Write, Access::Uniform);
        let planes_set = bindings(
            "face planes",
            compute,
            &[(1, read), (2, read), (3, read), (9, write)],
        );
        let classify_set = bindings(
            "classify",
            compute,
            &[
                (1, read),
                (2, read),
                (3, read),
                (5, write),
                (6, write),
                (8, write),
                (9, write),
                (10, write),
            ],
        );
        let joins_set = bindings(
            "joins",
            compute,
            &[
                (4, read),
                (5, write),
                (6, write),
                (7, write),
                (8, write),
                (10, write),
            ],
        );
        let records_set = bindings(
            "chamfer records",
            compute,
            &[
                (1, read),
                (2, read),
                (3, read),
                (6, write),
                (8, write),
                (9, write),
                (10, write),
                (11, write),
            ],
        );
        let draw_set = bindings(
            "edge draw",
            wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
            &[
                (6, read),
                (7, read),
                (8, read),
                (10, read),
                (11, read),
                (12, read),
                (13, uniform),
            ],
        );
        let args_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("edge args"),
            entries: &[
                storage_entry(0, true, compute),
                storage_entry(1, false, compute),
            ],
        });
        let args_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("edge args"),
            layout: &args_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: out.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: dispatch.as_entire_binding(),
                },
            ],
        });

        let module = |label, source: &str| {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            })
        };
        let classify_module = module("classify.wgsl", &shaders::classify());
        let joins_module = module("joins.wgsl", &shaders::joins());
        let args_module = module("args.wgsl", shaders::ARGS);
        let compute_pipeline = |layout: &wgpu::BindGroupLayout,
                                module: &wgpu::ShaderModule,
                                entry: &str| {
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
        };

        let draw_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("edge draw"),
            bind_group_layouts: &[Some(&draw_set.0)],
            immediate_size: 0,
        });
        let draw_pipeline = |label, module: &wgpu::ShaderModule, vertex: &str, fragment: &str| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&draw_pipeline_layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some(vertex),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: target.depth(false, wgpu::CompareFunction::LessEqual),
                multisample: target.multisample(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(fragment),
                    compilation_options: Default::default(),
                    targets: &[Some(target.blended_color())],
                }),
                multiview_mask: None,
                cache: None,
            })
        };

        Ok(Self {
            face_planes: compute_pipeline(&planes_set.0, &classify_module, "face_planes"),
            chamfer_records: compute_pipeline(
                &records_set.0,
                &module("chamfers.wgsl", &shaders::chamfers()),
                "chamfer_records",
            ),
            records_group: records_set.1,
            cos_power,
            lighting,
            row_exponent: None,
            highlight: false,
            reset: compute_pipeline(&classify_set.0, &classify_module, "reset"),
            classify: compute_pipeline(&classify_set.0, &classify_module, "classify"),
            finish: compute_pipeline(&classify_set.0, &classify_module, "finish"),
            args: compute_pipeline(&args_layout, &args_module, "args"),
            joins_next: compute_pipeline(&joins_set.0, &joins_module, "joins_next"),
            joins_heads: compute_pipeline(&joins_set.0, &joins_module, "joins_heads"),
            clear_joins: compute_pipeline(&joins_set.0, &joins_module, "clear_joins"),
            edge_pipeline: draw_pipeline(
                "edges",
                &module("edges.wgsl", &shaders::edges()),
                "edge_vertex_main",
                "edge_fragment",
            ),
            cap_pipeline: draw_pipeline(
                "caps",
                &module("caps.wgsl", &shaders::caps()),
                "cap_vertex_main",
                "cap_fragment",
            ),
            frame,
            out,
            dispatch,
            planes_group: planes_set.1,
            classify_group: classify_set.1,
            joins_group: joins_set.1,
            args_group,
            draw_group: draw_set.1,
            planes_ready: AtomicBool::new(false),
            edge_count: asset.edge_count,
            head_count: asset.head_count,
            has_rings: asset.has_rings,
            center: (Vec3::from(asset.bounds[0]) + Vec3::from(asset.bounds[1])) * 0.5,
            uniform: FrameUniform {
                edges_u16: u32::from(asset.edges_u16),
                rings_u16: u32::from(asset.rings_u16),
                edge_count: asset.edge_count,
                head_count: asset.head_count,
                heads_offset: asset.heads_offset,
                cap_capacity: cap_capacity as u32,
                radius_scale: asset.radius_scale,
                ..bytemuck::Zeroable::zeroed()
            },
            caps: CapMethod::NextIndex,
        })
    }

    /// Sets this frame's camera and style.
    pub fn prepare(&mut self, queue: &wgpu::Queue, camera: &Camera, style: &EdgeStyle) {
        let mvp = camera.view_projection();
        let depth_ref = if style.depth_scaled && !camera.is_orthographic() {
            (mvp * self.center.extend(1.0)).w.max(1e-6)
        } else {
            0.0
        };
        let width = style.width_px.max(0.0);
        let c = &style.colors;
        self.uniform = FrameUniform {
            mvp: mvp.to_cols_array_2d(),
            eye: camera.eye().to_array(),
            proj_z: camera.projection.z_axis.to_array(),
            colors: [c.contour, c.boundary, c.marked, c.ridge, c.valley],
            viewport: camera.viewport.map(|v| v.max(1) as f32),
            pixel_scale: camera.pixel_scale(),
            width,
            min_width: style.min_width_px.max(0.0),
            depth_ref,
            bias_px: style.depth_bias_px.unwrap_or(1.0 + 1.5 * width),
            classes: style.classes.0,
            cull_back: u32::from(style.cull_back_facing),
            half_quads: u32::from(style.half_quad_contours),
            ..self.uniform
        };
        self.highlight = false;
        if let Some(highlight) = &style.highlight {
            self.highlight = true;
            let material = highlight.material;
            let exponent = material.shininess.clamp(1.0, 128.0) + 1.0;
            if self.row_exponent != Some(exponent) {
                let row = crate::highlight::table::CosPowerRow::new(exponent);
                queue.write_buffer(&self.cos_power, 0, bytemuck::cast_slice(row.values()));
                self.row_exponent = Some(exponent);
            }
            let light = match highlight.light {
                Light::Directional(d) => {
                    let d = Vec3::from(d).normalize_or(Vec3::Z);
                    [d.x, d.y, d.z, 0.0]
                }
                Light::Point([x, y, z]) => [x, y, z, 1.0],
            };
            let k = highlight
                .k
                .unwrap_or_else(|| camera.eye().truncate().distance(self.center));
            let [r, g, b] = highlight.color;
            let uniform = LightingUniform {
                light,
                color: [r, g, b, k],
                material: [
                    material.diffuse,
                    material.specular,
                    exponent - 1.0,
                    highlight.ambient.clamp(0.0, 1.0),
                ],
            };
            queue.write_buffer(&self.lighting, 0, bytemuck::bytes_of(&uniform));
        }
        self.uniform.highlight = u32::from(self.highlight);
        self.caps = if self.has_rings {
            style.caps
        } else {
            CapMethod::None
        };
        queue.write_buffer(&self.frame, 0, bytemuck::bytes_of(&self.uniform));
    }

    /// Records this frame's classification and joins into `encoder`; call before the render pass.
    pub fn compute(&self, encoder: &mut wgpu::CommandEncoder) {
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("chamfer classify"),
                timestamp_writes: None,
            });
            let [x, y] = workgroups(self.edge_count);
            if !self.planes_ready.swap(true, Ordering::Relaxed) {
                pass.set_bind_group(0, &self.planes_group, &[]);
                pass.set_pipeline(&self.face_planes);
                pass.dispatch_workgroups(x, y, 1);
            }
            pass.set_bind_group(0, &self.classify_group, &[]);
            pass.set_pipeline(&self.reset);
            pass.dispatch_workgroups(1, 1, 1);
            pass.set_pipeline(&self.classify);
            pass.dispatch_workgroups(x, y, 1);
            if self.caps != CapMethod::None || self.highlight {
                pass.set_bind_group(0, &self.args_group, &[]);
                pass.set_pipeline(&self.args);
                pass.dispatch_workgroups(1, 1, 1);
            }
        }
        if self.caps == CapMethod::None && !self.highlight {
            return;
        }
        // A new pass: the dispatch arguments written above are read as an indirect buffer here.
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("chamfer joins"),
            timestamp_writes: None,
        });
        if self.highlight {
            // One thread per drawn edge end: twice as many as records need; the rest return.
            pass.set_bind_group(0, &self.records_group, &[]);
            pass.set_pipeline(&self.chamfer_records);
            pass.dispatch_workgroups_indirect(&self.dispatch, 0);
        }
        pass.set_bind_group(0, &self.joins_group, &[]);
        match self.caps {
            CapMethod::NextIndex => {
                pass.set_pipeline(&self.joins_next);
                pass.dispatch_workgroups_indirect(&self.dispatch, 0);
            }
            CapMethod::CapBuffer => {
                pass.set_pipeline(&self.clear_joins);
                pass.dispatch_workgroups_indirect(&self.dispatch, 0);
                pass.set_pipeline(&self.joins_heads);
                let [x, y] = workgroups(self.head_count);
                pass.dispatch_workgroups(x, y, 1);
            }
            CapMethod::None => {}
        }
        pass.set_bind_group(0, &self.classify_group, &[]);
        pass.set_pipeline(&self.finish);
        pass.dispatch_workgroups(1, 1, 1);
    }

    /// Draws this frame's edges and caps into `pass` (after the mesh, against its depth).
    pub fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(0, &self.draw_group, &[]);
        pass.set_pipeline(&self.edge_pipeline);
        pass.draw_indirect(&self.out, 0);
        if self.caps != CapMethod::None {
            pass.set_pipeline(&self.cap_pipeline);
            pass.draw_indirect(&self.out, CAP_DRAW_OFFSET);
        }
    }
}

/// What the last computed frame drew, read back from the GPU (see [`EdgeRenderer::read_counts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawCounts {
    /// Edges that passed classification.
    pub edges: u32,
    /// Caps the joins emitted.
    pub caps: u32,
}

impl EdgeRenderer {
    /// Reads back how many edges and caps the last submitted [`compute`](Self::compute) produced.
    /// Blocks until the GPU is idle: for statistics, tests and benchmarks, not for every frame.
    pub fn read_counts(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<DrawCounts, RenderError> {
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("edge counts readback"),
            size: 32,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("edge counts readback"),
        });
        encoder.copy_buffer_to_buffer(&self.out, 0, &staging, 0, 32);
        queue.submit([encoder.finish()]);
        let bytes = super::offscreen::map_read(device, &staging)?;
        let words: &[u32] = bytemuck::cast_slice(&bytes);
        Ok(DrawCounts {
            edges: words[1],
            caps: if self.caps == CapMethod::None {
                0
            } else {
                words[5]
            },
        })
    }
}

/// Workgroups covering `items` threads, spread over two dimensions past 65535.
fn workgroups(items: u32) -> [u32; 2] {
    let groups = items.div_ceil(WORKGROUP);
    let x = groups.min(65_535);
    [x, if x == 0 { 0 } else { groups.div_ceil(x) }]
}

fn storage_entry(
    binding: u32,
    read_only: bool,
    visibility: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// How a pass uses a binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Access {
    Read,
    Write,
    Uniform,
}

/// A layout and its bind group: the frame uniform at binding 0 plus `bindings`, whose buffers are
/// taken from `buffers` by binding number.
fn binding_set(
    device: &wgpu::Device,
    label: &str,
    visibility: wgpu::ShaderStages,
    buffers: &[(u32, &wgpu::Buffer)],
    bindings: &[(u32, Access)],
) -> (wgpu::BindGroupLayout, wgpu::BindGroup) {
    let uniform = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let mut entries = vec![uniform(0)];
    entries.extend(bindings.iter().map(|&(binding, access)| match access {
        Access::Read => storage_entry(binding, true, visibility),
        Access::Write => storage_entry(binding, false, visibility),
        Access::Uniform => uniform(binding),
    }));
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &entries,
    });
    let resources: Vec<wgpu::BindGroupEntry> = entries
        .iter()
        .filter_map(|entry| {
            let (_, buffer) = buffers.iter().find(|(b, _)| *b == entry.binding)?;
            Some(wgpu::BindGroupEntry {
                binding: entry.binding,
                resource: buffer.as_entire_binding(),
            })
        })
        .collect();
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout: &layout,
        entries: &resources,
    });
    (layout, group)
}
