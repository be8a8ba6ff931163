// Bindings of the compute passes (classify, joins): the asset's edge sections and the per-frame lists.

@group(0) @binding(3) var<storage, read> attributes: array<u32>;
// Next edge end per edge end (thesis §13).
@group(0) @binding(4) var<storage, read> rings: array<u32>;
// The ring heads of the capped vertices (§10.5), at the width of `rings`: a binding of their own, so
// that the next ends alone may fill one.
@group(0) @binding(5) var<storage, read> cap_heads: array<u32>;
// Per edge: its slot in `drawn` plus one when drawn this frame; otherwise 0 or a stale slot.
@group(0) @binding(16) var<storage, read_write> state: array<u32>;
// Per slot: (edge, drawn word).
@group(0) @binding(17) var<storage, read_write> drawn: array<vec2<u32>>;
// Per drawn edge end (2 * slot + end): the left and right split directions, packed snorm; 0 = none.
@group(0) @binding(18) var<storage, read_write> joins: array<vec2<u32>>;
@group(0) @binding(19) var<storage, read_write> out: Out;
// Per drawn instance, its first slot: instances are classified and joined one after the other, so
// an instance's drawn edges are the slots from its start to the count.
@group(0) @binding(24) var<storage, read_write> starts: array<u32>;

// Slots filled so far, at most the capacity.
fn slots_filled() -> u32 {
    return min(atomicLoad(&out.edges.instance_count), frame.capacity);
}

// This instance's first slot.
fn first_slot() -> u32 {
    return starts[frame.instance];
}

fn ring(i: u32) -> u32 {
    if frame.rings_u16 != 0u {
        return (rings[i >> 1u] >> ((i & 1u) * 16u)) & 0xffffu;
    }
    return rings[i];
}
// Per slot: the drawn edge's quad on screen (see ScreenRecord).
@group(0) @binding(20) var<storage, read_write> screen: array<ScreenRecord>;
@group(0) @binding(21) var<storage, read_write> chamfers: array<ChamferRecord>;
@group(0) @binding(22) var<storage, read> cos_power: array<f32>;
@group(0) @binding(23) var<uniform> lighting: Lighting;

fn cap_head(t: u32) -> u32 {
    if frame.rings_u16 != 0u {
        return (cap_heads[t >> 1u] >> ((t & 1u) * 16u)) & 0xffffu;
    }
    return cap_heads[t];
}
