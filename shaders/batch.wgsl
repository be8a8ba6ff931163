// The joined technique's compute passes work on every instance of an asset at once (issue 28). The
// uniform block is the batch's (the style, the viewport, the asset, one chunk of its edges; its
// `instance` is the batch's first), and each instance's view of it (camera in its model space,
// frustum, depth reference) is a row of `instance_frames`: a thread that works for an instance enters
// it, and the shared code reads its view through the `view_*` functions (frame.wgsl defines them for
// the passes with one instance per block).

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(29) var<storage, read> instance_frames: array<InstanceFrame>;

// The instance this thread works for.
var<private> viewing: u32;

fn enter_instance(i: u32) {
    viewing = i;
}

// Whether the place pass found instance `i` in view.
fn instance_visible(i: u32) -> bool {
    return instance_frames[i].visible != 0u;
}

fn view_mvp() -> mat4x4<f32> {
    return instance_frames[viewing].mvp;
}

fn view_eye() -> vec4<f32> {
    return instance_frames[viewing].eye;
}

// The highlight light's position (or direction) and spot axis as the instance sees them, in its
// model space (its own light, or the style's).
fn view_light_position() -> vec4<f32> {
    return instance_frames[viewing].light_position;
}

fn view_light_axis() -> vec3<f32> {
    return instance_frames[viewing].light_axis.xyz;
}

fn view_frustum(side: u32) -> vec4<f32> {
    return instance_frames[viewing].frustum[side];
}

fn view_depth_ref() -> f32 {
    return instance_frames[viewing].lo.w;
}

fn view_instance() -> u32 {
    return viewing;
}

fn view_color(k: u32) -> vec4<f32> {
    return instance_frames[viewing].colors[k];
}

fn view_section(k: u32) -> vec4<f32> {
    return instance_frames[viewing].section[k];
}

// The element (edge, triangle) a batched draw's instance index names, `per_instance` of them per
// instance of the batch; enters that instance.
fn enter_element(index: u32, per_instance: u32) -> u32 {
    let n = max(per_instance, 1u);
    enter_instance(frame.instance + index / n);
    return index % n;
}
