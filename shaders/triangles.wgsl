// Shared by the techniques that pull the mesh's triangles in the vertex shader (instance = triangle,
// no geometry shader): the render positions and indices as storage buffers.

@group(0) @binding(7) var<storage, read> render_positions: array<f32>;
@group(0) @binding(9) var<storage, read> mesh_indices: array<u32>;

fn mesh_index(i: u32) -> u32 {
    if frame.indices_u16 != 0u {
        return (mesh_indices[i >> 1u] >> ((i & 1u) * 16u)) & 0xffffu;
    }
    return mesh_indices[i];
}

fn render_position(r: u32) -> vec3<f32> {
    return vec3<f32>(render_positions[3u * r], render_positions[3u * r + 1u], render_positions[3u * r + 2u]);
}

// The three corners of triangle `t` in model space.
fn triangle(t: u32) -> array<vec3<f32>, 3> {
    return array<vec3<f32>, 3>(
        render_position(mesh_index(3u * t)),
        render_position(mesh_index(3u * t + 1u)),
        render_position(mesh_index(3u * t + 2u)),
    );
}

// True if triangle `t`'s front (counter-clockwise) side faces the camera.
fn triangle_front(p: array<vec3<f32>, 3>) -> bool {
    let n = cross(p[1] - p[0], p[2] - p[0]);
    return dot(n, frame.eye.xyz - p[0] * frame.eye.w) > 0.0;
}
