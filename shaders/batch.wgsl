// The joined technique's compute passes work on every instance of an asset at once (issue 28). The
// uniform block is the batch's (the style, the viewport, the asset, one chunk of its edges), each
// instance's camera is a row of `instance_frames`, and a thread works in `frame`: the block alone
// (`enter_batch`) or with its instance's camera (`enter_instance`). Every entry point enters first;
// what it does is then written as for one instance, as in the other techniques.

@group(0) @binding(0) var<uniform> batch: Frame;
@group(0) @binding(29) var<storage, read> instance_frames: array<InstanceFrame>;

var<private> frame: Frame;

fn enter_batch() {
    frame = batch;
}

// The batch's block with instance `i`'s camera.
fn enter_instance(i: u32) {
    frame = batch;
    let f = instance_frames[i];
    frame.mvp = f.mvp;
    frame.eye = f.eye;
    frame.frustum = f.frustum;
    frame.depth_ref = f.lo.w;
    frame.instance = i;
}

// Whether the place pass found instance `i` in view.
fn instance_visible(i: u32) -> bool {
    return instance_frames[i].visible != 0u;
}
