// The thesis' alternate drawable edge types (§9.3): one pass of twelve vertices (four triangles) per
// edge that carries the edge and its caps together, each built from the McGuire–Hughes screen values.
// `frame.technique` picks the shape:
//   1 half hex: the half quad on the side of m0 plus the two half caps; contours only (on other
//     edges the side flips with the projected normal);
//   2 plug: the full quad plus a triangle at each end reaching to s + m; creases and boundaries;
//   3 half hex for contours, plug for the rest: the combination the thesis recommends;
//   4 house: a base from the normal-offset points down to the inner side, under a roof through
//     them; shown for its artifacts (the thesis recommends it nowhere).
// Unused triangles collapse onto one point.

const HALF_HEX: u32 = 1u;
const PLUG: u32 = 2u;
const HALF_HEX_PLUG: u32 = 3u;
const HOUSE: u32 = 4u;

// The six corners of each shape (pixels) and which end's depth each takes, then four triangles.
struct Shape {
    p: array<vec2<f32>, 6>,
    end: array<u32, 6>,
    // Corner numbers of the four triangles, three per triangle.
    tris: array<u32, 12>,
}

fn half_hex(edge: VertexEdge) -> Shape {
    let a = outward(edge);
    let w = 2.0 * edge.h;
    // s0, s1, s1 + a, s0 + a, s0 + m0, s1 + m1
    return Shape(
        array<vec2<f32>, 6>(edge.s0, edge.s1, edge.s1 + a * w.y, edge.s0 + a * w.x,
                            edge.s0 + edge.m0 * w.x, edge.s1 + edge.m1 * w.y),
        array<u32, 6>(0u, 1u, 1u, 0u, 0u, 1u),
        array<u32, 12>(0u, 1u, 2u, 0u, 2u, 3u, 0u, 3u, 4u, 1u, 5u, 2u),
    );
}

fn plug(edge: VertexEdge) -> Shape {
    let a = outward(edge);
    let h = edge.h;
    // s0 - a, s1 - a, s1 + a, s0 + a, s0 + m0, s1 + m1
    return Shape(
        array<vec2<f32>, 6>(edge.s0 - a * h.x, edge.s1 - a * h.y, edge.s1 + a * h.y,
                            edge.s0 + a * h.x, edge.s0 + edge.m0 * h.x, edge.s1 + edge.m1 * h.y),
        array<u32, 6>(0u, 1u, 1u, 0u, 0u, 1u),
        array<u32, 12>(0u, 1u, 2u, 0u, 2u, 3u, 0u, 3u, 4u, 1u, 5u, 2u),
    );
}

fn house(edge: VertexEdge) -> Shape {
    let a = outward(edge);
    let h = edge.h;
    let r0 = edge.s0 + edge.m0 * h.x;
    let r1 = edge.s1 + edge.m1 * h.y;
    // The base's bottom corners: the normal-offset points moved along a onto the inner side line.
    let b0 = r0 - a * (dot(r0 - edge.s0, a) + h.x);
    let b1 = r1 - a * (dot(r1 - edge.s1, a) + h.y);
    // b0, b1, r1, s1 + a, s0 + a, r0: a fan from b0.
    return Shape(
        array<vec2<f32>, 6>(b0, b1, r1, edge.s1 + a * h.y, edge.s0 + a * h.x, r0),
        array<u32, 6>(0u, 1u, 1u, 1u, 0u, 0u),
        array<u32, 12>(0u, 1u, 2u, 0u, 2u, 3u, 0u, 3u, 4u, 0u, 4u, 5u),
    );
}

@vertex
fn alternate_vertex(@builtin(vertex_index) i: u32, @builtin(instance_index) e: u32) -> FlatVarying {
    var edge = vertex_edge(e);
    let contour = (edge.word & DRAWN_CONTOUR) != 0u;
    var shape: Shape;
    switch frame.technique {
        case HALF_HEX: {
            if !contour {
                edge.word = NOT_DRAWN;
            }
            shape = half_hex(edge);
        }
        case PLUG: {
            shape = plug(edge);
        }
        case HALF_HEX_PLUG: {
            if contour {
                shape = half_hex(edge);
            } else {
                shape = plug(edge);
            }
        }
        default: {
            shape = house(edge);
        }
    }
    let corner = shape.tris[i];
    return edge_vertex_out(edge, at_end(edge, shape.p[corner], shape.end[corner]));
}
