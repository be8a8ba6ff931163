//! Frame time and GPU memory of every edge technique, headless, in one run, against the mesh alone.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_techniques -- [--frames 9]
//!     [--size 1920x1080] [--only NAME,NAME] [MESH...]
//! ```
//! With no mesh it benches `fixtures/meshes/stanford-bunny.obj` and `bunny-loop2.ply.gz`. Per mesh,
//! every technique is drawn over the runtime's mesh pass; the configurations run round-robin (one
//! frame of each in turn, so the drifts of a shared machine hit all alike) after a warm-up that
//! compiles every pipeline; each frame is timed from encoding to the GPU finishing (submit + wait)
//! and the table shows medians. Memory per edge counts the asset's buffers, the extras the technique
//! needs and its per-frame state.

use std::path::{Path, PathBuf};
use std::time::Instant;

use chamfer_runtime::render::{
    Camera, EdgeRenderer, EdgeStyle, GpuAsset, MeshRenderer, MeshStyle, Offscreen, Orbit,
    Pipelines, Technique,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut frames = 9;
    let mut size = [1920, 1080];
    let mut only: Option<Vec<String>> = None;
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
            "--only" => {
                let names = args.next().ok_or("--only needs names")?;
                only = Some(names.split(',').map(str::to_owned).collect());
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
    let techniques: Vec<Technique> = Technique::all()
        .into_iter()
        .filter(|t| {
            only.as_ref()
                .is_none_or(|names| names.iter().any(|n| n == t.name()))
        })
        .collect();
    let gpu = Offscreen::new()?;
    println!(
        "adapter: {} ({:?}), {}x{}, 1 sample, {frames} frames per row (medians)\n",
        gpu.info.name, gpu.info.backend, size[0], size[1]
    );
    println!(
        "| mesh | triangles | edges | technique | frame ms | over mesh-only | post pass alone ms | GPU bytes per edge (asset + extras + per frame) | per-frame MB |"
    );
    println!("|---|---:|---:|---|---:|---:|---:|---:|---:|");
    for mesh in &meshes {
        let asset =
            chamfer_preprocess::bake_file(mesh, &chamfer_preprocess::BakeOptions::DEFAULT)?.asset;
        let name = mesh
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        bench(&gpu, &asset, &name, size, frames, &techniques)?;
    }
    Ok(())
}

fn bench(
    gpu: &Offscreen,
    asset: &chamfer_runtime::asset::Asset,
    name: &str,
    size: [u32; 2],
    frames: usize,
    techniques: &[Technique],
) -> Result<(), Box<dyn std::error::Error>> {
    let target = gpu.target(size[0], size[1], 1)?;
    let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
    let uploaded = GpuAsset::for_techniques(&gpu.device, asset, techniques)?;
    let camera = Camera::orbit(uploaded.bounds(), &Orbit::default(), size);
    let mut mesh = MeshRenderer::new(&pipelines, &uploaded)?;
    mesh.prepare(&gpu.queue, &camera, &MeshStyle::default());
    let mut renderers: Vec<(Technique, EdgeRenderer)> = techniques
        .iter()
        .map(|&t| (t, EdgeRenderer::new(&pipelines, &uploaded)))
        .collect();
    let mesh_only = |mesh: &MeshRenderer| -> Result<f64, Box<dyn std::error::Error>> {
        let start = Instant::now();
        let mut encoder = gpu.encoder();
        mesh.render(&mut target.begin_pass(&mut encoder, [1.0; 4]));
        gpu.submit(encoder)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    let with = |mesh: &MeshRenderer,
                technique: Technique,
                edges: &mut EdgeRenderer|
     -> Result<f64, Box<dyn std::error::Error>> {
        let start = Instant::now();
        let mut encoder = gpu.encoder();
        let style = EdgeStyle {
            technique,
            ..EdgeStyle::default()
        };
        let prepared = edges.prepare(&gpu.queue, &mut encoder, &camera, &style)?;
        {
            let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
            mesh.render(&mut pass);
            prepared.render(&mut pass);
        }
        prepared.finish(&mut encoder, &target.views())?;
        gpu.submit(encoder)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    // The post-process's own pass, alone: a frame that only records `finish` over the picture the
    // last frame left (what must not grow with the mesh).
    let finish_only = |technique: Technique,
                       edges: &mut EdgeRenderer|
     -> Result<f64, Box<dyn std::error::Error>> {
        let style = EdgeStyle {
            technique,
            ..EdgeStyle::default()
        };
        let mut dropped = gpu.encoder();
        let prepared = edges.prepare(&gpu.queue, &mut dropped, &camera, &style)?;
        let start = Instant::now();
        let mut encoder = gpu.encoder();
        prepared.finish(&mut encoder, &target.views())?;
        gpu.submit(encoder)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    let mut base = Vec::new();
    let mut times = vec![Vec::new(); renderers.len()];
    let mut post = vec![Vec::new(); renderers.len()];
    for round in 0..frames + 2 {
        let m = mesh_only(&mesh)?;
        let mut row = Vec::new();
        let mut post_row = Vec::new();
        for (t, r) in renderers.iter_mut() {
            row.push(with(&mesh, *t, r)?);
            post_row.push(if t.is_post_process() {
                Some(finish_only(*t, r)?)
            } else {
                None
            });
        }
        if round >= 2 {
            base.push(m);
            for (list, t) in times.iter_mut().zip(row) {
                list.push(t);
            }
            for (list, t) in post.iter_mut().zip(post_row) {
                list.extend(t);
            }
        }
    }
    let m = median(base);
    let edges = u64::from(uploaded.edge_count()).max(1);
    println!(
        "| {name} | {} | {} | mesh only | {m:.1} | | | {:.1} | |",
        asset.triangle_count(),
        asset.edge_count(),
        uploaded.gpu_bytes() as f64 / edges as f64 - extras_per_edge(&uploaded, techniques, edges)
    );
    let core =
        uploaded.gpu_bytes() - uploaded.extras_bytes(chamfer_runtime::render::AssetExtras::ALL);
    for (((technique, renderer), list), post) in renderers.iter().zip(times).zip(post) {
        let t = median(list);
        let post = if post.is_empty() {
            String::new()
        } else {
            format!("{:.1}", median(post))
        };
        let extras = uploaded.extras_bytes(technique.needs());
        let per_edge = (core + extras + renderer.gpu_bytes()) as f64 / edges as f64;
        println!(
            "| {name} | {} | {} | {} | {t:.1} | {:+.0}% | {post} | {per_edge:.1} ({:.1} + {:.1} + {:.1}) | {:.1} |",
            asset.triangle_count(),
            asset.edge_count(),
            technique.name(),
            (t / m - 1.0) * 100.0,
            core as f64 / edges as f64,
            extras as f64 / edges as f64,
            renderer.gpu_bytes() as f64 / edges as f64,
            renderer.gpu_bytes() as f64 / 1e6,
        );
    }
    Ok(())
}

fn extras_per_edge(asset: &GpuAsset, techniques: &[Technique], edges: u64) -> f64 {
    let all = techniques
        .iter()
        .fold(chamfer_runtime::render::AssetExtras::NONE, |a, t| {
            a | t.needs()
        });
    asset.extras_bytes(all) as f64 / edges as f64
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
