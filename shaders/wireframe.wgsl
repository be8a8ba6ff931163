// The barycentric thick wireframe (seed 001, final version): every triangle edge at a constant width
// in pixels whatever the triangle's size and shape. The geometry shader of the article becomes the
// vertex shader pulling its triangle's three corners: each corner gets edge coordinates from the
// triangle's screen-space side lengths and angles, d / (side · sin angle) (the "balance edge lengths"
// and "balance edge angles" steps), interpolated linearly in screen space; a pixel is on the edge
// opposite corner k where coordinate k exceeds 1, that is within d pixels of it. d is half the line
// width (each triangle draws its half of a shared edge), scaled with depth if the style asks.

struct WireParams {
    // 1: the seed's first, naive attempt (unit barycentrics, edge where a coordinate is below
    // `naive_threshold`: its width follows the triangle's size; kept as the comparison the seed shows).
    naive: u32,
    // 1: anti-aliased inner border.
    smooth_border: u32,
    // 1: only the asset's feature edges (not the diagonals of flat or smooth regions).
    feature_only: u32,
    naive_threshold: f32,
}

@group(0) @binding(15) var<uniform> params: WireParams;

// Per triangle, bit k: the edge from corner k to k + 1 is a feature edge.
@group(0) @binding(14) var<storage, read> triangle_edges: array<u32>;

struct WireVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(linear) coords: vec3<f32>,
    // Which coordinates mark a drawn edge (bit k: the edge opposite corner k).
    @location(1) @interpolate(flat) shown: u32,
    // The model-space point, for the section planes.
    @location(2) point: vec3<f32>,
}

fn balanced(d: f32, side: f32, sine: f32) -> f32 {
    return 1.0 / (1.0 - min(0.99999, d / max(side * sine, 1e-6)));
}

@vertex
fn wire_vertex(@builtin(vertex_index) k: u32, @builtin(instance_index) t: u32) -> WireVarying {
    var out: WireVarying;
    let p = triangle(t);
    var c: array<vec4<f32>, 3>;
    var s: array<vec2<f32>, 3>;
    for (var i = 0u; i < 3u; i += 1u) {
        c[i] = frame.mvp * vec4<f32>(p[i], 1.0);
        if c[i].w <= 0.0 || in_front(c[i]) < 0.0 {
            out.position = NOWHERE;
            return out;
        }
        s[i] = to_pixels(c[i]);
    }
    var shown = 7u;
    if params.feature_only == 1u {
        // Mask bit j is the edge from corner j to j + 1, opposite corner j + 2.
        let mask = triangle_edges[t];
        shown = ((mask & 1u) << 2u) | ((mask & 2u) >> 1u) | ((mask & 4u) >> 1u);
    }
    out.shown = shown;
    let b = s[(k + 1u) % 3u] - s[k];
    let a = s[(k + 2u) % 3u] - s[k];
    let lb = length(b);
    let la = length(a);
    if params.naive == 1u {
        out.coords = vec3<f32>(select(0.0, 1.0, k == 0u), select(0.0, 1.0, k == 1u), select(0.0, 1.0, k == 2u));
    } else {
        // The corner's angle, from the sides that meet there.
        let cosine = clamp(dot(a, b) / max(la * lb, 1e-12), -1.0, 1.0);
        let sine = sqrt(1.0 - cosine * cosine);
        let d = half_width(c[k].w);
        var coords = vec3<f32>(0.0);
        // Coordinate j (the edge opposite corner j) reaches 1 on the side from k to j at d / sin
        // from k, which is d from that edge.
        coords[(k + 1u) % 3u] = balanced(d, lb, sine);
        coords[(k + 2u) % 3u] = balanced(d, la, sine);
        out.coords = coords;
    }
    out.position = vec4<f32>(c[k].xy, biased_depth(c[k]) * c[k].w, c[k].w);
    out.point = p[k];
    return out;
}

@fragment
fn wire_fragment(v: WireVarying) -> @location(0) vec4<f32> {
    if section_cuts(v.point) {
        discard;
    }
    var coverage = 0.0;
    // How fast each coordinate changes, taken before any branch: derivatives need uniform control
    // flow (WebGPU's compilers refuse them inside the loop's `continue`).
    let ramp = max(fwidth(v.coords), vec3<f32>(1e-6));
    for (var k = 0u; k < 3u; k += 1u) {
        if ((v.shown >> k) & 1u) == 0u {
            continue;
        }
        let e = v.coords[k];
        var on = 0.0;
        if params.naive == 1u {
            on = select(0.0, 1.0, e < params.naive_threshold);
        } else if params.smooth_border == 1u {
            // A one-pixel ramp at the band's inner border, from how fast the coordinate changes.
            on = clamp((e - 1.0) / ramp[k] + 0.5, 0.0, 1.0);
        } else {
            on = select(0.0, 1.0, e > 1.0);
        }
        coverage = max(coverage, on);
    }
    if coverage <= 0.0 {
        discard;
    }
    let color = frame.colors[COLOR_CONTOUR];
    return vec4<f32>(color.rgb, color.a * coverage);
}
