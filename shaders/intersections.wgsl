// The asset's intersection edges (baked, thesis §2.2: object-space methods cannot find them at run
// time), drawn like creases: view-independent, depth tested with the edges' bias, a screen-space quad
// per segment and a round disc at each end so the polylines' joints close. Instance = segment,
// vertices 0-5 its quad, 6-11 and 12-17 the discs at its ends. Compiled with HIDDEN (display.wgsl),
// the hidden part in the hidden style.

@group(0) @binding(10) var<storage, read> segments: array<f32>;

struct SegmentVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) color: vec4<f32>,
    // The disc's centre in pixels and radius (z); radius 0 for the quad.
    @location(1) @interpolate(flat) disc: vec3<f32>,
    // The segment's start in pixels and its direction (the pattern runs from there).
    @location(2) @interpolate(flat) start: vec4<f32>,
    // How far the line reaches on each side here, and how far into the distance fade.
    @location(3) @interpolate(linear) reach_fade: vec3<f32>,
}

fn segment_end(s: u32, k: u32) -> vec3<f32> {
    let i = 6u * s + 3u * k;
    return vec3<f32>(segments[i], segments[i + 1u], segments[i + 2u]);
}

@vertex
fn segment_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) s: u32) -> SegmentVarying {
    var out: SegmentVarying;
    out.position = NOWHERE;
    if (frame.classes & INTERSECTION) == 0u {
        return out;
    }
    let p0 = segment_end(s, 0u);
    let p1 = segment_end(s, 1u);
    let span = section_span(p0, p1, vec2<f32>(0.0, 1.0));
    if !(span.x < span.y) {
        return out;
    }
    let c0 = frame.mvp * vec4<f32>(span_point(p0, p1, span.x), 1.0);
    let c1 = frame.mvp * vec4<f32>(span_point(p0, p1, span.y), 1.0);
    // Segments are short: one that reaches behind the camera is not drawn.
    if in_front(c0) < 0.0 || in_front(c1) < 0.0 || c0.w <= 0.0 || c1.w <= 0.0 {
        return out;
    }
    let s0 = to_pixels(c0);
    let s1 = to_pixels(c1);
    let along = s1 - s0;
    let direction = select(vec2<f32>(1.0, 0.0), normalize(along), dot(along, along) > 1e-8);
    let n = perp(direction);
    let part = i / 6u;
    let corner = i % 6u;
    out.color = frame.colors[COLOR_INTERSECTION];
    out.start = vec4<f32>(s0, direction);
    if part == 0u {
        // (end, side) = (0,-) (1,-) (1,+) / (0,-) (1,+) (0,+).
        let k = (0x16u >> corner) & 1u;
        let side = select(-1.0, 1.0, ((0x34u >> corner) & 1u) == 1u);
        let c = select(c0, c1, k == 1u);
        let p = select(s0, s1, k == 1u) + n * side * half_width(c.w);
        out.position = from_pixels(p, biased_depth(c), c.w);
        out.disc = vec3<f32>(0.0);
        out.reach_fade = vec3<f32>(vec2<f32>(half_width(c.w)), fade_at(c));
        return out;
    }
    let c = select(c0, c1, part == 2u);
    let centre = select(s0, s1, part == 2u);
    let r = half_width(c.w);
    let square = vec2<f32>(
        select(-1.0, 1.0, ((0x16u >> corner) & 1u) == 1u),
        select(-1.0, 1.0, ((0x34u >> corner) & 1u) == 1u),
    );
    out.position = from_pixels(centre + square * (r + 1.0), biased_depth(c), c.w);
    out.disc = vec3<f32>(centre, r);
    out.reach_fade = vec3<f32>(vec2<f32>(r), fade_at(c));
    return out;
}

@fragment
fn segment_fragment(v: SegmentVarying) -> @location(0) vec4<f32> {
    let q = v.position.xy - v.start.xy;
    let fade = v.reach_fade.z;
    if v.disc.z > 0.0 {
        let r = display_reach(vec2<f32>(v.disc.z), fade).x;
        if distance(v.position.xy, v.disc.xy) > r {
            discard;
        }
    } else if display_trims(dot(q, perp(v.start.zw)), v.reach_fade.xy, fade) {
        discard;
    }
    return display_color(v.color, dot(q, v.start.zw), fade);
}
