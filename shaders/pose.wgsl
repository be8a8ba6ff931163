// Per frame, before anything reads the asset (issue 41; runtime/src/rig and runtime/src/render/pose.rs):
// poses an animated asset into its own position buffers, so every technique then classifies and draws
// the pose that is shown. The glTF skinning formula: morph targets first (p + Σ wₖ δₖ), then the skin
// (Σ wᵢ Jᵢ p); normals turn by the inverse transpose of each joint's linear part. A vertex with no
// joint weights is not skinned.

struct PoseFrame {
    vertices: u32,
    render_vertices: u32,
    // 1 when the asset has joints and weights.
    skinned: u32,
    // 1 when the asset has per-topology-vertex normals to pose (AssetExtras::VERTEX_NORMALS).
    vertex_normals: u32,
}

@group(0) @binding(0) var<uniform> pose: PoseFrame;
// The rest positions, as common.wgsl binds them.
@group(0) @binding(1) var<storage, read> topology: array<f32>;
// Four u16 joint indices per vertex, as two words.
@group(0) @binding(40) var<storage, read> skin_joints: array<u32>;
@group(0) @binding(41) var<storage, read> skin_weights: array<vec4<f32>>;
@group(0) @binding(42) var<storage, read> joint_matrices: array<mat4x4<f32>>;
// Per joint, the inverse transpose of its linear part (in the upper 3 × 3).
@group(0) @binding(43) var<storage, read> joint_normals: array<mat4x4<f32>>;
// Per vertex, its first morph entry; one more at the end.
@group(0) @binding(44) var<storage, read> morph_ranges: array<u32>;
// xyz: the delta, w: its target's index (bits).
@group(0) @binding(45) var<storage, read> morph_entries: array<vec4<f32>>;
@group(0) @binding(46) var<storage, read> morph_weights: array<f32>;
@group(0) @binding(47) var<storage, read_write> posed_topology: array<f32>;
@group(0) @binding(8) var<storage, read> render_normals: array<f32>;
@group(0) @binding(12) var<storage, read> render_to_topology: array<u32>;
@group(0) @binding(48) var<storage, read_write> posed_render: array<f32>;
@group(0) @binding(49) var<storage, read_write> posed_normals: array<f32>;
@group(0) @binding(11) var<storage, read> vertex_normals: array<vec4<f32>>;
@group(0) @binding(50) var<storage, read_write> posed_vertex_normals: array<vec4<f32>>;

fn joints_of(v: u32) -> vec4<u32> {
    let a = skin_joints[2u * v];
    let b = skin_joints[2u * v + 1u];
    return vec4<u32>(a & 0xffffu, a >> 16u, b & 0xffffu, b >> 16u);
}

// Σ wᵢ Jᵢ, the matrix that moves vertex v (identity when it has no weights).
fn skin_matrix(v: u32) -> mat4x4<f32> {
    let w = skin_weights[v];
    if pose.skinned == 0u || all(w == vec4<f32>(0.0)) {
        return mat4x4<f32>(vec4(1.0, 0.0, 0.0, 0.0), vec4(0.0, 1.0, 0.0, 0.0), vec4(0.0, 0.0, 1.0, 0.0), vec4(0.0, 0.0, 0.0, 1.0));
    }
    let j = joints_of(v);
    return joint_matrices[j.x] * w.x + joint_matrices[j.y] * w.y + joint_matrices[j.z] * w.z
        + joint_matrices[j.w] * w.w;
}

// The normal of vertex v turned by its joints (unchanged when it has none).
fn skin_normal(v: u32, n: vec3<f32>) -> vec3<f32> {
    let w = skin_weights[v];
    if pose.skinned == 0u || all(w == vec4<f32>(0.0)) {
        return n;
    }
    let j = joints_of(v);
    let m = joint_normals[j.x] * w.x + joint_normals[j.y] * w.y + joint_normals[j.z] * w.z
        + joint_normals[j.w] * w.w;
    let turned = (m * vec4<f32>(n, 0.0)).xyz;
    let length2 = dot(turned, turned);
    return select(n, turned * inverseSqrt(length2), length2 > 0.0);
}

// One thread per topology vertex: its posed position (and normal, when the asset has them).
@compute @workgroup_size(WORKGROUP)
fn pose_vertices(@builtin(global_invocation_id) id: vec3<u32>) {
    let v = thread_index(id);
    if v >= pose.vertices {
        return;
    }
    var p = vec3<f32>(topology[3u * v], topology[3u * v + 1u], topology[3u * v + 2u]);
    for (var e = morph_ranges[v]; e < morph_ranges[v + 1u]; e++) {
        let entry = morph_entries[e];
        p += morph_weights[bitcast<u32>(entry.w)] * entry.xyz;
    }
    let q = skin_matrix(v) * vec4<f32>(p, 1.0);
    posed_topology[3u * v] = q.x;
    posed_topology[3u * v + 1u] = q.y;
    posed_topology[3u * v + 2u] = q.z;
    if pose.vertex_normals != 0u {
        let n = vertex_normals[v];
        posed_vertex_normals[v] = vec4<f32>(skin_normal(v, n.xyz), n.w);
    }
}

// One thread per render vertex: its topology vertex's posed position and its own normal, turned.
// Runs after pose_vertices (a separate dispatch: its writes are visible here).
@compute @workgroup_size(WORKGROUP)
fn pose_render(@builtin(global_invocation_id) id: vec3<u32>) {
    let r = thread_index(id);
    if r >= pose.render_vertices {
        return;
    }
    let t = render_to_topology[r];
    for (var k = 0u; k < 3u; k++) {
        posed_render[3u * r + k] = posed_topology[3u * t + k];
    }
    let n = vec3<f32>(render_normals[3u * r], render_normals[3u * r + 1u], render_normals[3u * r + 2u]);
    let turned = skin_normal(t, n);
    for (var k = 0u; k < 3u; k++) {
        posed_normals[3u * r + k] = turned[k];
    }
}
