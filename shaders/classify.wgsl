// Per frame, one thread per edge: which edges to draw (thesis §6.1, §10.4), appended to a compact
// list whose length is the instance count of the indirect draw.

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
    word |= select(0u, ON_SCREEN, s.visible) | (s.clipped << CLIPPED_SHIFT);
    let slot = atomicAdd(&out.edges.instance_count, 1u);
    drawn[slot] = vec2<u32>(e, word);
    screen[slot] = to_record(s);
    state[e] = slot + 1u;
}

// The cap list is bounded; never let the draw read past it.
@compute @workgroup_size(1)
fn finish() {
    let caps = atomicLoad(&out.caps.instance_count);
    atomicStore(&out.caps.instance_count, min(caps, frame.cap_capacity));
}
