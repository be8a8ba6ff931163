// The runtime's simple lit mesh pass: crease-split normals, one directional light plus ambient,
// lit on both sides so open meshes read correctly from behind.

struct MeshFrame {
    mvp: mat4x4<f32>,
    // Direction towards the light, in model space, unit length.
    light: vec4<f32>,
    color: vec4<f32>,
    // x: ambient share of the colour.
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> mesh: MeshFrame;

struct MeshVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) normal: vec3<f32>,
}

@vertex
fn mesh_vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> MeshVarying {
    return MeshVarying(mesh.mvp * vec4<f32>(position, 1.0), normal);
}

@fragment
fn mesh_fragment(v: MeshVarying, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    let n = normalize(select(-v.normal, v.normal, front));
    let diffuse = max(dot(n, mesh.light.xyz), 0.0);
    let ambient = mesh.params.x;
    return vec4<f32>(mesh.color.rgb * (ambient + (1.0 - ambient) * diffuse), mesh.color.a);
}
