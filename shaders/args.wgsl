// Turns the number of drawn edges into the workgroup counts of the next-index join pass: one
// thread per drawn edge end, 256 per workgroup, at most 65535 workgroups per dimension.

struct Counts {
    edges: array<u32, 4>,
    caps: array<u32, 4>,
}

@group(0) @binding(0) var<storage, read> counts: Counts;
@group(0) @binding(1) var<storage, read_write> dispatch: array<u32, 4>;

@compute @workgroup_size(1)
fn args() {
    let groups = (2u * counts.edges[1] + 255u) / 256u;
    let x = min(groups, 65535u);
    dispatch[0] = x;
    dispatch[1] = select(0u, (groups + x - 1u) / max(x, 1u), x > 0u);
    dispatch[2] = 1u;
}
