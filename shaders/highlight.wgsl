// The chamfer highlight of seed 000: a chamfer edge drawn as the rounded strip (a partial cylinder of
// the edge's radius, normals sweeping from one face's normal to the other's) it stands for, each
// pixel lit by Blinn's model integrated in closed form over the part of the arc the pixel sees
// (§3.1, eq. 3-5), then blended over the mesh with W = K r_e / (d r_max) (§3.2). Where the strip is
// wider than a pixel (beyond the paper's limit, §4) every pixel integrates its own slice of the arc,
// so near edges stay right. The CPU twin of this code, tested against sampling the arc, is
// runtime/src/highlight/strip.rs; the table is runtime/src/highlight/table.rs.
//
// Shared by the compute side (chamfer_records, after classify) and the edge fragment shader; each
// module that includes it declares `chamfers`, `cos_power` and `lighting` (compute.wgsl or draw.wgsl).

// Per drawn slot of a highlighted edge, in the model space of its instance.
struct ChamferRecord {
    // Face normals (unit); `n1.w` is the radius in mesh units.
    n1: vec4<f32>,
    // `n2.w`: the distance from the eye to the edge's middle, for the blend's K / d (0: orthographic).
    n2: vec4<f32>,
    // The edge's points at the two ends of its quad on screen (where the near plane may have moved
    // them).
    end0: vec4<f32>,
    end1: vec4<f32>,
    // The instance's eye: a point (w = 1), or the direction towards the viewer (w = 0).
    eye: vec4<f32>,
    // Pixels from end 0 (x) and end 1 (y) along the edge that a drawn rounded corner there takes
    // over (corners.wgsl); 0 without one.
    hand_over: vec4<f32>,
    // The instance's light: its position (or direction) and spot axis, in its model space.
    light_position: vec4<f32>,
    light_axis: vec4<f32>,
}

struct Lighting {
    light: PunctualLight,
    // Blinn: R_d, R_s, shininess n, ambient share of R_d. PBR: metallic, α = roughness², unused,
    // ambient share of the diffuse colour.
    material: vec4<f32>,
    // PBR: the base colour (linear RGB). w: K of the blend weight.
    base: vec4<f32>,
    // SHADE_PBR: glTF's metallic-roughness shading (brdf.wgsl, the GGX arc rule below), else Blinn
    // (seed 000); SHADE_ENVIRONMENT: plus the image-based light (edges.wgsl, `strip_environment`).
    pbr: u32,
    // 1: draw rounded corners where chamfer edges meet (corners.wgsl), 0: the seed's strip ends.
    corners: u32,
    _pad1: u32,
    _pad2: u32,
}

const SAMPLES: f32 = f32(COS_POWER_SAMPLES);

// F(φ, n + 1) from the row, Hermite with exact slopes cos^(n+1) (table.rs), odd in φ.
fn cos_power_integral(phi: f32) -> f32 {
    let m = lighting.material.z + 1.0;
    let h = 0.5 * PI / SAMPLES;
    let x = min(abs(phi), 0.5 * PI) / h;
    let i = min(u32(x), u32(SAMPLES) - 1u);
    let t = x - f32(i);
    let s0 = pow(max(cos(f32(i) * h), 0.0), m) * h;
    let s1 = pow(max(cos(f32(i + 1u) * h), 0.0), m) * h;
    let t2 = t * t;
    let t3 = t2 * t;
    let value = (2.0 * t3 - 3.0 * t2 + 1.0) * cos_power[i] + (t3 - 2.0 * t2 + t) * s0
        + (-2.0 * t3 + 3.0 * t2) * cos_power[i + 1u] + (t3 - t2) * s1;
    return sign(phi) * value;
}

// The arc's frame: angles from n1, towards n2.
struct Arc {
    ex: vec3<f32>,
    ey: vec3<f32>,
    ez: vec3<f32>,
    span: f32,
}

fn arc_of(n1: vec3<f32>, n2: vec3<f32>) -> Arc {
    let ez = normalize(cross(n1, n2));
    return Arc(n1, cross(ez, n1), ez, acos(clamp(dot(n1, n2), -1.0, 1.0)));
}

fn angle_in(arc: Arc, v: vec3<f32>) -> vec2<f32> {
    let x = dot(v, arc.ex);
    let y = dot(v, arc.ey);
    return vec2<f32>(atan2(y, x), length(vec2<f32>(x, y)));
}

// [a, b] clipped to the arc of half-width `half` (at most a half turn) centred on c; empty when x >= y.
fn clip_arc(range: vec2<f32>, c: f32, half: f32) -> vec2<f32> {
    let centre = select(c, c + 2.0 * PI, c < -half);
    return vec2<f32>(max(range.x, centre - half), min(range.y, centre + half));
}

// [a, b] clipped to the half-turn lobe centred on c; empty when x >= y.
fn clip_lobe(range: vec2<f32>, c: f32) -> vec2<f32> {
    return clip_arc(range, c, 0.5 * PI);
}

// ∫ (N·v)₊^m (P·T) dθ over `range`; `closed_f` picks F(·, 2) in closed form (diffuse, m = 1).
fn lobe(arc: Arc, across: vec3<f32>, v: vec3<f32>, range: vec2<f32>, m: f32, closed_f: bool) -> f32 {
    let polar = angle_in(arc, v);
    if polar.y < 1e-6 {
        return 0.0;
    }
    let clipped = clip_lobe(range, polar.x);
    if clipped.x >= clipped.y {
        return 0.0;
    }
    let centre = select(polar.x, polar.x + 2.0 * PI, polar.x < -0.5 * PI);
    let u = clipped - vec2<f32>(centre);
    let ex = arc.ex * cos(centre) + arc.ey * sin(centre);
    let ey = cross(arc.ez, ex);
    let px = dot(across, ex);
    let py = dot(across, ey);
    var f = vec2<f32>(0.0);
    if closed_f {
        f = 0.5 * u + 0.25 * sin(2.0 * u);
    } else {
        f = vec2<f32>(cos_power_integral(u.x), cos_power_integral(u.y));
    }
    let power = pow(max(cos(u), vec2<f32>(0.0)), vec2<f32>(m + 1.0));
    return pow(polar.y, m) * (py * (f.y - f.x) + px / (m + 1.0) * (power.y - power.x));
}

// The GGX arc rule (runtime/src/highlight/ggx.rs): ∫ D(N·H) Vis (N·L)₊ (P·T) dθ over `range`, after
// tan u = a tan w makes D's lobe a smooth weight, by 16-point Gauss–Legendre in w.
fn ggx_arc(arc: Arc, across: vec3<f32>, to_light: vec3<f32>, to_viewer: vec3<f32>, range: vec2<f32>, alpha: f32) -> f32 {
    let half = half_vector(to_light, to_viewer);
    let polar = angle_in(arc, half);
    if polar.y < 1e-6 {
        return 0.0;
    }
    let lobe = clip_lobe(range, polar.x);
    let lit = clip_lobe(lobe, angle_in(arc, to_light).x);
    if lobe.x >= lobe.y || lit.x >= lit.y {
        return 0.0;
    }
    let centre = select(polar.x, polar.x + 2.0 * PI, polar.x < -0.5 * PI);
    let axial = dot(half, arc.ez);
    let a2 = axial * axial + polar.y * polar.y * alpha * alpha;
    let a = sqrt(a2);
    let ua = lit - vec2<f32>(centre);
    let w = atan2(sin(ua), a * max(cos(ua), vec2<f32>(0.0)));
    let mid = 0.5 * (w.x + w.y);
    let half_width = 0.5 * (w.y - w.x);
    var nodes = GGX_NODES;
    var sum = 0.0;
    for (var k = 0u; k < 8u; k += 1u) {
        let node = nodes[k];
        for (var side = -1.0; side <= 1.0; side += 2.0) {
            let wk = mid + side * half_width * node.x;
            let theta = centre + atan2(a * sin(wk), cos(wk));
            let normal = arc.ex * cos(theta) + arc.ey * sin(theta);
            let tangent = arc.ey * cos(theta) - arc.ex * sin(theta);
            let n_dot_l = max(dot(normal, to_light), 0.0);
            let weight = cos(wk) * cos(wk) + a2 * sin(wk) * sin(wk);
            sum += node.y * weight * smith_visibility(n_dot_l, dot(normal, to_viewer), alpha) * n_dot_l
                * dot(tangent, across);
        }
    }
    return alpha * alpha / (PI * a2 * a) * half_width * sum;
}

// Mean PBR radiance over the arc range under a light of radiance 1 (ggx.rs, `arc_radiance`).
fn arc_radiance(arc: Arc, across: vec3<f32>, to_light: vec3<f32>, to_viewer: vec3<f32>, range: vec2<f32>) -> vec3<f32> {
    let projected = dot(arc.ex * (cos(range.y) - cos(range.x)) + arc.ey * (sin(range.y) - sin(range.x)), across);
    if abs(projected) < 1e-9 {
        return vec3<f32>(0.0);
    }
    let m = Pbr(lighting.base.rgb, lighting.material.x, lighting.material.y);
    let diffuse = lobe(arc, across, to_light, range, 1.0, true);
    let specular = ggx_arc(arc, across, to_light, to_viewer, range, m.alpha);
    let fresnel = schlick(m, dot(to_viewer, half_vector(to_light, to_viewer)));
    let lit = (vec3<f32>(1.0) - fresnel) * pbr_diffuse_color(m) / PI * diffuse + fresnel * specular;
    return max(lit / projected, vec3<f32>(0.0));
}

// Mean Blinn intensity over the arc range (angles from n1) under one light.
fn arc_intensity(arc: Arc, across: vec3<f32>, to_light: vec3<f32>, to_viewer: vec3<f32>, range: vec2<f32>) -> f32 {
    let projected = dot(arc.ex * (cos(range.y) - cos(range.x)) + arc.ey * (sin(range.y) - sin(range.x)), across);
    if abs(projected) < 1e-9 {
        return 0.0;
    }
    let half = half_vector(to_light, to_viewer);
    let diffuse = lobe(arc, across, to_light, range, 1.0, true);
    let specular = lobe(arc, across, half, range, lighting.material.z, false);
    let ambient = lighting.material.w;
    let lit = (lighting.material.x * (1.0 - ambient) * diffuse + lighting.material.y * specular) / projected;
    return max(lit, 0.0);
}

fn to_viewer_at(p: vec3<f32>) -> vec3<f32> {
    let eye = view_eye();
    return normalize(eye.xyz - p * eye.w);
}

// The style's light as the instance drawn sees it.
fn view_light() -> PunctualLight {
    var light = lighting.light;
    light.position = view_light_position();
    light.spot = vec4<f32>(view_light_axis(), light.spot.w);
    return light;
}

// The light a strip's record carries (the draw pass draws every instance at once).
fn record_light(record: ChamferRecord) -> PunctualLight {
    var light = lighting.light;
    light.position = record.light_position;
    light.spot = vec4<f32>(record.light_axis.xyz, light.spot.w);
    return light;
}

// What a pixel of the strip shows: its slice's mean radiance under `punctual` (the seed's Blinn or PBR).
fn strip_radiance(arc: Arc, across: vec3<f32>, middle: vec3<f32>, to_viewer: vec3<f32>, range: vec2<f32>, punctual: PunctualLight) -> vec3<f32> {
    let to_light = towards_light(punctual, middle);
    let light = light_radiance(punctual, middle);
    if (lighting.pbr & SHADE_PBR) != 0u {
        let m = Pbr(lighting.base.rgb, lighting.material.x, lighting.material.y);
        // The ambient term at the slice's middle normal (it varies slowly over the arc).
        let mid = 0.5 * (range.x + range.y);
        let normal = arc.ex * cos(mid) + arc.ey * sin(mid);
        return light * arc_radiance(arc, across, to_light, to_viewer, range)
            + lighting.material.w * uniform_environment(m, dot(normal, to_viewer));
    }
    // The ambient share is lit regardless of the light (its colour, distance and cone), as on the
    // mesh (mesh.wgsl).
    let ambient = lighting.material.x * lighting.material.w;
    return light * arc_intensity(arc, across, to_light, to_viewer, range) + vec3<f32>(ambient);
}

// The strip's cross-section through a pixel (issue 39), exact where it matters at the outline: the
// edge's point whose projection is the pixel's foot on the edge, the part of the arc the eye sees
// there (where the strip's normal faces the eye: of a cylinder seen from a point, a little less than
// a half turn), where that part's two ends land across the sharp edge (their projections), and which
// end, if any, is the rounded outline (the horizon, where a face turned away would begin).
struct Section {
    arc: Arc,
    // The visible angles, from n1 towards n2; empty when x >= y.
    visible: vec2<f32>,
    // Pixels across the sharp edge, along the quad's left normal, of the points at visible.x and .y.
    offsets: vec2<f32>,
    // 1 where visible.x (bit 0) or visible.y (bit 1) is the outline.
    outline: u32,
    // P: perpendicular to the edge and to the view at `point` (seed 000's projection direction).
    across: vec3<f32>,
    point: vec3<f32>,
    to_viewer: vec3<f32>,
    // P·N at visible.x and .y: between the two ends the offset follows P·N (the projection across a
    // pixel is affine), pinned to the exact offsets at the ends.
    shape: vec2<f32>,
}

// Pixels across the line from `ends.xy` to `ends.zw` (along its left normal) where `p` lands.
fn across_of(mvp: mat4x4<f32>, ends: vec4<f32>, p: vec3<f32>) -> f32 {
    let c = mvp * vec4<f32>(p, 1.0);
    let d = normalize(ends.zw - ends.xy);
    return dot(to_pixels(vec4<f32>(c.xyz, max(c.w, 1e-20))) - ends.xy, perp(d));
}

// The section of the strip of `record` (its quad from `ends.xy` to `ends.zw` on screen, drawn with
// `mvp`) at the point whose projection is `pixel`'s foot on the edge.
fn section_at(record: ChamferRecord, mvp: mat4x4<f32>, ends: vec4<f32>, pixel: vec2<f32>) -> Section {
    var s: Section;
    let n1 = record.n1.xyz;
    let n2 = record.n2.xyz;
    let r = record.n1.w;
    s.arc = arc_of(n1, n2);
    let along = ends.zw - ends.xy;
    let u = clamp(dot(pixel - ends.xy, along) / max(dot(along, along), 1e-20), 0.0, 1.0);
    // The screen's u is the edge's t after the perspective divide.
    let w0 = (mvp * vec4<f32>(record.end0.xyz, 1.0)).w;
    let w1 = (mvp * vec4<f32>(record.end1.xyz, 1.0)).w;
    let t = u * w0 / max((1.0 - u) * w1 + u * w0, 1e-20);
    s.point = mix(record.end0.xyz, record.end1.xyz, t);
    let axis = normalize(record.end1.xyz - record.end0.xyz);
    let eye = record.eye;
    s.to_viewer = normalize(eye.xyz - s.point * eye.w);
    // The cylinder's axis at this section: r inside both faces.
    let centre = s.point - r * (n1 + n2) / (1.0 + dot(n1, n2));
    var towards = eye.xyz;
    var half = 0.5 * PI;
    if eye.w > 0.0 {
        let rel = eye.xyz - centre;
        towards = rel - axis * dot(rel, axis);
        half = acos(clamp(r / max(length(towards), 1e-20), 0.0, 1.0));
    }
    s.visible = clip_arc(vec2<f32>(0.0, s.arc.span), angle_in(s.arc, towards).x, half);
    s.outline = select(0u, 1u, s.visible.x > 1e-5) | select(0u, 2u, s.visible.y < s.arc.span - 1e-5);
    s.across = normalize(cross(s.to_viewer, axis));
    let normal_x = s.arc.ex * cos(s.visible.x) + s.arc.ey * sin(s.visible.x);
    let normal_y = s.arc.ex * cos(s.visible.y) + s.arc.ey * sin(s.visible.y);
    s.offsets = vec2<f32>(
        across_of(mvp, ends, centre + r * normal_x),
        across_of(mvp, ends, centre + r * normal_y),
    );
    s.shape = vec2<f32>(dot(s.across, normal_x), dot(s.across, normal_y));
    return s;
}

// Whether the section shows any strip: a visible part that is not seen edge-on.
fn section_shows(s: Section) -> bool {
    return s.visible.x < s.visible.y && abs(s.offsets.y - s.offsets.x) > 1e-4
        && abs(s.shape.y - s.shape.x) > 1e-7;
}

// The angle on the visible arc whose point lies `offset` pixels across (inverse of the section's
// offsets).
fn section_angle(s: Section, offset: f32) -> f32 {
    let lin = s.shape.x + (offset - s.offsets.x) * (s.shape.y - s.shape.x) / (s.offsets.y - s.offsets.x);
    let p = angle_in(s.arc, s.across);
    let c = clamp(lin / max(p.y, 1e-6), -1.0, 1.0);
    let a = p.x + acos(c);
    let b = p.x - acos(c);
    // One of the two solutions (mod 2π) lies on the visible arc.
    let candidates = array<f32, 4>(a, b, a - 2.0 * PI, b + 2.0 * PI);
    var best = candidates[0];
    var best_miss = 1e9;
    for (var k = 0u; k < 4u; k += 1u) {
        let miss = max(s.visible.x - candidates[k], 0.0) + max(candidates[k] - s.visible.y, 0.0);
        if miss < best_miss {
            best_miss = miss;
            best = candidates[k];
        }
    }
    return clamp(best, s.visible.x, s.visible.y);
}

// The shares of the pixel `x` pixels across the sharp edge that the strip covers (x) and that lie
// beyond the rounded outline (y): what the sharp mesh covers there and the rounded solid does not.
fn section_shares(s: Section, x: f32) -> vec2<f32> {
    var shares = vec2<f32>(0.0);
    if !section_shows(s) {
        return shares;
    }
    let lo = min(s.offsets.x, s.offsets.y);
    let hi = max(s.offsets.x, s.offsets.y);
    shares.x = max(min(x + 0.5, hi) - max(x - 0.5, lo), 0.0);
    if (s.outline & 1u) != 0u {
        shares.y = max(shares.y, clamp(sign(s.offsets.x - s.offsets.y) * (x - s.offsets.x) + 0.5, 0.0, 1.0));
    }
    if (s.outline & 2u) != 0u {
        shares.y = max(shares.y, clamp(sign(s.offsets.y - s.offsets.x) * (x - s.offsets.y) + 0.5, 0.0, 1.0));
    }
    return shares;
}

// The depth where the plane through `p` spanned by `u` and `w` covers `pixel` (a plane's depth is
// affine on screen), and how much it changes from one pixel to the next (x + y).
fn plane_depth(mvp: mat4x4<f32>, p: vec3<f32>, u: vec3<f32>, w: vec3<f32>, pixel: vec2<f32>) -> vec2<f32> {
    let c0 = mvp * vec4<f32>(p, 1.0);
    let c1 = mvp * vec4<f32>(p + u, 1.0);
    let c2 = mvp * vec4<f32>(p + w, 1.0);
    let s0 = to_pixels(c0);
    let e1 = to_pixels(c1) - s0;
    let e2 = to_pixels(c2) - s0;
    let z0 = c0.z / c0.w;
    let dz1 = c1.z / c1.w - z0;
    let dz2 = c2.z / c2.w - z0;
    let det = cross2(e1, e2);
    if abs(det) < 1e-12 {
        return vec2<f32>(z0, 1.0);
    }
    let d = pixel - s0;
    let depth = z0 + (cross2(d, e2) * dz1 + cross2(e1, d) * dz2) / det;
    let gx = (dz1 * e2.y - dz2 * e1.y) / det;
    let gy = (dz2 * e1.x - dz1 * e2.x) / det;
    return vec2<f32>(depth, abs(gx) + abs(gy));
}

// The face of the section on the pixel's side of the sharp edge `x` pixels across (the one that looks
// at the camera on a silhouette): its normal and the offset from the edge, in its plane, to where the
// strip meets it.
fn section_face(record: ChamferRecord, s: Section, x: f32) -> array<vec3<f32>, 2> {
    let n1 = record.n1.xyz;
    let n2 = record.n2.xyz;
    let r = record.n1.w;
    // visible.x's end is where n1's face begins, unless it is the outline; visible.y's is n2's.
    var second = (s.outline & 1u) != 0u;
    if s.outline == 0u {
        second = sign(x) != sign(s.offsets.x);
    }
    let normal = select(n1, n2, second);
    let centre = s.point - r * (n1 + n2) / (1.0 + dot(n1, n2));
    return array<vec3<f32>, 2>(normal, centre + r * normal - s.point);
}

// The depth a strip's pixel is drawn at: the sharp face's under it (the rounded surface lies inside
// the solid, behind it), brought forward by the edges' bias, so it wins against its own faces and
// loses against anything in front of them.
fn strip_depth(record: ChamferRecord, mvp: mat4x4<f32>, s: Section, pixel: vec2<f32>, x: f32) -> f32 {
    let face = section_face(record, s, x);
    let depth = plane_depth(mvp, s.point, record.end1.xyz - record.end0.xyz, face[1], pixel);
    let w = (mvp * vec4<f32>(s.point, 1.0)).w;
    return biased_depth_by(from_pixels(pixel, depth.x, w), frame.bias_px);
}
