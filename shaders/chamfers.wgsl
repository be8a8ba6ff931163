// Per frame, after classify, one thread per drawn slot: for each highlighted chamfer edge, what its
// pixels need (a ChamferRecord, see highlight.wgsl), and its quad widened to the strip's projection.

// The pixels that edge end `end` hands over to a drawn rounded corner at its vertex (0: none, or the
// end was moved by the near-plane clip); `far` is the edge's other end.
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
    let n1 = normalize(normals[0]);
    let n2 = normalize(normals[1]);
    let middle = 0.5 * (p0 + p1);
    let to_viewer = to_viewer_at(middle);
    var across = normalize(cross(to_viewer, normalize(p1 - p0)));
    let s = from_record(screen[slot], item.y);
    let mvp = view_mvp();
    let c = mvp * vec4<f32>(middle, 1.0);
    let pixel = frame.pixel_scale * c.w;
    // P must point along the quad's left normal on screen.
    let nudged = mvp * vec4<f32>(middle + across * pixel, 1.0);
    if dot(to_pixels(nudged) - to_pixels(c), perp(s.d)) < 0.0 {
        across = -across;
    }
    let radius = unpack2x16float(attributes[e] >> 16u).x * frame.radius_scale;
    let eye = view_eye();
    let distance = select(0.0, length(eye.xyz - middle), eye.w > 0.0);
    let record = ChamferRecord(
        vec4<f32>(n1, radius / pixel),
        vec4<f32>(n2, dot(across, n1 + n2) / (1.0 + dot(n1, n2))),
        vec4<f32>(across, distance),
        vec4<f32>(middle, radius),
        vec4<f32>(to_viewer, 0.0),
        vec4<f32>(hand_over_at(2u * e, s.clipped & 1u, p1), hand_over_at(2u * e + 1u, s.clipped & 2u, p0), 0.0, 0.0),
        view_light_position(),
        vec4<f32>(view_light_axis(), 0.0),
    );
    chamfers[slot] = record;

    // The quad covers the visible strip plus a pixel, on whichever side of the sharp edge it lies,
    // and sits that much further forward in depth so the faces it overlaps do not hide it.
    let arc = arc_of(n1, n2);
    let visible = visible_range(arc, to_viewer);
    var left = 0.0;
    var right = 0.0;
    if visible.x < visible.y {
        let a = strip_offset(record, arc, visible.x);
        let b = strip_offset(record, arc, visible.y);
        left = max(max(a, b), 0.0) + 1.0;
        right = max(-min(a, b), 0.0) + 1.0;
    }
    var r = screen[slot];
    r.extents = vec4<f32>(left, left, right, right);
    let c0 = mvp * vec4<f32>(p0, 1.0);
    let c1 = mvp * vec4<f32>(p1, 1.0);
    let bias = frame.bias_px + max(left, right);
    if (s.clipped & 1u) == 0u {
        r.depth_w.x = biased_depth_by(c0, bias);
    }
    if (s.clipped & 2u) == 0u {
        r.depth_w.y = biased_depth_by(c1, bias);
    }
    screen[slot] = r;
}
