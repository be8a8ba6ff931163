// Image-space edges (thesis §5): a gradient operator over the depth buffer and over a normal buffer
// (§5.3), thresholded (§5.1). One shader, the operator a parameter: Sobel, Prewitt, Scharr (3×3,
// §5.1–5.2) or Roberts' cross (2×2). Depth gradients are taken of the view depth and divided by the
// centre's depth, so one threshold serves near and far; normal gradients of the model-space normals
// our own normal pass writes. The kernel's taps are `step` pixels apart: half the line width, and
// scaled with depth if the style asks (nearer is thicker; the thesis' §5.5 notes thickness is
// otherwise fixed by the resolution).

struct ImageParams {
    // The operator's kernel: 0 Sobel, 1 Prewitt, 2 Scharr, 3 Roberts.
    kernel: u32,
    // Thresholds of the depth and normal gradients (0: that buffer is not used).
    depth_threshold: f32,
    normal_threshold: f32,
    // The kernel's taps are this many pixels apart...
    step_px: f32,
    // ...scaled with depth if 1.
    depth_scaled: u32,
}

@group(0) @binding(15) var<uniform> params: ImageParams;

@group(0) @binding(17) var normals: texture_2d<f32>;

fn normal_at(p: vec2<i32>) -> vec3<f32> {
    return textureLoad(normals, clamp_pixel(p), 0).xyz;
}

struct Gradients {
    depth: f32,
    normal: f32,
}

// The 3×3 kernel's weights: the column (and row) weights (a, b, a) of Gx = [-a 0 a; -b 0 b; -a 0 a].
fn weights() -> vec2<f32> {
    switch params.kernel {
        case 1u: { return vec2<f32>(1.0, 1.0); }
        case 2u: { return vec2<f32>(3.0, 10.0); }
        default: { return vec2<f32>(1.0, 2.0); }
    }
}

fn gradients(p: vec2<i32>, s: i32) -> Gradients {
    var gx_d = 0.0;
    var gy_d = 0.0;
    var gx_n = vec3<f32>(0.0);
    var gy_n = vec3<f32>(0.0);
    if params.kernel == 3u {
        // Roberts' cross: [x A; B C], Gx = x - C, Gy = A - B.
        let x = p;
        let a = p + vec2<i32>(s, 0);
        let b = p + vec2<i32>(0, s);
        let c = p + vec2<i32>(s, s);
        gx_d = view_depth(x) - view_depth(c);
        gy_d = view_depth(a) - view_depth(b);
        gx_n = normal_at(x) - normal_at(c);
        gy_n = normal_at(a) - normal_at(b);
    } else {
        let w = weights();
        for (var j = -1; j <= 1; j += 1) {
            for (var i = -1; i <= 1; i += 1) {
                if i == 0 && j == 0 {
                    continue;
                }
                let q = p + vec2<i32>(i, j) * s;
                // Gx weights: sign of i times (a at the corners, b in the middle row); Gy likewise.
                let wx = f32(i) * select(w.x, w.y, j == 0);
                // Rows top to bottom: Gy = [a b a; 0 0 0; -a -b -a].
                let wy = -f32(j) * select(w.x, w.y, i == 0);
                let z = view_depth(q);
                let n = normal_at(q);
                gx_d += wx * z;
                gy_d += wy * z;
                gx_n += wx * n;
                gy_n += wy * n;
            }
        }
    }
    // Divided by the kernel's positive weights, so a step of size h reads h for every operator.
    var norm = 1.0;
    if params.kernel != 3u {
        let w = weights();
        norm = 2.0 * w.x + w.y;
    }
    return Gradients(
        sqrt(gx_d * gx_d + gy_d * gy_d) / norm,
        sqrt(dot(gx_n, gx_n) + dot(gy_n, gy_n)) / norm,
    );
}

@fragment
fn image_fragment(v: PostVarying) -> @location(0) vec4<f32> {
    let p = vec2<i32>(v.position.xy);
    let z0 = view_depth(p);
    var step = max(params.step_px, 1.0);
    if params.depth_scaled == 1u && post.depth_ref > 0.0 {
        step = max(step * post.depth_ref / max(z0, 1e-6), 1.0);
    }
    let g = gradients(p, i32(round(step)));
    var edge = 0.0;
    if params.depth_threshold > 0.0 {
        edge = max(edge, smoothstep(0.8, 1.2, g.depth / max(abs(z0), 1e-6) / params.depth_threshold));
    }
    if params.normal_threshold > 0.0 {
        edge = max(edge, smoothstep(0.8, 1.2, g.normal / params.normal_threshold));
    }
    if edge <= 0.0 {
        discard;
    }
    return vec4<f32>(post.color.rgb, post.color.a * edge);
}

struct NormalVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) model_position: vec3<f32>,
}

// The normal buffer (§5.3): the asset's model-space normals, into our own texture.
@vertex
fn normal_vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> NormalVarying {
    return NormalVarying(post.mvp * vec4<f32>(position, 1.0), normal, position);
}

@fragment
fn normal_fragment(v: NormalVarying) -> @location(0) vec4<f32> {
    if section_cuts(v.model_position) {
        discard;
    }
    return vec4<f32>(normalize(v.normal), 1.0);
}
