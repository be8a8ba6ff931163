// The thesis' alternate drawable edge types (§9.3): one pass of six points (four triangles) per edge
// that carries the edge and its caps together, each built from the McGuire–Hughes screen values.
// `params.shape` picks the shape:
//   1 half hex: the half quad on the side of m0 plus the two half caps; contours only (on other
//     edges the side flips with the projected normal);
//   2 plug: the full quad plus a triangle at each end reaching to s + m; creases and boundaries;
//   3 half hex for contours, plug for the rest: the combination the thesis recommends;
//   4 house: a base from the normal-offset points down to the inner side, under a roof through
//     them; shown for its artifacts (the thesis recommends it nowhere).

const HALF_HEX: u32 = 1u;
const PLUG: u32 = 2u;
const HALF_HEX_PLUG: u32 = 3u;
const HOUSE: u32 = 4u;

struct AlternateParams {
    shape: u32,
}

@group(0) @binding(15) var<uniform> params: AlternateParams;

// Point k (0..5) of each shape; techniques/alternate.rs draws them indexed into four triangles, so
// each point is shaded once (the thesis' six output vertices per edge).

// Half hex: s0, s1, s1 + a, s0 + a, s0 + m0, s1 + m1 (triangles 012 023 034 152).
fn half_hex_point(edge: VertexEdge, k: u32) -> vec4<f32> {
    let a = outward(edge);
    let w = 2.0 * edge.h;
    switch k {
        case 0u: { return at_end(edge, edge.s0, 0u); }
        case 1u: { return at_end(edge, edge.s1, 1u); }
        case 2u: { return at_end(edge, edge.s1 + a * w.y, 1u); }
        case 3u: { return at_end(edge, edge.s0 + a * w.x, 0u); }
        case 4u: { return at_end(edge, edge.s0 + edge.m0 * w.x, 0u); }
        default: { return at_end(edge, edge.s1 + edge.m1 * w.y, 1u); }
    }
}

// Plug: s0 - a, s1 - a, s1 + a, s0 + a, s0 + m0, s1 + m1 (the same triangles).
fn plug_point(edge: VertexEdge, k: u32) -> vec4<f32> {
    let a = outward(edge);
    let h = edge.h;
    switch k {
        case 0u: { return at_end(edge, edge.s0 - a * h.x, 0u); }
        case 1u: { return at_end(edge, edge.s1 - a * h.y, 1u); }
        case 2u: { return at_end(edge, edge.s1 + a * h.y, 1u); }
        case 3u: { return at_end(edge, edge.s0 + a * h.x, 0u); }
        case 4u: { return at_end(edge, edge.s0 + edge.m0 * h.x, 0u); }
        default: { return at_end(edge, edge.s1 + edge.m1 * h.y, 1u); }
    }
}

// House: b0, b1, r1, s1 + a, s0 + a, r0 (a fan from b0: 012 023 034 045), where r = s + m and the
// base's corners b are r moved along a onto the inner side line.
fn house_point(edge: VertexEdge, k: u32) -> vec4<f32> {
    let a = outward(edge);
    let h = edge.h;
    let r0 = edge.s0 + edge.m0 * h.x;
    let r1 = edge.s1 + edge.m1 * h.y;
    switch k {
        case 0u: { return at_end(edge, r0 - a * (dot(r0 - edge.s0, a) + h.x), 0u); }
        case 1u: { return at_end(edge, r1 - a * (dot(r1 - edge.s1, a) + h.y), 1u); }
        case 2u: { return at_end(edge, r1, 1u); }
        case 3u: { return at_end(edge, edge.s1 + a * h.y, 1u); }
        case 4u: { return at_end(edge, edge.s0 + a * h.x, 0u); }
        default: { return at_end(edge, r0, 0u); }
    }
}

@vertex
fn alternate_vertex(@builtin(vertex_index) k: u32, @builtin(instance_index) e: u32) -> FlatVarying {
    var edge = vertex_edge(e);
    let contour = (edge.word & DRAWN_CONTOUR) != 0u;
    var position: vec4<f32>;
    switch params.shape {
        case HALF_HEX: {
            if !contour {
                edge.word = NOT_DRAWN;
            }
            position = half_hex_point(edge, k);
        }
        case PLUG: {
            position = plug_point(edge, k);
        }
        case HALF_HEX_PLUG: {
            if contour {
                position = half_hex_point(edge, k);
            } else {
                position = plug_point(edge, k);
            }
        }
        default: {
            position = house_point(edge, k);
        }
    }
    return edge_vertex_out(edge, position);
}
