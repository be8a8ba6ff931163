// The frame's draw lists as the compute passes write them (args.wgsl, compute.wgsl): two indirect
// draws (edges, caps), what the frame wanted, and the caps. draw.wgsl reads the same layout with plain
// counts (no atomics in read-only storage).

struct DrawArgs {
    vertex_count: u32,
    instance_count: atomic<u32>,
    first_vertex: u32,
    first_instance: u32,
}

// A round join filling the gap on the outside of a bend: the sector of radius `radius` around the
// end's point, from direction `from_dir` counter-clockwise to `to_dir` (both packed snorm).
struct Cap {
    end: u32,
    color: u32,
    radius: f32,
    from_dir: u32,
    to_dir: u32,
}

struct Out {
    edges: DrawArgs,
    caps: DrawArgs,
    // Edges the frame wanted to draw, past the lists' capacity or not (the host grows the lists).
    needed: u32,
    // Clusters the cull passes kept this frame (cull.wgsl).
    kept_clusters: u32,
    // The most clusters one cull pass wanted to keep, past the list's capacity or not (the host
    // grows the list), and the instances the place pass found in view (instances.wgsl).
    survivors_wanted: atomic<u32>,
    instances_in_view: atomic<u32>,
    cap_list: array<Cap>,
}
