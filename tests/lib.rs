//! Shared helpers for the cross-crate tests: fixture paths and independent reference computations.
//!
//! The references here are deliberately naive (hash maps, f64, no parallelism) so that they share no
//! code and no cleverness with the bake they check.

use std::collections::HashMap;
use std::path::PathBuf;

use chamfer_preprocess::mesh::Mesh;

pub mod files;
pub mod rigged;
pub mod rounded;

pub use files::fixture;

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

/// The unit cube of `fixtures/shapes/cube.obj` and what a picture of it must show: shared by the
/// render and technique tests.
pub mod cube {
    use chamfer_runtime::render::{
        Camera, CapMethod, EdgeColors, EdgeStyle, Image, MeshStyle, Orbit,
    };
    use glam::{Vec2, Vec3};

    pub const RED: [f32; 4] = [1.0, 0.0, 0.0, 1.0];
    pub const BLUE_BACKGROUND: [f64; 4] = [0.0, 0.0, 1.0, 1.0];

    pub fn grey_mesh() -> MeshStyle {
        MeshStyle {
            color: [0.5, 0.5, 0.5, 1.0],
            ambient: 1.0,
            ..MeshStyle::default()
        }
    }

    pub fn edges_in(color: [f32; 4], width_px: f32, caps: CapMethod) -> EdgeStyle {
        EdgeStyle {
            colors: EdgeColors::all(color),
            width_px,
            caps,
            ..EdgeStyle::default()
        }
    }

    pub fn is_red(p: [u8; 4]) -> bool {
        p[0] > 200 && p[1] < 60 && p[2] < 60
    }

    pub fn is_background(p: [u8; 4]) -> bool {
        p[2] > 200 && p[0] < 60
    }

    /// Where `p` lands, in pixels from the top left (the shaders' convention).
    pub fn project(camera: &Camera, p: Vec3) -> Vec2 {
        let c = camera.view_projection() * p.extend(1.0);
        let [w, h] = camera.viewport.map(|v| v as f32);
        Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h)
    }

    pub fn pixel_at(image: &Image, p: Vec2) -> [u8; 4] {
        image.pixel(p.x as u32, p.y as u32)
    }

    /// Pixels within `radius` of `center`.
    pub fn disk(image: &Image, center: Vec2, radius: f32) -> Vec<[u8; 4]> {
        let mut pixels = Vec::new();
        for y in (center.y - radius).floor() as i32..=(center.y + radius).ceil() as i32 {
            for x in (center.x - radius).floor() as i32..=(center.x + radius).ceil() as i32 {
                let inside = Vec2::new(x as f32 + 0.5, y as f32 + 0.5).distance(center) <= radius;
                if inside
                    && x >= 0
                    && y >= 0
                    && (x as u32) < image.width
                    && (y as u32) < image.height
                {
                    pixels.push(image.pixel(x as u32, y as u32));
                }
            }
        }
        pixels
    }

    /// The unit cube of `fixtures/shapes/cube.obj`: corner `i` is at the bits of `i` (x, y, z).
    pub fn corner(i: usize) -> Vec3 {
        Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32)
    }

    /// The cube's 12 edges as corner pairs, each with the outward normals of its two faces.
    pub fn cube_edges() -> Vec<(usize, usize, [Vec3; 2])> {
        let mut edges = Vec::new();
        for axis in 0..3 {
            for c in 0..8usize {
                if c & (1 << axis) != 0 {
                    continue;
                }
                let normals: Vec<Vec3> = (0..3)
                    .filter(|&b| b != axis)
                    .map(|b| {
                        let sign = if c & (1 << b) != 0 { 1.0 } else { -1.0 };
                        Vec3::from_array(std::array::from_fn(|k| if k == b { sign } else { 0.0 }))
                    })
                    .collect();
                edges.push((c, c | (1 << axis), [normals[0], normals[1]]));
            }
        }
        edges
    }

    pub fn distance_to_segment(p: Vec2, (a, b): (Vec2, Vec2)) -> f32 {
        let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
        p.distance(a.lerp(b, t))
    }

    /// True if either face of a cube edge (from `cube_edges`) faces the camera.
    pub fn edge_seen(camera: &Camera, (a, b, normals): &(usize, usize, [Vec3; 2])) -> bool {
        let middle = (corner(*a) + corner(*b)) * 0.5;
        normals.iter().any(|&n| faces_eye(camera, n, middle))
    }

    pub fn faces_eye(camera: &Camera, normal: Vec3, on_face: Vec3) -> bool {
        let eye = camera.eye();
        normal.dot(eye.truncate() - on_face * eye.w) > 0.0
    }

    pub fn cube_camera(size: u32, orthographic: bool) -> Camera {
        let orbit = Orbit {
            azimuth: 35.0,
            elevation: 28.0,
            ortho: orthographic,
            ..Orbit::default()
        };
        Camera::orbit([[0.0; 3], [1.0; 3]], &orbit, [size, size])
    }

    /// Checks a picture of the unit cube from `camera` drawn with red edges over a grey mesh on blue:
    /// along each of the 12 edges, red within 2 px exactly where the edge is visible (a silhouette edge
    /// lies outside its line as a half quad, a crease on it), and the visible faces' middles grey.
    /// Returns the first disagreement.
    pub fn check_cube_edges(image: &Image, camera: &Camera) -> Result<(), String> {
        let edges: Vec<(usize, usize, bool)> = cube_edges()
            .into_iter()
            .map(|edge| (edge.0, edge.1, edge_seen(camera, &edge)))
            .collect();
        let on_screen =
            |a: usize, b: usize| (project(camera, corner(a)), project(camera, corner(b)));
        let near_visible_edge = |p: Vec2| {
            edges
                .iter()
                .filter(|e| e.2)
                .any(|&(a, b, _)| distance_to_segment(p, on_screen(a, b)) < 5.0)
        };
        let visible = edges.iter().filter(|e| e.2).count();
        if visible != 9 {
            return Err(format!(
                "the camera must see three faces, sees {visible} edges"
            ));
        }
        let mut hidden_checked = 0;
        for &(a, b, seen) in &edges {
            for t in [0.3, 0.4, 0.5, 0.6, 0.7] {
                let p = project(camera, corner(a).lerp(corner(b), t));
                if !seen && near_visible_edge(p) {
                    continue; // a hidden edge crossing behind a visible one in the picture
                }
                hidden_checked += usize::from(!seen);
                let red = disk(image, p, 2.0).into_iter().any(is_red);
                if red != seen {
                    return Err(format!(
                        "edge {a}-{b} at t = {t} ({p}): visible {seen}, red {red}"
                    ));
                }
            }
        }
        if hidden_checked < 8 {
            return Err(format!("only {hidden_checked} hidden samples"));
        }
        // Inside the visible faces: the mesh, not edge colour.
        for axis in 0..3 {
            for side in [0.0, 1.0] {
                let normal = Vec3::from_array(std::array::from_fn(|k| {
                    if k == axis { side * 2.0 - 1.0 } else { 0.0 }
                }));
                let center = Vec3::splat(0.5) + normal * 0.5;
                if faces_eye(camera, normal, center) {
                    let pixel = pixel_at(image, project(camera, center));
                    if is_red(pixel) || is_background(pixel) {
                        return Err(format!("face {normal}: {pixel:?}"));
                    }
                }
            }
        }
        Ok(())
    }

    /// Corners of the cube that the camera sees (on at least one visible face).
    pub fn visible_corners(camera: &Camera) -> Vec<usize> {
        (0..8)
            .filter(|&c| {
                cube_edges()
                    .iter()
                    .any(|e| (e.0 == c || e.1 == c) && edge_seen(camera, e))
            })
            .collect()
    }
}

/// What an asset holds, independent of how its bake numbered vertices, triangles and edges and of
/// the corner each triangle starts at: every number is named by the positions it refers to.
/// Two bakes of one mesh by bakes that order their output differently have equal contents.
#[derive(Debug, PartialEq, Eq)]
pub struct Content {
    /// Per render triangle, its corners' (position, normal) bits, rotated to start at the least.
    pub triangles: Vec<[[u32; 6]; 3]>,
    /// Per edge, the positions of `v0 v1 v2 v3`, its attribute word and, per end, the edge and end
    /// that follows it around its vertex.
    pub edges: Vec<([[u32; 3]; 4], u32, [Option<([[u32; 3]; 4], u32)>; 2])>,
    /// The positions of the vertices whose rings have a cap head.
    pub capped: Vec<[u32; 3]>,
}

/// The [`Content`] of `asset`.
pub fn content(asset: &chamfer_runtime::asset::Asset) -> Content {
    let bits = |p: [f32; 3]| p.map(f32::to_bits);
    let render = |v: u32| {
        let (p, n) = (
            bits(asset.render_positions[v as usize]),
            bits(asset.render_normals[v as usize]),
        );
        [p[0], p[1], p[2], n[0], n[1], n[2]]
    };
    let indices = asset.mesh_indices.to_u32_vec();
    let mut triangles: Vec<[[u32; 6]; 3]> = indices
        .chunks_exact(3)
        .map(|t| {
            let corners = [render(t[0]), render(t[1]), render(t[2])];
            let first = (0..3).min_by_key(|&k| corners[k]).unwrap_or(0);
            std::array::from_fn(|k| corners[(first + k) % 3])
        })
        .collect();
    triangles.sort_unstable();
    let vertices = asset.edge_vertices.to_u32_vec();
    let edge_key = |e: usize| -> [[u32; 3]; 4] {
        std::array::from_fn(|k| bits(asset.topology_positions[vertices[4 * e + k] as usize]))
    };
    let next = asset.next_ends.to_u32_vec();
    let mut edges: Vec<_> = (0..asset.edge_count())
        .map(|e| {
            let follower = |end: usize| next.get(end).map(|&n| (edge_key(n as usize / 2), n % 2));
            (
                edge_key(e),
                asset.edge_attributes[e],
                [follower(2 * e), follower(2 * e + 1)],
            )
        })
        .collect();
    edges.sort_unstable();
    let mut capped: Vec<[u32; 3]> = asset
        .cap_heads
        .iter()
        .map(|h| bits(asset.topology_positions[asset.end_vertex(h) as usize]))
        .collect();
    capped.sort_unstable();
    Content {
        triangles,
        edges,
        capped,
    }
}
