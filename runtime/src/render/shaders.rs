//! The WGSL of each pass, assembled from the files in `shaders/` (one file per pass, plus the
//! shared definitions each pass needs in front of it).

const COMMON: &str = include_str!("../../../shaders/common.wgsl");
const COMPUTE: &str = include_str!("../../../shaders/compute.wgsl");
const DRAW: &str = include_str!("../../../shaders/draw.wgsl");
const HIGHLIGHT: &str = include_str!("../../../shaders/highlight.wgsl");

/// Edge classification, plus the per-frame reset and the final clamp.
pub fn classify() -> String {
    [
        COMMON,
        HIGHLIGHT,
        COMPUTE,
        include_str!("../../../shaders/classify.wgsl"),
    ]
    .concat()
}

/// Workgroup counts of the next-index join pass.
pub const ARGS: &str = include_str!("../../../shaders/args.wgsl");

/// Joins and caps, by next-index walk or cap buffer.
pub fn joins() -> String {
    [
        COMMON,
        HIGHLIGHT,
        COMPUTE,
        include_str!("../../../shaders/joins.wgsl"),
    ]
    .concat()
}

/// Chamfer records of highlighted edges.
pub fn chamfers() -> String {
    [
        COMMON,
        HIGHLIGHT,
        COMPUTE,
        include_str!("../../../shaders/chamfers.wgsl"),
    ]
    .concat()
}

/// Edge quads.
pub fn edges() -> String {
    [
        COMMON,
        HIGHLIGHT,
        DRAW,
        include_str!("../../../shaders/edges.wgsl"),
    ]
    .concat()
}

/// Cap sectors.
pub fn caps() -> String {
    [
        COMMON,
        HIGHLIGHT,
        DRAW,
        include_str!("../../../shaders/caps.wgsl"),
    ]
    .concat()
}

/// The lit mesh.
pub const MESH: &str = include_str!("../../../shaders/mesh.wgsl");
