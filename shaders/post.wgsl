// Shared by the post-processes that run after the application's pass over its finished colour,
// reading its depth (hybrid.wgsl, image_space.wgsl): the uniform, a full-screen triangle, and view
// positions reconstructed from depth with the inverse projection (any projection, either depth
// convention).

struct Post {
    inv_projection: mat4x4<f32>,
    // The mesh pass of the techniques that draw their own buffers (normals, object mask).
    mvp: mat4x4<f32>,
    color: vec4<f32>,
    viewport: vec2<f32>,
    // Clip w of the model's centre, for depth-scaled steps; 0: constant.
    depth_ref: f32,
    _pad: u32,
    // The mesh pass's section planes, in its model space (section.wgsl).
    section: array<vec4<f32>, SECTION_PLANES>,
}

@group(0) @binding(0) var<uniform> post: Post;

fn view_section(k: u32) -> vec4<f32> {
    return post.section[k];
}

struct PostVarying {
    @builtin(position) position: vec4<f32>,
}

@vertex
fn post_vertex(@builtin(vertex_index) i: u32) -> PostVarying {
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u)) * 2.0 - 1.0;
    return PostVarying(vec4<f32>(xy, 0.0, 1.0));
}

fn clamp_pixel(p: vec2<i32>) -> vec2<i32> {
    return clamp(p, vec2<i32>(0), vec2<i32>(post.viewport) - vec2<i32>(1));
}

// The view-space position seen at pixel `p` (x right, y up, looking down -z).
fn view_position(p: vec2<i32>) -> vec3<f32> {
    let q = clamp_pixel(p);
    let d = scene_depth(q);
    let ndc = vec2<f32>(
        (f32(q.x) + 0.5) / post.viewport.x * 2.0 - 1.0,
        1.0 - (f32(q.y) + 0.5) / post.viewport.y * 2.0,
    );
    let v = post.inv_projection * vec4<f32>(ndc, d, 1.0);
    return v.xyz / v.w;
}

// Distance along the view axis to what pixel `p` sees.
fn view_depth(p: vec2<i32>) -> f32 {
    return -view_position(p).z;
}
