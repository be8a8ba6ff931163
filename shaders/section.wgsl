// Section planes (issue 43): what every pass that draws the model cuts away. A pass's host file
// defines `view_section(k)`, the instance's plane k in its model space (`ClipPlanes` in
// runtime/src/section.rs): `dot(plane, (p, 1)) >= 0` is cut, so a point on a plane is cut away as
// the drawings' exact cut has it, and unused rows (0, 0, 0, -1) cut nothing. Segments (edges) are
// clipped exactly where they are projected (`section_span`); surfaces discard cut fragments
// (`section_cuts`) or, where the device has clip distances, clip there.

// True if model-space point `p` is cut away by any plane.
fn section_cuts(p: vec3<f32>) -> bool {
    return section_cuts_except(p, SECTION_PLANES);
}

// True if `p` is cut away by a plane other than `skip` (a cut face lies on its own plane).
fn section_cuts_except(p: vec3<f32>, skip: u32) -> bool {
    for (var k = 0u; k < SECTION_PLANES; k++) {
        if k != skip && dot(view_section(k), vec4<f32>(p, 1.0)) >= 0.0 {
            return true;
        }
    }
    return false;
}

// The point at parameter t of the segment p0 -> p1, its ends exactly the vertices (a mix at t = 1
// need not give p1 to the bit, and uncut edges must meet their neighbours' ends exactly).
fn span_point(p0: vec3<f32>, p1: vec3<f32>, t: f32) -> vec3<f32> {
    if t <= 0.0 {
        return p0;
    }
    if t >= 1.0 {
        return p1;
    }
    return mix(p0, p1, t);
}

// The part `span` (parameters along p0 -> p1, 0 at p0) keeps of the segment from p0 to p1 once
// every plane has cut it: empty (x >= y) when nothing is left.
fn section_span(p0: vec3<f32>, p1: vec3<f32>, span: vec2<f32>) -> vec2<f32> {
    return section_span_except(p0, p1, span, SECTION_PLANES);
}

// `section_span` by the planes other than `skip` (a cut outline lies on its own plane).
fn section_span_except(p0: vec3<f32>, p1: vec3<f32>, span: vec2<f32>, skip: u32) -> vec2<f32> {
    var kept = span;
    for (var k = 0u; k < SECTION_PLANES; k++) {
        if k == skip {
            continue;
        }
        let plane = view_section(k);
        let a = dot(plane, vec4<f32>(p0, 1.0));
        let b = dot(plane, vec4<f32>(p1, 1.0));
        if a >= 0.0 && b >= 0.0 {
            return vec2<f32>(1.0, 0.0);
        }
        if a >= 0.0 {
            kept.x = max(kept.x, a / (a - b));
        } else if b >= 0.0 {
            kept.y = min(kept.y, a / (a - b));
        }
    }
    return kept;
}

// Cut faces (caps): how a point of a cut face is filled, shared by the runtime's stencil caps
// (cut.wgsl) and the Bevy crate's section material.

// Two unit vectors spanning the plane with unit normal `n`.
fn plane_axes(n: vec3<f32>) -> array<vec3<f32>, 2> {
    let helper = select(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, 0.0), abs(n.z) > 0.9);
    let u = normalize(cross(helper, n));
    return array<vec3<f32>, 2>(u, cross(n, u));
}

// The hatch coordinate across its lines at a cap point: model-space point `p` on the plane of unit
// normal `n`, pixel `pixel` (origin top left, y down), lines at `angle` radians, on the model or
// on the screen. Take its derivatives before any discard.
fn cap_hatch_across(p: vec3<f32>, pixel: vec2<f32>, n: vec3<f32>, angle: f32, in_model: bool) -> f32 {
    if in_model {
        let axes = plane_axes(n);
        return dot(p, -sin(angle) * axes[0] + cos(angle) * axes[1]);
    }
    // Screen y points down: the angle turns counter-clockwise as the viewer sees it.
    return dot(pixel, vec2<f32>(sin(angle), cos(angle)));
}

// A cap's colour where the hatch coordinate is `across` (changing by `per_pixel` per pixel):
// `hatch` is the spacing (0 = solid fill), angle and line width (pixels), as in `CutFrame`.
fn cap_fill(across: f32, per_pixel: f32, hatch: vec4<f32>, color: vec4<f32>, hatch_color: vec4<f32>) -> vec4<f32> {
    let spacing = hatch.x;
    if spacing > 0.0 {
        let off_line = abs(fract(across / spacing + 0.5) - 0.5) * spacing;
        if off_line < 0.5 * hatch.z * per_pixel {
            return hatch_color;
        }
    }
    return color;
}
