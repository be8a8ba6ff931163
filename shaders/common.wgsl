// Shared by every edge pass: the frame uniform, the asset's read-only sections, and where an edge
// lands on the screen. Screen positions are in framebuffer pixels (origin top left, y down), the space
// of @builtin(position) in fragment shaders, so vertex, compute and fragment code agree to the bit.

struct Frame {
    mvp: mat4x4<f32>,
    // The camera in model space: a point (w = 1) for perspective, a direction towards the viewer
    // (w = 0) for orthographic, so one front-facing test serves both (thesis §6.1).
    eye: vec4<f32>,
    // Third column of the projection: what a step of one unit towards the camera adds to a clip position.
    proj_z: vec4<f32>,
    colors: array<vec4<f32>, COLOR_COUNT>,
    viewport: vec2<f32>,
    // World size of one pixel at clip w = 1.
    pixel_scale: f32,
    width: f32,
    min_width: f32,
    // Clip w at which `width` holds when the width scales with depth (thesis §9.1); 0 = constant width.
    depth_ref: f32,
    bias_px: f32,
    classes: u32,
    cull_back: u32,
    edges_u16: u32,
    rings_u16: u32,
    // Edges of this dispatch: the asset's, or one chunk's when its edge section is bound in windows
    // (`edge_vertices` then holds the chunk's edges from `first_edge` on).
    edge_count: u32,
    head_count: u32,
    first_edge: u32,
    half_quads: u32,
    cap_capacity: u32,
    // Chamfer edges are drawn as lit rounded strips (highlight.wgsl) instead of lines.
    highlight: u32,
    // Radii in the attributes are multiples of this (the asset's radius_scale).
    radius_scale: f32,
    // Depth 1 is near and 0 far (reverse Z): the near plane is z = w in clip space, not z = 0.
    reverse_z: u32,
    _pad: u32,
    // Side planes of the view in model space, widened by an edge's reach in pixels: a point with
    // dot(plane, (p, 1)) > 0 is beyond that side (cull.wgsl). All zero: no frustum test.
    frustum: array<vec4<f32>, 4>,
    // The highlight's light as this instance sees it, in its model space: `PunctualLight`'s
    // position and spot axis (the instance's own light, or the style's).
    light_position: vec4<f32>,
    light_axis: vec4<f32>,
    // The mesh's index width and triangle count, for the techniques that pull triangles.
    indices_u16: u32,
    triangle_count: u32,
    // This instance's number among the frame's drawn instances (batch.wgsl: in a batch's block, its
    // first instance).
    instance: u32,
    // Slots of the frame's drawn-edge lists (joined technique).
    capacity: u32,
    // The joined technique's batches (batch.wgsl): this block's batch, the instances in it (in the
    // place pass's block: every instance of the frame), the mask of the slot table (its size - 1) and
    // the slots of the kept-cluster list.
    batch: u32,
    batch_instances: u32,
    table_mask: u32,
    survivor_capacity: u32,
    // The section planes in this instance's model space (section.wgsl).
    section: array<vec4<f32>, SECTION_PLANES>,
    // The hidden edges' style and the distance fade (display.wgsl).
    display: Display,
}

// How hidden and far edges look (display.wgsl; runtime/src/render/display.rs).
struct Display {
    // The hidden edges' colour (DISPLAY_HIDDEN_COLOR; else the class colour).
    hidden_color: vec4<f32>,
    // Opacity, width in pixels, the dash period in pixels, the dash lengths' count.
    hidden: vec4<f32>,
    // Dash, gap, dash, ... lengths in pixels.
    dashes: array<vec4<f32>, 4>,
    // Start and end of the fade (clip w, or clip z with DISPLAY_FADE_ORTHO), the opacity and width
    // multiples at its end.
    fade: vec4<f32>,
    flags: u32,
    // DISPLAY_PIXELS: bit i draws pixel i of each 32.
    pixels: u32,
    _pad0: u32,
    _pad1: u32,
}

// One instance's camera in its model space (the joined technique, batch.wgsl), written by the host
// each frame; the place pass (instances.wgsl) sets `visible`.
struct InstanceFrame {
    mvp: mat4x4<f32>,
    eye: vec4<f32>,
    frustum: array<vec4<f32>, 4>,
    // The asset's bounds in model space; `lo.w` is the instance's depth_ref.
    lo: vec4<f32>,
    hi: vec4<f32>,
    // The instance's class colours.
    colors: array<vec4<f32>, COLOR_COUNT>,
    // The highlight's light in the instance's model space: `PunctualLight`'s position and spot axis.
    light_position: vec4<f32>,
    light_axis: vec4<f32>,
    visible: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    // The instance's section planes in its model space.
    section: array<vec4<f32>, SECTION_PLANES>,
}
@group(0) @binding(1) var<storage, read> topology: array<f32>;
@group(0) @binding(2) var<storage, read> edge_vertices: array<u32>;

// A position outside the clip volume: every triangle made of it is dropped (thesis §8.3).
const NOWHERE: vec4<f32> = vec4<f32>(0.0, 0.0, -1.0, 1.0);

// Not a drawn edge this frame.
const NOT_DRAWN: u32 = 0xffffffffu;

// An edge with two faces, one towards the camera and one away (thesis §6.1).
fn is_contour(flags: u32, front_a: bool, front_b: bool) -> bool {
    return front_a != front_b && (flags & (BOUNDARY | NON_MANIFOLD)) == 0u;
}

// Whether and how an edge is drawn this frame given which of its faces look at the camera: its
// drawn word (colour index, contour bits), or NOT_DRAWN. Shared by every object-space technique, so
// all of them draw the same edges.
fn drawn_word(flags: u32, front_a: bool, front_b: bool) -> u32 {
    if is_contour(flags, front_a, front_b) && (frame.classes & CONTOUR) != 0u {
        return COLOR_CONTOUR | DRAWN_CONTOUR | select(0u, INSIDE_V3, !front_a);
    }
    let shown = flags & frame.classes;
    // A crease whose faces both look away is behind the mesh: skip it before it costs a quad.
    let seen = front_a || front_b || (flags & BOUNDARY) != 0u || frame.cull_back == 0u;
    if shown == 0u || !seen {
        return NOT_DRAWN;
    }
    if (shown & (BOUNDARY | NON_MANIFOLD)) != 0u {
        return COLOR_BOUNDARY;
    }
    if (shown & (MARKED | MATERIAL)) != 0u {
        return COLOR_MARKED;
    }
    if (shown & RIDGE) != 0u {
        return COLOR_RIDGE;
    }
    return COLOR_VALLEY;
}

// Vertex `i % 4` of edge `i / 4`: v0 v1 (the edge), v2 (face a's third), v3 (face b's third).
fn edge_vertex(i: u32) -> u32 {
    let j = i - 4u * frame.first_edge;
    if frame.edges_u16 != 0u {
        return (edge_vertices[j >> 1u] >> ((j & 1u) * 16u)) & 0xffffu;
    }
    return edge_vertices[j];
}

fn position(v: u32) -> vec3<f32> {
    return vec3<f32>(topology[3u * v], topology[3u * v + 1u], topology[3u * v + 2u]);
}

// The normals of an edge's two faces, a = (v0, v1, v2) and b = (v1, v0, v3), unnormalized and
// oriented alike (b negated for a FLIPPED edge); a boundary or non-manifold edge repeats a. The
// asset's clusters bound exactly these f32 products (runtime/src/asset/clusters.rs).
fn face_normals(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, v3: vec3<f32>, flags: u32) -> array<vec3<f32>, 2> {
    let a = cross(v1 - v0, v2 - v0);
    if (flags & (BOUNDARY | NON_MANIFOLD)) != 0u {
        return array<vec3<f32>, 2>(a, a);
    }
    let b = cross(v0 - v1, v3 - v1);
    return array<vec3<f32>, 2>(a, select(b, -b, (flags & FLIPPED) != 0u));
}

// Whether a face of normal `n` through `p` looks at the camera (thesis §6.1): the homogeneous eye is
// on its positive side.
fn face_front(n: vec3<f32>, p: vec3<f32>) -> bool {
    let eye = view_eye();
    return dot(n, eye.xyz - p * eye.w) > 0.0;
}

// Whether the faces a and b of the edge (v0, v1, v2, v3) look at the camera; a boundary or
// non-manifold edge's b is a.
fn fronts(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, v3: vec3<f32>, flags: u32) -> vec2<bool> {
    let n = face_normals(v0, v1, v2, v3, flags);
    let a = face_front(n[0], v0);
    if (flags & (BOUNDARY | NON_MANIFOLD)) != 0u {
        return vec2<bool>(a, a);
    }
    return vec2<bool>(a, face_front(n[1], v1));
}

// Whether edge `e`'s faces a and b look at the camera.
fn faces_front(e: u32, flags: u32) -> vec2<bool> {
    let v = array<vec3<f32>, 4>(
        position(edge_vertex(4u * e)),
        position(edge_vertex(4u * e + 1u)),
        position(edge_vertex(4u * e + 2u)),
        position(edge_vertex(4u * e + 3u)),
    );
    return fronts(v[0], v[1], v[2], v[3], flags);
}

// True if the point `p` is beyond one of the frame's widened side planes.
fn beyond_side(p: vec3<f32>, side: u32) -> bool {
    return dot(view_frustum(side), vec4<f32>(p, 1.0)) > 0.0;
}

// True if edge `e` lies wholly beyond one side of the view, so far out that its quad, its caps and
// its joins cannot reach the screen (never with the frustum test off).
fn edge_off_screen(e: u32) -> bool {
    let v0 = position(edge_vertex(4u * e));
    let v1 = position(edge_vertex(4u * e + 1u));
    for (var side = 0u; side < 4u; side++) {
        if beyond_side(v0, side) && beyond_side(v1, side) {
            return true;
        }
    }
    return false;
}

fn cross2(a: vec2<f32>, b: vec2<f32>) -> f32 {
    return a.x * b.y - a.y * b.x;
}

// The left normal of a direction: cross2(a, perp(a)) = 1.
fn perp(a: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(-a.y, a.x);
}

fn to_pixels(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>((ndc.x + 1.0) * 0.5 * frame.viewport.x, (1.0 - ndc.y) * 0.5 * frame.viewport.y);
}

fn from_pixels(px: vec2<f32>, depth: f32, w: f32) -> vec4<f32> {
    let ndc = vec2<f32>(px.x / frame.viewport.x * 2.0 - 1.0, 1.0 - px.y / frame.viewport.y * 2.0);
    return vec4<f32>(ndc * w, depth * w, w);
}

// Depth of a clip position moved `bias_px` pixels' worth of world distance towards the camera: the
// edge wins against the faces it lies on, while anything farther behind a surface stays hidden.
fn biased_depth(c: vec4<f32>) -> f32 {
    return biased_depth_by(c, frame.bias_px);
}

fn biased_depth_by(c: vec4<f32>, bias_px: f32) -> f32 {
    let b = c + bias_px * frame.pixel_scale * c.w * frame.proj_z;
    // A bias that reaches past the near plane puts the edge on it.
    if b.w <= 0.0 || in_front(b) <= 0.0 {
        return near_depth();
    }
    return b.z / b.w;
}

// How far a clip position is inside the near plane (>= 0 inside): z for depth 0 near, w - z for
// reverse Z, where depth 1 is near.
fn in_front(c: vec4<f32>) -> f32 {
    return select(c.z, c.w - c.z, frame.reverse_z != 0u);
}

// The depth of the near plane.
fn near_depth() -> f32 {
    return select(0.0, 1.0, frame.reverse_z != 0u);
}

fn half_width(w: f32) -> f32 {
    var px = frame.width;
    let depth_ref = view_depth_ref();
    if depth_ref > 0.0 {
        px = px * depth_ref / w;
    }
    return 0.5 * max(px, frame.min_width);
}

// The part of the segment p0 -> p1 that is drawn, as parameters from p0: what lies in front of the
// near plane (clip space is linear in the model's, so the near plane cuts at the same parameter)
// and is kept by the section planes. Empty (x >= y) when nothing is left.
fn kept_span(p0: vec3<f32>, p1: vec3<f32>) -> vec2<f32> {
    let mvp = view_mvp();
    let f0 = in_front(mvp * vec4<f32>(p0, 1.0));
    let f1 = in_front(mvp * vec4<f32>(p1, 1.0));
    var span = vec2<f32>(0.0, 1.0);
    if f0 < 0.0 && f1 < 0.0 {
        return vec2<f32>(1.0, 0.0);
    }
    if f0 < 0.0 {
        span.x = f0 / (f0 - f1);
    } else if f1 < 0.0 {
        span.y = f0 / (f0 - f1);
    }
    return section_span(p0, p1, span);
}

// An edge's quad on the screen. `left` and `right` are the quad's extents on either side of the
// line, per end (x: end 0, y: end 1), measured against the direction `d` from end 0 to end 1.
struct EdgeScreen {
    visible: bool,
    // Bit k: end k was moved by the near plane or a section plane, so it is not the mesh vertex.
    clipped: u32,
    s0: vec2<f32>,
    s1: vec2<f32>,
    d: vec2<f32>,
    depth: vec2<f32>,
    w: vec2<f32>,
    left: vec2<f32>,
    right: vec2<f32>,
}

fn edge_screen(e: u32, word: u32) -> EdgeScreen {
    var out: EdgeScreen;
    out.visible = false;
    let mvp = view_mvp();
    let p0 = position(edge_vertex(4u * e));
    let p1 = position(edge_vertex(4u * e + 1u));
    let span = kept_span(p0, p1);
    if !(span.x < span.y) {
        return out;
    }
    let c0 = mvp * vec4<f32>(span_point(p0, p1, span.x), 1.0);
    let c1 = mvp * vec4<f32>(span_point(p0, p1, span.y), 1.0);
    out.clipped = select(0u, 1u, span.x > 0.0) | select(0u, 2u, span.y < 1.0);
    out.s0 = to_pixels(c0);
    out.s1 = to_pixels(c1);
    let along = out.s1 - out.s0;
    let length_px = length(along);
    if !(length_px > 1e-4) {
        return out;
    }
    out.visible = true;
    out.d = along / length_px;
    out.depth = vec2<f32>(biased_depth(c0), biased_depth(c1));
    out.w = vec2<f32>(c0.w, c1.w);
    let h = vec2<f32>(half_width(c0.w), half_width(c1.w));
    out.left = h;
    out.right = h;
    if (word & DRAWN_CONTOUR) != 0u && frame.half_quads != 0u {
        // Half quad (thesis §8.3): the whole width goes outside the silhouette, away from the
        // front face's opposite vertex, so no part of the quad cuts into the surface.
        let inside = position(edge_vertex(4u * e + select(2u, 3u, (word & INSIDE_V3) != 0u)));
        let ci = mvp * vec4<f32>(inside, 1.0);
        if ci.w > 0.0 {
            if dot(to_pixels(ci) - out.s0, perp(out.d)) > 0.0 {
                out.left = vec2<f32>(0.0);
                out.right = 2.0 * h;
            } else {
                out.left = 2.0 * h;
                out.right = vec2<f32>(0.0);
            }
        }
    }
    return out;
}

// An edge's quad as classify stores it for the joins and the draws (the `screen` list, per slot),
// so each edge is projected once per frame rather than once per vertex and per neighbour.
struct ScreenRecord {
    ends: vec4<f32>,
    depth_w: vec4<f32>,
    extents: vec4<f32>,
}

fn to_record(s: EdgeScreen) -> ScreenRecord {
    return ScreenRecord(
        vec4<f32>(s.s0, s.s1),
        vec4<f32>(s.depth, s.w),
        vec4<f32>(s.left, s.right),
    );
}

fn from_record(r: ScreenRecord, word: u32) -> EdgeScreen {
    var s: EdgeScreen;
    s.visible = (word & ON_SCREEN) != 0u;
    s.clipped = (word >> CLIPPED_SHIFT) & 3u;
    s.s0 = r.ends.xy;
    s.s1 = r.ends.zw;
    s.d = normalize(s.s1 - s.s0);
    s.depth = r.depth_w.xy;
    s.w = r.depth_w.zw;
    s.left = r.extents.xy;
    s.right = r.extents.zw;
    return s;
}

// Vertex `vertex` (of 6) of an edge's quad: two triangles, (end, side) = (0,-) (1,-) (1,+) /
// (0,-) (1,+) (0,+).
fn quad_vertex(s: EdgeScreen, vertex: u32) -> vec4<f32> {
    let k = (0x16u >> vertex) & 1u;
    let side_left = ((0x34u >> vertex) & 1u) == 1u;
    if k == 1u {
        return from_pixels(s.s1 + perp(s.d) * select(-s.right.y, s.left.y, side_left), s.depth.y, s.w.y);
    }
    return from_pixels(s.s0 + perp(s.d) * select(-s.right.x, s.left.x, side_left), s.depth.x, s.w.x);
}

// One end of an edge seen from that end: its point, its direction away from it, and the quad's
// extents on the left and right of that direction.
struct EdgeEnd {
    p: vec2<f32>,
    a: vec2<f32>,
    left: f32,
    right: f32,
    depth: f32,
    w: f32,
}

fn edge_end(s: EdgeScreen, k: u32) -> EdgeEnd {
    if k == 0u {
        return EdgeEnd(s.s0, s.d, s.left.x, s.right.x, s.depth.x, s.w.x);
    }
    return EdgeEnd(s.s1, -s.d, s.right.y, s.left.y, s.depth.y, s.w.y);
}
