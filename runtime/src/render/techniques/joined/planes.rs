//! The view's side planes in model space, widened by an edge's reach on screen: the cull pass's
//! frustum test (`shaders/cull.wgsl`).

/// The four side planes of the view through `mvp` in model space, each moved out by `reach_px`
/// pixels and scaled to a unit normal: a point `p` with `dot(plane, (p, 1)) > 0` projects more than
/// `reach_px` beyond that side of the viewport (whatever its depth, behind the camera included,
/// since the test is linear in clip space). Zeros, which nothing is beyond, for a degenerate plane.
pub(super) fn side_planes(mvp: glam::Mat4, viewport: [f32; 2], reach_px: f32) -> [[f32; 4]; 4] {
    let mvp = mvp.as_dmat4();
    let [x, y, w] = [0, 1, 3].map(|i| mvp.row(i));
    let pad = |size: f32| 1.0 + 2.0 * f64::from(reach_px) / f64::from(size.max(1.0));
    let (px, py) = (pad(viewport[0]), pad(viewport[1]));
    [x - px * w, -x - px * w, y - py * w, -y - py * w].map(|plane| {
        let length = plane.truncate().length();
        if length > 0.0 && length.is_finite() && plane.is_finite() {
            (plane / length).as_vec4().to_array()
        } else {
            [0.0; 4]
        }
    })
}
