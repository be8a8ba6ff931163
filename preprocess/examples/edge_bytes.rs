//! Bytes per kept edge of the edge, attribute, next-index and cap sections, beside the thesis' layouts
//! (§11.2) in the same accounting.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example edge_bytes
//! ```
//! "as baked" uses the index widths the asset chose; the "all u32" and "all u16" columns re-count the
//! same sections with every index 4 or 2 bytes wide. McGuire–Hughes: 2688 bits per edge and two caps
//! of 96 bits; the thesis' non-duplicate method: 640 bits per edge and one 576-bit cap per pair of
//! edges meeting at a vertex (counted here on the same kept edges).

use std::collections::HashMap;
use std::path::Path;

use chamfer_preprocess::{BakeOptions, bake_file};
use chamfer_runtime::asset::SectionKind;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures");
    let meshes = [
        "meshes/cube.obj",
        "shapes/cylinder-16.obj",
        "meshes/cylinder-trimesh-32.obj",
        "shapes/cone-16.obj",
        "shapes/sphere-16x32.obj",
        "meshes/teapot.obj",
        "meshes/suzanne.obj",
        "meshes/stanford-bunny.obj",
    ];
    println!(
        "| mesh | kept edges | cap heads | pairs | as baked B/edge | all u32 B/edge | all u16 B/edge | McGuire–Hughes B/edge | non-duplicate B/edge | smaller than M–H |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for mesh in meshes {
        let asset = bake_file(&root.join(mesh), &BakeOptions::DEFAULT)?.asset;
        let edges = asset.edge_count() as f64;
        let heads = asset.cap_heads.len() as f64;
        let baked: usize = [
            SectionKind::EdgeVertices,
            SectionKind::EdgeAttributes,
            SectionKind::NextEnds,
            SectionKind::CapHeads,
        ]
        .iter()
        .map(|&k| asset.section_bytes(k).len())
        .sum();
        let indices = 4.0 * edges + 2.0 * edges + heads; // edge vertices + next ends + cap heads
        let all_u32 = (indices * 4.0 + 4.0 * edges) / edges;
        let all_u16 = (indices * 2.0 + 4.0 * edges) / edges;
        let mut degree: HashMap<u32, u64> = HashMap::new();
        for end in 0..2 * asset.edge_count() as u32 {
            *degree.entry(asset.end_vertex(end)).or_default() += 1;
        }
        let pairs: u64 = degree
            .values()
            .map(|&d| d * (d.saturating_sub(1)) / 2)
            .sum();
        let mcguire_hughes = (2688.0 + 2.0 * 96.0) / 8.0;
        let non_duplicate = (640.0 * edges + 576.0 * pairs as f64) / 8.0 / edges;
        println!(
            "| {} | {edges} | {heads} | {pairs} | {:.1} | {all_u32:.1} | {all_u16:.1} | {mcguire_hughes:.0} | {non_duplicate:.0} | {:.0}× |",
            mesh.rsplit('/').next().unwrap_or(mesh),
            baked as f64 / edges,
            mcguire_hughes / all_u32,
        );
    }
    Ok(())
}
