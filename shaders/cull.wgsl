// Per frame, one thread per edge cluster (issue 14; the cluster bounds of runtime/src/asset/clusters.rs,
// meshoptimizer's normal-cone test applied to edges): keeps the clusters that may hold a drawn edge,
// so classification runs over their edges only. A cluster is dropped only when it provably holds
// none: the test bounds, with the f32 rounding of the per-edge test, every value `classify_edge`
// compares with zero.

struct EdgeCluster {
    center: vec3<f32>,
    radius: f32,
    axis: vec3<f32>,
    // -1: the faces may look any way.
    cos_angle: f32,
    flags: u32,
}

// The clusters a cull pass kept, each with its instance: (instance, cluster of the chunk).
struct Survivors {
    count: atomic<u32>,
    // The count once every cluster is tested, at most the capacity (what classify_clusters reads).
    kept: u32,
    _pad: array<u32, 2>,
    clusters: array<vec2<u32>>,
}

@group(0) @binding(27) var<storage, read_write> survivors: Survivors;
@group(0) @binding(6) var<storage, read> clusters: array<EdgeCluster>;
// The indirect dispatch of classify_clusters: one workgroup per kept cluster. (Not in `survivors`:
// that dispatch reads the list, and a buffer cannot be both there.)
@group(0) @binding(28) var<storage, read_write> cull_dispatch: array<u32, 4>;

// One thread per (instance of the batch, cluster of the chunk): the instances out of view stop here.
@compute @workgroup_size(WORKGROUP)
fn cull(@builtin(global_invocation_id) id: vec3<u32>) {
    let t = thread_index(id);
    // This dispatch's clusters: those of its edges (a chunk starts on a cluster boundary).
    let per_instance = (frame.edge_count + CLUSTER_EDGES - 1u) / CLUSTER_EDGES;
    if t >= per_instance * frame.batch_instances {
        return;
    }
    let instance = frame.instance + t / per_instance;
    if !instance_visible(instance) {
        return;
    }
    let i = t % per_instance;
    enter_instance(instance);
    if may_draw(clusters[frame.first_edge / CLUSTER_EDGES + i]) {
        let k = atomicAdd(&survivors.count, 1u);
        if k < frame.survivor_capacity {
            survivors.clusters[k] = vec2<u32>(instance, i);
        }
    }
}

// The workgroups of classify_clusters, at most MAX_GROUPS per dimension; the count starts again at 0
// for the next dispatch. Clusters past the list's capacity are not drawn this frame; the host grows
// the list for the next.
@compute @workgroup_size(1)
fn cull_args() {
    let wanted = atomicLoad(&survivors.count);
    let kept = min(wanted, frame.survivor_capacity);
    let x = min(kept, MAX_GROUPS);
    cull_dispatch[0] = x;
    cull_dispatch[1] = select(0u, (kept + x - 1u) / max(x, 1u), x > 0u);
    cull_dispatch[2] = 1u;
    survivors.kept = kept;
    atomicStore(&survivors.count, 0u);
    out.kept_clusters += kept;
    atomicMax(&out.survivors_wanted, wanted);
}

// False only if no edge of `c` can be drawn this frame.
fn may_draw(c: EdgeCluster) -> bool {
    // Off screen: the sphere wholly beyond a widened side plane (the planes are unit length).
    for (var side = 0u; side < 4u; side++) {
        let plane = view_frustum(side);
        let distance = dot(plane.xyz, c.center) + plane.w;
        let slack = 1e-5 * (length(c.center) + c.radius + abs(plane.w));
        if distance - c.radius > slack {
            return false;
        }
    }
    let facing = facing_bounds(c);
    let shown = (c.flags & frame.classes) != 0u;
    if facing.x > 0.0 {
        // Every face looks at the camera: no contour; creases and the rest as classified.
        return shown || (frame.highlight != 0u && (c.flags & CHAMFER) != 0u);
    }
    if facing.y < 0.0 {
        // Every face looks away: only what is drawn from behind.
        return shown && (frame.cull_back == 0u || (c.flags & BOUNDARY) != 0u);
    }
    return true;
}

// Bounds (low, high) on the sign test `dot(n, eye.xyz - p eye.w)` of every face of `c` over unit
// normals n in the cone and points p in the sphere, moved outwards by the test's rounding: low > 0
// means every face looks at the camera, high < 0 that none does.
fn facing_bounds(c: EdgeCluster) -> vec2<f32> {
    if c.cos_angle <= -1.0 {
        return vec2<f32>(-1.0, 1.0);
    }
    let eye = view_eye();
    let q = eye.xyz - c.center * eye.w;
    let l = length(q);
    let reach = c.radius * abs(eye.w);
    let slack = reach + 1e-5 * (length(eye.xyz) + (length(c.center) + c.radius) * abs(eye.w) + l);
    if l <= slack {
        // The eye is in or next to the sphere: faces may look either way.
        return vec2<f32>(-1.0, 1.0);
    }
    // Between the cone's axis and the eye: cos_b; the cone's half-angle: cos_a.
    // Both sines from forms that keep their precision near 0 (1 - cos^2 would lose it).
    let cos_b = clamp(dot(c.axis, q) / l, -1.0, 1.0);
    let sin_b = min(length(cross(c.axis, q)) / l, 1.0);
    let cos_a = c.cos_angle;
    let sin_a = sqrt(max(0.0, (1.0 - cos_a) * (1.0 + cos_a)));
    // The normal closest to the eye direction is at angle max(0, b - a), the farthest at min(pi, b + a).
    var high = 1.0;
    if cos_b < cos_a {
        high = cos_b * cos_a + sin_b * sin_a;
    }
    var low = -1.0;
    if cos_b > -cos_a {
        low = cos_b * cos_a - sin_b * sin_a;
    }
    // 1e-5 more covers the rounding of these cosines.
    return vec2<f32>(l * (low - 1e-5) - slack, l * (high + 1e-5) + slack);
}
