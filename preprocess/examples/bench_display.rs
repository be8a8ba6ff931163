//! Frame cost of the display modes (issue 42), headless, against the shaded frame of the same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_display -- [--frames 9] [--size 1920x1080]
//!     [--grid 10] [MESH...]
//! ```
//! Per mesh (default: `fixtures/meshes/stanford-bunny.obj` and `bunny-loop2.ply.gz`), then for the
//! 1,000-instance scene of `bench_scene` (`--grid 0`: none), round-robin after two warm-up rounds
//! (one frame of each mode in turn, so a shared machine's drifts hit all alike), each frame timed
//! from encoding to the GPU finishing, medians shown: shaded with visible edges (the baseline);
//! shaded with hidden edges (dashed, the hidden pass); hidden-line (faces in the background colour,
//! hidden edges); X-ray (faces at 30 %, hidden edges); wireframe (no faces). All drawn by one scene
//! renderer and the mesh pass with the joined technique, so a single mesh is a scene of one.

use std::path::{Path, PathBuf};
use std::time::Instant;

use chamfer_runtime::render::{
    Camera, DisplaySettings, EdgeStyle, GpuAsset, Instance, MeshRenderer, MeshStyle, Offscreen,
    Orbit, Pipelines, SceneRenderer, Technique,
};
use glam::Mat4;

#[path = "common/lattice.rs"]
mod lattice;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The modes timed, by column.
fn modes() -> [DisplaySettings; 5] {
    let hidden = DisplaySettings {
        hidden_edges: true,
        ..DisplaySettings::default()
    };
    [
        DisplaySettings::default(),
        hidden,
        DisplaySettings {
            hidden_line: true,
            ..hidden
        },
        DisplaySettings {
            xray: Some(0.3),
            ..DisplaySettings::default()
        },
        DisplaySettings {
            wireframe: true,
            ..DisplaySettings::default()
        },
    ]
}

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
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures");
    if meshes.is_empty() {
        meshes.push(fixtures.join("meshes/stanford-bunny.obj"));
        meshes.push(fixtures.join("meshes/bunny-loop2.ply.gz"));
    }
    let gpu = Offscreen::new()?;
    println!(
        "adapter: {} ({:?}), {}x{}, 1 sample, {frames} frames per row (medians)\n",
        gpu.info.name, gpu.info.backend, size[0], size[1]
    );
    println!(
        "| mesh | triangles | shaded ms | + hidden edges ms | overhead | hidden-line ms | overhead | X-ray ms | overhead | wireframe ms | overhead |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for mesh in &meshes {
        let asset =
            chamfer_preprocess::bake_file(mesh, &chamfer_preprocess::BakeOptions::DEFAULT)?.asset;
        let uploaded = GpuAsset::new(&gpu.device, &asset)?;
        let name = mesh.file_name().map(|n| n.to_string_lossy().into_owned());
        row(
            &gpu,
            size,
            frames,
            &name.unwrap_or_default(),
            &[(&uploaded, Mat4::IDENTITY)],
            uploaded.bounds(),
        )?;
    }
    if grid > 0 {
        let scene = lattice::lattice(&gpu.device, &fixtures, grid, &[Technique::Joined])?;
        let placed: Vec<(&GpuAsset, Mat4)> = scene
            .placed
            .iter()
            .map(|&(a, transform)| (&scene.assets[a], transform))
            .collect();
        let name = format!("{} instances (scene)", placed.len());
        row(&gpu, size, frames, &name, &placed, scene.bounds)?;
    }
    Ok(())
}

/// Times every mode on `placed` (within `bounds`) round-robin (two warm-up rounds) and prints
/// their medians.
fn row(
    gpu: &Offscreen,
    size: [u32; 2],
    frames: usize,
    name: &str,
    placed: &[(&GpuAsset, Mat4)],
    bounds: [[f32; 3]; 2],
) -> Result<()> {
    let instances: Vec<Instance<'_>> = placed
        .iter()
        .map(|&(asset, transform)| Instance::new(asset).with_transform(transform))
        .collect();
    let triangles: u64 = instances
        .iter()
        .map(|i| u64::from(i.asset.triangle_count()))
        .sum();
    let target = gpu.target(size[0], size[1], 1)?;
    let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
    let camera = Camera::orbit(bounds, &Orbit::default(), size);
    let mut mesh_pass = MeshRenderer::for_scenes(&pipelines)?;
    let mut edges = SceneRenderer::new(&pipelines);
    let mut frame = |display: &DisplaySettings| -> Result<f64> {
        let start = Instant::now();
        let faces = display.faces().mesh_style(MeshStyle::default(), [1.0; 4]);
        if let Some(faces) = &faces {
            mesh_pass.prepare_scene(&gpu.queue, &camera, &instances, faces);
        }
        let mut encoder = gpu.encoder();
        let style = EdgeStyle {
            display: display.display(),
            ..EdgeStyle::default()
        };
        let prepared = edges.prepare(&gpu.queue, &mut encoder, &camera, &instances, &style)?;
        {
            let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
            if faces.is_some() {
                mesh_pass.render(&mut pass);
            }
            prepared.render(&mut pass);
        }
        prepared.finish(&mut encoder, &target.views())?;
        gpu.submit(encoder)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    let modes = modes();
    let mut times = modes.each_ref().map(|_| Vec::new());
    for round in 0..frames + 2 {
        for (list, display) in times.iter_mut().zip(&modes) {
            let t = frame(display)?;
            if round >= 2 {
                list.push(t);
            }
        }
    }
    let [shaded, hidden, hidden_line, xray, wireframe] = times.map(|mut v| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    });
    println!(
        "| {name} | {triangles} | {shaded:.1} | {hidden:.1} | {:.2}× | {hidden_line:.1} | {:.2}× | {xray:.1} | {:.2}× | {wireframe:.1} | {:.2}× |",
        hidden / shaded,
        hidden_line / shaded,
        xray / shaded,
        wireframe / shaded,
    );
    Ok(())
}
