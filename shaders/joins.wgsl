// Per frame: how drawn edges meet at their shared vertices. For each drawn edge end, find its
// nearest drawn neighbours by screen angle on either side. Where a neighbour bends towards the edge
// (less than half a turn) the two quads overlap: both are cut along the line through the vertex and
// the crossing of their outlines, so no pixel is covered twice. Where the gap is more than half a
// turn, a round cap fills it; the cap lies between the two quads' end lines, so it overlaps neither.
// Two ways to find the neighbours (thesis §13 and §10.5) give the same result:
//   joins_next:  one thread per drawn edge end, walking the next-index ring around its vertex;
//   joins_heads: one thread per capped vertex, walking its ring from the cap buffer's head.

// Ends are looked up per instance in the slot table (compute.wgsl): a batch joins every instance of
// its asset in one dispatch.
// Walks never need more than MAX_RING steps: the decoder refuses longer rings and checked every ring
// is a closed cycle. joins_heads gathers MAX_GATHER ends per vertex; further drawn edges get no join.

// Per drawn end, the end of the one other drawn edge that meets it there + 1 (0: none or several),
// while dashes continue along chains (DISPLAY_CHAINED, phase.wgsl).
@group(0) @binding(33) var<storage, read_write> chains: array<u32>;

fn set_chain(end: u32, joined: u32) {
    if (frame.display.flags & DISPLAY_CHAINED) != 0u {
        chains[end] = joined;
    }
}

// A drawn edge end as its vertex sees it.
struct End {
    ok: bool,
    index: u32,
    slot: u32,
    color: u32,
    g: EdgeEnd,
}

// Edge end `index` of instance `instance`, if that instance draws its edge this frame.
fn end_at(instance: u32, index: u32) -> End {
    var end: End;
    end.ok = false;
    end.index = index;
    let e = index >> 1u;
    let k = index & 1u;
    let entry = slot_of(instance, e);
    if entry == 0u {
        return end;
    }
    end.slot = entry - 1u;
    let word = drawn[end.slot].y;
    if (word & DRAWN_HIGHLIGHT) != 0u {
        return end;
    }
    // Where drawn_color finds it: the instance's five colours, then the class.
    end.color = word & (0xffu | ~((1u << INSTANCE_SHIFT) - 1u));
    let s = from_record(screen[end.slot], word);
    if !s.visible || (s.clipped & (1u << k)) != 0u {
        return end;
    }
    end.g = edge_end(s, k);
    end.ok = true;
    return end;
}

// Angle from a to b, counter-clockwise in [0, 2π).
fn turn(a: vec2<f32>, b: vec2<f32>) -> f32 {
    let angle = atan2(cross2(a, b), dot(a, b));
    return select(angle, angle + 2.0 * PI, angle < 0.0);
}

// The point where the lines dot(x, n1) = c1 and dot(x, n2) = c2 cross.
fn crossing(n1: vec2<f32>, c1: f32, n2: vec2<f32>, c2: f32) -> vec2<f32> {
    let det = cross2(n1, n2);
    return vec2<f32>(c1 * n2.y - c2 * n1.y, n1.x * c2 - n2.x * c1) / det;
}

fn split_direction(x: vec2<f32>) -> u32 {
    if dot(x, x) < 1e-12 {
        return 0u;
    }
    return pack2x16snorm(normalize(x));
}

// The nearest drawn neighbours of an end so far: counter-clockwise (`left`, `left_turn` away) and
// clockwise (`right`, `right_turn` away the other way).
struct Neighbours {
    left: End,
    right: End,
    left_turn: f32,
    right_turn: f32,
}

fn no_neighbours() -> Neighbours {
    var n: Neighbours;
    n.left.ok = false;
    n.right.ok = false;
    n.left_turn = 4.0 * PI;
    n.right_turn = 4.0 * PI;
    return n;
}

// `found` with `other` taken into account as a neighbour of the end pointing along `a`.
fn nearer(found: Neighbours, a: vec2<f32>, other: End) -> Neighbours {
    var n = found;
    let ccw = turn(a, other.g.a);
    if !other.ok || ccw <= 1e-6 {
        return n;
    }
    if ccw < n.left_turn {
        n.left_turn = ccw;
        n.left = other;
    }
    if 2.0 * PI - ccw < n.right_turn {
        n.right_turn = 2.0 * PI - ccw;
        n.right = other;
    }
    return n;
}

// Writes the joins of `me` given its nearest neighbours; emits its left cap.
fn resolve(me: End, n: Neighbours) {
    let left = n.left;
    let right = n.right;
    let left_turn = n.left_turn;
    let right_turn = n.right_turn;
    let a = me.g.a;
    var split_left = 0u;
    var split_right = 0u;
    if left.ok {
        if left_turn < PI - 1e-4 {
            // My left outline meets the neighbour's right outline.
            let x = crossing(perp(a), me.g.left, perp(left.g.a), -left.g.right);
            split_left = split_direction(x);
        } else if left_turn > PI + 1e-4 {
            let radius = max(me.g.left, left.g.right);
            if radius > 0.0 {
                let i = atomicAdd(&out.caps.instance_count, 1u);
                if i < frame.cap_capacity {
                    out.cap_list[i] = Cap(
                        2u * me.slot + (me.index & 1u),
                        me.color,
                        radius,
                        pack2x16snorm(perp(a)),
                        pack2x16snorm(-perp(left.g.a)),
                    );
                }
            }
        }
    }
    if right.ok && right_turn < PI - 1e-4 {
        let x = crossing(perp(a), -me.g.right, perp(right.g.a), right.g.left);
        split_right = split_direction(x);
    }
    joins[2u * me.slot + (me.index & 1u)] = vec2<u32>(split_left, split_right);
    let single = left.ok && right.ok && left.slot == right.slot
        && (left.index & 1u) == (right.index & 1u);
    set_chain(
        2u * me.slot + (me.index & 1u),
        select(0u, 2u * left.slot + (left.index & 1u) + 1u, single),
    );
}

@compute @workgroup_size(WORKGROUP)
fn joins_next(
    @builtin(global_invocation_id) id: vec3<u32>,
) {
    let t = thread_index(id);
    let first = first_slot();
    if t >= 2u * (slots_filled() - first) {
        return;
    }
    let index = 2u * first + t;
    let item = drawn[index >> 1u];
    let instance = item.y >> INSTANCE_SHIFT;
    let start = 2u * item.x + (index & 1u);
    let me = end_at(instance, start);
    if !me.ok {
        joins[index] = vec2<u32>(0u);
        set_chain(index, 0u);
        return;
    }
    var found = no_neighbours();
    var f = ring(start);
    for (var steps = 0u; f != start && steps < MAX_RING; steps += 1u) {
        found = nearer(found, me.g.a, end_at(instance, f));
        f = ring(f);
    }
    resolve(me, found);
}

// Before joins_heads: ends at vertices without a ring head (one kept edge) are never visited there.
@compute @workgroup_size(WORKGROUP)
fn clear_joins(
    @builtin(global_invocation_id) id: vec3<u32>,
) {
    let t = thread_index(id);
    let first = first_slot();
    if t < 2u * (slots_filled() - first) {
        joins[2u * first + t] = vec2<u32>(0u);
        set_chain(2u * first + t, 0u);
    }
}

@compute @workgroup_size(WORKGROUP)
fn joins_heads(
    @builtin(global_invocation_id) id: vec3<u32>,
) {
    // One thread per (instance of the batch, capped vertex).
    let t = thread_index(id);
    let heads = frame.head_count;
    if heads == 0u || t >= heads * frame.batch_instances {
        return;
    }
    let instance = frame.instance + t / heads;
    if !instance_visible(instance) {
        return;
    }
    let head = cap_head(t % heads);
    var ends: array<End, MAX_GATHER>;
    var count = 0u;
    var f = head;
    for (var steps = 0u; steps < MAX_RING; steps += 1u) {
        let end = end_at(instance, f);
        if end.ok && count < MAX_GATHER {
            ends[count] = end;
            count += 1u;
        }
        f = ring(f);
        if f == head {
            break;
        }
    }
    for (var i = 0u; i < count; i += 1u) {
        var found = no_neighbours();
        for (var j = 0u; j < count; j += 1u) {
            if j != i {
                found = nearer(found, ends[i].g.a, ends[j]);
            }
        }
        resolve(ends[i], found);
    }
}
