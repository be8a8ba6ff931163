// Shared by the techniques that classify every edge in the vertex shader, as McGuire and Hughes do
// (thesis §8.2): each vertex of an edge's geometry tests the edge again (the duplicated work §8.5
// describes), with nothing compacted, and builds its corner from the edge's screen-space values
// (§8.3): s0, s1 the ends in pixels, p the unit perpendicular, m0, m1 the vertex normals projected
// to the screen, unit. Geometry is pulled from the asset's storage buffers by instance (the edge) and
// vertex index (the corner), since wgpu has no geometry shaders.

@group(0) @binding(3) var<storage, read> attributes: array<u32>;
// A smooth normal per topology vertex (xyz; w unused), the n0, n1 of §8.1.
@group(0) @binding(11) var<storage, read> vertex_normals: array<vec4<f32>>;

struct VertexEdge {
    // NOT_DRAWN, or the drawn word (colour index, contour bit).
    word: u32,
    s0: vec2<f32>,
    s1: vec2<f32>,
    // Unit perpendicular to s1 - s0 (its left normal).
    p: vec2<f32>,
    // Projected vertex normals, unit (zero where the normal is seen end-on).
    m0: vec2<f32>,
    m1: vec2<f32>,
    // Half widths, pixels, at each end.
    h: vec2<f32>,
    depth: vec2<f32>,
    w: vec2<f32>,
    // The middle of the part the section keeps, in model space.
    kept: vec3<f32>,
}

fn screen_dir(from_px: vec2<f32>, to_clip: vec4<f32>) -> vec2<f32> {
    if to_clip.w <= 0.0 {
        return vec2<f32>(0.0);
    }
    let d = to_pixels(to_clip) - from_px;
    if dot(d, d) < 1e-12 {
        return vec2<f32>(0.0);
    }
    return normalize(d);
}

// Edge `e` classified and projected, as each of its vertices computes it.
fn vertex_edge(e: u32) -> VertexEdge {
    var out: VertexEdge;
    out.word = NOT_DRAWN;
    let flags = attributes[e] & 0xffffu;
    let i0 = edge_vertex(4u * e);
    let i1 = edge_vertex(4u * e + 1u);
    let v0 = position(i0);
    let v1 = position(i1);
    let v2 = position(edge_vertex(4u * e + 2u));
    let v3 = position(edge_vertex(4u * e + 3u));
    let front = fronts(v0, v1, v2, v3, flags);
    let word = drawn_word(flags, front.x, front.y);
    if word == NOT_DRAWN {
        return out;
    }
    let mvp = view_mvp();
    // The part the section planes keep (section.wgsl); its ends stand for the edge's.
    let span = section_span(v0, v1, vec2<f32>(0.0, 1.0));
    if !(span.x < span.y) {
        return out;
    }
    let e0 = span_point(v0, v1, span.x);
    let e1 = span_point(v0, v1, span.y);
    let c0 = mvp * vec4<f32>(e0, 1.0);
    let c1 = mvp * vec4<f32>(e1, 1.0);
    // Like the thesis, no near-plane clipping: an edge that reaches behind the camera is not drawn.
    if in_front(c0) < 0.0 || in_front(c1) < 0.0 || c0.w <= 0.0 || c1.w <= 0.0 {
        return out;
    }
    out.s0 = to_pixels(c0);
    out.s1 = to_pixels(c1);
    let along = out.s1 - out.s0;
    if !(dot(along, along) > 1e-8) {
        return out;
    }
    out.word = word;
    out.p = perp(normalize(along));
    out.m0 = screen_dir(out.s0, mvp * vec4<f32>(e0 + vertex_normals[i0].xyz, 1.0));
    out.m1 = screen_dir(out.s1, mvp * vec4<f32>(e1 + vertex_normals[i1].xyz, 1.0));
    out.h = vec2<f32>(half_width(c0.w), half_width(c1.w));
    out.depth = vec2<f32>(biased_depth(c0), biased_depth(c1));
    out.w = vec2<f32>(c0.w, c1.w);
    out.kept = mix(e0, e1, 0.5);
    return out;
}

// A corner of an edge's geometry: `px` in pixels at end `k`'s depth.
fn at_end(edge: VertexEdge, px: vec2<f32>, k: u32) -> vec4<f32> {
    return from_pixels(px, edge.depth[k], edge.w[k]);
}

// The perpendicular turned to the side the projected normal at v0 points to (§8.3 half quads).
fn outward(edge: VertexEdge) -> vec2<f32> {
    return edge.p * select(-1.0, 1.0, dot(edge.m0, edge.p) >= 0.0);
}

fn edge_vertex_out(edge: VertexEdge, position: vec4<f32>) -> FlatVarying {
    // The segment is clipped already; its kept middle passes the fragment's section test.
    return flat_vertex(edge.word, position, edge.kept);
}
