// Bindings of the draw passes (edges, caps, the outline): the lists the compute passes wrote this frame,
// read-only.

@group(0) @binding(17) var<storage, read> drawn: array<vec2<u32>>;
@group(0) @binding(18) var<storage, read> joins: array<vec2<u32>>;
@group(0) @binding(19) var<storage, read> out: Out;
@group(0) @binding(20) var<storage, read> screen: array<ScreenRecord>;
@group(0) @binding(21) var<storage, read> chamfers: array<ChamferRecord>;
@group(0) @binding(22) var<storage, read> cos_power: array<f32>;
@group(0) @binding(23) var<uniform> lighting: Lighting;
@group(0) @binding(30) var<storage, read> environment: array<vec4<f32>>;
// Per drawn instance, its camera in its model space (the highlight's sections project with it).
@group(0) @binding(29) var<storage, read> instance_frames: array<InstanceFrame>;

struct Cap {
    end: u32,
    color: u32,
    radius: f32,
    from_dir: u32,
    to_dir: u32,
}

struct Out {
    edges: array<u32, 4>,
    caps: array<u32, 4>,
    needed: u32,
    kept_clusters: u32,
    survivors_wanted: u32,
    instances_in_view: u32,
    cap_list: array<Cap>,
}

// Per slot, the hidden pattern's phase at end 0 and its sign along the edge (phase.wgsl), while
// DISPLAY_CHAINED.
@group(0) @binding(36) var<storage, read> phases: array<vec2<f32>>;

// The hidden pattern's phase `along` pixels from end 0 of slot `slot`'s edge: continued along its
// chain, or from end 0.
fn pattern_phase(slot: u32, along: f32) -> f32 {
    if (frame.display.flags & DISPLAY_CHAINED) == 0u {
        return along;
    }
    let p = phases[slot];
    return p.x + p.y * along;
}

// Per drawn instance, its COLOR_COUNT class colours (the drawn word's instance bits pick them).
@group(0) @binding(25) var<storage, read> instance_colors: array<vec4<f32>>;

fn drawn_color(word: u32) -> vec4<f32> {
    return instance_colors[(word >> INSTANCE_SHIFT) * COLOR_COUNT + (word & 0xffu)];
}

