// The cut faces and cut outlines of section planes (issue 43).
//
// Faces, by stencil parity: for each plane that crosses an instance, its mesh, clipped by that plane
// alone, flips the stencil's bit at every fragment (no depth test, no colour), so a pixel's bit ends
// up set exactly where the ray through it meets the plane inside the closed mesh (it crosses the
// kept surface an odd number of times). A quad on the plane then fills the pixels with the bit set,
// clipped by the other planes and depth tested, and the same parity draw flips the bits back to
// zero for the next plane or instance.
//
// Outlines: each triangle the plane crosses gives one segment (plane ∩ triangle), found in the
// vertex shader every frame, clipped by the other planes and drawn as a capsule (a thick line with
// round ends) so neighbouring segments join without gaps at any angle, as intersection lines are.

struct CutFrame {
    mvp: mat4x4<f32>,
    // The instance's planes in its model space (section.wgsl).
    section: array<vec4<f32>, SECTION_PLANES>,
    // The asset's box: centre (xyz) and half diagonal (w), to size the cap quad.
    bounds: vec4<f32>,
    color: vec4<f32>,
    hatch_color: vec4<f32>,
    // Hatch spacing (pixels, or model units when `hatch_in_model`; 0 = solid fill), angle (radians),
    // line width (pixels).
    hatch: vec4<f32>,
    // The plane this draw caps.
    plane: u32,
    hatch_in_model: u32,
    indices_u16: u32,
    reverse_z: u32,
    // The outline's colour.
    outline: vec4<f32>,
    // Viewport (pixels), world size of a pixel at clip w = 1, the outline's half width (pixels).
    screen: vec4<f32>,
    // Third column of the projection, for the outline's depth bias (common.wgsl's biased_depth).
    proj_z: vec4<f32>,
}

@group(0) @binding(0) var<uniform> cut: CutFrame;
@group(0) @binding(7) var<storage, read> render_positions: array<f32>;
@group(0) @binding(9) var<storage, read> mesh_indices: array<u32>;

fn view_section(k: u32) -> vec4<f32> {
    return cut.section[k];
}

struct ParityVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) model_position: vec3<f32>,
}

@vertex
fn parity_vertex(@location(0) position: vec3<f32>) -> ParityVarying {
    return ParityVarying(cut.mvp * vec4<f32>(position, 1.0), position);
}

// Only this draw's plane clips: the parity is that of the mesh cut by it alone.
@fragment
fn parity_fragment(v: ParityVarying) {
    if dot(cut.section[cut.plane], vec4<f32>(v.model_position, 1.0)) >= 0.0 {
        discard;
    }
}

// The cap quad: the square on the plane around the box centre's foot, as wide as the box's diagonal,
// so it covers every point of the plane inside the box.
@vertex
fn cap_face_vertex(@builtin(vertex_index) i: u32) -> ParityVarying {
    let plane = cut.section[cut.plane];
    let foot = cut.bounds.xyz - dot(plane, vec4<f32>(cut.bounds.xyz, 1.0)) * plane.xyz;
    let axes = plane_axes(plane.xyz);
    let a = select(-1.0, 1.0, ((0x16u >> i) & 1u) == 1u);
    let b = select(-1.0, 1.0, ((0x34u >> i) & 1u) == 1u);
    let p = foot + cut.bounds.w * (a * axes[0] + b * axes[1]);
    return ParityVarying(cut.mvp * vec4<f32>(p, 1.0), p);
}

@fragment
fn cap_face_fragment(v: ParityVarying) -> @location(0) vec4<f32> {
    // The hatch coordinate and its change per pixel, before any discard.
    let plane = cut.section[cut.plane].xyz;
    let across = cap_hatch_across(v.model_position, v.position.xy, plane, cut.hatch.y, cut.hatch_in_model != 0u);
    let per_pixel = max(length(vec2<f32>(dpdx(across), dpdy(across))), 1e-12);
    if section_cuts_except(v.model_position, cut.plane) {
        discard;
    }
    return cap_fill(across, per_pixel, cut.hatch, cut.color, cut.hatch_color);
}

fn cut_mesh_index(i: u32) -> u32 {
    if cut.indices_u16 != 0u {
        return (mesh_indices[i >> 1u] >> ((i & 1u) * 16u)) & 0xffffu;
    }
    return mesh_indices[i];
}

fn cut_render_position(r: u32) -> vec3<f32> {
    return vec3<f32>(render_positions[3u * r], render_positions[3u * r + 1u], render_positions[3u * r + 2u]);
}

// True if `a` comes before `b` in (x, y, z) order: both triangles of an edge then interpolate
// its cut point from the same end, and get the same point.
fn before(a: vec3<f32>, b: vec3<f32>) -> bool {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}

// The pixel position of clip position `c` (origin top left, y down: common.wgsl's to_pixels).
fn cut_pixels(c: vec4<f32>) -> vec2<f32> {
    return vec2<f32>((c.x / c.w + 1.0) * 0.5 * cut.screen.x, (1.0 - c.y / c.w) * 0.5 * cut.screen.y);
}

struct OutlineVarying {
    @builtin(position) position: vec4<f32>,
    // The segment's ends in pixels.
    @location(0) @interpolate(flat) ends: vec4<f32>,
}

// Vertex i (of 6) of the capsule of the segment where this draw's plane crosses triangle t.
@vertex
fn outline_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) t: u32) -> OutlineVarying {
    var out: OutlineVarying;
    out.position = vec4<f32>(2.0, 2.0, 2.0, 1.0);
    let plane = cut.section[cut.plane];
    var p: array<vec3<f32>, 3>;
    var d: array<f32, 3>;
    for (var k = 0u; k < 3u; k++) {
        p[k] = cut_render_position(cut_mesh_index(3u * t + k));
        d[k] = dot(plane, vec4<f32>(p[k], 1.0));
    }
    // A point on the plane counts as cut away (section.wgsl), so a triangle crosses 0 or 2 sides.
    var ends: array<vec3<f32>, 2>;
    var found = 0u;
    for (var k = 0u; k < 3u; k++) {
        let j = (k + 1u) % 3u;
        if (d[k] >= 0.0) != (d[j] >= 0.0) && found < 2u {
            var a = k;
            var b = j;
            if before(p[j], p[k]) {
                a = j;
                b = k;
            }
            ends[found] = mix(p[a], p[b], d[a] / (d[a] - d[b]));
            found += 1u;
        }
    }
    if found != 2u {
        return out;
    }
    // The part the other planes keep.
    let span = section_span_except(ends[0], ends[1], vec2<f32>(0.0, 1.0), cut.plane);
    if !(span.x < span.y) {
        return out;
    }
    let c0 = cut.mvp * vec4<f32>(span_point(ends[0], ends[1], span.x), 1.0);
    let c1 = cut.mvp * vec4<f32>(span_point(ends[0], ends[1], span.y), 1.0);
    // Short segments: one reaching behind the camera is not drawn.
    if c0.w <= 0.0 || c1.w <= 0.0 {
        return out;
    }
    let s0 = cut_pixels(c0);
    let s1 = cut_pixels(c1);
    let along = s1 - s0;
    let dir = select(vec2<f32>(1.0, 0.0), normalize(along), dot(along, along) > 1e-8);
    let side = vec2<f32>(-dir.y, dir.x);
    // One pixel more than the half width, for the round ends' coverage.
    let r = cut.screen.w + 1.0;
    let at_end = ((0x16u >> i) & 1u) == 1u;
    let left = ((0x34u >> i) & 1u) == 1u;
    let c = select(c0, c1, at_end);
    let px = select(s0 - dir * r, s1 + dir * r, at_end) + side * select(-r, r, left);
    // Pulled towards the camera by a width's worth, to win against the cap and faces it lies on.
    let bias = (1.0 + 3.0 * cut.screen.w) * cut.screen.z * c.w;
    let biased = c + bias * cut.proj_z;
    var depth = biased.z / biased.w;
    let in_front = select(biased.z, biased.w - biased.z, cut.reverse_z != 0u);
    if biased.w <= 0.0 || in_front <= 0.0 {
        depth = select(0.0, 1.0, cut.reverse_z != 0u);
    }
    let ndc = vec2<f32>(px.x / cut.screen.x * 2.0 - 1.0, 1.0 - px.y / cut.screen.y * 2.0);
    out.position = vec4<f32>(ndc * c.w, depth * c.w, c.w);
    out.ends = vec4<f32>(s0, s1);
    return out;
}

@fragment
fn outline_fragment(v: OutlineVarying) -> @location(0) vec4<f32> {
    let a = v.ends.xy;
    let b = v.ends.zw;
    let q = v.position.xy;
    let ab = b - a;
    let t = clamp(dot(q - a, ab) / max(dot(ab, ab), 1e-12), 0.0, 1.0);
    if distance(q, a + t * ab) > cut.screen.w {
        discard;
    }
    return cut.outline;
}
