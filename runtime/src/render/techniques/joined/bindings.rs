//! The joined technique's bindings: the asset sections its passes read, the frame's lists and its
//! instances (the numbers `shaders/compute.wgsl`, `draw.wgsl`, `args.wgsl`, `cull.wgsl`,
//! `batch.wgsl` and `instances.wgsl` use). Each pass binds only
//! what its entry points use, which keeps every stage within wgpu's default limit of 8 storage
//! buffers.

pub(crate) use crate::render::bindings::INSTANCE_FRAMES;
use crate::render::bindings::Kind::{Read, ReadWrite, Texture, Uniform};
use crate::render::bindings::{Binding, Bindings, FRAME, asset};
use crate::render::techniques::post;

/// The slot table: per (instance, edge) drawn, its slot + 1, written by classify, read by the joins.
pub(crate) const TABLE: Binding = Binding::new(16, "table", ReadWrite);
/// The drawn edges: (edge, drawn word) per slot.
pub(crate) const DRAWN: Binding = Binding::new(17, "drawn", ReadWrite);
/// Per drawn end, its split directions (the joins).
pub(crate) const JOINS: Binding = Binding::new(18, "joins", ReadWrite);
/// The indirect draws' arguments, the wanted count and the cap list.
pub(crate) const OUT: Binding = Binding::new(19, "out", ReadWrite);
/// Per slot, the edge's quad on screen.
pub(crate) const SCREEN: Binding = Binding::new(20, "screen", ReadWrite);
/// Per slot, a highlighted chamfer edge's record.
pub(crate) const CHAMFERS: Binding = Binding::new(21, "chamfers", ReadWrite);
/// The F(φ, n + 1) row of the highlight's exponent.
pub(crate) const COS_POWER: Binding = Binding::new(22, "cos_power", Read);
/// The highlight's light and material.
pub(crate) const LIGHTING: Binding = Binding::new(23, "lighting", Uniform);
/// Per drawn instance, its first slot.
pub(crate) const STARTS: Binding = Binding::new(24, "starts", ReadWrite);
/// Per drawn instance, its class colours.
pub(crate) const COLORS: Binding = Binding::new(25, "instance_colors", Read);
/// The indirect dispatch of the joins, sized by what an instance drew.
pub(crate) const DISPATCH: Binding = Binding::new(26, "dispatch", ReadWrite);
/// The clusters a chunk's cull pass kept.
pub(crate) const SURVIVORS: Binding = Binding::new(27, "survivors", ReadWrite);
/// The indirect dispatch over the kept clusters.
pub(crate) const CULL_DISPATCH: Binding = Binding::new(28, "cull_dispatch", ReadWrite);
/// The place pass writes whether each instance is in view.
const PLACED_FRAMES: Binding = Binding::new(29, "instance_frames", ReadWrite);
/// The highlight's image-based light: the environment's prefiltered maps.
pub(crate) const ENVIRONMENT: Binding = Binding::new(30, "environment", Read);

/// Per drawn end, the end of the one other drawn edge meeting it + 1 (the join pass, phase.wgsl).
pub(crate) const CHAINS: Binding = Binding::new(33, "chains", ReadWrite);
/// The dash phases' list ranking: the round's input and output (two buffers, swapped each round).
pub(crate) const RANKS_IN: Binding = Binding::new(34, "ranks_in", Read);
pub(crate) const RANKS_OUT: Binding = Binding::new(35, "ranks_out", ReadWrite);
/// Per slot, the hidden pattern's phase at end 0 and its sign along the edge.
pub(crate) const PHASES: Binding = Binding::new(36, "phases", ReadWrite);

/// What the draw passes read of the lists the compute passes wrote.
const fn read_only(binding: Binding) -> Binding {
    Binding::new(binding.index, binding.name, Read)
}

pub(crate) const CLASSIFY: Bindings = Bindings::compute(
    "classify",
    &[
        FRAME,
        STARTS,
        asset::TOPOLOGY,
        asset::EDGE_VERTICES,
        asset::ATTRIBUTES,
        TABLE,
        DRAWN,
        OUT,
        SCREEN,
        SURVIVORS,
        INSTANCE_FRAMES,
    ],
);
pub(crate) const CULL: Bindings = Bindings::compute(
    "cull",
    &[
        FRAME,
        OUT,
        SURVIVORS,
        asset::CLUSTERS,
        CULL_DISPATCH,
        INSTANCE_FRAMES,
    ],
);
pub(crate) const PLACE: Bindings = Bindings::compute("place", &[FRAME, OUT, PLACED_FRAMES]);
pub(crate) const JOIN: Bindings = Bindings::compute(
    "joins",
    &[
        FRAME,
        STARTS,
        asset::RINGS,
        TABLE,
        DRAWN,
        JOINS,
        OUT,
        SCREEN,
        asset::CAP_HEADS,
        INSTANCE_FRAMES,
        CHAINS,
    ],
);
pub(crate) const RECORDS: Bindings = Bindings::compute(
    "chamfer records",
    &[
        FRAME,
        asset::TOPOLOGY,
        asset::EDGE_VERTICES,
        asset::ATTRIBUTES,
        DRAWN,
        OUT,
        SCREEN,
        CHAMFERS,
        STARTS,
        INSTANCE_FRAMES,
        LIGHTING,
        asset::CORNERS,
    ],
);
pub(crate) const ARGS: Bindings = Bindings::compute("edge lists", &[FRAME, OUT, STARTS, DISPATCH]);
pub(crate) const DRAW: Bindings = Bindings::draw(
    "edge draw",
    &[
        FRAME,
        COLORS,
        read_only(DRAWN),
        read_only(JOINS),
        read_only(OUT),
        read_only(SCREEN),
        read_only(CHAMFERS),
        COS_POWER,
        LIGHTING,
        ENVIRONMENT,
        INSTANCE_FRAMES,
        read_only(PHASES),
    ],
);
/// The dash phases' passes (phase.wgsl), after the frame's joins; their dispatch is sized by
/// `rank_args` through [`ARGS`] (a buffer read as indirect arguments cannot be bound as well).
pub(crate) const PHASE: Bindings = Bindings::compute(
    "dash phases",
    &[
        FRAME,
        read_only(DRAWN),
        OUT,
        read_only(SCREEN),
        read_only(CHAINS),
        RANKS_IN,
        RANKS_OUT,
        PHASES,
    ],
);
pub(crate) const CORNER_DRAW: Bindings = Bindings::draw(
    "rounded corners",
    &[FRAME, asset::CORNERS, LIGHTING, ENVIRONMENT],
);
/// The outline pass's copy of the application's colour (`outline.wgsl`).
pub(crate) const SCENE_COLOR: Binding = Binding::new(32, "scene_color", Texture);
/// The outline pass over the silhouette strips (after the application's pass).
pub(crate) const OUTLINE_STRIPS: Bindings = Bindings::draw(
    "outline of silhouette strips",
    &[
        FRAME,
        read_only(DRAWN),
        read_only(SCREEN),
        read_only(CHAMFERS),
        INSTANCE_FRAMES,
        SCENE_COLOR,
        post::DEPTH,
    ],
);
/// The outline pass over the rounded corners, an instance at a time.
pub(crate) const OUTLINE_CORNERS: Bindings = Bindings::draw(
    "outline of rounded corners",
    &[FRAME, asset::CORNERS, LIGHTING, SCENE_COLOR, post::DEPTH],
);
pub(crate) const SEGMENTS: Bindings =
    Bindings::draw("intersection edges", &[FRAME, asset::SEGMENTS]);
