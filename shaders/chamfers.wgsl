// Per frame, after classify, one thread per drawn slot: for each highlighted chamfer edge, what its
// pixels need (a ChamferRecord, see highlight.wgsl), and its quad widened to the strip's projection
// and, at a silhouette, to the sharp edge (the pixels the outline pass trims, outline.wgsl).

// The pixels that edge end `end` hands over to a drawn rounded corner at its vertex (0: none, or the
// end was moved by the near plane or a section plane); `far` is the edge's other end.
fn hand_over_at(end: u32, clipped: u32, far: vec3<f32>) -> f32 {
    if lighting.corners == 0u || clipped != 0u {
        return 0.0;
    }
    let k = corner_of_end(end);
    if k == 0u {
        return 0.0;
    }
    let c = corner_at(k - 1u);
    return select(0.0, hand_over(c, far), corner_drawn(c));
}

// The edge's model-space points at the ends of its screen quad: where the near plane and the
// section planes left them, as `edge_screen` did.
fn quad_ends(p0: vec3<f32>, p1: vec3<f32>) -> array<vec3<f32>, 2> {
    let span = kept_span(p0, p1);
    return array<vec3<f32>, 2>(span_point(p0, p1, span.x), span_point(p0, p1, span.y));
}

@compute @workgroup_size(WORKGROUP)
fn chamfer_records(@builtin(global_invocation_id) id: vec3<u32>) {
    let first = first_slot();
    let slot = first + thread_index(id);
    if slot >= slots_filled() {
        return;
    }
    let item = drawn[slot];
    if (item.y & DRAWN_HIGHLIGHT) == 0u {
        return;
    }
    let e = item.x;
    // One dispatch per chunk of the asset's edges (gpu_asset.rs): each records its own.
    if e < frame.first_edge || e - frame.first_edge >= frame.edge_count {
        return;
    }
    enter_instance(item.y >> INSTANCE_SHIFT);
    let p0 = position(edge_vertex(4u * e));
    let p1 = position(edge_vertex(4u * e + 1u));
    let normals = face_normals(
        p0,
        p1,
        position(edge_vertex(4u * e + 2u)),
        position(edge_vertex(4u * e + 3u)),
        attributes[e] & 0xffffu,
    );
    let s = from_record(screen[slot], item.y);
    let middle = 0.5 * (p0 + p1);
    let radius = unpack2x16float(attributes[e] >> 16u).x * frame.radius_scale;
    let eye = view_eye();
    let distance = select(0.0, length(eye.xyz - middle), eye.w > 0.0);
    let ends = quad_ends(p0, p1);
    let record = ChamferRecord(
        vec4<f32>(normalize(normals[0]), radius),
        vec4<f32>(normalize(normals[1]), distance),
        vec4<f32>(ends[0], 0.0),
        vec4<f32>(ends[1], 0.0),
        eye,
        vec4<f32>(hand_over_at(2u * e, s.clipped & 1u, p1), hand_over_at(2u * e + 1u, s.clipped & 2u, p0), 0.0, 0.0),
        view_light_position(),
        vec4<f32>(view_light_axis(), 0.0),
    );
    chamfers[slot] = record;

    // The quad covers the sharp edge and the visible strip, on whichever side of the edge it lies,
    // plus a pixel and a half (the sections between the ends and the middle move a little off the
    // straight line between theirs), and sits that much further forward in depth so the faces it
    // overlaps do not hide it.
    let mvp = view_mvp();
    let quad = vec4<f32>(s.s0, s.s1);
    var left = 0.0;
    var right = 0.0;
    for (var k = 0u; k < 3u; k += 1u) {
        let section = section_at(record, mvp, quad, mix(s.s0, s.s1, 0.5 * f32(k)));
        if section.visible.x < section.visible.y {
            left = max(left, max(section.offsets.x, section.offsets.y));
            right = max(right, -min(section.offsets.x, section.offsets.y));
        }
    }
    left += 1.5;
    right += 1.5;
    var r = screen[slot];
    r.extents = vec4<f32>(left, left, right, right);
    let c0 = mvp * vec4<f32>(ends[0], 1.0);
    let c1 = mvp * vec4<f32>(ends[1], 1.0);
    let bias = frame.bias_px + max(left, right);
    r.depth_w.x = biased_depth_by(c0, bias);
    r.depth_w.y = biased_depth_by(c1, bias);
    screen[slot] = r;
}
