//! Frame time and GPU memory of a scene of many instances drawn by one `SceneRenderer`, against the
//! same instances each drawn by a renderer of its own (one per object, as before scenes), same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_scene -- [--frames 7] [--size 1920x1080]
//!     [--grid 10] [--no-separate] [--large MESH] [--technique NAME]
//! ```
//! The scene: ten assets (fixtures shapes and meshes, each scaled into a unit cell) repeated over a
//! grid×grid×grid lattice (1,000 instances by default), each turned a little, seen from outside the
//! lattice. The configurations run round-robin after a warm-up; frames are timed from encoding to the
//! GPU finishing, medians shown. `prepare` is also timed alone (the host's work: recording the
//! frame's compute). The same run measures one large mesh (bunny-loop2 unless `--large` names
//! another) framed alone, for the edge work per edge and per drawn edge of one big instance.

use std::path::Path;
use std::time::Instant;

use chamfer_runtime::render::{
    Camera, EdgeStyle, GpuAsset, Instance, MeshRenderer, MeshStyle, Offscreen, Orbit, Pipelines,
    SceneRenderer, Technique,
};

#[path = "common/lattice.rs"]
mod lattice;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut frames = 7;
    let mut size = [1920, 1080];
    let mut grid = 10;
    let mut separate_too = true;
    let mut technique = Technique::Joined;
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures");
    let mut large = root.join("meshes/bunny-loop2.ply.gz");
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--frames" => frames = args.next().ok_or("--frames needs a number")?.parse()?,
            "--grid" => grid = args.next().ok_or("--grid needs a number")?.parse()?,
            "--no-separate" => separate_too = false,
            "--technique" => {
                let name = args.next().ok_or("--technique needs a name")?;
                technique = Technique::from_name(&name).ok_or("unknown technique")?;
            }
            "--large" => large = args.next().ok_or("--large needs a mesh")?.into(),
            "--size" => {
                let text = args.next().ok_or("--size needs WxH")?;
                let (w, h) = text.split_once('x').ok_or("--size needs WxH")?;
                size = [w.parse()?, h.parse()?];
            }
            other => return Err(format!("unknown argument {other}").into()),
        }
    }
    let gpu = Offscreen::new()?;
    let target = gpu.target(size[0], size[1], 1)?;
    let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
    let lattice = lattice::lattice(&gpu.device, &root, grid, &[technique])?;
    let instances: Vec<Instance<'_>> = lattice
        .placed
        .iter()
        .map(|&(a, transform)| Instance::new(&lattice.assets[a]).with_transform(transform))
        .collect();
    let bounds = lattice.bounds;
    let camera = Camera::orbit(bounds, &Orbit::default(), size);
    let triangles: u64 = instances
        .iter()
        .map(|i| u64::from(i.asset.triangle_count()))
        .sum();
    let edges: u64 = instances
        .iter()
        .map(|i| u64::from(i.asset.edge_count()))
        .sum();
    println!(
        "adapter: {} ({:?}), {}x{}, {} instances of {} assets ({triangles} triangles, {edges} edges), {}, {frames} frames (medians)\n",
        gpu.info.name,
        gpu.info.backend,
        size[0],
        size[1],
        instances.len(),
        lattice::ASSETS.len(),
        technique.name()
    );
    let mut mesh = MeshRenderer::for_scenes(&pipelines)?;
    mesh.prepare_scene(&gpu.queue, &camera, &instances, &MeshStyle::default());
    let style = EdgeStyle {
        technique,
        ..EdgeStyle::default()
    };
    let mut scene = SceneRenderer::new(&pipelines);
    let mut separate: Vec<SceneRenderer> = if separate_too {
        instances
            .iter()
            .map(|_| SceneRenderer::new(&pipelines))
            .collect()
    } else {
        Vec::new()
    };
    let mut prepare_times = Vec::new();

    let frame = |draw: &mut Recording| -> Result<f64, Box<dyn std::error::Error>> {
        let start = Instant::now();
        let mut encoder = gpu.encoder();
        draw(&mut encoder)?;
        gpu.submit(encoder)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    let mut times = [Vec::new(), Vec::new(), Vec::new()];
    for round in 0..frames + 2 {
        let m = frame(&mut |encoder| {
            mesh.render(&mut target.begin_pass(encoder, [1.0; 4]));
            Ok(())
        })?;
        let s = frame(&mut |encoder| {
            let start = Instant::now();
            let prepared = scene.prepare(&gpu.queue, encoder, &camera, &instances, &style)?;
            prepare_times.push(start.elapsed().as_secs_f64() * 1e3);
            let mut pass = target.begin_pass(encoder, [1.0; 4]);
            mesh.render(&mut pass);
            prepared.render(&mut pass);
            Ok(())
        })?;
        let p = if !separate_too {
            0.0
        } else {
            frame(&mut |encoder| {
                // Every renderer's compute first, then one pass that draws them all.
                let mut prepared = Vec::with_capacity(separate.len());
                for (renderer, instance) in separate.iter_mut().zip(&instances) {
                    prepared.push(renderer.prepare(
                        &gpu.queue,
                        encoder,
                        &camera,
                        std::slice::from_ref(instance),
                        &style,
                    )?);
                }
                let mut pass = target.begin_pass(encoder, [1.0; 4]);
                mesh.render(&mut pass);
                for prepared in &prepared {
                    prepared.render(&mut pass);
                }
                Ok(())
            })?
        };
        if round >= 2 {
            times[0].push(m);
            times[1].push(s);
            times[2].push(p);
        }
    }
    let [m, s, p] = times.map(median);
    let counts = scene
        .read_counts(&gpu.device, &gpu.queue)
        .unwrap_or_default();
    let prepare_ms = median(prepare_times);
    let separate_bytes: u64 = separate.iter().map(SceneRenderer::gpu_bytes).sum();
    let asset_bytes: u64 = lattice.assets.iter().map(GpuAsset::gpu_bytes).sum();
    println!("| configuration | frame ms | over mesh-only | per-frame GPU MB | drawn edges |");
    println!("|---|---:|---:|---:|---:|");
    println!("| mesh only (instanced mesh pass) | {m:.1} | | | |");
    println!(
        "| + one SceneRenderer | {s:.1} | {:+.0}% | {:.2} | {} |",
        (s / m - 1.0) * 100.0,
        scene.gpu_bytes() as f64 / 1e6,
        counts.edges
    );
    if separate_too {
        println!(
            "| + {} renderers of one instance each | {p:.1} | {:+.0}% | {:.2} | |",
            separate.len(),
            (p / m - 1.0) * 100.0,
            separate_bytes as f64 / 1e6,
        );
    }
    let work = s - m;
    println!(
        "\nscene: edge work {work:.1} ms = {:.0} ns per edge, {:.0} ns per drawn edge; {} of {} instances in view; {} clusters kept; prepare (host) {prepare_ms:.2} ms",
        work * 1e6 / edges as f64,
        work * 1e6 / f64::from(counts.edges.max(1)),
        counts.instances_in_view,
        instances.len(),
        counts.clusters_kept,
    );
    if separate_too {
        println!(
            "assets' buffers, shared by both: {:.2} MB; per-frame memory, separate / scene: {:.1}x; edge work (frame minus mesh), separate / scene: {:.1}x",
            asset_bytes as f64 / 1e6,
            separate_bytes as f64 / scene.gpu_bytes().max(1) as f64,
            (p - m) / (s - m).max(1e-3)
        );
    }
    large_mesh(&gpu, &target, &pipelines, &large, size, frames, &style)
}

/// One large mesh framed alone, mesh-only against with edges, round-robin: its edge work per edge
/// and per drawn edge.
fn large_mesh(
    gpu: &Offscreen,
    target: &chamfer_runtime::render::OffscreenTarget,
    pipelines: &Pipelines,
    path: &Path,
    size: [u32; 2],
    frames: usize,
    style: &EdgeStyle,
) -> Result<(), Box<dyn std::error::Error>> {
    let asset = chamfer_preprocess::bake_file(path, &Default::default())?.asset;
    let uploaded = GpuAsset::for_techniques(&gpu.device, &asset, &[style.technique])?;
    let instances = [Instance::new(&uploaded)];
    let camera = Camera::orbit(
        [asset.header.bounds_min, asset.header.bounds_max],
        &Orbit::default(),
        size,
    );
    let mut mesh = MeshRenderer::for_scenes(pipelines)?;
    mesh.prepare_scene(&gpu.queue, &camera, &instances, &MeshStyle::default());
    let mut scene = SceneRenderer::new(pipelines);
    let mut times = [Vec::new(), Vec::new()];
    for round in 0..frames + 2 {
        let start = Instant::now();
        let mut encoder = gpu.encoder();
        mesh.render(&mut target.begin_pass(&mut encoder, [1.0; 4]));
        gpu.submit(encoder)?;
        let m = start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        let mut encoder = gpu.encoder();
        let prepared = scene.prepare(&gpu.queue, &mut encoder, &camera, &instances, style)?;
        {
            let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
            mesh.render(&mut pass);
            prepared.render(&mut pass);
        }
        gpu.submit(encoder)?;
        let s = start.elapsed().as_secs_f64() * 1e3;
        if round >= 2 {
            times[0].push(m);
            times[1].push(s);
        }
    }
    let [m, s] = times.map(median);
    let counts = scene
        .read_counts(&gpu.device, &gpu.queue)
        .unwrap_or_default();
    let work = s - m;
    println!(
        "one large mesh ({}, {} edges): mesh only {m:.1} ms, with edges {s:.1} ms; edge work {work:.1} ms = {:.0} ns per edge, {:.0} ns per drawn edge ({} drawn)",
        path.file_name()
            .map(|n| n.to_string_lossy())
            .unwrap_or_default(),
        asset.edge_count(),
        work * 1e6 / asset.edge_count() as f64,
        work * 1e6 / f64::from(counts.edges.max(1)),
        counts.edges
    );
    Ok(())
}

/// What one frame records into its encoder.
type Recording<'a> =
    dyn FnMut(&mut wgpu::CommandEncoder) -> Result<(), Box<dyn std::error::Error>> + 'a;

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
