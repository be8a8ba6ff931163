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
    // The rig's joints: `pose_data` holds their matrices, then their normal matrices, then the
    // morph weights.
    joints: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Each pass binds at most seven storage buffers (WebGPU guarantees eight per stage), so what
// belongs together shares one: the skin, the pose, the morph targets.
@group(0) @binding(0) var<uniform> pose: PoseFrame;
// The rest positions, as common.wgsl binds them.
@group(0) @binding(1) var<storage, read> topology: array<f32>;
// Six words per vertex: four u16 joint indices in two, then four f32 weights.
@group(0) @binding(40) var<storage, read> skin: array<u32>;
// 4 columns per joint matrix, 4 per joint's normal matrix (the inverse transpose of its linear
// part, in the upper 3 × 3), then the morph weights, four a vec4.
@group(0) @binding(42) var<storage, read> pose_data: array<vec4<f32>>;
// V + 1 words: each vertex's first morph entry (and the end); then four words per entry: the
// delta's three f32 and its target.
@group(0) @binding(44) var<storage, read> morphs: array<u32>;
@group(0) @binding(47) var<storage, read_write> posed_topology: array<f32>;
// pose_render reads what pose_vertices wrote (a separate dispatch: its writes are visible).
@group(0) @binding(52) var<storage, read> posed_topology_in: array<f32>;
@group(0) @binding(8) var<storage, read> render_normals: array<f32>;
@group(0) @binding(12) var<storage, read> render_to_topology: array<u32>;
@group(0) @binding(48) var<storage, read_write> posed_render: array<f32>;
@group(0) @binding(49) var<storage, read_write> posed_normals: array<f32>;
@group(0) @binding(11) var<storage, read> vertex_normals: array<vec4<f32>>;
@group(0) @binding(50) var<storage, read_write> posed_vertex_normals: array<vec4<f32>>;

fn joints_of(v: u32) -> vec4<u32> {
    let a = skin[6u * v];
    let b = skin[6u * v + 1u];
    return vec4<u32>(a & 0xffffu, a >> 16u, b & 0xffffu, b >> 16u);
}

fn weights_of(v: u32) -> vec4<f32> {
    let at = 6u * v + 2u;
    return bitcast<vec4<f32>>(vec4<u32>(skin[at], skin[at + 1u], skin[at + 2u], skin[at + 3u]));
}

fn joint_matrix(first: u32, j: u32) -> mat4x4<f32> {
    let at = first + 4u * j;
    return mat4x4<f32>(pose_data[at], pose_data[at + 1u], pose_data[at + 2u], pose_data[at + 3u]);
}

fn morph_weight(t: u32) -> f32 {
    return pose_data[8u * pose.joints + t / 4u][t % 4u];
}

// Σ wᵢ Mᵢ over the vertex's joints, of the matrices from `first` on (the joints' or their
// normals'); the identity when it has no weights.
fn blended(v: u32, first: u32) -> mat4x4<f32> {
    let w = weights_of(v);
    if pose.skinned == 0u || all(w == vec4<f32>(0.0)) {
        return mat4x4<f32>(vec4(1.0, 0.0, 0.0, 0.0), vec4(0.0, 1.0, 0.0, 0.0), vec4(0.0, 0.0, 1.0, 0.0), vec4(0.0, 0.0, 0.0, 1.0));
    }
    let j = joints_of(v);
    return joint_matrix(first, j.x) * w.x + joint_matrix(first, j.y) * w.y
        + joint_matrix(first, j.z) * w.z + joint_matrix(first, j.w) * w.w;
}

// The normal of vertex v turned by its joints (unchanged when it has none).
fn skin_normal(v: u32, n: vec3<f32>) -> vec3<f32> {
    let turned = (blended(v, 4u * pose.joints) * vec4<f32>(n, 0.0)).xyz;
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
    let entries = pose.vertices + 1u;
    for (var e = morphs[v]; e < morphs[v + 1u]; e++) {
        let at = entries + 4u * e;
        let delta = bitcast<vec3<f32>>(vec3<u32>(morphs[at], morphs[at + 1u], morphs[at + 2u]));
        p += morph_weight(morphs[at + 3u]) * delta;
    }
    let q = blended(v, 0u) * vec4<f32>(p, 1.0);
    posed_topology[3u * v] = q.x;
    posed_topology[3u * v + 1u] = q.y;
    posed_topology[3u * v + 2u] = q.z;
    if pose.vertex_normals != 0u {
        let n = vertex_normals[v];
        posed_vertex_normals[v] = vec4<f32>(skin_normal(v, n.xyz), n.w);
    }
}

// One thread per render vertex: its topology vertex's posed position and its own normal, turned.
// Runs after pose_vertices, in its own bind group (the posed positions read-only here).
@compute @workgroup_size(WORKGROUP)
fn pose_render(@builtin(global_invocation_id) id: vec3<u32>) {
    let r = thread_index(id);
    if r >= pose.render_vertices {
        return;
    }
    let t = render_to_topology[r];
    for (var k = 0u; k < 3u; k++) {
        posed_render[3u * r + k] = posed_topology_in[3u * t + k];
    }
    let n = vec3<f32>(render_normals[3u * r], render_normals[3u * r + 1u], render_normals[3u * r + 2u]);
    let turned = skin_normal(t, n);
    for (var k = 0u; k < 3u; k++) {
        posed_normals[3u * r + k] = turned[k];
    }
}
