// Bindings of the compute passes (classify, joins): the asset's edge sections and the per-frame lists.

@group(0) @binding(3) var<storage, read> attributes: array<u32>;
// Next edge end per edge end (thesis §13).
@group(0) @binding(4) var<storage, read> rings: array<u32>;
// The ring heads of the capped vertices (§10.5), at the width of `rings`: a binding of their own, so
// that the next ends alone may fill one.
@group(0) @binding(5) var<storage, read> cap_heads: array<u32>;
// The slot table: per (instance, edge) drawn this frame, its slot in `drawn` plus one, in an
// open-addressed hash table of `table_mask + 1` entries (a power of two, at least twice the lists'
// slots, so at most half full), cleared by the host before each frame.
@group(0) @binding(16) var<storage, read_write> table: array<atomic<u32>>;
// Per slot: (edge, drawn word).
@group(0) @binding(17) var<storage, read_write> drawn: array<vec2<u32>>;
// Per drawn edge end (2 * slot + end): the left and right split directions, packed snorm; 0 = none.
@group(0) @binding(18) var<storage, read_write> joins: array<vec2<u32>>;
@group(0) @binding(19) var<storage, read_write> out: Out;
// Per batch, its first slot: batches are classified and joined one after the other, so a batch's
// drawn edges are the slots from its start to the count.
@group(0) @binding(24) var<storage, read_write> starts: array<u32>;

// Slots filled so far, at most the capacity.
fn slots_filled() -> u32 {
    return min(atomicLoad(&out.edges.instance_count), frame.capacity);
}

// This batch's first slot.
fn first_slot() -> u32 {
    return starts[frame.batch];
}

// Where (instance, edge) starts looking in the slot table.
fn table_home(instance: u32, e: u32) -> u32 {
    var h = (e * 0x9e3779b1u) ^ (instance * 0x85ebca77u + 0x27d4eb2fu);
    h = (h ^ (h >> 15u)) * 0x2c1b3c6du;
    return (h ^ (h >> 12u)) & frame.table_mask;
}

// Records that instance `instance` draws edge `e` in `slot` (classify). The table is at least twice
// the slots, so a free entry is always found.
fn remember(instance: u32, e: u32, slot: u32) {
    var h = table_home(instance, e);
    for (var tries = 0u; tries <= 2u * frame.table_mask; tries += 1u) {
        let result = atomicCompareExchangeWeak(&table[h], 0u, slot + 1u);
        if result.exchanged {
            return;
        }
        // A weak exchange may fail on a free entry: try it again, else the next one.
        if result.old_value != 0u {
            h = (h + 1u) & frame.table_mask;
        }
    }
}

// The slot + 1 where instance `instance` draws edge `e` this frame, or 0 (joins).
fn slot_of(instance: u32, e: u32) -> u32 {
    var h = table_home(instance, e);
    for (var tries = 0u; tries <= frame.table_mask; tries += 1u) {
        let entry = atomicLoad(&table[h]);
        if entry == 0u {
            return 0u;
        }
        let item = drawn[entry - 1u];
        if item.x == e && (item.y >> INSTANCE_SHIFT) == instance {
            return entry;
        }
        h = (h + 1u) & frame.table_mask;
    }
    return 0u;
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
