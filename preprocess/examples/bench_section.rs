//! Frame cost of section planes (issue 43), headless, against the same frame uncut in the same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_section -- [--frames 9] [--size 1920x1080]
//!     [--grid 10] [MESH...]
//! ```
//! Per mesh (default: `fixtures/meshes/bunny-loop2.ply.gz`), round-robin after two warm-up rounds
//! (one frame of each configuration in turn, so a shared machine's drifts hit all alike), each frame
//! timed from encoding to the GPU finishing, medians shown: the mesh and its joined edges uncut; one
//! plane through the middle clipping them only; the same plane with its cut face filled and
//! outlined; six planes (a box inside the bounds, each plane crossing the mesh) clipping only and
//! with caps and outlines. Then the same five for the 1,000-instance scene of `bench_scene`
//! (`--grid 0`: none), the planes across the lattice: every instance a plane crosses gets its
//! parity draws, cap and outline.

use std::path::{Path, PathBuf};
use std::time::Instant;

use chamfer_runtime::render::{
    Camera, CutRenderer, CutStyle, EdgeRenderer, EdgeStyle, GpuAsset, Instance, MeshRenderer,
    MeshStyle, Offscreen, OffscreenTarget, Orbit, Pipelines, SceneRenderer, Technique,
};
use chamfer_runtime::schema::Numbers;
use chamfer_runtime::section::{ClipPlanes, Section};

#[path = "common/lattice.rs"]
mod lattice;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn main() -> Result<()> {
    let mut frames = 9;
    let mut grid = 10;
    let mut size = [1920, 1080];
    let mut meshes = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--frames" => frames = args.next().ok_or("--frames needs a number")?.parse()?,
            "--grid" => grid = args.next().ok_or("--grid needs a number")?.parse()?,
            "--size" => {
                let text = args.next().ok_or("--size needs WxH")?;
                let (w, h) = text.split_once('x').ok_or("--size needs WxH")?;
                size = [w.parse()?, h.parse()?];
            }
            _ => meshes.push(PathBuf::from(arg)),
        }
    }
    if meshes.is_empty() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/meshes");
        meshes.push(root.join("bunny-loop2.ply.gz"));
    }
    let gpu = Offscreen::new()?;
    println!(
        "adapter: {} ({:?}), {}x{}, 1 sample, {frames} frames per row (medians)\n",
        gpu.info.name, gpu.info.backend, size[0], size[1]
    );
    println!(
        "| mesh | triangles | uncut ms | 1 plane, clip only ms | 1 plane + cap + outline ms | overhead | 6 planes, clip only ms | 6 planes + caps + outlines ms | overhead |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for mesh in &meshes {
        let asset =
            chamfer_preprocess::bake_file(mesh, &chamfer_preprocess::BakeOptions::DEFAULT)?.asset;
        let target = gpu.target(size[0], size[1], 1)?;
        let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
        let uploaded = GpuAsset::new(&gpu.device, &asset)?;
        let [lo, hi] = uploaded.bounds();
        let camera = Camera::orbit([lo, hi], &Orbit::default(), size);
        let [one, six] = planes([lo, hi])?;
        let mut mesh_pass = MeshRenderer::new(&pipelines, &uploaded)?;
        let mut cut = CutRenderer::new(&pipelines)?;
        let mut edges = EdgeRenderer::new(&pipelines, &uploaded);
        let instances = [Instance::new(&uploaded)];
        let mut frame = |section: ClipPlanes, capped: bool| {
            let start = Instant::now();
            mesh_pass.prepare(
                &gpu.queue,
                &camera,
                &MeshStyle {
                    section,
                    ..MeshStyle::default()
                },
            );
            if capped {
                cut.prepare(
                    &gpu.queue,
                    &camera,
                    &instances,
                    &CutStyle {
                        section,
                        ..CutStyle::default()
                    },
                );
            }
            let mut encoder = gpu.encoder();
            let style = EdgeStyle {
                section,
                ..EdgeStyle::default()
            };
            let prepared = edges.prepare(&gpu.queue, &mut encoder, &camera, &style)?;
            {
                let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
                mesh_pass.render(&mut pass);
                if capped {
                    cut.render(&mut pass);
                }
                prepared.render(&mut pass);
            }
            prepared.finish(&mut encoder, &target.views())?;
            gpu.submit(encoder)?;
            Ok::<f64, Box<dyn std::error::Error>>(start.elapsed().as_secs_f64() * 1e3)
        };
        let name = mesh.file_name().map(|n| n.to_string_lossy().into_owned());
        let name = name.unwrap_or_default();
        row(
            &name,
            asset.triangle_count() as u64,
            frames,
            one,
            six,
            &mut frame,
        )?;
    }
    if grid > 0 {
        scene_row(&gpu, size, grid, frames)?;
    }
    Ok(())
}

/// One plane across the middle of `bounds` (z), and a box of six at 20 % to 80 % of it.
fn planes([lo, hi]: [[f32; 3]; 2]) -> Result<[ClipPlanes; 2]> {
    let mid = |k: usize, t: f32| lo[k] + (hi[k] - lo[k]) * t;
    let one = ClipPlanes::from_section(&Section {
        section: Some(Numbers::from_array([0.0, 0.0, 1.0, mid(2, 0.5)])),
        ..Section::default()
    })?;
    let six = ClipPlanes::from_section(&Section {
        section_box: Some(Numbers::from_array([
            mid(0, 0.2),
            mid(1, 0.2),
            mid(2, 0.2),
            mid(0, 0.8),
            mid(1, 0.8),
            mid(2, 0.8),
        ])),
        ..Section::default()
    })?;
    Ok([one, six])
}

/// Times the five configurations round-robin (two warm-up rounds) and prints their medians.
fn row(
    name: &str,
    triangles: u64,
    frames: usize,
    one: ClipPlanes,
    six: ClipPlanes,
    frame: &mut dyn FnMut(ClipPlanes, bool) -> Result<f64>,
) -> Result<()> {
    let mut times = [(); 5].map(|_| Vec::new());
    for round in 0..frames + 2 {
        let row = [
            frame(ClipPlanes::NONE, false)?,
            frame(one, false)?,
            frame(one, true)?,
            frame(six, false)?,
            frame(six, true)?,
        ];
        if round >= 2 {
            for (list, t) in times.iter_mut().zip(row) {
                list.push(t);
            }
        }
    }
    let [none, one_clip, one_cut, six_clip, six_cut] = times.map(|mut v| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    });
    println!(
        "| {name} | {triangles} | {none:.1} | {one_clip:.1} | {one_cut:.1} | {:.2}× | {six_clip:.1} | {six_cut:.1} | {:.2}× |",
        one_cut / none,
        six_cut / none,
    );
    Ok(())
}

/// The five configurations on the lattice of `grid`³ instances, drawn by one scene renderer.
fn scene_row(gpu: &Offscreen, size: [u32; 2], grid: usize, frames: usize) -> Result<()> {
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures");
    let scene = lattice::lattice(&gpu.device, &fixtures, grid, &[Technique::Joined])?;
    let instances: Vec<Instance<'_>> = scene
        .placed
        .iter()
        .map(|&(a, transform)| Instance::new(&scene.assets[a]).with_transform(transform))
        .collect();
    let triangles = instances
        .iter()
        .map(|i| u64::from(i.asset.triangle_count()))
        .sum();
    let target: OffscreenTarget = gpu.target(size[0], size[1], 1)?;
    let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
    let camera = Camera::orbit(scene.bounds, &Orbit::default(), size);
    let [one, six] = planes(scene.bounds)?;
    let mut mesh_pass = MeshRenderer::for_scenes(&pipelines)?;
    let mut cut = CutRenderer::new(&pipelines)?;
    let mut edges = SceneRenderer::new(&pipelines);
    let mut frame = |section: ClipPlanes, capped: bool| -> Result<f64> {
        let start = Instant::now();
        let mesh_style = MeshStyle {
            section,
            ..MeshStyle::default()
        };
        mesh_pass.prepare_scene(&gpu.queue, &camera, &instances, &mesh_style);
        if capped {
            let style = CutStyle {
                section,
                ..CutStyle::default()
            };
            cut.prepare(&gpu.queue, &camera, &instances, &style);
        }
        let mut encoder = gpu.encoder();
        let style = EdgeStyle {
            section,
            ..EdgeStyle::default()
        };
        let prepared = edges.prepare(&gpu.queue, &mut encoder, &camera, &instances, &style)?;
        {
            let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
            mesh_pass.render(&mut pass);
            if capped {
                cut.render(&mut pass);
            }
            prepared.render(&mut pass);
        }
        prepared.finish(&mut encoder, &target.views())?;
        gpu.submit(encoder)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    let name = format!("{} instances (scene)", instances.len());
    row(&name, triangles, frames, one, six, &mut frame)
}
