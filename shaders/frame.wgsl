// The frame uniform of the passes that draw one instance per uniform block: every technique's but
// the joined technique's compute passes (batch.wgsl). Shared code reads the instance's view through
// the `view_*` functions, which batch.wgsl defines per thread.

@group(0) @binding(0) var<uniform> frame: Frame;

fn view_mvp() -> mat4x4<f32> {
    return frame.mvp;
}

fn view_eye() -> vec4<f32> {
    return frame.eye;
}

// The highlight light's position (or direction) and spot axis as the block's instance sees them,
// in its model space (its own light, or the style's).
fn view_light_position() -> vec4<f32> {
    return frame.light_position;
}

fn view_light_axis() -> vec3<f32> {
    return frame.light_axis.xyz;
}

fn view_frustum(side: u32) -> vec4<f32> {
    return frame.frustum[side];
}

fn view_depth_ref() -> f32 {
    return frame.depth_ref;
}

fn view_instance() -> u32 {
    return frame.instance;
}

fn view_color(k: u32) -> vec4<f32> {
    return frame.colors[k];
}

fn view_section(k: u32) -> vec4<f32> {
    return frame.section[k];
}

// The element (edge, triangle) a vertex shader's instance index names: with one instance per
// block, the index itself (batch.wgsl splits it into instance and element).
fn enter_element(index: u32, per_instance: u32) -> u32 {
    return index;
}
