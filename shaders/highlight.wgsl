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

// Per drawn slot of a highlighted edge, in model space.
struct ChamferRecord {
    // Face normals (unit); `n1.w` is the radius in pixels at the edge's middle.
    n1: vec4<f32>,
    // `n2.w`: the sharp edge's offset from the strip, P·(N1 + N2) / (1 + N1·N2).
    n2: vec4<f32>,
    // The screen's across direction P (unit, perpendicular to the edge and the view); `w`: the
    // distance from the eye to the edge's middle.
    across: vec4<f32>,
    // The edge's middle; `w`: the radius in mesh units.
    middle: vec4<f32>,
    // Towards the viewer from the middle, unit: the draw pass cannot know the instance's eye.
    viewer: vec4<f32>,
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

// [a, b] clipped to the half-turn lobe centred on c; empty when x >= y.
fn clip_lobe(range: vec2<f32>, c: f32) -> vec2<f32> {
    let centre = select(c, c + 2.0 * PI, c < -0.5 * PI);
    return vec2<f32>(max(range.x, centre - 0.5 * PI), min(range.y, centre + 0.5 * PI));
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

// The visible arc: where the strip's normal faces the viewer.
fn visible_range(arc: Arc, to_viewer: vec3<f32>) -> vec2<f32> {
    return clip_lobe(vec2<f32>(0.0, arc.span), angle_in(arc, to_viewer).x);
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

// Screen offset (pixels, along the quad's left normal) of the strip's point with normal angle θ.
fn strip_offset(record: ChamferRecord, arc: Arc, theta: f32) -> f32 {
    let normal = arc.ex * cos(theta) + arc.ey * sin(theta);
    return record.n1.w * (dot(record.across.xyz, normal) - record.n2.w);
}

// The angle on the visible arc whose point lies `offset` pixels across (inverse of strip_offset).
fn strip_angle(record: ChamferRecord, arc: Arc, visible: vec2<f32>, offset: f32) -> f32 {
    let p = angle_in(arc, record.across.xyz);
    let c = clamp((offset / record.n1.w + record.n2.w) / max(p.y, 1e-6), -1.0, 1.0);
    let a = p.x + acos(c);
    let b = p.x - acos(c);
    // One of the two solutions (mod 2π) lies on the visible arc.
    let candidates = array<f32, 4>(a, b, a - 2.0 * PI, b + 2.0 * PI);
    var best = candidates[0];
    var best_miss = 1e9;
    for (var k = 0u; k < 4u; k += 1u) {
        let miss = max(visible.x - candidates[k], 0.0) + max(candidates[k] - visible.y, 0.0);
        if miss < best_miss {
            best_miss = miss;
            best = candidates[k];
        }
    }
    return clamp(best, visible.x, visible.y);
}
