// Draws each drawn edge as a screen-space quad (thesis §8.3): six vertices per instance, pulled from
// the compact list. The fragment shader cuts the quad where it meets its neighbours (see joins.wgsl).

struct EdgeVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) color: vec4<f32>,
    // End points in pixels: end 0 in xy, end 1 in zw.
    @location(1) @interpolate(flat) ends: vec4<f32>,
    // Split directions: end 0 left, end 0 right, end 1 left, end 1 right.
    @location(2) @interpolate(flat) splits: vec4<u32>,
    // Slot and drawn word.
    @location(3) @interpolate(flat) item: vec2<u32>,
}

@vertex
fn edge_vertex_main(
    @builtin(vertex_index) vertex: u32,
    @builtin(instance_index) slot: u32,
) -> EdgeVarying {
    var v: EdgeVarying;
    let item = drawn[slot];
    let s = from_record(screen[slot], item.y);
    if !s.visible {
        v.position = NOWHERE;
        return v;
    }
    // Two triangles: (end, side) = (0,-) (1,-) (1,+) / (0,-) (1,+) (0,+).
    let k = (0x16u >> vertex) & 1u;
    let side_left = ((0x34u >> vertex) & 1u) == 1u;
    let n = perp(s.d);
    var p = s.s0;
    var extent = select(-s.right.x, s.left.x, side_left);
    var depth = s.depth.x;
    var w = s.w.x;
    if k == 1u {
        p = s.s1;
        extent = select(-s.right.y, s.left.y, side_left);
        depth = s.depth.y;
        w = s.w.y;
    }
    v.position = from_pixels(p + n * extent, depth, w);
    v.color = drawn_color(item.y);
    v.ends = vec4<f32>(s.s0, s.s1);
    let j0 = joins[2u * slot];
    let j1 = joins[2u * slot + 1u];
    v.splits = vec4<u32>(j0.x, j0.y, j1.x, j1.y);
    v.item = vec2<u32>(slot, item.y);
    return v;
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
    if (v.item.y & DRAWN_HIGHLIGHT) != 0u {
        let record = chamfers[v.item.x];
        // The pixels near a drawn rounded corner are the corner's (corners.wgsl).
        let along = dot(pixel - v.ends.xy, d);
        if along < record.hand_over.x || length(v.ends.zw - v.ends.xy) - along < record.hand_over.y {
            discard;
        }
        return highlight_pixel(record, dot(pixel - v.ends.xy, perp(d)));
    }
    if !on_own_side(pixel - v.ends.xy, d, v.splits.x, v.splits.y)
        || !on_own_side(pixel - v.ends.zw, -d, v.splits.z, v.splits.w) {
        discard;
    }
    return v.color;
}

// The pixel `across_px` pixels across the sharp edge integrates the slice of the strip it covers.
fn highlight_pixel(record: ChamferRecord, across_px: f32) -> vec4<f32> {
    let arc = arc_of(record.n1.xyz, record.n2.xyz);
    let middle = record.middle.xyz;
    let to_viewer = record.viewer.xyz;
    let visible = visible_range(arc, to_viewer);
    if visible.x >= visible.y {
        discard;
    }
    let a = strip_offset(record, arc, visible.x);
    let b = strip_offset(record, arc, visible.y);
    let lo = max(min(a, b), across_px - 0.5);
    let hi = min(max(a, b), across_px + 0.5);
    if hi <= lo {
        discard;
    }
    let ta = strip_angle(record, arc, visible, lo);
    let tb = strip_angle(record, arc, visible, hi);
    let range = vec2<f32>(min(ta, tb), max(ta, tb));
    var color = strip_radiance(arc, record.across.xyz, middle, to_viewer, range, record_light(record));
    if (lighting.pbr & SHADE_ENVIRONMENT) != 0u {
        color += strip_environment(arc, record.across.xyz, to_viewer, range);
    }
    // W = K r_e / (d r_max) (§3.2): r_e / r_max is the share of the pixel the strip covers.
    let k_over_d = select(1.0, lighting.base.w / record.across.w, record.across.w > 0.0);
    let weight = clamp(k_over_d * (hi - lo), 0.0, 1.0);
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
