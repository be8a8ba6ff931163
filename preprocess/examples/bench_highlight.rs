//! Frame cost of the chamfer highlight under PBR shading (issue 29) against seed 000's Blinn one, in
//! the same run, headless.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_highlight -- [--frames 15] [--size 1920x1080]
//!     [MESH:RADIUS_REL...]
//! ```
//! With no mesh it benches the cube with wide strips (radius 5 % of its diagonal: tens of pixels
//! across, where the per-pixel integral dominates), the fandisk and the Stanford bunny (0.4 %: strips
//! about a pixel wide). Every crease gets the radius. Per mesh, six configurations run round-robin
//! after two warm-up rounds: the mesh alone (Blinn faces), the mesh with Blinn strips, the mesh alone
//! with PBR faces, the mesh with PBR strips, and the last two again lit by `fixtures/environments/sky.hdr`
//! too (image-based light), and the PBR strips once more without rounded corners (the seed's strip
//! ends); each frame is timed from encoding to the GPU finishing, and the table shows medians.

use std::path::{Path, PathBuf};
use std::time::Instant;

use chamfer_preprocess::{BakeOptions, Radius};
use chamfer_runtime::highlight::ggx::PbrMaterial;
use chamfer_runtime::highlight::strip::Material;
use chamfer_runtime::render::{
    Camera, EdgeClasses, EdgeRenderer, EdgeStyle, GpuAsset, Highlight, Light, MeshLight,
    MeshRenderer, MeshStyle, Offscreen, Orbit, Pipelines, Shading,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut frames = 15;
    let mut size = [1920, 1080];
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
            _ => {
                let (path, radius) = arg.rsplit_once(':').ok_or("MESH:RADIUS_REL")?;
                meshes.push((PathBuf::from(path), radius.parse::<f32>()?));
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures");
    if meshes.is_empty() {
        meshes = vec![
            (root.join("shapes/cube.obj"), 0.05),
            (root.join("meshes/fandisk.obj"), 0.004),
            (root.join("meshes/stanford-bunny.obj"), 0.004),
        ];
    }
    let gpu = Offscreen::new()?;
    println!(
        "adapter: {} ({:?}), {}x{}, 1 sample, {frames} frames per row (medians)\n",
        gpu.info.name, gpu.info.backend, size[0], size[1]
    );
    println!(
        "| mesh | radius (of diagonal) | chamfer edges | rounded corners | Blinn: mesh ms | Blinn: + strips ms | Blinn strips ms | PBR: mesh ms | PBR: + strips ms | PBR strips ms | PBR strips / Blinn strips | PBR frame / Blinn frame | PBR + environment: mesh ms | + strips ms | strips ms | env strips / Blinn strips | PBR without rounded corners: + strips ms | rounded corners ms |"
    );
    println!(
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    let sky = chamfer_preprocess::environment::read_environment(
        &root.join("environments/sky.hdr"),
        &chamfer_preprocess::Limits::DEFAULT,
    )?;
    let start = Instant::now();
    let _ = sky.prefilter(PbrMaterial::default().alpha());
    let prefilter_ms = start.elapsed().as_secs_f64() * 1e3;
    let sky = std::sync::Arc::new(sky);
    for (path, radius) in &meshes {
        let options = BakeOptions::DEFAULT.with_radius(Radius::Relative(*radius));
        let asset = chamfer_preprocess::bake_file(path, &options)?.asset;
        let target = gpu.target(size[0], size[1], 1)?;
        let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
        let uploaded = GpuAsset::new(&gpu.device, &asset)?;
        let camera = Camera::orbit(uploaded.bounds(), &Orbit::default(), size);
        let light = Light::Directional([0.4, 0.8, 0.45]);
        let blinn = Material {
            diffuse: 0.7,
            specular: 0.5,
            shininess: 32.0,
        };
        let pbr = PbrMaterial::default();
        let mesh_blinn = MeshStyle {
            light: MeshLight::Model(light),
            color: [0.7, 0.7, 0.7, 1.0],
            ambient: 0.1,
            specular: 0.5,
            ..MeshStyle::default()
        };
        let mesh_pbr = MeshStyle {
            light_color: [std::f32::consts::PI; 3],
            pbr: Some(pbr),
            ..mesh_blinn
        };
        let strips = |shading, color| EdgeStyle {
            classes: EdgeClasses::NONE,
            highlight: Some(Highlight {
                light,
                color,
                shading,
                ambient: 0.1,
                k: None,
                ..Highlight::default()
            }),
            ..EdgeStyle::default()
        };
        let style_blinn = strips(Shading::Blinn(blinn), [1.0; 3]);
        let style_pbr = strips(Shading::Pbr(pbr), [std::f32::consts::PI; 3]);
        let mut style_pbr_notched = style_pbr;
        if let Some(highlight) = &mut style_pbr_notched.highlight {
            highlight.rounded_corners = false;
        }
        let mut lit = [
            (
                MeshRenderer::new(&pipelines, &uploaded)?,
                EdgeRenderer::new(&pipelines, &uploaded),
            ),
            (
                MeshRenderer::new(&pipelines, &uploaded)?,
                EdgeRenderer::new(&pipelines, &uploaded),
            ),
        ];
        lit[1].0.set_environment(Some(sky.clone()));
        lit[1].1.set_environment(Some(sky.clone()));
        let mut frame = |with_sky: bool, mesh_style: &MeshStyle, edge_style: Option<&EdgeStyle>| {
            let (mesh, edges) = &mut lit[usize::from(with_sky)];
            let start = Instant::now();
            let mut encoder = gpu.encoder();
            mesh.prepare(&gpu.queue, &camera, mesh_style);
            let prepared = match edge_style {
                Some(style) => Some(edges.prepare(&gpu.queue, &mut encoder, &camera, style)?),
                None => None,
            };
            {
                let mut pass = target.begin_pass(&mut encoder, [1.0; 4]);
                mesh.render(&mut pass);
                if let Some(prepared) = &prepared {
                    prepared.render(&mut pass);
                }
            }
            gpu.submit(encoder)?;
            Ok::<f64, Box<dyn std::error::Error>>(start.elapsed().as_secs_f64() * 1e3)
        };
        let mut times = [(); 7].map(|_| Vec::new());
        for round in 0..frames + 2 {
            let row = [
                frame(false, &mesh_blinn, None)?,
                frame(false, &mesh_blinn, Some(&style_blinn))?,
                frame(false, &mesh_pbr, None)?,
                frame(false, &mesh_pbr, Some(&style_pbr))?,
                frame(true, &mesh_pbr, None)?,
                frame(true, &mesh_pbr, Some(&style_pbr))?,
                frame(false, &mesh_pbr, Some(&style_pbr_notched))?,
            ];
            if round >= 2 {
                for (list, t) in times.iter_mut().zip(row) {
                    list.push(t);
                }
            }
        }
        let [bm, bs, pm, ps, em, es, pn] = times.map(|mut v| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        });
        println!(
            "| {} | {:.1} % | {} | {} | {bm:.2} | {bs:.2} | {:.2} | {pm:.2} | {ps:.2} | {:.2} | {:.2}× | {:.2}× | {em:.2} | {es:.2} | {:.2} | {:.2}× | {pn:.2} | {:.2} |",
            path.file_name()
                .map(|n| n.to_string_lossy())
                .unwrap_or_default(),
            radius * 100.0,
            asset.header.stats.chamfer.edges,
            uploaded.corner_count(),
            bs - bm,
            ps - pm,
            (ps - pm) / (bs - bm).max(1e-3),
            ps / bs,
            es - em,
            (es - em) / (bs - bm).max(1e-3),
            ps - pn,
        );
    }
    println!(
        "\nprefiltering environments/sky.hdr for one roughness (CPU, once per environment and roughness): {prefilter_ms:.1} ms"
    );
    Ok(())
}
