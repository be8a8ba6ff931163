// Rounded corners (issue 29; runtime/src/highlight/corners.rs finds them): where the chamfer edges at a
// convex vertex share one radius r, the rounded solid near the vertex is a sphere of radius r, centred
// r inside the vertex's three face planes, with the edges' cylinders running from it. A drawn corner
// owns the pixels around its vertex: each strip hands over those within `hand_over` pixels of the
// vertex along its edge (edges.wgsl discards them) and the corner draw (corner_draw.wgsl) traces the
// local solid there per sub-sample. Both sides decide with the functions below, from the same record.
//
// Shared by chamfers.wgsl (compute) and corner_draw.wgsl; both bind the asset's corner buffer: its
// count, the records (CORNER_WORDS words each), then each edge end's corner + 1 (0: none), four a word.

@group(0) @binding(31) var<storage, read> corners: array<vec4<u32>>;

struct Corner {
    // The sphere's centre and radius.
    sphere: vec4<f32>,
    // The sharp vertex; w: how far each cylinder is followed from the centre (the shortest edge).
    vertex: vec4<f32>,
    // The three planes' outward normals; normals[0].w: the reach around the vertex (model units).
    normals: array<vec4<f32>, 3>,
    // Per plane pair (k, k + 1): the far end of its kept edge (w = 1), or w = 0 for none.
    far: array<vec4<f32>, 3>,
}

fn corner_count() -> u32 {
    return corners[0].x;
}

fn corner_at(k: u32) -> Corner {
    let base = 1u + k * CORNER_WORDS;
    let w = array<vec4<f32>, 8>(
        bitcast<vec4<f32>>(corners[base]),
        bitcast<vec4<f32>>(corners[base + 1u]),
        bitcast<vec4<f32>>(corners[base + 2u]),
        bitcast<vec4<f32>>(corners[base + 3u]),
        bitcast<vec4<f32>>(corners[base + 4u]),
        bitcast<vec4<f32>>(corners[base + 5u]),
        bitcast<vec4<f32>>(corners[base + 6u]),
        bitcast<vec4<f32>>(corners[base + 7u]),
    );
    return Corner(w[0], w[1], array<vec4<f32>, 3>(w[2], w[3], w[4]), array<vec4<f32>, 3>(w[5], w[6], w[7]));
}

// The corner at edge end `end` (2 e + k) + 1, or 0.
fn corner_of_end(end: u32) -> u32 {
    let i = 1u + corner_count() * CORNER_WORDS + end / 4u;
    return corners[i][end % 4u];
}

// Whether the corner is drawn in this view: its three faces look at the camera (so its strips are all
// highlighted) and its vertex is in front of the near plane.
fn corner_drawn(c: Corner) -> bool {
    let v = c.vertex.xyz;
    let clip = view_mvp() * vec4<f32>(v, 1.0);
    if clip.w <= 0.0 || in_front(clip) < 0.0 {
        return false;
    }
    return face_front(c.normals[0].xyz, v) && face_front(c.normals[1].xyz, v) && face_front(c.normals[2].xyz, v);
}

// The model-space steps that move a point at `p`'s depth one pixel right and one pixel down on screen
// (in the plane through `p` where the projection is affine: constant w, or constant depth when
// orthographic).
fn pixel_steps(p: vec3<f32>) -> array<vec3<f32>, 2> {
    let m = transpose(view_mvp());
    let w_row = m[3].xyz;
    let depth_row = select(m[2].xyz, w_row, dot(w_row, w_row) > 0.0);
    let u = normalize(cross(m[1].xyz, depth_row));
    let v = normalize(cross(depth_row, m[0].xyz));
    let mvp = view_mvp();
    let q = to_pixels(mvp * vec4<f32>(p, 1.0));
    let pu = to_pixels(mvp * vec4<f32>(p + u, 1.0)) - q;
    let pv = to_pixels(mvp * vec4<f32>(p + v, 1.0)) - q;
    let det = cross2(pu, pv);
    return array<vec3<f32>, 2>((pv.y * u - pu.y * v) / det, (pu.x * v - pv.x * u) / det);
}

// The model-space size of a pixel with these steps (pixel_steps).
fn pixel_size(steps: array<vec3<f32>, 2>) -> f32 {
    return max(0.5 * (length(steps[0]) + length(steps[1])), 1e-20);
}

// How many pixels from the vertex, along the edge to `far`, a strip hands over to the corner: the
// corner's reach on screen, at most half the edge (the corner at the far end takes the other half);
// none where `far` is behind the camera (the strip keeps its seed ends, the corner leaves it alone).
fn hand_over(c: Corner, far: vec3<f32>) -> f32 {
    let mvp = view_mvp();
    let v = to_pixels(mvp * vec4<f32>(c.vertex.xyz, 1.0));
    let reach = c.normals[0].w / pixel_size(pixel_steps(c.vertex.xyz));
    let clip = mvp * vec4<f32>(far, 1.0);
    if clip.w <= 0.0 {
        return 0.0;
    }
    return min(reach, 0.5 * length(to_pixels(clip) - v));
}
