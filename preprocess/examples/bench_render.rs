//! Frame-time benchmark of the runtime, headless, beside a naive edge pass in the same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_render -- [--frames 15] [--size 1920x1080]
//!     [--caps next-index|cap-buffer|none] [--radius-rel 0.004] [MESH...]
//! ```
//! Meshes are baked with chamfer radii (`--radius-rel` of the diagonal on ridges; 0: none), so the
//! highlight column times strips, rounded corners and the outline pass after the mesh.
//! With no mesh it benches `fixtures/meshes/stanford-bunny.obj` and the largest shared mesh,
//! `bunny-loop2.ply.gz`. Per mesh, the configurations run round-robin (one frame of each in turn, so
//! drifts of a shared machine hit all alike) after a warm-up that compiles every pipeline; each frame is
//! timed from encoding to the GPU finishing (`submit` + `poll(wait)`), and the table shows medians.
//!
//! The unculled columns are the same frames with `EdgeStyle::cluster_culling` off (every edge
//! classified, the path before issue 14), in the same round-robin. GPU bytes per edge count the
//! asset's edge sections ([`GpuAsset::edge_bytes`]: not the mesh's own buffers) and the renderer's
//! per-frame state after the timed frames.
//!
//! The naive baseline is McGuire–Hughes' layout as the thesis measures it (§8.3): every edge is drawn
//! as a quad of 4 vertices (6 indices), each vertex shader instance classifies its edge again, and edges
//! that are not drawn become degenerate quads — no compaction, no indirect draw, no caps.

use std::path::{Path, PathBuf};
use std::time::Instant;

use chamfer_runtime::asset::Asset;
use chamfer_runtime::render::{
    Camera, CapMethod, EdgeRenderer, EdgeStyle, GpuAsset, MeshRenderer, MeshStyle, Offscreen,
    OffscreenTarget, Orbit, Pipelines,
};
use wgpu::util::DeviceExt;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut frames = 15;
    let mut size = [1920, 1080];
    let mut caps = CapMethod::NextIndex;
    let mut radius_rel = 0.004f32;
    let mut meshes = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--frames" => frames = args.next().ok_or("--frames needs a number")?.parse()?,
            "--size" => {
                let text = args.next().ok_or("--size needs WxH")?;
                let (w, h) = text.split_once('x').ok_or("--size needs WxH")?;
                size = [w.parse()?, h.parse()?];
            }
            "--caps" => {
                caps = match args.next().as_deref() {
                    Some("next-index") => CapMethod::NextIndex,
                    Some("cap-buffer") => CapMethod::CapBuffer,
                    Some("none") => CapMethod::None,
                    _ => return Err("--caps needs next-index, cap-buffer or none".into()),
                }
            }
            "--radius-rel" => {
                radius_rel = args.next().ok_or("--radius-rel needs a number")?.parse()?
            }
            _ => meshes.push(PathBuf::from(arg)),
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/meshes");
    if meshes.is_empty() {
        meshes = vec![
            root.join("stanford-bunny.obj"),
            root.join("bunny-loop2.ply.gz"),
        ];
    }
    let gpu = Offscreen::new()?;
    println!(
        "adapter: {} ({:?}), {}x{}, 1 sample, {frames} frames per row (medians)\n",
        gpu.info.name, gpu.info.backend, size[0], size[1]
    );
    println!(
        "| mesh | triangles | edges | drawn edges | mesh only ms | + edges + caps ms | edges overhead | + naive edges ms | naive overhead | edge pass: naive / ours | classify + joins only ms | edge + cap draws only ms | + edges + highlight ms | highlight overhead | clusters kept | + edges + caps unculled ms | unculled overhead | classify + joins unculled ms | classify + joins: unculled / culled | GPU bytes per edge (asset + frame) |"
    );
    println!(
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for mesh in &meshes {
        let options = chamfer_preprocess::BakeOptions::DEFAULT;
        let options = if radius_rel > 0.0 {
            options.with_radius(chamfer_preprocess::Radius::Relative(radius_rel))
        } else {
            options
        };
        let asset = chamfer_preprocess::bake_file(mesh, &options)?.asset;
        bench(&gpu, &asset, mesh, size, frames, caps)?;
    }
    Ok(())
}

fn bench(
    gpu: &Offscreen,
    asset: &Asset,
    path: &Path,
    size: [u32; 2],
    frames: usize,
    caps: CapMethod,
) -> Result<(), Box<dyn std::error::Error>> {
    let target = gpu.target(size[0], size[1], 1)?;
    let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
    let uploaded = GpuAsset::new(&gpu.device, asset)?;
    let camera = Camera::orbit(uploaded.bounds(), &Orbit::default(), size);
    let style = EdgeStyle {
        caps,
        ..EdgeStyle::default()
    };
    let lit_style = EdgeStyle {
        highlight: Some(chamfer_runtime::render::Highlight::default()),
        ..style
    };
    let mut mesh = MeshRenderer::new(&pipelines, &uploaded)?;
    mesh.prepare(&gpu.queue, &camera, &MeshStyle::default());
    let mut edges = EdgeRenderer::new(&pipelines, &uploaded);
    // The naive pass binds the whole edge section: not for assets past one binding (NaN columns).
    let limit = gpu.device.limits().max_storage_buffer_binding_size;
    let naive = (uploaded.edge_vertices().size() <= limit)
        .then(|| NaiveEdges::new(gpu, &target, &uploaded, &camera, &style));
    let mut lit = EdgeRenderer::new(&pipelines, &uploaded);
    let mut unculled = EdgeRenderer::new(&pipelines, &uploaded);
    let unculled_style = EdgeStyle {
        cluster_culling: false,
        ..style
    };

    let mesh_only = || frame(gpu, &target, |_| Ok(()), |pass| mesh.render(pass));
    let with_edges = |edges: &mut EdgeRenderer, style: &EdgeStyle, compute: bool, draw: bool| {
        let start = Instant::now();
        let mut encoder = gpu.encoder();
        let prepared = edges.prepare(&gpu.queue, &mut encoder, &camera, style)?;
        if !compute {
            // The draws alone: drop this frame's compute work, draw what the last frame left.
            encoder = gpu.encoder();
        }
        if draw {
            {
                let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
                mesh.render(&mut pass);
                prepared.render(&mut pass);
            }
            // The highlight's outline pass (nothing without one).
            prepared.finish(&mut encoder, &target.views())?;
        }
        gpu.submit(encoder)?;
        Ok::<f64, Box<dyn std::error::Error>>(start.elapsed().as_secs_f64() * 1e3)
    };
    let with_naive = || {
        let Some(naive) = &naive else {
            return Ok(f64::NAN);
        };
        frame(
            gpu,
            &target,
            |_| Ok(()),
            |pass| {
                mesh.render(pass);
                naive.render(pass);
            },
        )
    };
    let mut times = [(); 8].map(|_| Vec::new());
    for round in 0..frames + 2 {
        let row = [
            mesh_only()?,
            with_edges(&mut edges, &style, true, true)?,
            with_naive()?,
            with_edges(&mut edges, &style, true, false)?,
            with_edges(&mut edges, &style, false, true)?,
            with_edges(&mut lit, &lit_style, true, true)?,
            with_edges(&mut unculled, &unculled_style, true, true)?,
            with_edges(&mut unculled, &unculled_style, true, false)?,
        ];
        // The first two rounds warm up (pipelines compile on first use).
        if round >= 2 {
            for (list, t) in times.iter_mut().zip(row) {
                list.push(t);
            }
        }
    }
    let [m, e, n, c, d, h, u, uc] = times.map(median);
    let counts = edges.read_counts(&gpu.device, &gpu.queue)?;
    let unculled_drawn = drawn_edges(gpu, &unculled)?;
    if unculled_drawn != counts.edges {
        return Err(format!(
            "culled frames drew {} edges, unculled {unculled_drawn}",
            counts.edges
        )
        .into());
    }
    let drawn = counts.edges;
    let clusters = asset.clusters().len().max(1);
    let bytes_per_edge =
        (uploaded.edge_bytes() + edges.gpu_bytes()) as f64 / asset.edge_count().max(1) as f64;
    println!(
        "| {} | {} | {} | {drawn} | {m:.1} | {e:.1} | {:+.0}% | {n:.1} | {:+.0}% | {:.1}× | {c:.1} | {:.1} | {h:.1} | {:+.0}% | {} of {clusters} ({:.1}%) | {u:.1} | {:+.0}% | {uc:.1} | {:.1}× | {bytes_per_edge:.1} |",
        path.file_name()
            .map(|n| n.to_string_lossy())
            .unwrap_or_default(),
        asset.triangle_count(),
        asset.edge_count(),
        (e / m - 1.0) * 100.0,
        (n / m - 1.0) * 100.0,
        (n - m) / (e - m).max(1e-3),
        d - m,
        (h / m - 1.0) * 100.0,
        counts.clusters_kept,
        100.0 * f64::from(counts.clusters_kept) / clusters as f64,
        (u / m - 1.0) * 100.0,
        uc / c.max(1e-3),
    );
    Ok(())
}

fn frame(
    gpu: &Offscreen,
    target: &OffscreenTarget,
    before: impl FnOnce(&mut wgpu::CommandEncoder) -> Result<(), Box<dyn std::error::Error>>,
    inside: impl FnOnce(&mut wgpu::RenderPass<'_>),
) -> Result<f64, Box<dyn std::error::Error>> {
    let start = Instant::now();
    let mut encoder = gpu.encoder();
    before(&mut encoder)?;
    inside(&mut target.begin_pass(&mut encoder, [1.0; 4]));
    gpu.submit(encoder)?;
    Ok(start.elapsed().as_secs_f64() * 1e3)
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// How many edges the last frame drew (the instance count the classification wrote).
fn drawn_edges(gpu: &Offscreen, edges: &EdgeRenderer) -> Result<u32, Box<dyn std::error::Error>> {
    Ok(edges.read_counts(&gpu.device, &gpu.queue)?.edges)
}

/// The naive baseline: all edges, 4 vertices each, classified per vertex.
struct NaiveEdges {
    pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
    indices: wgpu::Buffer,
    index_count: u32,
}

const NAIVE_WGSL: &str = r#"
struct Naive {
    mvp: mat4x4<f32>,
    eye: vec4<f32>,
    proj_z: vec4<f32>,
    viewport: vec2<f32>,
    half_width: f32,
    bias: f32,
    edges_u16: u32,
    classes: u32,
}
@group(0) @binding(0) var<uniform> naive: Naive;
@group(0) @binding(1) var<storage, read> topology: array<f32>;
@group(0) @binding(2) var<storage, read> edge_vertices: array<u32>;
@group(0) @binding(3) var<storage, read> attributes: array<u32>;

fn edge_vertex(i: u32) -> u32 {
    if naive.edges_u16 != 0u {
        return (edge_vertices[i >> 1u] >> ((i & 1u) * 16u)) & 0xffffu;
    }
    return edge_vertices[i];
}
fn position(v: u32) -> vec3<f32> {
    return vec3<f32>(topology[3u * v], topology[3u * v + 1u], topology[3u * v + 2u]);
}
fn faces(n: vec3<f32>, p: vec3<f32>) -> bool {
    return dot(n, naive.eye.xyz - p * naive.eye.w) > 0.0;
}

@vertex
fn naive_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let e = index / 4u;
    let corner = index % 4u;
    let flags = attributes[e] & 0xffffu;
    let p0 = position(edge_vertex(4u * e));
    let p1 = position(edge_vertex(4u * e + 1u));
    let p2 = position(edge_vertex(4u * e + 2u));
    let p3 = position(edge_vertex(4u * e + 3u));
    let front_a = faces(cross(p1 - p0, p2 - p0), p0);
    var front_b = front_a;
    if (flags & 3u) == 0u {
        var nb = cross(p0 - p1, p3 - p1);
        if (flags & 64u) != 0u { nb = -nb; }
        front_b = faces(nb, p1);
    }
    let contour = front_a != front_b;
    let shown = (flags & naive.classes) != 0u && (front_a || front_b || (flags & 1u) != 0u);
    if !(contour || shown) {
        return vec4<f32>(0.0, 0.0, -1.0, 1.0);
    }
    let c0 = naive.mvp * vec4<f32>(p0, 1.0);
    let c1 = naive.mvp * vec4<f32>(p1, 1.0);
    let s0 = c0.xy / c0.w * naive.viewport * 0.5;
    let s1 = c1.xy / c1.w * naive.viewport * 0.5;
    let d = normalize(s1 - s0);
    let n = vec2<f32>(-d.y, d.x);
    let c = select(c0, c1, corner >= 2u);
    let s = select(s0, s1, corner >= 2u) + n * naive.half_width * select(-1.0, 1.0, (corner & 1u) == 1u);
    let b = c + naive.bias * c.w * naive.proj_z;
    return vec4<f32>(s / (naive.viewport * 0.5) * c.w, b.z / b.w * c.w, c.w);
}

@fragment
fn naive_fragment() -> @location(0) vec4<f32> {
    return vec4<f32>(0.08, 0.08, 0.1, 1.0);
}
"#;

impl NaiveEdges {
    fn new(
        gpu: &Offscreen,
        target: &OffscreenTarget,
        asset: &GpuAsset,
        camera: &Camera,
        style: &EdgeStyle,
    ) -> Self {
        let device = &gpu.device;
        let edge_count = asset.edge_count();
        let indices: Vec<u32> = (0..edge_count)
            .flat_map(|e| [0, 1, 2, 2, 1, 3].map(|k| 4 * e + k))
            .collect();
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("naive indices"),
            contents: bytemuck::cast_slice(&indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let mut uniform = Vec::new();
        uniform.extend_from_slice(&camera.view_projection().to_cols_array());
        uniform.extend_from_slice(&camera.eye().to_array());
        uniform.extend_from_slice(&camera.projection.z_axis.to_array());
        uniform.extend_from_slice(&camera.viewport.map(|v| v as f32));
        uniform.push(style.width_px * 0.5);
        uniform.push((1.0 + 1.5 * style.width_px) * camera.pixel_scale());
        let mut bytes: Vec<u8> = bytemuck::cast_slice(&uniform).to_vec();
        bytes.extend_from_slice(&u32::from(asset.edges_are_16_bit()).to_le_bytes());
        bytes.extend_from_slice(&style.classes.0.to_le_bytes());
        bytes.resize(bytes.len().div_ceil(16) * 16, 0);
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("naive uniform"),
            contents: &bytes,
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("naive"),
            source: wgpu::ShaderSource::Wgsl(NAIVE_WGSL.into()),
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("naive"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("naive_vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: target
                .formats()
                .depth_format
                .map(|format| wgpu::DepthStencilState {
                    format,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(wgpu::CompareFunction::LessEqual),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("naive_fragment"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: target.formats().color_format,
                    blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("naive"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                (0, &uniform),
                (1, asset.topology_positions()),
                (2, asset.edge_vertices()),
                (3, asset.edge_attributes()),
            ]
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            }),
        });
        Self {
            pipeline,
            group,
            indices,
            index_count: 6 * edge_count,
        }
    }

    fn render(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, 0..1);
    }
}
