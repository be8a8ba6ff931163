// Fins (seed 003, Doss, "Inking the Cube"): silhouette and crease edges found per frame and drawn as
// quads extruded from the edge along its vertices' normals by a constant thickness. The article's
// geometry shader runs per front-facing triangle with its neighbours; here the vertex shader runs
// per edge (instance) with its two faces: each front-facing face whose edge is a silhouette (the
// other face looks away) or a crease emits one fin, extruded along that face's own corner normals
// (crease-split, as a mesh with hard edges has them). That is what makes the article's artifacts:
// - a gap where a silhouette passes a hard edge, as the extrusion direction jumps between faces;
// - on a valley near 90° the normal lies in the other face, so its fin is coplanar with it and
//   z-fights; Listing 3 moves crease fins `z_bias` towards the camera in view space.

struct FinParams {
    // The fin's length: world units, or pixels at the vertex's depth if `in_pixels` is 1.
    thickness: f32,
    in_pixels: u32,
    // How far crease fins move towards the camera, world units.
    z_bias: f32,
}

@group(0) @binding(15) var<uniform> params: FinParams;

@group(0) @binding(3) var<storage, read> attributes: array<u32>;
// The render vertices' normals (crease-split), xyz per vertex.
@group(0) @binding(8) var<storage, read> render_normals: array<f32>;
// Per edge: the render vertices at v0 and v1 of face a, then of face b (0xffffffff: no face).
@group(0) @binding(13) var<storage, read> fin_corners: array<vec4<u32>>;

fn render_normal(r: u32) -> vec3<f32> {
    return vec3<f32>(render_normals[3u * r], render_normals[3u * r + 1u], render_normals[3u * r + 2u]);
}

fn fin_front(n: vec3<f32>, p: vec3<f32>) -> bool {
    let eye = view_eye();
    return dot(n, eye.xyz - p * eye.w) > 0.0;
}

// Vertex i of 12: fin of face a (0..5) or face b (6..11), two triangles each.
@vertex
fn fin_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) index: u32) -> FlatVarying {
    // Every instance of the asset in one draw: instance = an instance's edge.
    let e = enter_element(index, frame.edge_count);
    let flags = attributes[e] & 0xffffu;
    let v0 = position(edge_vertex(4u * e));
    let v1 = position(edge_vertex(4u * e + 1u));
    let v2 = position(edge_vertex(4u * e + 2u));
    let v3 = position(edge_vertex(4u * e + 3u));
    let two_faces = (flags & (BOUNDARY | NON_MANIFOLD)) == 0u;
    let front_a = fin_front(cross(v1 - v0, v2 - v0), v0);
    var front_b = front_a;
    if two_faces {
        let nb = cross(v0 - v1, v3 - v1);
        front_b = fin_front(select(nb, -nb, (flags & FLIPPED) != 0u), v1);
    }
    var word = drawn_word(flags, front_a, front_b);
    let face_b = i >= 6u;
    let corners = fin_corners[e];
    let c0 = select(corners.x, corners.z, face_b);
    let c1 = select(corners.y, corners.w, face_b);
    // Only a face that looks at the camera emits, and a boundary has no face b.
    if !select(front_a, front_b && two_faces, face_b) || c0 == 0xffffffffu {
        word = NOT_DRAWN;
    }
    let k = ((0x16u >> (i % 6u)) & 1u) == 1u;
    let tip = ((0x34u >> (i % 6u)) & 1u) == 1u;
    let base = select(v0, v1, k);
    let normal = normalize(render_normal(select(c0, c1, k)));
    var thickness = params.thickness;
    if params.in_pixels == 1u {
        // Pixels: the world length that covers that many pixels at this vertex's depth.
        thickness = params.thickness * frame.pixel_scale * (view_mvp() * vec4<f32>(base, 1.0)).w;
    }
    var clip = view_mvp() * vec4<f32>(base + select(0.0, thickness, tip) * normal, 1.0);
    if (word & DRAWN_CONTOUR) == 0u {
        // Listing 3: crease fins move towards the camera in view space.
        clip = clip + params.z_bias * frame.proj_z;
    }
    return flat_vertex(word, clip, base);
}
