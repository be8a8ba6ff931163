// McGuire and Hughes' hardware-determined feature edges (thesis §8): every edge of every instance of
// the asset is drawn in one draw (instance = an instance's edge, vertex = one of its four edge vertices), each of which classifies it again and either builds its corner or sends
// it nowhere. The edge pass draws a quad per edge, full or half (contours, §8.3); two cap passes draw
// a triangle at each end that meets the neighbouring edge's cap along the projected vertex normal
// (§8.4). The caps' known flaw (§8.5): where the projected normal does not follow the surface's bend,
// a cap lands on the wrong side of the joint and leaves the gap open.

// Corner `i` (0..3) of the edge's quad, drawn indexed (0 1 2, 0 2 3) so each corner is shaded once,
// as the thesis' four edge vertices are: 0 (s0, below), 1 (s1, below), 2 (s1, above), 3 (s0, above).
@vertex
fn mh_edge_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) index: u32) -> FlatVarying {
    let edge = vertex_edge(enter_element(index, frame.edge_count));
    let k = select(0u, 1u, i == 1u || i == 2u);
    let above = i >= 2u;
    let s = select(edge.s0, edge.s1, k == 1u);
    let h = edge.h[k];
    var offset = edge.p * select(-h, h, above);
    if (edge.word & DRAWN_CONTOUR) != 0u && frame.half_quads != 0u {
        // Half quad: from the edge out to the side the vertex normal points to, full width.
        offset = select(vec2<f32>(0.0), outward(edge) * 2.0 * h, above);
    }
    return edge_vertex_out(edge, at_end(edge, s + offset, k));
}

// The cap at end `k`: (s, s + p sign(m·p), s + m), scaled like the quad (§8.4).
fn cap_corner(edge: VertexEdge, i: u32, k: u32) -> vec4<f32> {
    let s = select(edge.s0, edge.s1, k == 1u);
    let m = select(edge.m0, edge.m1, k == 1u);
    var scale = edge.h[k];
    if (edge.word & DRAWN_CONTOUR) != 0u && frame.half_quads != 0u {
        scale = 2.0 * scale;
    }
    let side = edge.p * select(-1.0, 1.0, dot(m, edge.p) >= 0.0);
    var px = s;
    if i == 1u {
        px = s + side * scale;
    } else if i == 2u {
        px = s + m * scale;
    }
    return at_end(edge, px, k);
}

@vertex
fn mh_cap0_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) index: u32) -> FlatVarying {
    let edge = vertex_edge(enter_element(index, frame.edge_count));
    return edge_vertex_out(edge, cap_corner(edge, i, 0u));
}

@vertex
fn mh_cap1_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) index: u32) -> FlatVarying {
    let edge = vertex_edge(enter_element(index, frame.edge_count));
    return edge_vertex_out(edge, cap_corner(edge, i, 1u));
}
