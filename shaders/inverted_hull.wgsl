// The expanded inverted hull (thesis §7.2, Evans; what most games ship): the mesh drawn a second
// time, each vertex pushed out along its normal by the line width (pixels at its depth), with its
// front faces culled, so only the hull's far side shows, as a rim around the silhouette. With the
// asset's crease-split normals the hull tears open at hard edges; `smooth_normals` pushes along the
// smooth normal of each render vertex's topology vertex instead, which keeps it closed.

struct HullParams {
    smooth_normals: u32,
}

@group(0) @binding(15) var<uniform> params: HullParams;

@group(0) @binding(11) var<storage, read> vertex_normals: array<vec4<f32>>;
// The topology vertex of each render vertex.
@group(0) @binding(12) var<storage, read> render_to_topology: array<u32>;

@vertex
fn hull_vertex(
    @builtin(vertex_index) r: u32,
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
) -> FlatVarying {
    var n = normal;
    if params.smooth_normals == 1u {
        n = vertex_normals[render_to_topology[r]].xyz;
    }
    let w = (frame.mvp * vec4<f32>(position, 1.0)).w;
    let push = 2.0 * half_width(w) * frame.pixel_scale * w;
    let c = frame.mvp * vec4<f32>(position + normalize(n) * push, 1.0);
    return flat_vertex(COLOR_CONTOUR, c, position);
}
