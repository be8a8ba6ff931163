// Draws each drawn edge as a screen-space quad (thesis §8.3): six vertices per instance, pulled from
// the compact list. The fragment shader cuts the quad where it meets its neighbours (see joins.wgsl).
// Highlighted chamfer edges are drawn by a second pipeline over the same list (strip_vertex,
// strip_fragment): the lit rounded strips of seed 000 (highlight.wgsl), at their faces' depth.
// Compiled with HIDDEN (display.wgsl), edge_vertex_main and edge_fragment draw the hidden part of
// every drawn edge, highlighted ones too, as lines in the hidden style.

struct EdgeVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) color: vec4<f32>,
    // End points in pixels: end 0 in xy, end 1 in zw.
    @location(1) @interpolate(flat) ends: vec4<f32>,
    // Split directions: end 0 left, end 0 right, end 1 left, end 1 right.
    @location(2) @interpolate(flat) splits: vec4<u32>,
    // Slot and drawn word.
    @location(3) @interpolate(flat) item: vec2<u32>,
    // The quad's reach left and right of the centre line here, pixels.
    @location(4) @interpolate(linear) reach: vec2<f32>,
    // How far into the distance fade (fade_at).
    @location(5) @interpolate(linear) fade: f32,
}

// The quad of slot `slot` if its edge is drawn as a highlight strip (`strips`) or as a line (not).
fn edge_varying(vertex: u32, slot: u32, strips: bool) -> EdgeVarying {
    var v: EdgeVarying;
    let item = drawn[slot];
    let s = from_record(screen[slot], item.y);
    let as_strip = (item.y & DRAWN_HIGHLIGHT) != 0u && !HIDDEN;
    if !s.visible || as_strip != strips {
        v.position = NOWHERE;
        return v;
    }
    v.position = quad_vertex(s, vertex);
    let at_end_1 = ((0x16u >> vertex) & 1u) == 1u;
    v.reach = select(vec2<f32>(s.left.x, s.right.x), vec2<f32>(s.left.y, s.right.y), at_end_1);
    v.fade = fade_at(v.position);
    v.color = drawn_color(item.y);
    v.ends = vec4<f32>(s.s0, s.s1);
    let j0 = joins[2u * slot];
    let j1 = joins[2u * slot + 1u];
    v.splits = vec4<u32>(j0.x, j0.y, j1.x, j1.y);
    v.item = vec2<u32>(slot, item.y);
    return v;
}

@vertex
fn edge_vertex_main(
    @builtin(vertex_index) vertex: u32,
    @builtin(instance_index) slot: u32,
) -> EdgeVarying {
    return edge_varying(vertex, slot, false);
}

@vertex
fn strip_vertex(
    @builtin(vertex_index) vertex: u32,
    @builtin(instance_index) slot: u32,
) -> EdgeVarying {
    return edge_varying(vertex, slot, true);
}

// False if `q` (relative to the end's point) lies on the neighbour's side of a split line.
fn on_own_side(q: vec2<f32>, a: vec2<f32>, split_left: u32, split_right: u32) -> bool {
    if cross2(a, q) > 0.0 {
        return split_left == 0u || cross2(unpack2x16snorm(split_left), q) < 0.0;
    }
    return split_right == 0u || cross2(unpack2x16snorm(split_right), q) >= 0.0;
}

@fragment
fn edge_fragment(v: EdgeVarying) -> @location(0) vec4<f32> {
    let d = normalize(v.ends.zw - v.ends.xy);
    let pixel = v.position.xy;
    if !on_own_side(pixel - v.ends.xy, d, v.splits.x, v.splits.y)
        || !on_own_side(pixel - v.ends.zw, -d, v.splits.z, v.splits.w) {
        discard;
    }
    let q = pixel - v.ends.xy;
    if display_trims(dot(q, perp(d)), v.reach, v.fade) {
        discard;
    }
    return display_color(v.color, pattern_phase(v.item.x, dot(q, d)), v.fade);
}

struct StripPixel {
    @location(0) color: vec4<f32>,
    // At the sharp face under the pixel (strip_depth), not at the quad's.
    @builtin(frag_depth) depth: f32,
}

@fragment
fn strip_fragment(v: EdgeVarying) -> StripPixel {
    let d = normalize(v.ends.zw - v.ends.xy);
    let pixel = v.position.xy;
    let record = chamfers[v.item.x];
    // The pixels near a drawn rounded corner are the corner's (corners.wgsl).
    let along = dot(pixel - v.ends.xy, d);
    if along < record.hand_over.x || length(v.ends.zw - v.ends.xy) - along < record.hand_over.y {
        discard;
    }
    let mvp = instance_frames[v.item.y >> INSTANCE_SHIFT].mvp;
    let s = section_at(record, mvp, v.ends, pixel);
    let x = dot(pixel - v.ends.xy, perp(d));
    let h = highlight_pixel(record, s, x);
    return StripPixel(h, strip_depth(record, mvp, s, pixel, x));
}

// What the pixel shows of the strip: the slice of its section (section_at) that the pixel covers,
// integrated (seed 000), blended over the mesh by the share it covers of what the sharp mesh shows
// there (the part beyond the rounded outline is the outline pass's to trim).
fn highlight_pixel(record: ChamferRecord, s: Section, x: f32) -> vec4<f32> {
    let shares = section_shares(s, x);
    if shares.x <= 0.0 {
        discard;
    }
    let lo = max(min(s.offsets.x, s.offsets.y), x - 0.5);
    let hi = min(max(s.offsets.x, s.offsets.y), x + 0.5);
    let ta = section_angle(s, lo);
    let tb = section_angle(s, hi);
    let range = vec2<f32>(min(ta, tb), max(ta, tb));
    var color = strip_radiance(s.arc, s.across, s.point, s.to_viewer, range, record_light(record));
    if (lighting.pbr & SHADE_ENVIRONMENT) != 0u {
        color += strip_environment(s.arc, s.across, s.to_viewer, range);
    }
    // W = K r_e / (d r_max) (§3.2) with K given; r_e / r_max is the share of the pixel the strip
    // covers, here of the part the sharp mesh covers and the rounded solid too.
    let k_over_d = select(1.0, lighting.base.w / record.n2.w, lighting.base.w > 0.0 && record.n2.w > 0.0);
    let weight = clamp(k_over_d * shares.x / max(1.0 - shares.y, shares.x), 0.0, 1.0);
    return vec4<f32>(color, weight);
}

// The image-based light over the pixel's slice of the arc: the environment's light at normals across
// the slice, weighted by P·T (the projected length) as the punctual integral is, a sample per 0.03 rad
// (the prefiltered map's lobes are at least 0.05 wide), 2 to 48 of them.
fn strip_environment(arc: Arc, across: vec3<f32>, to_viewer: vec3<f32>, range: vec2<f32>) -> vec3<f32> {
    let m = Pbr(lighting.base.rgb, lighting.material.x, lighting.material.y);
    let steps = u32(clamp(ceil((range.y - range.x) / 0.03), 2.0, 48.0));
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var k = 0u; k < steps; k += 1u) {
        let theta = range.x + (f32(k) + 0.5) / f32(steps) * (range.y - range.x);
        let normal = arc.ex * cos(theta) + arc.ey * sin(theta);
        let w = dot(arc.ey * cos(theta) - arc.ex * sin(theta), across);
        sum += w * environment_light(m, normal, to_viewer);
        weight += w;
    }
    return select(vec3<f32>(0.0), sum / weight, abs(weight) > 1e-9);
}
