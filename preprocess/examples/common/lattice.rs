//! The benchmarks' many-instance scene (issue 28), shared by `bench_scene` and `bench_section`: ten
//! assets (fixtures shapes and meshes, each scaled into a unit cell) repeated over a
//! grid×grid×grid lattice, each turned a little.

use std::path::Path;

use chamfer_runtime::render::{GpuAsset, Technique};
use glam::{Mat4, Quat, Vec3};

pub const ASSETS: [&str; 10] = [
    "shapes/cube.obj",
    "shapes/cylinder-16.obj",
    "shapes/cone-16.obj",
    "shapes/sphere-16x32.obj",
    "shapes/step.obj",
    "meshes/suzanne.obj",
    "meshes/spot.obj",
    "meshes/teapot.obj",
    "meshes/fandisk.obj",
    "meshes/cow.obj",
];

/// The lattice: the assets uploaded for `techniques`, each instance's asset and transform, and
/// the lattice's bounds.
pub struct Lattice {
    pub assets: Vec<GpuAsset>,
    pub placed: Vec<(usize, Mat4)>,
    pub bounds: [[f32; 3]; 2],
}

/// Bakes the assets from `fixtures` (the fixtures folder) and places grid³ instances.
pub fn lattice(
    device: &wgpu::Device,
    fixtures: &Path,
    grid: usize,
    techniques: &[Technique],
) -> Result<Lattice, Box<dyn std::error::Error>> {
    let mut assets = Vec::new();
    let mut fits = Vec::new();
    for name in ASSETS {
        let asset = chamfer_preprocess::bake_file(&fixtures.join(name), &Default::default())?.asset;
        let [lo, hi] = [asset.header.bounds_min, asset.header.bounds_max].map(Vec3::from);
        // Into a cell of side 0.8 around the origin.
        fits.push(
            Mat4::from_scale(Vec3::splat(0.8 / (hi - lo).max_element().max(1e-6)))
                * Mat4::from_translation(-(lo + hi) * 0.5),
        );
        assets.push(GpuAsset::for_techniques(device, &asset, techniques)?);
    }
    let placed = (0..grid * grid * grid)
        .map(|i| {
            let (x, y, z) = (i % grid, (i / grid) % grid, i / (grid * grid));
            let a = i % ASSETS.len();
            let turn =
                Quat::from_rotation_y(i as f32 * 0.7) * Quat::from_rotation_x(i as f32 * 0.3);
            let transform = Mat4::from_translation(Vec3::new(x as f32, y as f32, z as f32))
                * Mat4::from_quat(turn)
                * fits[a];
            (a, transform)
        })
        .collect();
    let extent = grid as f32 - 1.0;
    Ok(Lattice {
        assets,
        placed,
        bounds: [[-0.5; 3], [extent + 0.5; 3]],
    })
}
