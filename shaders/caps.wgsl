// Draws the round joins the join pass emitted: a square around the vertex, cut to the cap's sector,
// in the hidden style too when compiled with HIDDEN (display.wgsl).

struct CapVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) color: vec4<f32>,
    // The vertex in pixels (xy), then the radius (z).
    @location(1) @interpolate(flat) center: vec3<f32>,
    // Sector bounds: from (xy) counter-clockwise to (zw).
    @location(2) @interpolate(flat) sector: vec4<f32>,
    // Pixels along the edge from its start to this end (the pattern's phase here), and how far
    // into the distance fade the vertex is.
    @location(3) @interpolate(flat) along_fade: vec2<f32>,
}

@vertex
fn cap_vertex_main(
    @builtin(vertex_index) vertex: u32,
    @builtin(instance_index) instance: u32,
) -> CapVarying {
    var v: CapVarying;
    let cap = out.cap_list[instance];
    let slot = cap.end >> 1u;
    let item = drawn[slot];
    let s = from_record(screen[slot], item.y);
    if !s.visible {
        v.position = NOWHERE;
        return v;
    }
    let end = edge_end(s, cap.end & 1u);
    let corner = vec2<f32>(
        select(-1.0, 1.0, ((0x16u >> vertex) & 1u) == 1u),
        select(-1.0, 1.0, ((0x34u >> vertex) & 1u) == 1u),
    );
    // One pixel of margin so the sector's rim is never cut by the square.
    v.position = from_pixels(end.p + corner * (cap.radius + 1.0), end.depth, end.w);
    v.color = drawn_color(cap.color);
    v.center = vec3<f32>(end.p, cap.radius);
    v.sector = vec4<f32>(unpack2x16snorm(cap.from_dir), unpack2x16snorm(cap.to_dir));
    v.along_fade = vec2<f32>(
        pattern_phase(slot, select(0.0, distance(s.s0, s.s1), (cap.end & 1u) == 1u)),
        fade_at(from_pixels(end.p, end.depth, end.w)),
    );
    return v;
}

@fragment
fn cap_fragment(v: CapVarying) -> @location(0) vec4<f32> {
    let q = v.position.xy - v.center.xy;
    let r = display_reach(vec2<f32>(v.center.z), v.along_fade.y).x;
    if dot(q, q) > r * r
        || cross2(v.sector.xy, q) <= 0.0
        || cross2(q, v.sector.zw) <= 0.0 {
        discard;
    }
    return display_color(v.color, v.along_fade.x, v.along_fade.y);
}
