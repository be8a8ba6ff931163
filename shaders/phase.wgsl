// Dash phases along chains of drawn edges (issue 42, runtime/src/render/display.rs): where exactly
// two drawn edges meet (the join pass's `chains`), a hidden line's pattern continues across the
// join instead of restarting at every mesh edge. Each drawn edge is two directed items, (slot,
// forward) leaving by its end 1 and (slot, backward) leaving by its end 0; pointer jumping (Wyllie's
// list ranking) sums the screen lengths from every item to the end of its walk in log2(items)
// rounds. A closed loop never ends: after those rounds its items still point somewhere, so it is
// cut once, at end 0 of its lowest slot (where its backward item leaves and its forward item
// enters: both directions at one vertex), and ranked again. Per slot, `phases` then holds the
// pattern's phase at end 0 and its sign along the edge, measured from the chain's end with the
// lower slot, so every edge of a chain counts from the same end.

// What an item knows: the item its walk reaches next (NO_ITEM: none), the walk's last item so far,
// the screen length summed from here to there (this edge's included) and the lowest slot passed.
struct Rank {
    next: u32,
    last: u32,
    sum: f32,
    low: u32,
}

const NO_ITEM: u32 = 0xffffffffu;

@group(0) @binding(17) var<storage, read> drawn: array<vec2<u32>>;
@group(0) @binding(19) var<storage, read_write> out: Out;
@group(0) @binding(20) var<storage, read> screen: array<ScreenRecord>;
@group(0) @binding(26) var<storage, read_write> dispatch: array<u32, 4>;
@group(0) @binding(33) var<storage, read> chains: array<u32>;
@group(0) @binding(34) var<storage, read> ranks_in: array<Rank>;
@group(0) @binding(35) var<storage, read_write> ranks_out: array<Rank>;
@group(0) @binding(36) var<storage, read_write> phases: array<vec2<f32>>;

// Two items per drawn edge of the frame.
fn items() -> u32 {
    return 2u * min(atomicLoad(&out.edges.instance_count), frame.capacity);
}

fn edge_length(slot: u32) -> f32 {
    let s = from_record(screen[slot], drawn[slot].y);
    return select(0.0, distance(s.s0, s.s1), s.visible);
}

// The item after `i`: across the end it leaves by, into the edge joined there, the way that leaves
// that edge by its other end (entering by end 0 is its forward item, 2 slot + 0, by end 1 its
// backward one: the end's own index).
fn successor(i: u32) -> u32 {
    let leaving = 2u * (i >> 1u) + 1u - (i & 1u);
    let joined = chains[leaving];
    if joined == 0u || joined - 1u >= items() || chains[joined - 1u] != leaving + 1u {
        return NO_ITEM;
    }
    return joined - 1u;
}

// The workgroups of one thread per item (one per drawn edge end, as the join pass runs).
@compute @workgroup_size(1)
fn rank_args() {
    let groups = (items() + WORKGROUP - 1u) / WORKGROUP;
    let x = min(groups, MAX_GROUPS);
    dispatch[0] = x;
    dispatch[1] = select(0u, (groups + x - 1u) / max(x, 1u), x > 0u);
    dispatch[2] = 1u;
}

@compute @workgroup_size(WORKGROUP)
fn rank_init(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = thread_index(id);
    if i >= items() {
        return;
    }
    ranks_out[i] = Rank(successor(i), i, edge_length(i >> 1u), i >> 1u);
}

@compute @workgroup_size(WORKGROUP)
fn rank_jump(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = thread_index(id);
    if i >= items() {
        return;
    }
    var r = ranks_in[i];
    if r.next != NO_ITEM {
        let n = ranks_in[r.next];
        r = Rank(n.next, n.last, r.sum + n.sum, min(r.low, n.low));
    }
    ranks_out[i] = r;
}

@compute @workgroup_size(WORKGROUP)
fn rank_cut(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = thread_index(id);
    if i >= items() {
        return;
    }
    let ranked = ranks_in[i];
    var next = successor(i);
    if ranked.next != NO_ITEM && (i == 2u * ranked.low + 1u || next == 2u * ranked.low) {
        next = NO_ITEM;
    }
    ranks_out[i] = Rank(next, i, edge_length(i >> 1u), i >> 1u);
}

@compute @workgroup_size(WORKGROUP)
fn rank_finish(@builtin(global_invocation_id) id: vec3<u32>) {
    let slot = thread_index(id);
    if 2u * slot >= items() {
        return;
    }
    let forward = ranks_in[2u * slot];
    let backward = ranks_in[2u * slot + 1u];
    if (backward.last >> 1u) <= (forward.last >> 1u) {
        // From the chain's end behind end 0: its length up to end 0, growing along the edge.
        phases[slot] = vec2<f32>(backward.sum - edge_length(slot), 1.0);
    } else {
        // From the end beyond end 1: its length up to end 0 (this edge's included), shrinking.
        phases[slot] = vec2<f32>(forward.sum, -1.0);
    }
}
