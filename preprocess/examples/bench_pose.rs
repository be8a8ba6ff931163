//! What posing an animated asset costs each frame (issue 41), headless, against the same mesh
//! drawn still in the same run.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_pose -- [--frames 9] [--size 1920x1080]
//!     [--vertices 10000,100000,1000000] [--joints 16]
//! ```
//! Per size, a tube of about that many vertices is baked and given a skin of `--joints` joints in a
//! chain along it (each vertex on its two nearest joints), bent a little each frame. Round-robin
//! after two warm-up rounds, each frame timed from encoding to the GPU finishing, medians shown:
//! the posing pass alone; the still frame (mesh pass and joined edges); the posed frame (posing,
//! then the same passes over the posed buffers, whose clusters cull nothing). Also the bytes the
//! skin sections add per topology vertex.

use std::time::Instant;

use chamfer_preprocess::mesh::Mesh;
use chamfer_runtime::asset::{Asset, Motion};
use chamfer_runtime::render::{
    Camera, EdgeRenderer, EdgeStyle, GpuAsset, MeshRenderer, MeshStyle, Offscreen, Orbit,
    Pipelines, PosedAsset,
};
use chamfer_runtime::rig::{Joint, Node, Pose, Rig, Transform};
use glam::{Mat4, Quat, Vec3};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn main() -> Result<()> {
    let mut frames = 9;
    let mut size = [1920, 1080];
    let mut sizes = vec![10_000usize, 100_000, 1_000_000];
    let mut joints = 16usize;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().ok_or_else(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--frames" => frames = value()?.parse()?,
            "--joints" => joints = value()?.parse::<usize>()?.max(2),
            "--vertices" => {
                sizes = value()?
                    .split(',')
                    .map(str::parse)
                    .collect::<std::result::Result<_, _>>()?
            }
            "--size" => {
                let text = value()?;
                let (w, h) = text.split_once('x').ok_or("--size needs WxH")?;
                size = [w.parse()?, h.parse()?];
            }
            other => return Err(format!("unknown argument {other}").into()),
        }
    }
    let gpu = Offscreen::new()?;
    println!(
        "adapter: {} ({:?}), {}x{}, {joints} joints, {frames} frames per row (medians)\n",
        gpu.info.name, gpu.info.backend, size[0], size[1]
    );
    println!(
        "| vertices | triangles | edges | posing ms | still frame ms | posed frame ms | overhead | skin bytes / vertex |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &vertices in &sizes {
        let still = tube(vertices)?;
        let animated = skinned(&still, joints);
        let skin_bytes = animated.encoded_len() - still.encoded_len();
        let target = gpu.target(size[0], size[1], 1)?;
        let pipelines = Pipelines::new(&gpu.device, &target.formats())?;
        let still_gpu = GpuAsset::new(&gpu.device, &still)?;
        let animated_gpu = GpuAsset::new(&gpu.device, &animated)?;
        let mut posed = PosedAsset::new(&pipelines, &animated_gpu)?;
        let rig = &animated.motion.rig;
        let camera = Camera::orbit(still_gpu.bounds(), &Orbit::default(), size);
        let style = EdgeStyle::default();
        let mut still_mesh = MeshRenderer::new(&pipelines, &still_gpu)?;
        let mut still_edges = EdgeRenderer::new(&pipelines, &still_gpu);
        let mut posed_mesh = MeshRenderer::new(&pipelines, posed.asset())?;
        let mut posed_edges = EdgeRenderer::new(&pipelines, posed.asset());
        let mut times = [Vec::new(), Vec::new(), Vec::new()];
        for round in 0..frames + 2 {
            let pose = bent(rig, joints, round as f32 * 0.05);
            let start = Instant::now();
            let mut encoder = gpu.encoder();
            posed.prepare(&gpu.queue, &mut encoder, &pose)?;
            gpu.submit(encoder)?;
            let posing = start.elapsed().as_secs_f64() * 1e3;
            let frame = |mesh: &mut MeshRenderer,
                         edges: &mut EdgeRenderer,
                         posed: Option<&mut PosedAsset>|
             -> Result<f64> {
                let start = Instant::now();
                let mut encoder = gpu.encoder();
                if let Some(posed) = posed {
                    posed.prepare(&gpu.queue, &mut encoder, &pose)?;
                }
                mesh.prepare(&gpu.queue, &camera, &MeshStyle::default());
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
            let still_ms = frame(&mut still_mesh, &mut still_edges, None)?;
            let posed_ms = frame(&mut posed_mesh, &mut posed_edges, Some(&mut posed))?;
            if round >= 2 {
                for (list, t) in times.iter_mut().zip([posing, still_ms, posed_ms]) {
                    list.push(t);
                }
            }
        }
        let [posing, still_ms, posed_ms] = times.map(|mut v| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        });
        println!(
            "| {} | {} | {} | {posing:.2} | {still_ms:.1} | {posed_ms:.1} | {:.2}× | {:.1} |",
            still.topology_positions.len(),
            still.triangle_count(),
            still.edge_count(),
            posed_ms / still_ms,
            skin_bytes as f64 / still.topology_positions.len() as f64,
        );
    }
    Ok(())
}

/// A closed tube along y, height 4, of about `vertices` vertices (rings of 64), baked.
fn tube(vertices: usize) -> Result<Asset> {
    let around = 64usize;
    let rings = (vertices / around).max(3);
    let mut positions = Vec::with_capacity(rings * around + 2);
    for r in 0..rings {
        let y = 4.0 * r as f32 / (rings - 1) as f32;
        for s in 0..around {
            let a = std::f32::consts::TAU * s as f32 / around as f32;
            positions.push(Vec3::new(0.3 * a.cos(), y, 0.3 * a.sin()));
        }
    }
    positions.push(Vec3::ZERO);
    positions.push(Vec3::new(0.0, 4.0, 0.0));
    let at = |r: usize, s: usize| (r * around + s % around) as u32;
    let mut triangles = Vec::with_capacity(2 * rings * around);
    for r in 0..rings - 1 {
        for s in 0..around {
            triangles.push([at(r, s), at(r + 1, s), at(r, s + 1)]);
            triangles.push([at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)]);
        }
    }
    let (bottom, top) = ((rings * around) as u32, (rings * around + 1) as u32);
    for s in 0..around {
        triangles.push([bottom, at(0, s), at(0, s + 1)]);
        triangles.push([top, at(rings - 1, s + 1), at(rings - 1, s)]);
    }
    let mesh = Mesh {
        positions,
        triangles,
        ..Mesh::default()
    };
    let options =
        chamfer_preprocess::BakeOptions::DEFAULT.with_limits(chamfer_preprocess::Limits::NONE);
    Ok(chamfer_preprocess::bake(mesh, "tube", &options)?.asset)
}

/// `still` with a chain of `joints` joints up the tube (each vertex on its two nearest).
fn skinned(still: &Asset, joints: usize) -> Asset {
    let step = 4.0 / (joints - 1) as f32;
    let nodes = (0..joints)
        .map(|j| Node {
            name: format!("joint {j}"),
            parent: j.checked_sub(1).map(|p| p as u32),
            rest: Transform {
                translation: [0.0, if j == 0 { 0.0 } else { step }, 0.0],
                ..Transform::IDENTITY
            },
        })
        .collect();
    let rig_joints = (0..joints)
        .map(|j| Joint {
            node: j as u32,
            inverse_bind: Mat4::from_translation(Vec3::new(0.0, -step * j as f32, 0.0))
                .to_cols_array(),
        })
        .collect();
    let (mut vertex_joints, mut weights) = (Vec::new(), Vec::new());
    for p in &still.topology_positions {
        let at = (p[1] / step).clamp(0.0, (joints - 1) as f32);
        let low = (at.floor() as usize).min(joints - 2);
        let t = at - low as f32;
        vertex_joints.push([low as u16, low as u16 + 1, 0, 0]);
        weights.push([1.0 - t, t, 0.0, 0.0]);
    }
    Asset {
        motion: Motion {
            joints: vertex_joints,
            weights,
            rig: Rig {
                nodes,
                joints: rig_joints,
                ..Rig::default()
            },
            ..Motion::default()
        },
        ..still.clone()
    }
}

/// Every joint turned `angle` about z: the tube curls.
fn bent(rig: &Rig, joints: usize, angle: f32) -> Pose {
    let locals: Vec<Transform> = rig
        .nodes
        .iter()
        .map(|n| Transform {
            rotation: Quat::from_rotation_z(angle / joints as f32).to_array(),
            ..n.rest
        })
        .collect();
    Pose::of_nodes(rig, &locals, Vec::new())
}
