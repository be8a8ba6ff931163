//! Our exact weld against meshoptimizer's `meshopt_generateVertexRemap` on the same positions
//! (issue 15): this times `weld(positions, 0.0)` (and, for reference, the bake's default relative
//! tolerance) on a mesh's positions; `scripts/bench-peers.py` times the peer on the same file.
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example bench_weld_remap -- MESH [RUNS]
//! ```
//! Prints one JSON object: the median seconds of each weld, the vertex and unique counts, on the
//! file's vertex positions and on its triangles' corner positions (one position per corner, as an
//! unindexed export or an STL file holds them).

use std::path::Path;
use std::time::Instant;

use chamfer_preprocess::weld::weld;
use chamfer_preprocess::{Limits, WeldTolerance, load};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mesh = args.first().ok_or("usage: bench_weld_remap MESH [RUNS]")?;
    let runs: usize = args.get(1).map_or(Ok(7), |r| r.parse())?;
    let mesh = load::load(Path::new(mesh), &Limits::DEFAULT)?.mesh;
    let corners: Vec<_> = mesh
        .triangles
        .as_flattened()
        .iter()
        .map(|&v| mesh.positions[v as usize])
        .collect();
    let mut fields = Vec::new();
    for (name, positions) in [("vertices", &mesh.positions), ("corners", &corners)] {
        let median = |epsilon: f32| {
            let mut times: Vec<f64> = (0..runs.max(1))
                .map(|_| {
                    let start = Instant::now();
                    let welded = weld(positions, epsilon);
                    let seconds = start.elapsed().as_secs_f64();
                    std::hint::black_box(welded);
                    seconds
                })
                .collect();
            times.sort_by(f64::total_cmp);
            times[times.len() / 2]
        };
        let tolerance = WeldTolerance::DEFAULT.distance(positions);
        fields.push(format!(
            "\"{name}\": {{\"weld_exact\": {}, \"weld_default\": {}, \"count\": {}, \"unique\": {}}}",
            median(0.0),
            median(tolerance),
            positions.len(),
            weld(positions, 0.0).positions.len()
        ));
    }
    println!(
        "{{{}, \"threads\": {}}}",
        fields.join(", "),
        rayon::current_num_threads()
    );
    Ok(())
}
