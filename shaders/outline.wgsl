// The outline pass of the chamfer highlight (issue 39), after the application's pass. Where a chamfer
// edge or a rounded corner lies on the silhouette, the sharp mesh covers pixels the rounded solid does
// not: between the rounded outline (the horizon of the strip's cylinder, of the corner's sphere) and
// the sharp one. This pass repaints each of them with what lies just beyond the sharp outline beside it
// (the frame's colour, copied before the pass, from the first pixel past the sharp edge), blended by
// the share of the pixel beyond the rounded outline; the strips and corners blended their own share
// over what the sharp mesh showed (edges.wgsl, corner_draw.wgsl), so an outline pixel ends as the
// rounded solid's: strip, face and background by their shares. The application's mesh pass is left
// as it is (its own, or Bevy's).

// The application's colour as the edges left it.
@group(0) @binding(32) var scene_color: texture_2d<f32>;

// Whether nothing the application drew lies in front of the sharp face seen at `pixel`, whose depth
// there is `face` (plane_depth): the scene's depth is the face's, to within a pixel's change (the
// depth may be sampled anywhere in the pixel), or farther.
fn unoccluded(pixel: vec2<f32>, face: vec2<f32>) -> bool {
    let scene = scene_depth(vec2<i32>(pixel));
    let slack = face.y + 1e-6;
    return select(scene >= face.x - slack, scene <= face.x + slack, frame.reverse_z != 0u);
}

// The colour at the screen point `q`, to cover `share` of a pixel.
fn beyond(q: vec2<f32>, share: f32) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(scene_color));
    let p = clamp(vec2<i32>(floor(q)), vec2<i32>(0), size - vec2<i32>(1));
    return vec4<f32>(textureLoad(scene_color, p, 0).rgb, share);
}

struct StripTrim {
    @builtin(position) position: vec4<f32>,
    // End points in pixels: end 0 in xy, end 1 in zw.
    @location(0) @interpolate(flat) ends: vec4<f32>,
    // Slot and drawn word.
    @location(1) @interpolate(flat) item: vec2<u32>,
}

// The quad of each highlighted edge on the silhouette (chamfers.wgsl sized it to reach the sharp edge).
@vertex
fn strip_trim_vertex(
    @builtin(vertex_index) vertex: u32,
    @builtin(instance_index) slot: u32,
) -> StripTrim {
    var v: StripTrim;
    let item = drawn[slot];
    let s = from_record(screen[slot], item.y);
    let silhouette = DRAWN_HIGHLIGHT | DRAWN_SILHOUETTE;
    if (item.y & silhouette) != silhouette || !s.visible {
        v.position = NOWHERE;
        return v;
    }
    v.position = quad_vertex(s, vertex);
    v.ends = vec4<f32>(s.s0, s.s1);
    v.item = vec2<u32>(slot, item.y);
    return v;
}

@fragment
fn strip_trim_fragment(v: StripTrim) -> @location(0) vec4<f32> {
    let record = chamfers[v.item.x];
    let pixel = v.position.xy;
    let d = normalize(v.ends.zw - v.ends.xy);
    // The pixels near a drawn rounded corner are the corner's.
    let along = dot(pixel - v.ends.xy, d);
    if along < record.hand_over.x || length(v.ends.zw - v.ends.xy) - along < record.hand_over.y {
        discard;
    }
    let mvp = instance_frames[v.item.y >> INSTANCE_SHIFT].mvp;
    let s = section_at(record, mvp, v.ends, pixel);
    let x = dot(pixel - v.ends.xy, perp(d));
    let shares = section_shares(s, x);
    // Outwards: from the strip's face end towards its outline.
    let at_x = (s.outline & 1u) != 0u;
    let outwards = sign(select(s.offsets.y, s.offsets.x, at_x) - select(s.offsets.x, s.offsets.y, at_x));
    // A pixel well past the sharp edge shows what is beyond already.
    if shares.y <= 0.0 || outwards * x >= 1.25 {
        discard;
    }
    let face = plane_depth(mvp, s.point, record.end1.xyz - record.end0.xyz, section_face(record, s, x)[1], pixel);
    if !unoccluded(pixel, face) {
        discard;
    }
    return beyond(pixel + perp(d) * (outwards * 1.25 - x), shares.y);
}

struct CornerTrim {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) corner: u32,
    @location(1) @interpolate(flat) vertex_px: vec2<f32>,
    // The model-space steps of one pixel right and down at the vertex (pixel_steps).
    @location(2) @interpolate(flat) step_x: vec3<f32>,
    @location(3) @interpolate(flat) step_y: vec3<f32>,
    // The strips' hand-over lines (hand_over_lines).
    @location(4) @interpolate(flat) line0: vec4<f32>,
    @location(5) @interpolate(flat) line1: vec4<f32>,
    @location(6) @interpolate(flat) line2: vec4<f32>,
}

// The square of each drawn corner (corner_draw.wgsl's, a pixel wider).
@vertex
fn corner_trim_vertex(
    @builtin(vertex_index) vertex: u32,
    @builtin(instance_index) k: u32,
) -> CornerTrim {
    var v: CornerTrim;
    v.corner = k;
    let c = corner_at(k);
    if lighting.corners == 0u || !corner_drawn(c) {
        v.position = NOWHERE;
        return v;
    }
    let square = corner_square(c, vertex, 1.0);
    v.position = square.position;
    v.vertex_px = square.vertex_px;
    v.step_x = square.steps[0];
    v.step_y = square.steps[1];
    let lines = square.lines;
    v.line0 = lines[0];
    v.line1 = lines[1];
    v.line2 = lines[2];
    return v;
}

// Sub-samples a side of a corner pixel's coverage.
const TRIM_SAMPLES: u32 = 4u;

@fragment
fn corner_trim_fragment(v: CornerTrim) -> @location(0) vec4<f32> {
    let c = corner_at(v.corner);
    let pixel = v.position.xy;
    let steps = array<vec3<f32>, 2>(v.step_x, v.step_y);
    let per_pixel = pixel_size(steps);
    let eye = view_eye();
    let back = ray_start(c);
    // Nothing is drawn, so nothing trimmed, a pixel past the sharp corner; and where the corner's solid
    // is not the mesh's, the strips trim.
    let centre = pixel_ray(c.vertex.xyz, v.vertex_px, steps, eye, back, pixel);
    let lines = array<vec4<f32>, 3>(v.line0, v.line1, v.line2);
    if !enters_sharp(c, centre[0], centre[1], per_pixel) || !local_at(c, lines, v.vertex_px, pixel, per_pixel) {
        discard;
    }
    let none = vec3<bool>(false);
    // Most of the square lies inside the rounded solid: a pixel whose four corners are inside is left.
    var outside = false;
    for (var i = 0u; i < 4u; i += 1u) {
        let q = pixel + vec2<f32>(f32(i & 1u), f32(i >> 1u)) - 0.5;
        let r = pixel_ray(c.vertex.xyz, v.vertex_px, steps, eye, back, q);
        outside = outside || enter(c, r[0], r[1], none, false).part == MISSED;
    }
    if !outside {
        discard;
    }
    var missed = 0u;
    let side = TRIM_SAMPLES;
    for (var i = 0u; i < side * side; i += 1u) {
        let q = pixel + (vec2<f32>(f32(i % side), f32(i / side)) + 0.5) / f32(side) - 0.5;
        let r = pixel_ray(c.vertex.xyz, v.vertex_px, steps, eye, back, q);
        missed += select(0u, 1u, enter(c, r[0], r[1], none, false).part == MISSED);
    }
    if missed == 0u {
        discard;
    }
    // The sharp face the pixel's ray meets first, in front of which nothing may lie.
    let n = c.normals[sharp_entry(c, centre[0], centre[1]).plane].xyz;
    let u = normalize(cross(n, select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(n.x) > 0.9)));
    let face = plane_depth(view_mvp(), c.vertex.xyz, u * c.sphere.w, cross(n, u) * c.sphere.w, pixel);
    if !unoccluded(pixel, face) {
        discard;
    }
    // What lies beyond: the first pixel outwards from the sphere's centre whose ray passes a pixel
    // clear of the sharp corner.
    let centre_px = to_pixels(view_mvp() * vec4<f32>(c.sphere.xyz, 1.0));
    var outwards = pixel - centre_px;
    outwards = select(vec2<f32>(1.0, 0.0), normalize(outwards), dot(outwards, outwards) > 1e-12);
    let reach = 2.0 * (c.normals[0].w + 3.0 * c.sphere.w) / per_pixel + 2.0;
    for (var step = 1.0; step <= reach; step += 1.0) {
        let q = pixel + outwards * step;
        let r = pixel_ray(c.vertex.xyz, v.vertex_px, steps, eye, back, q);
        if !enters_sharp(c, r[0], r[1], per_pixel) {
            return beyond(q, f32(missed) / f32(side * side));
        }
    }
    // WGSL's discard does not end the function (it demotes to a helper invocation), so Tint requires
    // the return that follows.
    discard;
    return vec4<f32>(0.0);
}
