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
    let square = corner_square(c, vertex, 0.0);
    let mvp = view_mvp();
    let vertex_px = square.vertex_px;
    let steps = square.steps;
    let per_pixel = pixel_size(steps);
    let lines = square.lines;
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
    v.position = square.position;
    return v;
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

struct CornerPixel {
    @location(0) color: vec4<f32>,
    // At the sharp corner under the pixel (corner_depth), not at the square's.
    @builtin(frag_depth) depth: f32,
}

@fragment
fn corner_fragment(v: CornerVarying) -> CornerPixel {
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
    let back = ray_start(c);
    // Most of the square sees flat faces only: a pixel whose centre's ray misses the sphere and the
    // owned cylinders, whole and grown by a pixel and a half, is left to the mesh without tracing its
    // sub-samples.
    var grown = c;
    grown.sphere.w += 1.5 * pixel_size(steps);
    let centre = pixel_ray(vertex, vertex_px, steps, eye, back, pixel);
    if enter(grown, centre[0], centre[1], owned, true).t < 0.0 {
        discard;
    }
    let side = u32(v.vertex_px.z);
    // Samples beyond the rounded outline count only where the corner's solid is the mesh's.
    let local = local_at(c, lines, vertex_px, pixel, pixel_size(steps));
    var sum = vec3<f32>(0.0);
    var hits = 0u;
    var missed = 0u;
    for (var i = 0u; i < side * side; i += 1u) {
        let offset = (vec2<f32>(f32(i % side), f32(i / side)) + 0.5) / f32(side) - 0.5;
        let sample = pixel_ray(vertex, vertex_px, steps, eye, back, pixel + offset);
        let origin = sample[0];
        let dir = sample[1];
        let hit = enter(c, origin, dir, owned, false);
        if hit.part == ROUNDED {
            let p = origin + hit.t * dir;
            sum += surface_radiance(hit.normal, p, to_viewer_at(p));
            hits += 1u;
        } else if hit.part == MISSED && local {
            missed += 1u;
        }
    }
    if hits == 0u {
        discard;
    }
    // Blended over the mesh by the share it covers of what the sharp mesh shows there: the samples
    // beyond the rounded outline are the outline pass's to trim (outline.wgsl).
    let distance = select(0.0, length(eye.xyz - vertex), eye.w > 0.0);
    let k_over_d = select(1.0, lighting.base.w / distance, lighting.base.w > 0.0 && distance > 0.0);
    let coverage = f32(hits) / f32(side * side - missed);
    let color = vec4<f32>(sum / f32(hits), clamp(k_over_d * coverage, 0.0, 1.0));
    return CornerPixel(color, corner_depth(c, centre[0], centre[1]));
}
