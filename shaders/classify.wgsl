// Per frame, one thread per edge: which edges to draw (thesis §6.1, §10.4), appended to a compact
// list whose length is the instance count of the indirect draw.

// Before an instance's classification: its slots start at the count so far.
@compute @workgroup_size(1)
fn mark() {
    starts[frame.instance] = slots_filled();
}

@compute @workgroup_size(WORKGROUP)
fn classify(
    @builtin(global_invocation_id) id: vec3<u32>,
) {
    let e = thread_index(id);
    if e >= frame.edge_count {
        return;
    }
    let flags = attributes[e] & 0xffffu;
    let front_a = dot(planes[2u * e], frame.eye) > 0.0;
    let front_b = dot(planes[2u * e + 1u], frame.eye) > 0.0;
    var word = NOT_DRAWN;
    if frame.highlight != 0u && (flags & CHAMFER) != 0u && front_a && front_b {
        word = COLOR_RIDGE | DRAWN_HIGHLIGHT;
    } else {
        word = drawn_word(flags, front_a, front_b);
    }
    if word == NOT_DRAWN {
        // No store: `state` may keep a stale slot from an earlier frame; readers check it (joins.wgsl).
        return;
    }
    let s = edge_screen(e, word);
    word |= select(0u, ON_SCREEN, s.visible) | (s.clipped << CLIPPED_SHIFT)
        | (frame.instance << INSTANCE_SHIFT);
    let slot = atomicAdd(&out.edges.instance_count, 1u);
    if slot >= frame.capacity {
        // Past the lists: not drawn this frame; `finish` reports how many were wanted.
        return;
    }
    drawn[slot] = vec2<u32>(e, word);
    screen[slot] = to_record(s);
    state[e] = slot + 1u;
}
