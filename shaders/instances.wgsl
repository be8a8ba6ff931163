// Per frame, one thread per instance (the joined technique, issue 28): whether the instance's bounds
// can be on screen. The passes after it skip the instances out of view before any edge work, so the
// host writes every instance's camera and culls none.

@group(0) @binding(29) var<storage, read_write> instance_frames: array<InstanceFrame>;
@group(0) @binding(19) var<storage, read_write> out: Out;

@compute @workgroup_size(WORKGROUP)
fn place(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = thread_index(id);
    // The place pass's block counts every instance of the frame.
    if i >= frame.batch_instances {
        return;
    }
    let f = instance_frames[i];
    let seen = in_view(f.mvp, f.lo.xyz, f.hi.xyz);
    instance_frames[i].visible = select(0u, 1u, seen);
    if seen {
        atomicAdd(&out.instances_in_view, 1u);
    }
}

// False only if the box `lo..hi`, through `mvp`, lies wholly beyond one plane of the clip volume.
fn in_view(mvp: mat4x4<f32>, lo: vec3<f32>, hi: vec3<f32>) -> bool {
    var beyond = array<bool, 6>(true, true, true, true, true, true);
    for (var k = 0u; k < 8u; k += 1u) {
        let p = select(lo, hi, vec3<bool>((k & 1u) != 0u, (k & 2u) != 0u, (k & 4u) != 0u));
        let c = mvp * vec4<f32>(p, 1.0);
        beyond[0] = beyond[0] && c.x < -c.w;
        beyond[1] = beyond[1] && c.x > c.w;
        beyond[2] = beyond[2] && c.y < -c.w;
        beyond[3] = beyond[3] && c.y > c.w;
        beyond[4] = beyond[4] && c.z < 0.0;
        beyond[5] = beyond[5] && c.z > c.w;
    }
    return !(beyond[0] || beyond[1] || beyond[2] || beyond[3] || beyond[4] || beyond[5]);
}
