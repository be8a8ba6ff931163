// Display modes (issue 42, runtime/src/render/display.rs): how the hidden part of an edge and far
// edges look. A technique's hidden pipelines are its draw shaders compiled with HIDDEN = true and
// the depth test reversed; the pixel functions here then give the hidden style. Reads `frame`.

override HIDDEN: bool = false;

// How far into the fade a clip position is: 0 before its start, 1 at its end and beyond.
fn fade_at(c: vec4<f32>) -> f32 {
    let d = frame.display;
    if (d.flags & DISPLAY_FADE) == 0u || c.w <= 0.0 {
        return 0.0;
    }
    let x = select(c.w, c.z / c.w, (d.flags & DISPLAY_FADE_ORTHO) != 0u);
    return clamp((x - d.fade.x) / (d.fade.y - d.fade.x), 0.0, 1.0);
}

// True if the pattern draws the pixel `along` pixels from the line's start.
fn in_pattern(along: f32) -> bool {
    let d = frame.display;
    if (d.flags & DISPLAY_PIXELS) != 0u {
        let bit = u32(floor(along - 32.0 * floor(along / 32.0))) & 31u;
        return ((d.pixels >> bit) & 1u) == 1u;
    }
    let period = d.hidden.z;
    if period <= 0.0 {
        return true;
    }
    var t = along - period * floor(along / period);
    let count = u32(d.hidden.w);
    for (var k = 0u; k < count; k += 1u) {
        let length = d.dashes[k / 4u][k % 4u];
        if t < length {
            return (k & 1u) == 0u;
        }
        t -= length;
    }
    return true;
}

// The colour of a pixel of a line: `color` in the visible pass; the hidden colour and opacity in
// the hidden pass (discarded in the pattern's gaps); faded by `fade` (fade_at) in both.
fn display_color(color: vec4<f32>, along: f32, fade: f32) -> vec4<f32> {
    let d = frame.display;
    var c = color;
    if HIDDEN {
        if !in_pattern(along) {
            discard;
        }
        if (d.flags & DISPLAY_HIDDEN_COLOR) != 0u {
            c = vec4<f32>(d.hidden_color.rgb, c.a);
        }
        c.a *= d.hidden.x;
    }
    c.a *= mix(1.0, d.fade.z, fade);
    return c;
}

// How far a line reaches on each side of its centre line at this pixel (left, right), given its
// quad's reach: the quad's in the visible pass, the hidden width within it in the hidden pass (on
// both sides, or on the one side a half quad has), narrowed by the fade.
fn display_reach(quad: vec2<f32>, fade: f32) -> vec2<f32> {
    let d = frame.display;
    var reach = quad;
    if HIDDEN {
        let both = quad.x > 0.0 && quad.y > 0.0;
        let half = select(d.hidden.y, 0.5 * d.hidden.y, both);
        reach = min(quad, vec2<f32>(select(0.0, half, quad.x > 0.0), select(0.0, half, quad.y > 0.0)));
    }
    return reach * mix(1.0, d.fade.w, fade);
}

// True if the line's width (display_reach) leaves the pixel `across` pixels left of the centre
// line out. Nothing is trimmed in the visible pass without a fade (the quad is the line).
fn display_trims(across: f32, quad: vec2<f32>, fade: f32) -> bool {
    if !HIDDEN && fade <= 0.0 {
        return false;
    }
    let reach = display_reach(quad, fade);
    return across > reach.x || -across > reach.y;
}
