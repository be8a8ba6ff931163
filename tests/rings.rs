//! Property test: next-index rings are closed and complete on arbitrary triangle soups, including
//! non-manifold, inconsistently wound, degenerate and open ones.

use chamfer_preprocess::mesh::{Mesh, MeshError};
use chamfer_preprocess::{BakeOptions, Error, bake};
use chamfer_tests::check_rings;
use glam::Vec3;
use proptest::prelude::*;

fn soup() -> impl Strategy<Value = Mesh> {
    (4usize..24).prop_flat_map(|n| {
        (
            proptest::collection::vec((0..8i32, 0..8i32, 0..4i32), n),
            proptest::collection::vec([0..n as u32, 0..n as u32, 0..n as u32], 1..60),
        )
            .prop_map(|(points, triangles)| Mesh {
                // Points on a small integer grid: coplanar faces and exact zero areas happen often.
                positions: points
                    .iter()
                    .map(|&(x, y, z)| Vec3::new(x as f32, y as f32, z as f32))
                    .collect(),
                triangles,
                ..Mesh::default()
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn rings_are_closed_and_complete(mesh in soup()) {
        match bake(mesh, "soup", &BakeOptions::DEFAULT) {
            Ok(baked) => {
                let asset = chamfer_runtime::asset::Asset::decode(&baked.asset.encode_to_vec())
                    .map_err(|e| TestCaseError::fail(e.to_string()))?;
                check_rings(&asset).map_err(TestCaseError::fail)?;
            }
            // A soup whose every triangle is degenerate has nothing to check; anything else is a failure.
            Err(Error::Mesh { source: MeshError::AllDegenerate { .. }, .. }) => {}
            Err(e) => return Err(TestCaseError::fail(e.to_string())),
        }
    }
}
