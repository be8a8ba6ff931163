// The thesis' hardware methods (§4): contours as a by-product of render state, no edge detection.
// wgpu has no geometry shaders and no wide lines, so every pass pulls its triangles in the vertex
// shader (triangles.wgsl: instance = triangle) and draws lines as screen-space quads. Each entry point
// is one pass of one method; techniques/hardware.rs strings them together with their pipeline state:
//   §4.1 Rossignac–van Emmerik: the mesh into depth, then every triangle's wireframe, thick, pushed
//        back by a depth offset (hw_wire_vertex, `offset_px`);
//   §4.1 Gooch: back faces in wireframe with LessEqual (hw_wire_vertex, `back_only`, no offset);
//   §4.2 back faces filled with LessEqual (hw_back_vertex, no offset);
//   §4.3 back faces filled, pulled towards the camera (hw_back_vertex, `offset_px`);
//   §4.4 back faces "fattened": each edge pushed out by the line width in screen space, the polygon
//        closed as a fan of 2N triangles around its centre (hw_fat_vertex);
//   §4.5 the mesh (front faces) drawn four times one step off in x and y into the stencil (increment), then a
//        screen quad where the stencil is 2 or 3 (hw_shift_vertex, fullscreen_vertex);
//   §4.6 front faces' wireframe inverting the stencil, then a screen quad where it is 1: shared
//        edges are drawn twice and cancel, contour edges once (hw_line_vertex, fullscreen_vertex);
//   §4.7 Raskar: fattened back faces for contours; per front face edge a quad rotated about the edge
//        by the crease angle, hidden by the next face unless the fold is sharper (ridges,
//        hw_crease_vertex, instances below the triangle count), or rotated the other way and drawn
//        only where it lies between the front surface and a second depth buffer of the back faces
//        (valleys, the instances above it, valley_fragment).

struct HardwareParams {
    // 1: the wireframe of back faces only (Gooch).
    back_only: u32,
    // How far lines and faces move in depth, in pixels' worth (positive: towards the camera).
    offset_px: f32,
    // §4.7's crease angle, radians.
    crease_angle: f32,
}

@group(0) @binding(15) var<uniform> params: HardwareParams;

// The back faces' depth, a second depth buffer for §4.7's valleys (our own texture).
@group(0) @binding(16) var back_depth: texture_depth_2d;

// Triangle t's clip corners; `ok` false if a corner is behind the camera.
struct ClipTriangle {
    ok: bool,
    front: bool,
    p: array<vec3<f32>, 3>,
    c: array<vec4<f32>, 3>,
    s: array<vec2<f32>, 3>,
}

fn clip_triangle(t: u32) -> ClipTriangle {
    var out: ClipTriangle;
    out.p = triangle(t);
    out.front = triangle_front(out.p);
    out.ok = true;
    for (var i = 0u; i < 3u; i += 1u) {
        out.c[i] = frame.mvp * vec4<f32>(out.p[i], 1.0);
        if out.c[i].w <= 0.0 || in_front(out.c[i]) < 0.0 {
            out.ok = false;
        }
        out.s[i] = to_pixels(out.c[i]);
    }
    return out;
}

// A clip position `px` pixels on screen at corner k's depth moved `offset_px` pixels' worth of world
// distance towards the camera (negative: away).
fn at_corner(tri: ClipTriangle, k: u32, px: vec2<f32>, offset_px: f32) -> vec4<f32> {
    let c = tri.c[k];
    let depth = biased_depth_by(c, offset_px);
    return from_pixels(px, depth, c.w);
}

fn contour_out(ok: bool, position: vec4<f32>, point: vec3<f32>) -> FlatVarying {
    return flat_vertex(select(NOT_DRAWN, COLOR_CONTOUR, ok), position, point);
}

// Corner i (0..5) of the quad of width 2h around the segment a-b; ends in `k0`, `k1` of `tri`.
fn segment_quad(tri: ClipTriangle, k0: u32, k1: u32, i: u32, h: f32, offset_px: f32) -> vec4<f32> {
    let a = tri.s[k0];
    let b = tri.s[k1];
    let n = perp(normalize(b - a + vec2<f32>(1e-6, 0.0)));
    let end = (0x16u >> i) & 1u;
    let side = select(-h, h, ((0x34u >> i) & 1u) == 1u);
    let k = select(k0, k1, end == 1u);
    return at_corner(tri, k, select(a, b, end == 1u) + n * side, offset_px);
}

@vertex
fn hw_wire_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) t: u32) -> FlatVarying {
    let tri = clip_triangle(t);
    let edge = i / 6u;
    let back_only = params.back_only == 1u;
    let ok = tri.ok && !(back_only && tri.front);
    let h = half_width(tri.c[edge].w);
    let position = segment_quad(tri, edge, (edge + 1u) % 3u, i % 6u, h, -params.offset_px);
    let k = select(edge, (edge + 1u) % 3u, ((0x16u >> (i % 6u)) & 1u) == 1u);
    return contour_out(ok, position, tri.p[k]);
}

@vertex
fn hw_back_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) t: u32) -> FlatVarying {
    let tri = clip_triangle(t);
    return contour_out(tri.ok && !tri.front, at_corner(tri, i, tri.s[i], params.offset_px), tri.p[i]);
}

// The fattened polygon of a back face: corner k's two pushed-out copies (one per edge at k), as a
// fan of six triangles around the centre.
@vertex
fn hw_fat_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) t: u32) -> FlatVarying {
    let tri = clip_triangle(t);
    let centre = (tri.s[0] + tri.s[1] + tri.s[2]) / 3.0;
    // Ring point r (0..5): corner r / 2, pushed out along the edge before it (even) or after it (odd).
    let triangle_vertex = i % 3u;
    let ring = (i / 3u + select(0u, triangle_vertex - 1u, triangle_vertex > 0u)) % 6u;
    if triangle_vertex == 0u {
        let c = (tri.c[0] + tri.c[1] + tri.c[2]) / 3.0;
        return contour_out(tri.ok && !tri.front, from_pixels(centre, c.z / c.w, c.w), (tri.p[0] + tri.p[1] + tri.p[2]) / 3.0);
    }
    let k = ring / 2u;
    // Even: the edge from k - 1 to k; odd: the edge from k to k + 1.
    let other = select((k + 1u) % 3u, (k + 2u) % 3u, ring % 2u == 0u);
    let along = tri.s[other] - tri.s[k];
    var n = perp(normalize(along + vec2<f32>(1e-6, 0.0)));
    if dot(n, centre - tri.s[k]) > 0.0 {
        n = -n;
    }
    let h = 2.0 * half_width(tri.c[k].w);
    // No depth offset: the fattened rim shows only where it leaves the front faces' outline.
    let c = tri.c[k];
    return contour_out(tri.ok && !tri.front, from_pixels(tri.s[k] + n * h, c.z / c.w, c.w), tri.p[k]);
}

// §4.5: the whole mesh, shifted by a pixel step in one of four directions (instance / triangles).
@vertex
fn hw_shift_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) instance: u32) -> FlatVarying {
    let t = instance % frame.triangle_count;
    let step = max(0.5 * frame.width, 1.0);
    let shifts = array<vec2<f32>, 4>(vec2<f32>(0.0, step), vec2<f32>(0.0, -step), vec2<f32>(step, 0.0), vec2<f32>(-step, 0.0));
    let tri = clip_triangle(t);
    let px = tri.s[i] + shifts[min(instance / frame.triangle_count, 3u)];
    // Front faces only, as the mesh is normally drawn: each copy then covers a pixel once where the
    // surface does not fold over itself.
    return contour_out(tri.ok && tri.front, from_pixels(px, tri.c[i].z / tri.c[i].w, tri.c[i].w), tri.p[i]);
}

struct LineVarying {
    @builtin(position) position: vec4<f32>,
    @location(1) section_point: vec4<f32>,
}

// §4.6: the front faces' wireframe as one-pixel lines, each drawn between its ends in one order (by
// screen position) so both faces of an edge rasterize the same pixels, whatever their winding.
@vertex
fn hw_line_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) t: u32) -> LineVarying {
    let tri = clip_triangle(t);
    if !tri.ok || !tri.front {
        return LineVarying(NOWHERE, vec4<f32>(0.0));
    }
    let edge = i / 2u;
    let a = tri.s[edge];
    let b = tri.s[(edge + 1u) % 3u];
    let a_first = a.x < b.x || (a.x == b.x && a.y < b.y);
    var k = edge;
    if (i % 2u == 1u) == a_first {
        k = (edge + 1u) % 3u;
    }
    return LineVarying(at_corner(tri, k, tri.s[k], frame.bias_px), vec4<f32>(tri.p[k], 1.0));
}

// Writes stencil (and depth) only, where the section keeps the geometry.
@fragment
fn stencil_only(@location(1) section_point: vec4<f32>) {
    if flat_cut(section_point) {
        discard;
    }
}

// The mesh from its position vertex buffer, for depth-only passes.
@vertex
fn hw_depth_vertex(@location(0) position: vec3<f32>) -> FlatVarying {
    return FlatVarying(frame.mvp * vec4<f32>(position, 1.0), vec4<f32>(0.0), vec4<f32>(position, 1.0));
}

// A triangle covering the screen.
@vertex
fn fullscreen_vertex(@builtin(vertex_index) i: u32) -> FlatVarying {
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u)) * 2.0 - 1.0;
    return FlatVarying(vec4<f32>(xy, near_depth(), 1.0), frame.colors[COLOR_CONTOUR], vec4<f32>(0.0));
}

// §4.7: for each edge of a front face, a quad of the line width leaving the edge away from the face,
// in the face's plane turned by the crease angle about the edge: down (away from the normal) for
// ridges, up for valleys.
@vertex
fn hw_crease_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) instance: u32) -> FlatVarying {
    let t = instance % frame.triangle_count;
    let ridge = instance < frame.triangle_count;
    let tri = clip_triangle(t);
    let edge = i / 6u;
    let corner = i % 6u;
    let k0 = edge;
    let k1 = (edge + 1u) % 3u;
    let k2 = (edge + 2u) % 3u;
    let normal = normalize(cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]));
    let along = normalize(tri.p[k1] - tri.p[k0]);
    // In the face's plane, perpendicular to the edge, away from the opposite corner.
    var out_dir = normalize(cross(along, normal));
    if dot(out_dir, tri.p[k2] - tri.p[k0]) > 0.0 {
        out_dir = -out_dir;
    }
    let angle = params.crease_angle;
    let dir = cos(angle) * out_dir - select(-1.0, 1.0, ridge) * sin(angle) * normal;
    let end = (0x16u >> corner) & 1u;
    let far = ((0x34u >> corner) & 1u) == 1u;
    let k = select(k0, k1, end == 1u);
    let base = tri.p[k];
    // As long as the line is wide on screen at that depth.
    let length_world = 2.0 * half_width(tri.c[k].w) * frame.pixel_scale * tri.c[k].w;
    let p = base + select(0.0, length_world, far) * dir;
    let color = select(COLOR_VALLEY, COLOR_RIDGE, ridge);
    return flat_vertex(select(NOT_DRAWN, color, tri.ok && tri.front), frame.mvp * vec4<f32>(p, 1.0), base);
}

// Valleys are kept only between the front surface (the pipeline's reversed depth test) and the back
// faces' depth.
@fragment
fn valley_fragment(v: FlatVarying) -> @location(0) vec4<f32> {
    let back = textureLoad(back_depth, vec2<i32>(v.position.xy), 0);
    let behind_back = select(v.position.z >= back, v.position.z <= back, frame.reverse_z != 0u);
    if behind_back || flat_cut(v.section_point) {
        discard;
    }
    return v.color;
}
