//! Shared helpers for the cross-crate tests: fixture paths and independent reference computations.
//!
//! The references here are deliberately naive (hash maps, f64, no parallelism) so that they share no
//! code and no cleverness with the bake they check.

use std::collections::HashMap;
use std::path::PathBuf;

use chamfer_preprocess::mesh::Mesh;

/// A file under `fixtures/`.
pub fn fixture(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures")
        .join(relative)
}

/// Every mesh in `fixtures/meshes/` (a copy of `shared/meshes/`), sorted by name.
pub fn public_meshes() -> Vec<PathBuf> {
    let dir = fixture("meshes");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| chamfer_preprocess::load::format_of(p).is_some())
        .collect();
    paths.sort();
    paths
}

/// Edge counts of a mesh after an exact weld, computed the obvious way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EdgeCounts {
    /// Vertices after welding bitwise-equal positions (+0 and -0 are equal), used or not.
    pub welded_vertices: usize,
    /// Triangles that repeat a welded vertex or have zero area (exact, in f64).
    pub degenerate_triangles: usize,
    /// Unique undirected edges of the remaining triangles.
    pub edges: usize,
    /// Edges with exactly one face.
    pub boundary: usize,
    /// Edges with more than two faces.
    pub non_manifold: usize,
}

/// The reference: a `HashMap` weld on position bits and a `HashMap<(u32, u32), faces>` adjacency.
pub fn brute_force_edges(mesh: &Mesh) -> EdgeCounts {
    let key = |p: glam::Vec3| p.to_array().map(|c| if c == 0.0 { 0 } else { c.to_bits() });
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let remap: Vec<u32> = mesh
        .positions
        .iter()
        .map(|&p| {
            let next = ids.len() as u32;
            *ids.entry(key(p)).or_insert(next)
        })
        .collect();
    let mut counts = EdgeCounts {
        welded_vertices: ids.len(),
        ..EdgeCounts::default()
    };
    let mut faces: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &mesh.triangles {
        let w = t.map(|i| remap[i as usize]);
        let p = t.map(|i| mesh.positions[i as usize].as_dvec3());
        let zero_area = (p[1] - p[0]).cross(p[2] - p[0]) == glam::DVec3::ZERO;
        if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || zero_area {
            counts.degenerate_triangles += 1;
            continue;
        }
        for k in 0..3 {
            let (a, b) = (w[k], w[(k + 1) % 3]);
            *faces.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    counts.edges = faces.len();
    counts.boundary = faces.values().filter(|&&n| n == 1).count();
    counts.non_manifold = faces.values().filter(|&&n| n > 2).count();
    counts
}

/// Checks the next-index rings and cap heads of an asset: from every kept edge end, following `next`
/// returns to the start after visiting exactly the kept ends at that vertex; one head per vertex with
/// two or more kept edges, in vertex order. Returns a description of the first failure.
pub fn check_rings(asset: &chamfer_runtime::asset::Asset) -> Result<(), String> {
    let ends = 2 * asset.edge_count();
    let next = asset.next_ends.to_u32_vec();
    if next.len() != ends {
        return Err(format!("{} next entries for {ends} ends", next.len()));
    }
    let mut degree: HashMap<u32, usize> = HashMap::new();
    for end in 0..ends as u32 {
        *degree.entry(asset.end_vertex(end)).or_default() += 1;
    }
    for start in 0..ends as u32 {
        let v = asset.end_vertex(start);
        let mut seen = std::collections::HashSet::new();
        let mut end = start;
        loop {
            if asset.end_vertex(end) != v {
                return Err(format!("walk from end {start} left vertex {v}"));
            }
            if !seen.insert(end) {
                return Err(format!("walk from end {start} loops without returning"));
            }
            end = next[end as usize];
            if end == start {
                break;
            }
        }
        if seen.len() != degree[&v] {
            return Err(format!(
                "walk from end {start} visits {} of the {} ends at vertex {v}",
                seen.len(),
                degree[&v]
            ));
        }
    }
    let heads: Vec<u32> = asset
        .cap_heads
        .to_u32_vec()
        .iter()
        .map(|&h| asset.end_vertex(h))
        .collect();
    let mut expected: Vec<u32> = degree
        .iter()
        .filter(|&(_, &d)| d >= 2)
        .map(|(&v, _)| v)
        .collect();
    expected.sort_unstable();
    if heads != expected {
        return Err(format!(
            "cap heads at {} vertices, expected {}",
            heads.len(),
            expected.len()
        ));
    }
    Ok(())
}

/// The shared headless GPU for render tests. There is no skipping: a machine without an adapter
/// fails every render test loudly (CI installs Mesa's software Vulkan through scripts/setup.sh).
pub fn gpu() -> &'static chamfer_runtime::render::Offscreen {
    static GPU: std::sync::OnceLock<chamfer_runtime::render::Offscreen> =
        std::sync::OnceLock::new();
    GPU.get_or_init(|| {
        chamfer_runtime::render::Offscreen::new().unwrap_or_else(|e| {
            panic!("render tests need a GPU adapter and found none: {e}. Run scripts/setup.sh.")
        })
    })
}

/// Bakes a fixture with the default options.
pub fn bake_fixture(relative: &str) -> chamfer_runtime::asset::Asset {
    let path = fixture(relative);
    chamfer_preprocess::bake_file(&path, &chamfer_preprocess::BakeOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .asset
}

/// The pipeline cache of the shared GPU for `formats`, made once per test binary so every test
/// shares the compiled pipelines (as an application would).
pub fn pipelines(formats: chamfer_runtime::render::Target) -> chamfer_runtime::render::Pipelines {
    use chamfer_runtime::render::{Pipelines, Target};
    static CACHE: std::sync::Mutex<Vec<(Target, Pipelines)>> = std::sync::Mutex::new(Vec::new());
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, p)) = cache.iter().find(|(t, _)| *t == formats) {
        return p.clone();
    }
    let p = Pipelines::new(&gpu().device, &formats).expect("pipelines");
    cache.push((formats, p.clone()));
    p
}

/// One headless frame: the runtime's mesh pass (if `mesh` is given), then the edges.
pub fn render(
    asset: &chamfer_runtime::asset::Asset,
    camera: &chamfer_runtime::render::Camera,
    mesh: Option<&chamfer_runtime::render::MeshStyle>,
    edges: Option<&chamfer_runtime::render::EdgeStyle>,
    background: [f64; 4],
) -> chamfer_runtime::render::Image {
    let [width, height] = camera.viewport;
    let target = gpu().target(width, height, 1).expect("target");
    render_on(&target, asset, camera, mesh, edges, background)
}

/// [`render`] into `target`.
pub fn render_on(
    target: &chamfer_runtime::render::OffscreenTarget,
    asset: &chamfer_runtime::asset::Asset,
    camera: &chamfer_runtime::render::Camera,
    mesh: Option<&chamfer_runtime::render::MeshStyle>,
    edges: Option<&chamfer_runtime::render::EdgeStyle>,
    background: [f64; 4],
) -> chamfer_runtime::render::Image {
    use chamfer_runtime::render::{EdgeRenderer, GpuAsset, MeshRenderer};
    let gpu = gpu();
    let pipelines = pipelines(target.formats());
    let uploaded = GpuAsset::new(&gpu.device, asset).expect("upload");
    let mut mesh_renderer = MeshRenderer::new(&pipelines, &uploaded).expect("mesh renderer");
    let mut edge_renderer = EdgeRenderer::new(&pipelines, &uploaded);
    draw_frame(
        target,
        camera,
        background,
        mesh.map(|style| (&mut mesh_renderer, style)),
        edges.map(|style| (&mut edge_renderer, style)),
    )
}

/// One frame of the given renderers into `target`, read back (and saved where
/// `CHAMFER_TEST_IMAGES` names a folder).
pub fn draw_frame(
    target: &chamfer_runtime::render::OffscreenTarget,
    camera: &chamfer_runtime::render::Camera,
    background: [f64; 4],
    mesh: Option<(
        &mut chamfer_runtime::render::MeshRenderer,
        &chamfer_runtime::render::MeshStyle,
    )>,
    edges: Option<(
        &mut chamfer_runtime::render::EdgeRenderer,
        &chamfer_runtime::render::EdgeStyle,
    )>,
) -> chamfer_runtime::render::Image {
    let gpu = gpu();
    let mut encoder = gpu.encoder();
    let mesh = mesh.map(|(renderer, style)| {
        renderer.prepare(&gpu.queue, camera, style);
        &*renderer
    });
    let prepared = edges.map(|(renderer, style)| {
        renderer
            .prepare(&gpu.queue, &mut encoder, camera, style)
            .expect("prepare")
    });
    {
        let mut pass = target.begin_pass(&mut encoder, background);
        if let Some(mesh) = mesh {
            mesh.render(&mut pass);
        }
        if let Some(prepared) = &prepared {
            prepared.render(&mut pass);
        }
    }
    if let Some(prepared) = &prepared {
        prepared
            .finish(&mut encoder, &target.views())
            .expect("finish");
    }
    gpu.submit(encoder).expect("submit");
    let image = target.read(gpu).expect("read back");
    if let Ok(dir) = std::env::var("CHAMFER_TEST_IMAGES") {
        save_png(
            &image,
            &std::path::Path::new(&dir).join(format!("{}.png", image_name())),
        );
    }
    image
}

fn image_name() -> String {
    let thread = std::thread::current();
    let name = thread.name().unwrap_or("image").replace("::", "-");
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    format!("{name}-{n}")
}

/// Writes `image` as a PNG (for looking at what a test saw: set `CHAMFER_TEST_IMAGES=dir`).
pub fn save_png(image: &chamfer_runtime::render::Image, path: &std::path::Path) {
    let file = std::fs::File::create(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), image.width, image.height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder
        .write_header()
        .and_then(|mut writer| writer.write_image_data(&image.rgba))
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}
