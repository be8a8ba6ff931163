//! Loads the assets `build.rs` baked and embedded, and prints what they hold.

use chamfer_runtime::asset::Asset;

static CUBE: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/cube.chamfer"));
static MARKED_CUBE: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/marked-cube.chamfer"));
static TWO_CUBES: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/two-cubes.chamfer"));

fn main() -> Result<(), chamfer_runtime::asset::DecodeError> {
    for (name, bytes) in [
        ("cube", CUBE),
        ("marked-cube", MARKED_CUBE),
        ("two-cubes", TWO_CUBES),
    ] {
        let asset = Asset::decode(bytes)?;
        let stats = asset.header.stats;
        println!(
            "{name}: {} triangles, {} edges ({} creases, {} chamfered), {} intersection polylines \
             {:.3} long, {} bytes",
            asset.triangle_count(),
            asset.edge_count(),
            stats.edges.crease,
            stats.chamfer.edges,
            asset.intersection_polylines().len(),
            asset.intersection_length(),
            bytes.len()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_assets_decode_with_their_chamfer_edges() {
        let cube = Asset::decode(CUBE).expect("baked by build.rs");
        assert_eq!(cube.edge_count(), 12);
        assert_eq!(
            cube.header.stats.chamfer.edges, 12,
            "the radius rule of build.rs"
        );
        let marked = Asset::decode(MARKED_CUBE).expect("baked by build.rs");
        assert_eq!(marked.header.stats.edges.marked, 4);
        assert_eq!(marked.header.stats.chamfer.edges, 13);
        assert_eq!(cube.intersection_polylines().len(), 0);
        let cubes = Asset::decode(TWO_CUBES).expect("baked by build.rs");
        assert_eq!(
            cubes.intersection_polylines().len(),
            1,
            "with_intersections in build.rs"
        );
        assert!((cubes.intersection_length() - 3.9).abs() < 1e-5);
    }
}
