// Turns the number of drawn edges into the workgroup counts of the next-index join pass: one
// thread per drawn edge end, WORKGROUP per workgroup, at most MAX_GROUPS workgroups per dimension.

struct Cap {
    end: u32,
    color: u32,
    radius: f32,
    from_dir: u32,
    to_dir: u32,
}

struct Out {
    edges: array<u32, 4>,
    caps: array<u32, 4>,
    _pad: array<u32, 4>,
    cap_list: array<Cap>,
}

@group(0) @binding(0) var<storage, read> counts: Out;
@group(0) @binding(1) var<storage, read_write> dispatch: array<u32, 4>;

@compute @workgroup_size(1)
fn args() {
    let groups = (2u * counts.edges[1] + WORKGROUP - 1u) / WORKGROUP;
    let x = min(groups, MAX_GROUPS);
    dispatch[0] = x;
    dispatch[1] = select(0u, (groups + x - 1u) / max(x, 1u), x > 0u);
    dispatch[2] = 1u;
}
