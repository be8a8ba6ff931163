//! Building the BVHs of the hidden-line drawing and the intersection search: obvhs's PLOC build
//! with its `fast_build` parameters, then reinsertion and leaf collapsing, as obvhs's own
//! `build_bvh2` helper does them. That helper also times the build with `std::time::Instant`,
//! which panics in a browser; this one has no clock.

use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::leaf_collapser::collapse;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::ploc::PlocBuilder;

/// A BVH over `boxes` (primitive `i` is `boxes[i]`), deterministic for any thread count.
pub(crate) fn build(boxes: &[Aabb]) -> Bvh2 {
    let config = BvhBuildParams::fast_build();
    let mut bvh = PlocBuilder::with_capacity(boxes.len()).build(
        config.ploc_search_distance,
        boxes,
        (0..boxes.len() as u32).collect(),
        config.sort_precision,
        config.search_depth_threshold,
    );
    let mut reinsertion = ReinsertionOptimizer::default();
    reinsertion.run(&mut bvh, config.reinsertion_batch_ratio, None);
    collapse(
        &mut bvh,
        config.max_prims_per_leaf.clamp(1, 255),
        config.collapse_traversal_cost,
    );
    reinsertion.run(
        &mut bvh,
        config.reinsertion_batch_ratio * config.post_collapse_reinsertion_batch_ratio_multiplier,
        None,
    );
    bvh
}
