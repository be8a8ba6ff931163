// Per frame, one thread per edge of each instance: which edges to draw (thesis §6.1, §10.4), appended to a compact
// list whose length is the instance count of the indirect draw. `classify` runs over every edge of
// the dispatch; `classify_clusters` over the edges of the clusters cull.wgsl kept, one workgroup per
// cluster. Both draw exactly the same edges: a cluster is dropped only when none of its edges would
// pass `classify_edge`.

// Before a batch's classification: its slots start at the count so far, and no cluster is kept.
@compute @workgroup_size(1)
fn mark() {
    starts[frame.batch] = slots_filled();
    atomicStore(&survivors.count, 0u);
}

// One thread per (instance of the batch, edge of the chunk).
@compute @workgroup_size(WORKGROUP)
fn classify(@builtin(global_invocation_id) id: vec3<u32>) {
    let t = thread_index(id);
    let n = frame.edge_count;
    if n == 0u || t >= n * frame.batch_instances {
        return;
    }
    let instance = frame.instance + t / n;
    if !instance_visible(instance) {
        return;
    }
    enter_instance(instance);
    classify_edge(frame.first_edge + t % n);
}

@compute @workgroup_size(CLUSTER_EDGES)
fn classify_clusters(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) k: u32,
) {
    let g = group.y * MAX_GROUPS + group.x;
    if g >= survivors.kept {
        return;
    }
    let kept = survivors.clusters[g];
    enter_instance(kept.x);
    let i = kept.y * CLUSTER_EDGES + k;
    if i < frame.edge_count {
        classify_edge(frame.first_edge + i);
    }
}

fn classify_edge(e: u32) {
    let flags = attributes[e] & 0xffffu;
    let front = faces_front(e, flags);
    var word = NOT_DRAWN;
    // With the highlight, a chamfer edge with a face towards the camera is drawn as its strip, never
    // as a line; one on the silhouette (a face turned away) as the visible part of its strip, whose
    // outline the outline pass rounds (outline.wgsl).
    let seen_chamfer = (flags & CHAMFER) != 0u && (flags & (BOUNDARY | NON_MANIFOLD)) == 0u
        && (front.x || front.y);
    if frame.highlight != 0u && seen_chamfer {
        word = COLOR_RIDGE | DRAWN_HIGHLIGHT | select(0u, DRAWN_SILHOUETTE, front.x != front.y);
    } else {
        word = drawn_word(flags, front.x, front.y);
    }
    if word == NOT_DRAWN || edge_off_screen(e) {
        return;
    }
    let s = edge_screen(e, word);
    word |= select(0u, ON_SCREEN, s.visible) | (s.clipped << CLIPPED_SHIFT)
        | (view_instance() << INSTANCE_SHIFT);
    let slot = atomicAdd(&out.edges.instance_count, 1u);
    if slot >= frame.capacity {
        // Past the lists: not drawn this frame; `finish` reports how many were wanted.
        return;
    }
    drawn[slot] = vec2<u32>(e, word);
    screen[slot] = to_record(s);
    remember(view_instance(), e, slot);
}
