//! Animated glTF files baked and posed on the CPU (issue 41), against the skinning formula worked
//! out in f64 from the numbers the files were generated from; and the bad input a loader of skins,
//! morph targets and animations must refuse, one test per class.

use std::path::Path;

use chamfer_preprocess::{BakeOptions, Baked, Error, Limits};
use chamfer_runtime::asset::Asset;
use chamfer_runtime::rig::{Interpolation, Pose, Target};
use chamfer_tests::rigged::{self, bend_angle, posed_cylinder_vertex};
use serde_json::Value;

fn bake(name: &str, glb: &[u8]) -> Baked {
    chamfer_preprocess::bake_bytes(Path::new(name), glb, &BakeOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The largest distance between the baked asset's posed vertices and `expected(i)` for every
/// input vertex `i` (model positions `input`).
fn worst(baked: &Baked, pose: &Pose, expected: impl Fn(usize) -> [f64; 3]) -> f64 {
    let asset = &baked.asset;
    let posed = asset.motion.pose_positions(&asset.topology_positions, pose);
    let mut worst = 0.0f64;
    for (i, &v) in baked.input_vertex_map.iter().enumerate() {
        let got = posed[v as usize];
        let want = expected(i);
        let d = (0..3)
            .map(|k| (f64::from(got[k]) - want[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        worst = worst.max(d);
    }
    worst
}

#[test]
fn a_skinned_cylinder_bends_as_the_skinning_formula_says() {
    let (model, _) = rigged::cylinder();
    for interpolation in ["LINEAR", "STEP", "CUBICSPLINE"] {
        // The node's offset places the bind pose; skinning ignores it (glTF 2.0 §3.7.3.3).
        let baked = bake(
            "cylinder.glb",
            &rigged::skinned_cylinder(interpolation, [3.0, 0.0, 0.0]),
        );
        let motion = &baked.asset.motion;
        assert_eq!(motion.rig.joints.len(), 2, "{interpolation}");
        assert_eq!(motion.joints.len(), baked.asset.topology_positions.len());
        assert_eq!(baked.asset.motion.rig.animation("bend"), Some(0));
        let channel = &motion.rig.animations[0].channels[0];
        assert!(matches!(channel.target, Target::Rotation(_)));
        assert_eq!(
            channel.interpolation,
            match interpolation {
                "STEP" => Interpolation::Step,
                "CUBICSPLINE" => Interpolation::CubicSpline,
                _ => Interpolation::Linear,
            }
        );
        for time in [0.0, 0.25, 0.5, 0.999, 1.0, 2.0] {
            let pose = Pose::sampled(&motion.rig, 0, time as f32).expect("animation 0");
            let angle = bend_angle(interpolation, time);
            let error = worst(&baked, &pose, |i| {
                posed_cylinder_vertex(model[i].map(f64::from), angle)
            });
            assert!(error < 2e-6, "{interpolation} at {time} s: off by {error}");
        }
        // A control: the bent pose is not the rest pose (the comparison can fail).
        let bent = Pose::sampled(&motion.rig, 0, 1.0).expect("animation 0");
        let rest = worst(&baked, &bent, |i| model[i].map(f64::from));
        assert!(
            rest > 0.5,
            "{interpolation}: bending moved nothing ({rest})"
        );
    }
}

#[test]
fn a_morph_cube_rises_by_its_weight_and_keeps_its_rest_weight() {
    let (rest_weight, rise) = (0.25f32, f64::from(rigged::RISE));
    let baked = bake("cube.glb", &rigged::morph_cube(rest_weight));
    let motion = &baked.asset.motion;
    assert!(!motion.is_skinned(), "no skin, no joints");
    assert_eq!(motion.rig.morph_weights, [rest_weight]);
    assert_eq!(motion.rig.morph_names, ["rise"]);
    // 24 corners welded into 8 vertices; the top four move.
    assert_eq!(baked.asset.topology_positions.len(), 8);
    assert_eq!(motion.morph_target(0).0.len(), 4);
    let input = cube_input(&baked);
    let expect = |weight: f64| {
        let input = &input;
        move |i: usize| {
            let p: [f64; 3] = input[i];
            [
                p[0],
                if p[1] == 1.0 {
                    1.0 + weight * rise
                } else {
                    p[1]
                },
                p[2],
            ]
        }
    };
    let rest = Pose::rest(&motion.rig);
    assert!(worst(&baked, &rest, expect(0.25)) < 1e-6);
    let half = Pose::sampled(&motion.rig, 0, 0.5).expect("animation 0");
    assert_eq!(half.weights, [0.5]);
    assert!(worst(&baked, &half, expect(0.5)) < 1e-6);
    assert!(worst(&baked, &half, expect(0.0)) > 0.2, "control");
}

/// The cube's input positions, as the bake saw them (its topology positions mapped back).
fn cube_input(baked: &Baked) -> Vec<[f64; 3]> {
    baked
        .input_vertex_map
        .iter()
        .map(|&v| baked.asset.topology_positions[v as usize].map(f64::from))
        .collect()
}

#[test]
fn an_animated_asset_survives_encoding_and_a_still_one_has_no_motion_sections() {
    let baked = bake(
        "cylinder.glb",
        &rigged::skinned_cylinder("LINEAR", [0.0; 3]),
    );
    let decoded = Asset::decode(&baked.asset.encode_to_vec()).expect("decodes");
    assert_eq!(decoded.motion, baked.asset.motion);
    // A compact file keeps the motion sections raw.
    let compact = baked
        .asset
        .encode_compact_to_vec(
            &chamfer_runtime::asset::CompactOptions::LOSSLESS,
            &chamfer_preprocess::compact::Meshopt,
        )
        .expect("encodes");
    assert_eq!(
        Asset::decode(&compact).expect("decodes").motion,
        baked.asset.motion
    );
    let cube = bake("cube.glb", &rigged::morph_cube(0.0));
    let decoded = Asset::decode(&cube.asset.encode_to_vec()).expect("decodes");
    assert_eq!(decoded.motion, cube.asset.motion);
    let still = chamfer_tests::bake_fixture("meshes/cube.obj");
    assert!(still.motion.is_empty());
    let sections = still.encoded_sections();
    assert!(
        sections
            .iter()
            .filter(|s| s.kind >= chamfer_runtime::asset::SectionKind::SkinJoints as u32)
            .all(|s| s.length == 0),
        "a still asset stores no motion bytes"
    );
}

// --- Bad input -------------------------------------------------------------------------------

/// The cylinder's accessors, in the order `skinned_cylinder` adds them.
const JOINTS: usize = 2;
const WEIGHTS: usize = 3;
const INVERSE_BINDS: usize = 4;
const TIMES: usize = 5;

/// The GLB's JSON and binary chunks.
fn split(glb: &[u8]) -> (Value, Vec<u8>) {
    let json_len = u32::from_le_bytes(glb[12..16].try_into().expect("4 bytes")) as usize;
    let document = serde_json::from_slice(&glb[20..20 + json_len]).expect("JSON chunk");
    let bin = glb[20 + json_len + 8..].to_vec();
    (document, bin)
}

/// The skinned cylinder changed by `change`.
fn broken_cylinder(change: impl FnOnce(&mut Value, &mut Vec<u8>)) -> Vec<u8> {
    let (mut document, mut bin) = split(&rigged::skinned_cylinder("LINEAR", [0.0; 3]));
    change(&mut document, &mut bin);
    rigged::glb(&document, &bin)
}

/// Where accessor `a`'s element `e` component `k` (of `size` bytes each, `n` per element) lies.
fn at(document: &Value, a: usize, e: usize, k: usize, n: usize, size: usize) -> usize {
    let view = document["accessors"][a]["bufferView"]
        .as_u64()
        .expect("view") as usize;
    let start = document["bufferViews"][view]["byteOffset"]
        .as_u64()
        .expect("offset") as usize;
    start + (e * n + k) * size
}

fn set_f32(bin: &mut [u8], at: usize, value: f32) {
    bin[at..at + 4].copy_from_slice(&value.to_le_bytes());
}

/// The error baking `glb` gives, as text; it must name the file.
fn refused(glb: &[u8], limits: Limits) -> String {
    let options = BakeOptions::default().with_limits(limits);
    match chamfer_preprocess::bake_bytes(Path::new("broken.glb"), glb, &options) {
        Ok(_) => panic!("a broken file was baked"),
        Err(e) => {
            let text = e.to_string();
            assert!(
                text.contains("broken.glb"),
                "the error names the file: {text}"
            );
            assert!(!matches!(e, Error::Read { .. }), "{text}");
            text
        }
    }
}

#[test]
fn hostile_weights_that_are_nan_negative_or_do_not_sum_to_one() {
    let nan = broken_cylinder(|d, bin| set_f32(bin, at(d, WEIGHTS, 5, 0, 4, 4), f32::NAN));
    assert!(refused(&nan, Limits::DEFAULT).contains("NaN"));
    let negative = broken_cylinder(|d, bin| {
        set_f32(bin, at(d, WEIGHTS, 5, 0, 4, 4), 1.5);
        set_f32(bin, at(d, WEIGHTS, 5, 1, 4, 4), -0.5);
    });
    assert!(refused(&negative, Limits::DEFAULT).contains("negative"));
    let short = broken_cylinder(|d, bin| set_f32(bin, at(d, WEIGHTS, 5, 0, 4, 4), 0.5));
    let text = refused(&short, Limits::DEFAULT);
    assert!(
        text.contains("sum to") && text.contains("vertex 5"),
        "{text}"
    );
}

#[test]
fn hostile_joint_indices_out_of_range() {
    let glb = broken_cylinder(|d, bin| {
        let at = at(d, JOINTS, 67, 1, 4, 2);
        bin[at..at + 2].copy_from_slice(&9u16.to_le_bytes());
    });
    let text = refused(&glb, Limits::DEFAULT);
    assert!(
        text.contains("joint 9") && text.contains("2 joints"),
        "{text}"
    );
}

#[test]
fn hostile_a_skin_whose_inverse_bind_matrices_are_missing_or_short() {
    let missing = broken_cylinder(|d, _| d["skins"][0]["inverseBindMatrices"] = 99.into());
    assert!(refused(&missing, Limits::DEFAULT).contains("accessor 99 does not exist"));
    let short = broken_cylinder(|d, _| d["accessors"][INVERSE_BINDS]["count"] = 1.into());
    let text = refused(&short, Limits::DEFAULT);
    assert!(
        text.contains("2 joints but 1 inverse bind matrices"),
        "{text}"
    );
    // None at all is valid glTF: identities.
    let none = broken_cylinder(|d, _| {
        if let Some(skin) = d["skins"][0].as_object_mut() {
            skin.remove("inverseBindMatrices");
        }
    });
    bake("identities.glb", &none);
}

#[test]
fn hostile_morph_targets_of_a_different_length() {
    let (mut document, bin) = split(&rigged::morph_cube(0.0));
    document["accessors"][2]["count"] = 23.into();
    document["accessors"][2]["sparse"]["count"] = 3.into();
    let text = refused(&rigged::glb(&document, &bin), Limits::DEFAULT);
    assert!(
        text.contains("23 positions") && text.contains("24 vertices"),
        "{text}"
    );
}

#[test]
fn hostile_animations_with_non_increasing_times() {
    let glb = broken_cylinder(|d, bin| set_f32(bin, at(d, TIMES, 1, 0, 1, 4), 0.0));
    let text = refused(&glb, Limits::DEFAULT);
    assert!(
        text.contains("animation 0 channel 0") && text.contains("not increasing"),
        "{text}"
    );
}

#[test]
fn hostile_more_joints_than_the_limit() {
    let glb = rigged::skinned_cylinder("LINEAR", [0.0; 3]);
    // Counted from the skins the file declares, before anything is read: a typed limit error.
    let options = BakeOptions::default().with_limits(Limits::DEFAULT.with_max_joints(1));
    let error = chamfer_preprocess::bake_bytes(Path::new("broken.glb"), &glb, &options)
        .expect_err("more joints than the limit");
    assert!(
        matches!(
            error,
            Error::LimitExceeded {
                count: 2,
                limit: 1,
                ..
            }
        ),
        "{error}"
    );
    let text = refused(&glb, Limits::DEFAULT.with_max_joints(1));
    assert!(
        text.contains("2 joints") && text.contains("--max-joints"),
        "{text}"
    );
}

/// The generated files, kept in `fixtures/shapes/` for the fuzz harness and the other front ends'
/// tests; `CHAMFER_WRITE_FIXTURES=1` rewrites them.
#[test]
fn the_rigged_fixtures_are_what_the_generator_writes() {
    for (name, bytes) in [
        (
            "shapes/cylinder-skinned.glb",
            rigged::skinned_cylinder("LINEAR", [0.0; 3]),
        ),
        ("shapes/cube-morph.glb", rigged::morph_cube(0.0)),
    ] {
        let path = chamfer_tests::fixture(name);
        if std::env::var_os("CHAMFER_WRITE_FIXTURES").is_some() {
            std::fs::write(&path, &bytes).expect("write fixture");
        }
        let stored = std::fs::read(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            stored == bytes,
            "{name} differs from the generator's output"
        );
    }
}

// --- On the GPU ------------------------------------------------------------------------------

mod gpu {
    use super::*;
    use chamfer_preprocess::mesh::Mesh;
    use chamfer_runtime::render::{
        Camera, EdgeRenderer, GpuAsset, Image, MeshRenderer, Orbit, PosedAsset,
    };
    use chamfer_tests::cube::{BLUE_BACKGROUND, RED, edges_in, grey_mesh, is_red};
    use chamfer_tests::{gpu, pipelines};

    /// The posed topology positions the GPU wrote, read back.
    fn read_positions(posed: &PosedAsset) -> Vec<[f32; 3]> {
        let gpu = gpu();
        let source = posed.asset().topology_positions();
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("posed positions readback"),
            size: source.size(),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.encoder();
        encoder.copy_buffer_to_buffer(source, 0, &staging, 0, source.size());
        gpu.submit(encoder).expect("submit");
        let slice = staging.slice(..);
        slice.map_async(wgpu::MapMode::Read, |r| r.expect("map"));
        gpu.wait().expect("wait");
        let bytes = slice.get_mapped_range().expect("mapped");
        bytemuck::cast_slice::<u8, [f32; 3]>(&bytes).to_vec()
    }

    fn posed_on_the_gpu(asset: &Asset, pose: &Pose) -> (PosedAsset, Vec<[f32; 3]>) {
        let gpu = gpu();
        let target = gpu.target(8, 8, 1).expect("target");
        let pipelines = pipelines(target.formats());
        let uploaded = GpuAsset::new(&gpu.device, asset).expect("upload");
        let mut posed = PosedAsset::new(&pipelines, &uploaded).expect("posed");
        let mut encoder = gpu.encoder();
        posed
            .prepare(&gpu.queue, &mut encoder, pose)
            .expect("prepare");
        gpu.submit(encoder).expect("submit");
        let positions = read_positions(&posed);
        (posed, positions)
    }

    fn farthest(a: &[[f32; 3]], b: &[[f32; 3]]) -> f32 {
        a.iter()
            .zip(b)
            .map(|(p, q)| (glam::Vec3::from(*p) - glam::Vec3::from(*q)).length())
            .fold(0.0, f32::max)
    }

    #[test]
    fn the_gpu_poses_as_the_cpu_does() {
        for (name, glb) in [
            (
                "cylinder.glb",
                rigged::skinned_cylinder("CUBICSPLINE", [1.0, 0.0, 0.0]),
            ),
            ("cube.glb", rigged::morph_cube(0.25)),
        ] {
            let asset = bake(name, &glb).asset;
            let rig = &asset.motion.rig;
            for time in [0.0, 0.4, 1.0] {
                let pose = Pose::sampled(rig, 0, time).expect("animation 0");
                let cpu = asset
                    .motion
                    .pose_positions(&asset.topology_positions, &pose);
                let (posed, gpu) = posed_on_the_gpu(&asset, &pose);
                assert_eq!(gpu.len(), cpu.len());
                let off = farthest(&gpu, &cpu);
                assert!(
                    off < 1e-5,
                    "{name} at {time} s: the GPU is {off} from the CPU"
                );
                // The refitted box holds the pose.
                let [lo, hi] = posed.asset().bounds();
                assert!(
                    gpu.iter()
                        .all(|p| (0..3).all(|k| p[k] >= lo[k] - 1e-5 && p[k] <= hi[k] + 1e-5)),
                    "{name} at {time} s: a vertex outside the refitted box"
                );
            }
            let pose = Pose::sampled(rig, 0, 1.0).expect("animation 0");
            let (_, gpu) = posed_on_the_gpu(&asset, &pose);
            assert!(
                farthest(&gpu, &asset.topology_positions) > 0.1,
                "{name}: the control moved"
            );
        }
    }

    /// Bakes the cylinder, and the same cylinder posed on the CPU at the end of the bend (90°),
    /// with creases at 60° (the rims; the bend's folds stay smooth in both).
    fn cylinders() -> (Asset, Asset) {
        let options = BakeOptions::default().with_crease_deg(60.0);
        let glb = rigged::skinned_cylinder("LINEAR", [0.0; 3]);
        let animated = chamfer_preprocess::bake_bytes(Path::new("cylinder.glb"), &glb, &options)
            .expect("bakes")
            .asset;
        let (model, triangles) = rigged::cylinder();
        let positions = model
            .iter()
            .map(|p| {
                let q = posed_cylinder_vertex(p.map(f64::from), rigged::BEND);
                glam::Vec3::new(q[0] as f32, q[1] as f32, q[2] as f32)
            })
            .collect();
        let mesh = Mesh {
            positions,
            triangles,
            ..Mesh::default()
        };
        let still = chamfer_preprocess::bake(mesh, "bent.obj", &options)
            .expect("bakes")
            .asset;
        (animated, still)
    }

    /// One frame of `asset` (posed by `pose` when given) with the grey mesh and red edges.
    fn frame(asset: &Asset, pose: Option<&Pose>, camera: &Camera) -> Image {
        let gpu = gpu();
        let [width, height] = camera.viewport;
        let target = gpu.target(width, height, 1).expect("target");
        let pipelines = pipelines(target.formats());
        let uploaded = GpuAsset::new(&gpu.device, asset).expect("upload");
        let mut encoder = gpu.encoder();
        let mut posed = None;
        if let Some(pose) = pose {
            let p = posed.insert(PosedAsset::new(&pipelines, &uploaded).expect("posed"));
            p.prepare(&gpu.queue, &mut encoder, pose).expect("pose");
        }
        let drawn = posed.as_ref().map_or(&uploaded, PosedAsset::asset);
        let mut mesh = MeshRenderer::new(&pipelines, drawn).expect("mesh");
        mesh.prepare(&gpu.queue, camera, &grey_mesh());
        let mut edges = EdgeRenderer::new(&pipelines, drawn);
        let style = edges_in(RED, 2.0, Default::default());
        let prepared = edges
            .prepare(&gpu.queue, &mut encoder, camera, &style)
            .expect("prepare");
        {
            let mut pass = target.begin_pass(&mut encoder, BLUE_BACKGROUND);
            mesh.render(&mut pass);
            prepared.render(&mut pass);
        }
        gpu.submit(encoder).expect("submit");
        let image = target.read(gpu).expect("read");
        if let Ok(dir) = std::env::var("CHAMFER_TEST_IMAGES") {
            let n = if pose.is_some() { "posed" } else { "still" };
            chamfer_tests::save_png(&image, &Path::new(&dir).join(format!("motion-{n}.png")));
        }
        image
    }

    /// Red pixels of `a` with no red pixel of `b` within a pixel.
    fn unmatched(a: &Image, b: &Image) -> usize {
        let [w, h] = [a.width, a.height];
        let red = |image: &Image, x: i64, y: i64| {
            x >= 0
                && y >= 0
                && x < i64::from(w)
                && y < i64::from(h)
                && is_red(image.pixel(x as u32, y as u32))
        };
        let mut count = 0;
        for y in 0..i64::from(h) {
            for x in 0..i64::from(w) {
                if red(a, x, y) && !(-1..=1).any(|dy| (-1..=1).any(|dx| red(b, x + dx, y + dy))) {
                    count += 1;
                }
            }
        }
        count
    }

    #[test]
    fn a_bent_cylinder_draws_as_the_same_mesh_posed_on_the_cpu_and_baked_still() {
        let (animated, still) = cylinders();
        let bent = Pose::sampled(&animated.motion.rig, 0, 1.0).expect("animation 0");
        for (azimuth, elevation) in [(35.0, 25.0), (-120.0, 10.0), (90.0, 60.0)] {
            let orbit = Orbit {
                azimuth,
                elevation,
                ..Orbit::default()
            };
            let bounds = [still.header.bounds_min, still.header.bounds_max];
            let camera = Camera::orbit(bounds, &orbit, [320, 240]);
            let posed = frame(&animated, Some(&bent), &camera);
            let reference = frame(&still, None, &camera);
            let red = posed
                .rgba
                .chunks_exact(4)
                .filter(|p| is_red([p[0], p[1], p[2], p[3]]))
                .count();
            assert!(red > 500, "edges drawn ({red} red pixels)");
            let (extra, missing) = (unmatched(&posed, &reference), unmatched(&reference, &posed));
            assert!(
                extra == 0 && missing == 0,
                "from ({azimuth}, {elevation}): {extra} edge pixels beyond a pixel of the still \
                 render's, {missing} of its missing ({red} drawn)"
            );
            // The control: the rest pose is not the bent one.
            let rest = frame(&animated, None, &camera);
            assert!(unmatched(&rest, &reference) > 200, "the control differs");
        }
    }
}
