// The hybrid shader for edge detection and ambient shading (seed 004, Tsivilskiy, Gaisin and
// Kugurakova): one full-screen pass over the depth alone, no normal buffer and no noise texture.
// For each pixel, the four neighbours r pixels away (§3.3, eq. 4) give four tangents; their dot
// product with the screen's normal (0, 0, 1) is the depth difference, here of view depths divided by
// `range` (§3.4's AGAL parameter), since we reconstruct positions from our depth buffer (the paper
// packed depth into RGB only because Flash could not read a depth buffer). The depth map is read as
// a height field of nearness, as the paper's figures draw it: a neighbour nearer than the pixel
// counts positive, so pixels in hollows (inside corners) and just outside silhouettes darken, while
// convex edges and open surfaces stay light. Each is
// bleached (eq. 5, dp (2 - dp / L)), shifted by the brightness and turned into a shade 1 / (1 + t²)
// (Appendix A); the average of four, raised to the contrast, multiplies the scene colour (§3.1).
// The same code gives edges, ambient shading or both: only the parameters differ (§4).

struct HybridParams {
    // r, the neighbours' distance.
    step_px: f32,
    // L, the bleach factor of eq. 5.
    bleach: f32,
    contrast: f32,
    brightness: f32,
    // What a depth difference is divided by, view units.
    range: f32,
    // 1: only over the object (its mask's Laplacian outline and its pixels, §3.1).
    object_only: u32,
}

@group(0) @binding(15) var<uniform> params: HybridParams;

@group(0) @binding(17) var mask: texture_2d<f32>;

fn shade(z0: f32, p: vec2<i32>) -> f32 {
    let bleach = max(params.bleach, 1e-4);
    var dp = (z0 - view_depth(p)) / max(params.range, 1e-12);
    dp = dp * (2.0 - dp / bleach);
    let t = 0.5 * max(dp + params.brightness, 0.0);
    return 1.0 / (1.0 + t * t);
}

fn masked(p: vec2<i32>) -> f32 {
    return textureLoad(mask, clamp_pixel(p), 0).r;
}

@fragment
fn hybrid_fragment(v: PostVarying) -> @location(0) vec4<f32> {
    let p = vec2<i32>(v.position.xy);
    let r = i32(max(round(params.step_px), 1.0));
    let z0 = view_depth(p);
    var o = shade(z0, p + vec2<i32>(r, 0)) + shade(z0, p - vec2<i32>(r, 0))
        + shade(z0, p + vec2<i32>(0, r)) + shade(z0, p - vec2<i32>(0, r));
    o = pow(o / 4.0, max(params.contrast, 0.0));
    if params.object_only == 1u {
        // §3.1: the object alone, white on black; the Laplacian of that picture is its outline.
        let m = masked(p);
        let laplacian = masked(p + vec2<i32>(0, r)) + masked(p - vec2<i32>(0, r))
            + masked(p + vec2<i32>(r, 0)) + masked(p - vec2<i32>(r, 0)) - 4.0 * m;
        o = mix(1.0, o, m) * (1.0 - clamp(abs(laplacian), 0.0, 1.0));
    }
    // Multiplied over the scene by the blend state (dst × src).
    return vec4<f32>(vec3<f32>(o), 1.0);
}

struct MaskVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) model_position: vec3<f32>,
}

// The object of interest filled white (§3.1's first steps), into our own mask texture.
@vertex
fn mask_vertex(@location(0) position: vec3<f32>) -> MaskVarying {
    return MaskVarying(post.mvp * vec4<f32>(position, 1.0), position);
}

@fragment
fn mask_fragment(v: MaskVarying) -> @location(0) vec4<f32> {
    if section_cuts(v.model_position) {
        discard;
    }
    return vec4<f32>(1.0);
}
