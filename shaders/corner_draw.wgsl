// Draws the rounded corners (corners.wgsl) of one instance, one square per corner around its vertex:
// each pixel the corner owns traces the rounded solid there (the sphere patch and, up to the pixels its
// strips hand over, their cylinders) at up to 4 × 4 sub-samples, shades every hit normal as the strips
// and the mesh are shaded, and blends the mean over the mesh with the strips' weight (§3.2): K / d
// times the share of sub-samples that hit a rounded part (the flat faces are the mesh's own).

@group(0) @binding(22) var<storage, read> cos_power: array<f32>;
@group(0) @binding(23) var<uniform> lighting: Lighting;
@group(0) @binding(30) var<storage, read> environment: array<vec4<f32>>;

struct CornerVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) corner: u32,
    // What every pixel of the corner shares, worked out once here: the vertex on screen (xy) and the
    // sub-samples a side (z).
    @location(1) @interpolate(flat) vertex_px: vec3<f32>,
    // The model-space steps of one pixel right and down at the vertex (pixel_steps).
    @location(2) @interpolate(flat) step_x: vec3<f32>,
    @location(3) @interpolate(flat) step_y: vec3<f32>,
    // Per plane pair k, its strip's hand-over line: the edge's direction on screen (xy) and how far along
    // it the corner owns the cylinder (z); z < 0: the whole cylinder (no strip), w = 0: none of it.
    @location(4) @interpolate(flat) line0: vec4<f32>,
    @location(5) @interpolate(flat) line1: vec4<f32>,
    @location(6) @interpolate(flat) line2: vec4<f32>,
}

@vertex
fn corner_vertex(
    @builtin(vertex_index) vertex: u32,
    @builtin(instance_index) k: u32,
) -> CornerVarying {
    var v: CornerVarying;
    v.corner = k;
    let c = corner_at(k);
    if lighting.corners == 0u || !corner_drawn(c) {
        v.position = NOWHERE;
        return v;
    }
    let mvp = view_mvp();
    let clip = mvp * vec4<f32>(c.vertex.xyz, 1.0);
    let vertex_px = to_pixels(clip);
    let steps = pixel_steps(c.vertex.xyz);
    let per_pixel = pixel_size(steps);
    var lines: array<vec4<f32>, 3>;
    for (var pair = 0u; pair < 3u; pair += 1u) {
        lines[pair] = vec4<f32>(0.0, 0.0, -1.0, 1.0);
        let far = c.far[pair];
        if far.w > 0.0 {
            // A strip whose far end is behind the camera hands nothing over (hand_over).
            let far_clip = mvp * vec4<f32>(far.xyz, 1.0);
            let along = normalize(to_pixels(far_clip) - vertex_px);
            lines[pair] = vec4<f32>(along, hand_over(c, far.xyz), select(0.0, 1.0, far_clip.w > 0.0));
        }
    }
    // Sub-samples a side: enough that neighbouring ones' normals differ by at most half the lobe's
    // width (the normal turns by a pixel over r across the pixel), so a wide corner is not shaded 16
    // times a pixel where its light hardly changes.
    var lobe = inverseSqrt(lighting.material.z + 1.0);
    if (lighting.pbr & SHADE_PBR) != 0u {
        lobe = max(lighting.material.y, 0.05);
    }
    let side = clamp(ceil(2.0 * per_pixel / c.sphere.w / lobe), 1.0, f32(SUBSAMPLES));
    v.vertex_px = vec3<f32>(vertex_px, side);
    v.step_x = steps[0];
    v.step_y = steps[1];
    v.line0 = lines[0];
    v.line1 = lines[1];
    v.line2 = lines[2];
    // The hand-over reach along an edge and a rounded edge's reach across it (at most 3 r from the
    // sharp edge; the sphere lies within).
    let reach = c.normals[0].w;
    let extent = sqrt(reach * reach + 9.0 * c.sphere.w * c.sphere.w) / per_pixel + 1.0;
    let corner = vec2<f32>(
        select(-1.0, 1.0, ((0x16u >> vertex) & 1u) == 1u),
        select(-1.0, 1.0, ((0x34u >> vertex) & 1u) == 1u),
    );
    let depth = biased_depth_by(clip, frame.bias_px + extent);
    v.position = from_pixels(vertex_px + corner * extent, depth, clip.w);
    return v;
}

// Whether unit `n` lies in the arc from `a` to `b` (less than a half turn).
fn in_arc(n: vec3<f32>, a: vec3<f32>, b: vec3<f32>) -> bool {
    let axis = cross(a, b);
    return dot(cross(a, n), axis) >= 0.0 && dot(cross(n, b), axis) >= 0.0;
}

// Whether unit `n` lies in the cone spanned by the corner's three normals.
fn in_cone(c: Corner, n: vec3<f32>) -> bool {
    for (var k = 0u; k < 3u; k += 1u) {
        let m = cross(c.normals[(k + 1u) % 3u].xyz, c.normals[(k + 2u) % 3u].xyz);
        if dot(n, m) * dot(c.normals[k].xyz, m) < 0.0 {
            return false;
        }
    }
    return true;
}

struct Hit {
    t: f32,
    normal: vec3<f32>,
}

// The first point where the ray (`origin`, unit `dir`) enters the corner's rounded parts: the sphere
// where its normal is in the normals' cone, and cylinder k (planes k, k + 1) between its two normals,
// from the centre up to the followed length, where `owned[k]`. t < 0: none. `anywhere`: the whole
// sphere and cylinders, whatever the normal (a bound on where the rounded parts can be).
fn trace(c: Corner, origin: vec3<f32>, dir: vec3<f32>, owned: vec3<bool>, anywhere: bool) -> Hit {
    var best = Hit(-1.0, vec3<f32>(0.0));
    let center = c.sphere.xyz;
    let r = c.sphere.w;
    let oc = origin - center;
    let b = dot(oc, dir);
    let disc = b * b - (dot(oc, oc) - r * r);
    if disc >= 0.0 {
        let t = -b - sqrt(disc);
        let n = (oc + t * dir) / r;
        if t >= 0.0 && (anywhere || in_cone(c, n)) {
            best = Hit(t, n);
        }
    }
    for (var k = 0u; k < 3u; k += 1u) {
        if !owned[k] {
            continue;
        }
        let na = c.normals[k].xyz;
        let nb = c.normals[(k + 1u) % 3u].xyz;
        var axis = normalize(cross(na, nb));
        // The edge runs from the centre away from the third plane.
        axis = select(axis, -axis, dot(axis, c.normals[(k + 2u) % 3u].xyz) > 0.0);
        let oc_perp = oc - dot(oc, axis) * axis;
        let d_perp = dir - dot(dir, axis) * axis;
        let qa = dot(d_perp, d_perp);
        let qb = dot(oc_perp, d_perp);
        let qc = dot(oc_perp, oc_perp) - r * r;
        let q = qb * qb - qa * qc;
        if qa < 1e-12 || q < 0.0 {
            continue;
        }
        let t = (-qb - sqrt(q)) / qa;
        let p = oc + t * dir;
        let along = dot(p, axis);
        let n = (p - along * axis) / r;
        if t >= 0.0 && along >= 0.0 && along <= c.vertex.w && (anywhere || in_arc(n, na, nb)) && (best.t < 0.0 || t < best.t) {
            best = Hit(t, n);
        }
    }
    return best;
}

// What a point of the rounded surface with normal `n` at `p` sends to the viewer: the strips' model
// (highlight.wgsl) at one normal instead of integrated over a slice.
fn surface_radiance(n: vec3<f32>, p: vec3<f32>, to_viewer: vec3<f32>) -> vec3<f32> {
    let light = view_light();
    let to_light = towards_light(light, p);
    let radiance = light_radiance(light, p);
    if (lighting.pbr & SHADE_PBR) != 0u {
        let m = Pbr(lighting.base.rgb, lighting.material.x, lighting.material.y);
        var lit = radiance * pbr_radiance(m, n, to_light, to_viewer)
            + lighting.material.w * uniform_environment(m, dot(n, to_viewer));
        if (lighting.pbr & SHADE_ENVIRONMENT) != 0u {
            lit += environment_light(m, n, to_viewer);
        }
        return lit;
    }
    let ambient = lighting.material.x * lighting.material.w;
    let diffuse = lighting.material.x * (1.0 - lighting.material.w) * max(dot(n, to_light), 0.0);
    let specular = lighting.material.y * pow(max(dot(n, half_vector(to_light, to_viewer)), 0.0), lighting.material.z);
    return radiance * (diffuse + specular) + vec3<f32>(ambient);
}

const SUBSAMPLES: u32 = 4u;

// The ray (origin, unit direction) through the screen point `q` (pixels): through the plane of constant
// depth at the vertex (where `steps` are the model-space pixel steps), starting `back` before it.
fn pixel_ray(vertex: vec3<f32>, vertex_px: vec2<f32>, steps: array<vec3<f32>, 2>, eye: vec4<f32>, back: f32, q: vec2<f32>) -> array<vec3<f32>, 2> {
    let d = q - vertex_px;
    let on_plane = vertex + steps[0] * d.x + steps[1] * d.y;
    let dir = select(-normalize(eye.xyz), normalize(on_plane - eye.xyz), eye.w > 0.0);
    return array<vec3<f32>, 2>(on_plane - back * dir, dir);
}

@fragment
fn corner_fragment(v: CornerVarying) -> @location(0) vec4<f32> {
    let c = corner_at(v.corner);
    let vertex = c.vertex.xyz;
    let vertex_px = v.vertex_px.xy;
    let pixel = v.position.xy;
    // Cylinder k is this corner's where the pixel is short of its strip's hand-over.
    let lines = array<vec4<f32>, 3>(v.line0, v.line1, v.line2);
    var owned = vec3<bool>(true);
    for (var k = 0u; k < 3u; k += 1u) {
        let line = lines[k];
        owned[k] = line.w > 0.0 && (line.z < 0.0 || dot(pixel - vertex_px, line.xy) < line.z);
    }
    let steps = array<vec3<f32>, 2>(v.step_x, v.step_y);
    let eye = view_eye();
    let back = 4.0 * (c.normals[0].w + c.sphere.w);
    // Most of the square sees flat faces only: a pixel whose centre's ray misses the sphere and the
    // owned cylinders, whole and grown by a pixel and a half, is left to the mesh without tracing its
    // sub-samples.
    var grown = c;
    grown.sphere.w += 1.5 * pixel_size(steps);
    let centre = pixel_ray(vertex, vertex_px, steps, eye, back, pixel);
    if trace(grown, centre[0], centre[1], owned, true).t < 0.0 {
        discard;
    }
    let side = u32(v.vertex_px.z);
    var sum = vec3<f32>(0.0);
    var hits = 0u;
    for (var i = 0u; i < side * side; i += 1u) {
        let offset = (vec2<f32>(f32(i % side), f32(i / side)) + 0.5) / f32(side) - 0.5;
        let sample = pixel_ray(vertex, vertex_px, steps, eye, back, pixel + offset);
        let origin = sample[0];
        let dir = sample[1];
        let hit = trace(c, origin, dir, owned, false);
        if hit.t >= 0.0 {
            let p = origin + hit.t * dir;
            sum += surface_radiance(hit.normal, p, to_viewer_at(p));
            hits += 1u;
        }
    }
    if hits == 0u {
        discard;
    }
    let distance = select(0.0, length(eye.xyz - vertex), eye.w > 0.0);
    let k_over_d = select(1.0, lighting.base.w / distance, distance > 0.0);
    let coverage = f32(hits) / f32(side * side);
    return vec4<f32>(sum / f32(hits), clamp(k_over_d * coverage, 0.0, 1.0));
}
