//! Cluster culling (issue 14) must not change a frame: over a sweep of cameras (an orbit of 36
//! positions, close-ups inside the bounding sphere, perspective and orthographic), the culled and the
//! unculled path draw the same edges, the same caps and the same pixels, while the cull pass keeps
//! only part of the clusters. The edge section bound in several chunks draws what one binding does.

use chamfer_runtime::asset::Asset;
use chamfer_runtime::render::{
    Camera, CapMethod, DrawCounts, EdgeClasses, EdgeRenderer, EdgeStyle, GpuAsset, Image,
    MeshRenderer, Offscreen, Orbit, Pipelines,
};
use chamfer_tests::bake_fixture;
use chamfer_tests::cube::{BLUE_BACKGROUND, RED, edges_in, grey_mesh};

const SIZE: [u32; 2] = [192, 144];

/// One frame of `asset` on `gpu`, with what the edge pass counted.
struct Scene<'a> {
    gpu: &'a Offscreen,
    target: chamfer_runtime::render::OffscreenTarget,
    pipelines: Pipelines,
    uploaded: GpuAsset,
}

impl<'a> Scene<'a> {
    fn new(gpu: &'a Offscreen, asset: &Asset) -> Self {
        let target = gpu.target(SIZE[0], SIZE[1], 1).expect("target");
        let pipelines = Pipelines::new(&gpu.device, &target.formats()).expect("pipelines");
        let uploaded = GpuAsset::new(&gpu.device, asset).expect("upload");
        Self {
            gpu,
            target,
            pipelines,
            uploaded,
        }
    }

    fn frame(&self, camera: &Camera, style: &EdgeStyle) -> (Image, DrawCounts) {
        let gpu = self.gpu;
        let mut mesh = MeshRenderer::new(&self.pipelines, &self.uploaded).expect("mesh");
        let mut edges = EdgeRenderer::new(&self.pipelines, &self.uploaded);
        let mut encoder = gpu.encoder();
        mesh.prepare(&gpu.queue, camera, &grey_mesh());
        let prepared = edges
            .prepare(&gpu.queue, &mut encoder, camera, style)
            .expect("prepare");
        {
            let mut pass = self.target.begin_pass(&mut encoder, BLUE_BACKGROUND);
            mesh.render(&mut pass);
            prepared.render(&mut pass);
        }
        prepared
            .finish(&mut encoder, &self.target.views())
            .expect("finish");
        gpu.submit(encoder).expect("submit");
        let image = self.target.read(gpu).expect("read back");
        let counts = edges.read_counts(&gpu.device, &gpu.queue).expect("counts");
        assert_eq!(counts.wanted, counts.edges, "the lists held every edge");
        (image, counts)
    }
}

/// The sweep: 36 orbit positions (elevation swinging between -60° and 60°), then close-ups from
/// inside the bounding sphere; every other camera orthographic.
fn cameras(asset: &Asset) -> Vec<Camera> {
    let bounds = [asset.header.bounds_min, asset.header.bounds_max];
    let radius = 0.5 * (glam::Vec3::from(bounds[1]) - glam::Vec3::from(bounds[0])).length();
    let orbit = (0..36).map(|k| Orbit {
        azimuth: 10.0 * k as f32,
        elevation: 60.0 * (k as f32 * 0.7).sin(),
        ortho: k % 2 == 1,
        ..Orbit::default()
    });
    let close = (0..12).map(|k| Orbit {
        azimuth: 30.0 * k as f32 + 7.0,
        elevation: 25.0 * (k as f32).cos(),
        distance: Some(radius * [0.35, 0.6, 0.9][k % 3]),
        ortho: k % 4 == 3,
        fov_y: 60.0,
    });
    orbit
        .chain(close)
        .map(|o| Camera::orbit(bounds, &o, SIZE))
        .collect()
}

/// The styles the sweep cycles through: every class, contours alone (where the cone test culls
/// most), creases with back faces kept, and the cap buffer.
fn styles() -> [EdgeStyle; 4] {
    let all = edges_in(RED, 2.0, CapMethod::NextIndex);
    [
        all,
        EdgeStyle {
            classes: EdgeClasses::CONTOUR,
            ..all
        },
        EdgeStyle {
            classes: EdgeClasses::CREASE | EdgeClasses::BOUNDARY,
            cull_back_facing: false,
            ..all
        },
        EdgeStyle {
            caps: CapMethod::CapBuffer,
            width_px: 3.0,
            ..all
        },
    ]
}

fn differing_pixels(a: &Image, b: &Image) -> usize {
    a.rgba
        .chunks(4)
        .zip(b.rgba.chunks(4))
        .filter(|(p, q)| p != q)
        .count()
}

/// Runs the sweep over `asset`; returns the clusters kept and tested over the contour-only frames.
fn sweep(name: &str, asset: &Asset) -> (u64, u64) {
    let scene = Scene::new(chamfer_tests::gpu(), asset);
    let clusters = asset.clusters().len() as u64;
    let (mut kept, mut tested) = (0, 0);
    for (i, camera) in cameras(asset).iter().enumerate() {
        let style = styles()[i % 4];
        let (culled, counts) = scene.frame(camera, &style);
        let unculled_style = EdgeStyle {
            cluster_culling: false,
            ..style
        };
        let (unculled, reference) = scene.frame(camera, &unculled_style);
        assert_eq!(reference.clusters_kept, 0, "{name} camera {i}");
        assert_eq!(
            (counts.edges, counts.caps),
            (reference.edges, reference.caps),
            "{name} camera {i}: culled and unculled edges, caps"
        );
        assert_eq!(
            differing_pixels(&culled, &unculled),
            0,
            "{name} camera {i}: pixels"
        );
        assert!(u64::from(counts.clusters_kept) <= clusters);
        if style.classes == EdgeClasses::CONTOUR {
            kept += u64::from(counts.clusters_kept);
            tested += clusters;
        }
    }
    (kept, tested)
}

#[test]
fn culled_frames_draw_what_unculled_frames_do_over_a_camera_sweep() {
    let (mut kept, mut tested) = (0, 0);
    for fixture in [
        "meshes/fandisk.obj",
        "meshes/spot.obj",
        "meshes/suzanne.obj",
    ] {
        let asset = bake_fixture(fixture);
        let (mesh_kept, mesh_tested) = sweep(fixture, &asset);
        eprintln!("{fixture}: the cull pass kept {mesh_kept} of {mesh_tested} clusters");
        assert!(mesh_kept < mesh_tested, "{fixture}: nothing culled");
        kept += mesh_kept;
        tested += mesh_tested;
    }
    // Contours can only be where a cluster's faces turn from the camera. (These meshes are small:
    // 64-edge clusters cover a large share of their surface, so cones are wide; see BENCHMARKS.md
    // for large meshes.)
    assert!(
        kept * 10 < tested * 7,
        "the cull pass kept {kept} of {tested} clusters"
    );
}

#[test]
fn the_sweep_catches_a_cluster_bound_that_is_too_tight() {
    // The control for the test above: clusters whose cones claim every face looks along +Z cull
    // edges the per-edge test draws, and the comparison sees it.
    let mut asset = bake_fixture("meshes/spot.obj");
    let mut clusters = asset.clusters().into_owned();
    for c in &mut clusters {
        c.axis = [0.0, 0.0, 1.0];
        c.cos_angle = 0.999;
    }
    asset.edge_clusters = clusters;
    let scene = Scene::new(chamfer_tests::gpu(), &asset);
    let camera = Camera::orbit(
        [asset.header.bounds_min, asset.header.bounds_max],
        &Orbit::default(),
        SIZE,
    );
    let style = EdgeStyle {
        classes: EdgeClasses::CONTOUR,
        ..edges_in(RED, 2.0, CapMethod::NextIndex)
    };
    let (culled, counts) = scene.frame(&camera, &style);
    let unculled_style = EdgeStyle {
        cluster_culling: false,
        ..style
    };
    let (unculled, reference) = scene.frame(&camera, &unculled_style);
    assert!(
        counts.edges < reference.edges,
        "{} vs {}",
        counts.edges,
        reference.edges
    );
    assert!(differing_pixels(&culled, &unculled) > 0);
}

/// A torus of `rings` × `sides` quads as OBJ text (each quad two triangles).
fn torus_obj(rings: u32, sides: u32) -> String {
    use std::fmt::Write;
    let mut obj = String::new();
    for i in 0..rings {
        let u = i as f32 / rings as f32 * std::f32::consts::TAU;
        for j in 0..sides {
            let v = j as f32 / sides as f32 * std::f32::consts::TAU;
            let r = 1.0 + 0.35 * v.cos();
            let _ = writeln!(obj, "v {} {} {}", r * u.cos(), 0.35 * v.sin(), r * u.sin());
        }
    }
    let at = |i: u32, j: u32| (i % rings) * sides + (j % sides) + 1;
    for i in 0..rings {
        for j in 0..sides {
            let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            let _ = writeln!(obj, "f {a} {d} {c}\nf {a} {c} {b}");
        }
    }
    obj
}

#[test]
fn an_edge_section_bound_in_chunks_draws_what_one_binding_does() {
    // A device that binds at most 2 MiB: a 72 k-vertex torus's 216 k edges (16 bytes each at 32
    // bits) bind in two windows, while every other section still fits one binding.
    const LIMIT: u32 = 2 << 20;
    let small = Offscreen::with_limits(|limits| {
        limits.max_storage_buffer_binding_size = LIMIT.into();
    })
    .expect("a device with a smaller binding limit");
    let obj = torus_obj(300, 240);
    let asset = chamfer_preprocess::bake_bytes(
        std::path::Path::new("torus.obj"),
        obj.as_bytes(),
        &chamfer_preprocess::BakeOptions::DEFAULT,
    )
    .expect("bakes")
    .asset;
    let chunked = Scene::new(&small, &asset);
    let chunks: Vec<(u32, u32)> = chunked.uploaded.edge_chunks().collect();
    assert!(chunks.len() >= 2, "{chunks:?}");
    assert_eq!(
        chunks.iter().map(|c| c.1).sum::<u32>(),
        chunked.uploaded.edge_count()
    );
    let whole = Scene::new(chamfer_tests::gpu(), &asset);
    assert_eq!(whole.uploaded.edge_chunks().count(), 1);
    let mut drawn = 0;
    for (i, camera) in cameras(&asset).iter().enumerate().step_by(5) {
        for culling in [true, false] {
            let style = EdgeStyle {
                cluster_culling: culling,
                ..styles()[i % 4]
            };
            let (a, a_counts) = chunked.frame(camera, &style);
            let (b, b_counts) = whole.frame(camera, &style);
            assert_eq!(a_counts, b_counts, "camera {i} culling {culling}");
            assert_eq!(differing_pixels(&a, &b), 0, "camera {i} culling {culling}");
            drawn += a_counts.edges;
        }
    }
    assert!(drawn > 0);
}
