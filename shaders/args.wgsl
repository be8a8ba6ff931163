// The frame's bookkeeping passes over the draw lists: `reset` before the first batch, `args` after
// each batch's classification (the workgroup counts of its join pass: one thread per drawn edge
// end, WORKGROUP per workgroup, at most MAX_GROUPS per dimension), `finish` after the last (the
// lists' counts clamped to their capacity, and what was wanted). Included after common.wgsl, for the
// frame uniform, and lists.wgsl.

@group(0) @binding(19) var<storage, read_write> out: Out;
@group(0) @binding(24) var<storage, read_write> starts: array<u32>;
@group(0) @binding(26) var<storage, read_write> dispatch: array<u32, 4>;

@compute @workgroup_size(1)
fn reset() {
    out.edges.vertex_count = 6u;
    atomicStore(&out.edges.instance_count, 0u);
    out.edges.first_vertex = 0u;
    out.edges.first_instance = 0u;
    out.caps.vertex_count = 6u;
    atomicStore(&out.caps.instance_count, 0u);
    out.caps.first_vertex = 0u;
    out.caps.first_instance = 0u;
    out.kept_clusters = 0u;
    atomicStore(&out.survivors_wanted, 0u);
    atomicStore(&out.instances_in_view, 0u);
}

@compute @workgroup_size(1)
fn args() {
    let filled = min(atomicLoad(&out.edges.instance_count), frame.capacity) - starts[frame.batch];
    let groups = (2u * filled + WORKGROUP - 1u) / WORKGROUP;
    let x = min(groups, MAX_GROUPS);
    dispatch[0] = x;
    dispatch[1] = select(0u, (groups + x - 1u) / max(x, 1u), x > 0u);
    dispatch[2] = 1u;
}

// The lists are bounded; never let the draws read past them, and say how much was wanted.
@compute @workgroup_size(1)
fn finish() {
    let wanted = atomicLoad(&out.edges.instance_count);
    out.needed = wanted;
    atomicStore(&out.edges.instance_count, min(wanted, frame.capacity));
    let caps = atomicLoad(&out.caps.instance_count);
    atomicStore(&out.caps.instance_count, min(caps, frame.cap_capacity));
}
