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
