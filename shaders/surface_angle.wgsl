// Surface-angle contours (thesis §7.1, Marshall's pixel shader): the mesh drawn again over itself,
// each pixel inked where its interpolated normal is nearly perpendicular to the view, |N·V| below
// `threshold`. Cheap and mesh-independent, but its width follows the surface's curvature: flat faces
// are all ink or none (the thesis' cube failure).

struct AngleParams {
    threshold: f32,
}

@group(0) @binding(15) var<uniform> params: AngleParams;

struct AngleVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) model_position: vec3<f32>,
}

@vertex
fn angle_vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> AngleVarying {
    let c = frame.mvp * vec4<f32>(position, 1.0);
    return AngleVarying(vec4<f32>(c.xy, biased_depth(c) * c.w, c.w), normal, position);
}

@fragment
fn angle_fragment(v: AngleVarying) -> @location(0) vec4<f32> {
    if section_cuts(v.model_position) {
        discard;
    }
    let to_viewer = normalize(frame.eye.xyz - v.model_position * frame.eye.w);
    if abs(dot(normalize(v.normal), to_viewer)) >= params.threshold {
        discard;
    }
    return frame.colors[COLOR_CONTOUR];
}
