//! The WGSL sources of Chamfer's renderer, one file per pass or technique, as string constants.
//!
//! This crate is the one place the shaders live; `chamfer-runtime` assembles each pipeline's module
//! from these pieces (shared definitions first, then the pass) and prepends the constants it shares
//! with the Rust side, so a constant is never written twice. See `README.md` for what each file holds.
//!
//! ```
//! // Each file is a constant, and `ALL` lists them by file name (for tools that check or bundle WGSL).
//! assert!(chamfer_shaders::COMMON.contains("struct Frame"));
//! let (name, source) = chamfer_shaders::ALL[0];
//! assert_eq!((name, source), ("common.wgsl", chamfer_shaders::COMMON));
//! ```

macro_rules! wgsl {
    ($($(#[$doc:meta])* $name:ident = $file:literal;)*) => {
        $($(#[$doc])* pub const $name: &str = include_str!($file);)*
        /// Every file, by name (for tooling and tests).
        pub const ALL: &[(&str, &str)] = &[$(($file, $name)),*];
    };
}

wgsl! {
    /// Frame uniform, asset reads, an edge's screen quad: shared by every object-space edge pass.
    COMMON = "common.wgsl";
    /// The draw lists' layout as the compute passes write it.
    LISTS = "lists.wgsl";
    /// Read-write bindings of the compute passes.
    COMPUTE = "compute.wgsl";
    /// Read-only bindings of the draw passes.
    DRAW = "draw.wgsl";
    /// The chamfer highlight of seed 000.
    HIGHLIGHT = "highlight.wgsl";
    /// Per-frame cluster culling before classification.
    CULL = "cull.wgsl";
    /// Per-frame edge classification and compaction.
    CLASSIFY = "classify.wgsl";
    /// Workgroup counts of the join pass.
    ARGS = "args.wgsl";
    /// Joins and caps (next-index walk or cap buffer).
    JOINS = "joins.wgsl";
    /// Records of highlighted chamfer edges.
    CHAMFERS = "chamfers.wgsl";
    /// Compacted edge quads.
    EDGES = "edges.wgsl";
    /// Round caps.
    CAPS = "caps.wgsl";
    /// The lit mesh pass.
    MESH = "mesh.wgsl";
    /// Baked intersection edges, drawn like creases.
    INTERSECTIONS = "intersections.wgsl";
    /// Flat-coloured pulled geometry.
    FLAT = "flat.wgsl";
    /// Per-vertex edge classification and screen values (thesis §8.2–8.3).
    VERTEX_EDGES = "vertex_edges.wgsl";
    /// McGuire–Hughes edges and caps (thesis §8).
    MCGUIRE_HUGHES = "mcguire_hughes.wgsl";
    /// Half-hex, plug and house edges (thesis §9.3).
    ALTERNATE = "alternate.wgsl";
    /// Fins (seed 003).
    FINS = "fins.wgsl";
    /// Triangles pulled from the render sections.
    TRIANGLES = "triangles.wgsl";
    /// The barycentric thick wireframe (seed 001).
    WIREFRAME = "wireframe.wgsl";
    /// The hardware contour methods (thesis §4).
    HARDWARE = "hardware.wgsl";
    /// Surface-angle contours (thesis §7.1).
    SURFACE_ANGLE = "surface_angle.wgsl";
    /// The inverted hull (thesis §7.2).
    INVERTED_HULL = "inverted_hull.wgsl";
    /// What the post-processes share.
    POST = "post.wgsl";
    /// The application's depth, single-sampled.
    DEPTH_SINGLE = "depth_single.wgsl";
    /// The application's depth, multisampled.
    DEPTH_MULTI = "depth_multi.wgsl";
    /// The hybrid depth shader (seed 004).
    HYBRID = "hybrid.wgsl";
    /// Image-space gradient operators (thesis §5).
    IMAGE_SPACE = "image_space.wgsl";
}
