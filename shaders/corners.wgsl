// Rounded corners (issue 29; runtime/src/highlight/corners.rs finds them): where the chamfer edges at a
// convex vertex share one radius r, the rounded solid near the vertex is a sphere of radius r, centred
// r inside the vertex's three face planes, with the edges' cylinders running from it. A drawn corner
// owns the pixels around its vertex: each strip hands over those within `hand_over` pixels of the
// vertex along its edge (edges.wgsl discards them) and the corner draw (corner_draw.wgsl) traces the
// local solid there per sub-sample. Both sides decide with the functions below, from the same record.
//
// Shared by chamfers.wgsl (compute), corner_draw.wgsl and outline.wgsl; all bind the asset's corner
// buffer: its count, the records (CORNER_WORDS words each), then each edge end's corner + 1 (0: none),
// four a word. The rays below are in the instance's model space.

@group(0) @binding(31) var<storage, read> corners: array<vec4<u32>>;

struct Corner {
    // The sphere's centre and radius.
    sphere: vec4<f32>,
    // The sharp vertex; w: how far each cylinder is followed from the centre (the shortest edge).
    vertex: vec4<f32>,
    // The three planes' outward normals; normals[0].w: the reach around the vertex (model units).
    normals: array<vec4<f32>, 3>,
    // Per plane pair (k, k + 1): the far end of its kept edge (w = 1), or w = 0 for none.
    far: array<vec4<f32>, 3>,
}

fn corner_count() -> u32 {
    return corners[0].x;
}

fn corner_at(k: u32) -> Corner {
    let base = 1u + k * CORNER_WORDS;
    let w = array<vec4<f32>, 8>(
        bitcast<vec4<f32>>(corners[base]),
        bitcast<vec4<f32>>(corners[base + 1u]),
        bitcast<vec4<f32>>(corners[base + 2u]),
        bitcast<vec4<f32>>(corners[base + 3u]),
        bitcast<vec4<f32>>(corners[base + 4u]),
        bitcast<vec4<f32>>(corners[base + 5u]),
        bitcast<vec4<f32>>(corners[base + 6u]),
        bitcast<vec4<f32>>(corners[base + 7u]),
    );
    return Corner(w[0], w[1], array<vec4<f32>, 3>(w[2], w[3], w[4]), array<vec4<f32>, 3>(w[5], w[6], w[7]));
}

// The corner at edge end `end` (2 e + k) + 1, or 0.
fn corner_of_end(end: u32) -> u32 {
    let i = 1u + corner_count() * CORNER_WORDS + end / 4u;
    return corners[i][end % 4u];
}

// Whether the corner is drawn in this view: a face of it looks at the camera (on the silhouette the
// part of the sphere and cylinders the eye sees, issue 39) and its vertex is in front of the near
// plane and kept by the section (a cut edge ends at the cut, without a corner).
fn corner_drawn(c: Corner) -> bool {
    let v = c.vertex.xyz;
    let clip = view_mvp() * vec4<f32>(v, 1.0);
    if clip.w <= 0.0 || in_front(clip) < 0.0 || section_cuts(v) {
        return false;
    }
    return face_front(c.normals[0].xyz, v) || face_front(c.normals[1].xyz, v) || face_front(c.normals[2].xyz, v);
}

// The model-space steps that move a point at `p`'s depth one pixel right and one pixel down on screen
// (in the plane through `p` where the projection is affine: constant w, or constant depth when
// orthographic).
fn pixel_steps(p: vec3<f32>) -> array<vec3<f32>, 2> {
    let m = transpose(view_mvp());
    let w_row = m[3].xyz;
    let depth_row = select(m[2].xyz, w_row, dot(w_row, w_row) > 0.0);
    let u = normalize(cross(m[1].xyz, depth_row));
    let v = normalize(cross(depth_row, m[0].xyz));
    let mvp = view_mvp();
    let q = to_pixels(mvp * vec4<f32>(p, 1.0));
    let pu = to_pixels(mvp * vec4<f32>(p + u, 1.0)) - q;
    let pv = to_pixels(mvp * vec4<f32>(p + v, 1.0)) - q;
    let det = cross2(pu, pv);
    return array<vec3<f32>, 2>((pv.y * u - pu.y * v) / det, (pu.x * v - pv.x * u) / det);
}

// The model-space size of a pixel with these steps (pixel_steps).
fn pixel_size(steps: array<vec3<f32>, 2>) -> f32 {
    return max(0.5 * (length(steps[0]) + length(steps[1])), 1e-20);
}

// How many pixels from the vertex, along the edge to `far`, a strip hands over to the corner: the
// corner's reach on screen, at most half the edge (the corner at the far end takes the other half);
// none where `far` is behind the camera (the strip keeps its seed ends, the corner leaves it alone).
fn hand_over(c: Corner, far: vec3<f32>) -> f32 {
    let mvp = view_mvp();
    let v = to_pixels(mvp * vec4<f32>(c.vertex.xyz, 1.0));
    let reach = c.normals[0].w / pixel_size(pixel_steps(c.vertex.xyz));
    let clip = mvp * vec4<f32>(far, 1.0);
    if clip.w <= 0.0 {
        return 0.0;
    }
    return min(reach, 0.5 * length(to_pixels(clip) - v));
}

// Where a corner's square lies on screen, and what every pixel of it shares (the vertex on screen,
// the model-space steps of a pixel there, the strips' hand-over lines).
struct CornerSquare {
    position: vec4<f32>,
    vertex_px: vec2<f32>,
    steps: array<vec3<f32>, 2>,
    lines: array<vec4<f32>, 3>,
}

// Vertex `vertex` (of 6) of the square around corner `c`, in front of the faces around it by its
// half-width: all the corner draws or trims, plus `margin` pixels. Every rounded point it owns is
// c + r n + a axis with n in its normals' cone (the sphere) or in a pair's arc (a cylinder, a >= 0):
// c + r n lies within sqrt(|c - v|^2 - r^2) of the vertex (each normal is r above the centre), and
// the cylinders run along their edges no farther than their hand-over. The square is no wider: on a
// faceted rim (short edges, many corners) the reach alone made it ten times the corner's pixels.
fn corner_square(c: Corner, vertex: u32, margin: f32) -> CornerSquare {
    var q: CornerSquare;
    let clip = view_mvp() * vec4<f32>(c.vertex.xyz, 1.0);
    q.vertex_px = to_pixels(clip);
    q.steps = pixel_steps(c.vertex.xyz);
    q.lines = hand_over_lines(c, q.vertex_px);
    let per_pixel = pixel_size(q.steps);
    let to_centre = c.sphere.xyz - c.vertex.xyz;
    let r = c.sphere.w;
    // The 1.5 pixels the fragment grows the sphere by to find the pixels worth tracing.
    let around = sqrt(max(dot(to_centre, to_centre) - r * r, 0.0)) / per_pixel + 1.5;
    var along = around;
    for (var k = 0u; k < 3u; k += 1u) {
        if pair_rounded(c, k) && q.lines[k].w > 0.0 {
            along = max(along, q.lines[k].z + 1.5);
        }
    }
    let extent = sqrt(along * along + around * around) + 1.0 + margin;
    let corner = vec2<f32>(
        select(-1.0, 1.0, ((0x16u >> vertex) & 1u) == 1u),
        select(-1.0, 1.0, ((0x34u >> vertex) & 1u) == 1u),
    );
    let depth = biased_depth_by(clip, frame.bias_px + extent);
    q.position = from_pixels(q.vertex_px + corner * extent, depth, clip.w);
    return q;
}

// Per plane pair k, its strip's hand-over line: the edge's direction on screen (xy) and how far along
// it from the vertex the corner owns the cylinder (z); z < 0: the whole cylinder (no strip), w = 0: none
// of it (its far end behind the camera: hand_over).
fn hand_over_lines(c: Corner, vertex_px: vec2<f32>) -> array<vec4<f32>, 3> {
    let mvp = view_mvp();
    var lines: array<vec4<f32>, 3>;
    for (var pair = 0u; pair < 3u; pair += 1u) {
        lines[pair] = vec4<f32>(0.0, 0.0, -1.0, 1.0);
        let far = c.far[pair];
        if far.w > 0.0 {
            let far_clip = mvp * vec4<f32>(far.xyz, 1.0);
            let along = normalize(to_pixels(far_clip) - vertex_px);
            lines[pair] = vec4<f32>(along, hand_over(c, far.xyz), select(0.0, 1.0, far_clip.w > 0.0));
        }
    }
    return lines;
}

// Whether the corner's local solid stands for the mesh at `pixel`: short of every strip's hand-over
// that is shorter than the corner's reach (there the edge itself is short: a faceted rim, whose next
// facets turn away from the corner's planes).
fn local_at(c: Corner, lines: array<vec4<f32>, 3>, vertex_px: vec2<f32>, pixel: vec2<f32>, per_pixel: f32) -> bool {
    let reach = c.normals[0].w / per_pixel;
    for (var k = 0u; k < 3u; k += 1u) {
        let line = lines[k];
        if line.z >= 0.0 && line.z < reach && dot(pixel - vertex_px, line.xy) >= line.z {
            return false;
        }
    }
    return true;
}

// Whether unit `n` lies in the arc from `a` to `b` (less than a half turn), within `slack`.
fn in_arc(n: vec3<f32>, a: vec3<f32>, b: vec3<f32>, slack: f32) -> bool {
    let axis = cross(a, b);
    return dot(cross(a, n), axis) >= -slack && dot(cross(n, b), axis) >= -slack;
}

// Whether unit `n` lies in the cone spanned by the corner's three normals, within `slack`.
fn in_cone(c: Corner, n: vec3<f32>, slack: f32) -> bool {
    for (var k = 0u; k < 3u; k += 1u) {
        let m = cross(c.normals[(k + 1u) % 3u].xyz, c.normals[(k + 2u) % 3u].xyz);
        if dot(n, m) * sign(dot(c.normals[k].xyz, m)) < -slack {
            return false;
        }
    }
    return true;
}

// What a ray enters first of the corner's rounded solid.
const MISSED: u32 = 0u;
// The sphere, or a cylinder the corner draws.
const ROUNDED: u32 = 1u;
// A face (the mesh's), or a cylinder its strip draws.
const COVERED: u32 = 2u;

struct Hit {
    t: f32,
    normal: vec3<f32>,
    part: u32,
}

// Cylinder k's axis (planes k and k + 1): from the centre, away from the third plane.
fn cylinder_axis(c: Corner, k: u32) -> vec3<f32> {
    let axis = normalize(cross(c.normals[k].xyz, c.normals[(k + 1u) % 3u].xyz));
    return select(axis, -axis, dot(axis, c.normals[(k + 2u) % 3u].xyz) > 0.0);
}

// Whether plane pair k (planes k, k + 1) meets at a chamfer edge, rounded; else at a sharp facet edge.
fn pair_rounded(c: Corner, k: u32) -> bool {
    return c.far[k].w > 0.0;
}

// An empty interval of the ray.
const NO_INTERVAL: vec2<f32> = vec2<f32>(1.0, -1.0);

// `i` where a0 + a1 t >= s.
fn at_least(i: vec2<f32>, a0: f32, a1: f32, s: f32) -> vec2<f32> {
    if abs(a1) < 1e-12 {
        return select(NO_INTERVAL, i, a0 >= s);
    }
    let t = (s - a0) / a1;
    return select(vec2<f32>(i.x, min(i.y, t)), vec2<f32>(max(i.x, t), i.y), a1 > 0.0);
}

// `i` where a0 + a1 t < s.
fn below(i: vec2<f32>, a0: f32, a1: f32, s: f32) -> vec2<f32> {
    return at_least(i, -a0, -a1, -s);
}

// The smallest interval holding `a` and `b` (either may be empty).
fn hull(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    if a.x > a.y {
        return b;
    }
    if b.x > b.y {
        return a;
    }
    return vec2<f32>(min(a.x, b.x), max(a.y, b.y));
}

// `i` less the part of `zone` outside `keep`: a convex solid less a zone rounded away, whose result is
// convex again, so one interval (the hull of what is left).
fn round_away(i: vec2<f32>, zone: vec2<f32>, keep: vec2<f32>) -> vec2<f32> {
    let before = vec2<f32>(i.x, min(i.y, zone.x));
    let after = vec2<f32>(max(i.x, zone.y), i.y);
    let kept = vec2<f32>(max(max(i.x, zone.x), keep.x), min(min(i.y, zone.y), keep.y));
    return hull(hull(before, after), kept);
}

// Where the ray's line lies within `r` of the line through `p` along unit `axis` (or of `p` itself
// with a zero axis).
fn near_line(origin: vec3<f32>, dir: vec3<f32>, p: vec3<f32>, axis: vec3<f32>, r: f32) -> vec2<f32> {
    let o = origin - p;
    let op = o - dot(o, axis) * axis;
    let dp = dir - dot(dir, axis) * axis;
    let qa = dot(dp, dp);
    let qb = dot(op, dp);
    let q = qb * qb - qa * (dot(op, op) - r * r);
    if qa < 1e-12 {
        return select(NO_INTERVAL, vec2<f32>(-1e30, 1e30), dot(op, op) <= r * r);
    }
    if q < 0.0 {
        return NO_INTERVAL;
    }
    return vec2<f32>((-qb - sqrt(q)) / qa, (-qb + sqrt(q)) / qa);
}

// The part of the ray (`origin`, unit `dir`; t >= 0) inside the corner's rounded solid: the sharp
// corner (inside its three planes) with each chamfer edge rounded by its cylinder (where a point is
// within r of both its planes it must be within r of the axis) and, where all three edges are
// chamfers, the sphere (where it is within r of all three planes, within r of the centre). Each
// rounding leaves a convex solid, so the ray meets it in one interval; empty when x > y. A facet
// edge between its two planes stays sharp, as it is on the mesh around.
fn rounded_interval(c: Corner, origin: vec3<f32>, dir: vec3<f32>) -> vec2<f32> {
    let v = c.vertex.xyz;
    let r = c.sphere.w;
    // Depth below plane k at t: d0[k] + d1[k] t.
    var d0: array<f32, 3>;
    var d1: array<f32, 3>;
    var inside = vec2<f32>(0.0, 1e30);
    for (var k = 0u; k < 3u; k += 1u) {
        let n = c.normals[k].xyz;
        d0[k] = -dot(n, origin - v);
        d1[k] = -dot(n, dir);
        inside = at_least(inside, d0[k], d1[k], 0.0);
    }
    var corner_zone = vec2<f32>(-1e30, 1e30);
    var all_rounded = true;
    for (var k = 0u; k < 3u; k += 1u) {
        let j = (k + 1u) % 3u;
        corner_zone = below(corner_zone, d0[k], d1[k], r);
        if !pair_rounded(c, k) {
            all_rounded = false;
            continue;
        }
        let zone = below(below(vec2<f32>(-1e30, 1e30), d0[k], d1[k], r), d0[j], d1[j], r);
        inside = round_away(inside, zone, near_line(origin, dir, c.sphere.xyz, cylinder_axis(c, k), r));
    }
    if all_rounded {
        inside = round_away(inside, corner_zone, near_line(origin, dir, c.sphere.xyz, vec3<f32>(0.0), r));
    }
    return inside;
}

// The first point where the ray (`origin`, unit `dir`) enters the corner's rounded solid
// (rounded_interval), and which part: the sphere where its normal lies in the normals' cone (a corner
// of three chamfer edges), a chamfer edge's cylinder between its faces' normals (ROUNDED up to the
// followed length where `owned[k]`, short of its strip's hand-over; COVERED beyond) or a face
// (COVERED). With `anywhere`, the whole sphere and cylinders count, whatever the normal (a bound on
// where the rounded parts can be), and the faces not at all.
fn enter(c: Corner, origin: vec3<f32>, dir: vec3<f32>, owned: vec3<bool>, anywhere: bool) -> Hit {
    // Patches meet edge to edge: a little slack, so no ray slips between two of them.
    let slack = 1e-4;
    var best = Hit(-1.0, vec3<f32>(0.0), MISSED);
    let center = c.sphere.xyz;
    let r = c.sphere.w;
    let oc = origin - center;
    let all_rounded = pair_rounded(c, 0u) && pair_rounded(c, 1u) && pair_rounded(c, 2u);
    let b = dot(oc, dir);
    let disc = b * b - (dot(oc, oc) - r * r);
    if disc >= 0.0 && (all_rounded || anywhere) {
        let t = -b - sqrt(disc);
        let n = (oc + t * dir) / r;
        if t >= 0.0 && (anywhere || in_cone(c, n, slack)) {
            best = Hit(t, n, ROUNDED);
        }
    }
    for (var k = 0u; k < 3u; k += 1u) {
        if !pair_rounded(c, k) {
            continue;
        }
        let na = c.normals[k].xyz;
        let nb = c.normals[(k + 1u) % 3u].xyz;
        let axis = cylinder_axis(c, k);
        let span = near_line(origin, dir, center, axis, r);
        let t = span.x;
        if span.x > span.y || t < 0.0 {
            continue;
        }
        let p = oc + t * dir;
        let along = dot(p, axis);
        let n = (p - along * axis) / r;
        let drawn = owned[k] && along <= c.vertex.w;
        if along >= -slack * r && (anywhere || in_arc(n, na, nb, slack))
            && (best.t < 0.0 || t < best.t) && (drawn || !anywhere) {
            best = Hit(t, n, select(COVERED, ROUNDED, drawn));
        }
    }
    if anywhere {
        return best;
    }
    let inside = rounded_interval(c, origin, dir);
    if inside.x > inside.y {
        return Hit(-1.0, vec3<f32>(0.0), MISSED);
    }
    // A patch entered farther along than the solid is (beyond a twentieth of r: grazing rays meet
    // the two at f32's mercy) is inside already: the ray entered through a face, the mesh's.
    if best.t < 0.0 || best.t > inside.x + 0.05 * r {
        return Hit(inside.x, vec3<f32>(0.0), COVERED);
    }
    return best;
}

// Whether the ray (`origin`, unit `dir`) meets the sharp corner (the three planes' inside) grown by
// `grow` model units.
fn enters_sharp(c: Corner, origin: vec3<f32>, dir: vec3<f32>, grow: f32) -> bool {
    var lo = 0.0;
    var hi = 1e30;
    let v = c.vertex.xyz;
    for (var k = 0u; k < 3u; k += 1u) {
        let n = c.normals[k].xyz;
        let towards = dot(n, dir);
        let height = dot(n, origin - v) - grow;
        if abs(towards) < 1e-12 {
            if height > 0.0 {
                return false;
            }
            continue;
        }
        let t = -height / towards;
        if towards > 0.0 {
            hi = min(hi, t);
        } else {
            lo = max(lo, t);
        }
    }
    return lo <= hi;
}

// The ray (origin, unit direction) through the screen point `q` (pixels): through the plane of constant
// depth at the vertex (where `steps` are the model-space pixel steps), starting `back` before it.
fn pixel_ray(vertex: vec3<f32>, vertex_px: vec2<f32>, steps: array<vec3<f32>, 2>, eye: vec4<f32>, back: f32, q: vec2<f32>) -> array<vec3<f32>, 2> {
    let d = q - vertex_px;
    let on_plane = vertex + steps[0] * d.x + steps[1] * d.y;
    let dir = select(-normalize(eye.xyz), normalize(on_plane - eye.xyz), eye.w > 0.0);
    return array<vec3<f32>, 2>(on_plane - back * dir, dir);
}

// Where the ray (`origin`, unit `dir`) enters the sharp corner, if it does: the last of the three
// planes it crosses inwards, and how far along the ray.
struct SharpEntry {
    t: f32,
    plane: u32,
}

fn sharp_entry(c: Corner, origin: vec3<f32>, dir: vec3<f32>) -> SharpEntry {
    var entry = SharpEntry(0.0, 0u);
    var lo = -1e30;
    for (var k = 0u; k < 3u; k += 1u) {
        let n = c.normals[k].xyz;
        let towards = dot(n, dir);
        if towards < 0.0 {
            let t = -dot(n, origin - c.vertex.xyz) / towards;
            if t > lo {
                lo = t;
                entry = SharpEntry(max(t, 0.0), k);
            }
        }
    }
    return entry;
}

// The depth a corner's pixel is drawn at: the sharp corner's where the ray through the pixel's centre
// meets it (the rounded surface lies inside, behind it), brought forward by the edges' bias (as
// strip_depth does for strips).
fn corner_depth(c: Corner, origin: vec3<f32>, dir: vec3<f32>) -> f32 {
    let p = origin + sharp_entry(c, origin, dir).t * dir;
    return biased_depth_by(view_mvp() * vec4<f32>(p, 1.0), frame.bias_px);
}

// How far before the vertex's plane a corner's rays start: beyond anything of the corner.
fn ray_start(c: Corner) -> f32 {
    return 4.0 * (c.normals[0].w + c.sphere.w);
}
