// The cut faces of section planes (issue 43), by stencil parity: for each plane that crosses an
// instance, its mesh, clipped by that plane alone, flips the stencil's bit at every fragment (no
// depth test, no colour), so a pixel's bit ends up set exactly where the ray through it meets the
// plane inside the closed mesh (it crosses the kept surface an odd number of times). A quad on the
// plane then fills the pixels with the bit set, clipped by the other planes and depth tested, and
// the same parity draw flips the bits back to zero for the next plane or instance.

struct CutFrame {
    mvp: mat4x4<f32>,
    // The instance's planes in its model space (section.wgsl).
    section: array<vec4<f32>, SECTION_PLANES>,
    // The asset's box: centre (xyz) and half diagonal (w), to size the cap quad.
    bounds: vec4<f32>,
    color: vec4<f32>,
    hatch_color: vec4<f32>,
    // Hatch spacing (pixels, or model units when `hatch_in_model`; 0 = solid fill), angle (radians),
    // line width (pixels).
    hatch: vec4<f32>,
    // The plane this draw caps.
    plane: u32,
    hatch_in_model: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> cut: CutFrame;

fn view_section(k: u32) -> vec4<f32> {
    return cut.section[k];
}

struct ParityVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) model_position: vec3<f32>,
}

@vertex
fn parity_vertex(@location(0) position: vec3<f32>) -> ParityVarying {
    return ParityVarying(cut.mvp * vec4<f32>(position, 1.0), position);
}

// Only this draw's plane clips: the parity is that of the mesh cut by it alone.
@fragment
fn parity_fragment(v: ParityVarying) {
    if dot(cut.section[cut.plane], vec4<f32>(v.model_position, 1.0)) >= 0.0 {
        discard;
    }
}

// Two unit vectors spanning the plane with unit normal `n`.
fn plane_axes(n: vec3<f32>) -> array<vec3<f32>, 2> {
    let helper = select(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, 0.0), abs(n.z) > 0.9);
    let u = normalize(cross(helper, n));
    return array<vec3<f32>, 2>(u, cross(n, u));
}

// The cap quad: the square on the plane around the box centre's foot, as wide as the box's diagonal,
// so it covers every point of the plane inside the box.
@vertex
fn cap_face_vertex(@builtin(vertex_index) i: u32) -> ParityVarying {
    let plane = cut.section[cut.plane];
    let foot = cut.bounds.xyz - dot(plane, vec4<f32>(cut.bounds.xyz, 1.0)) * plane.xyz;
    let axes = plane_axes(plane.xyz);
    let a = select(-1.0, 1.0, ((0x16u >> i) & 1u) == 1u);
    let b = select(-1.0, 1.0, ((0x34u >> i) & 1u) == 1u);
    let p = foot + cut.bounds.w * (a * axes[0] + b * axes[1]);
    return ParityVarying(cut.mvp * vec4<f32>(p, 1.0), p);
}

@fragment
fn cap_face_fragment(v: ParityVarying) -> @location(0) vec4<f32> {
    // The hatch coordinate across its lines, and its change per pixel, before any discard.
    let angle = cut.hatch.y;
    var across: f32;
    if cut.hatch_in_model != 0u {
        let axes = plane_axes(cut.section[cut.plane].xyz);
        across = dot(v.model_position, -sin(angle) * axes[0] + cos(angle) * axes[1]);
    } else {
        // Screen y points down: the angle turns counter-clockwise as the viewer sees it.
        across = dot(v.position.xy, vec2<f32>(sin(angle), cos(angle)));
    }
    let per_pixel = max(length(vec2<f32>(dpdx(across), dpdy(across))), 1e-12);
    for (var k = 0u; k < SECTION_PLANES; k++) {
        if k != cut.plane && dot(cut.section[k], vec4<f32>(v.model_position, 1.0)) >= 0.0 {
            discard;
        }
    }
    let spacing = cut.hatch.x;
    if spacing > 0.0 {
        let off_line = abs(fract(across / spacing + 0.5) - 0.5) * spacing;
        if off_line < 0.5 * cut.hatch.z * per_pixel {
            return cut.hatch_color;
        }
    }
    return cut.color;
}
