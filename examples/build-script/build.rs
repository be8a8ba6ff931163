//! Bakes every mesh under `assets/` into `OUT_DIR` (skipping unchanged ones); a broken mesh fails the build.

fn main() -> Result<(), chamfer_preprocess::Error> {
    let options = chamfer_preprocess::BakeOptions::DEFAULT
        .with_radius(chamfer_preprocess::Radius::Relative(0.01))
        .with_intersections(true);
    chamfer_preprocess::build::bake_dir("assets", &options)?;
    Ok(())
}
