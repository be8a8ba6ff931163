// Flat-coloured geometry of the techniques that pull their vertices in the vertex shader: the colour
// of the edge's class, or nowhere for edges not drawn.

struct FlatVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) color: vec4<f32>,
}

fn flat_vertex(word: u32, position: vec4<f32>) -> FlatVarying {
    if word == NOT_DRAWN {
        return FlatVarying(NOWHERE, vec4<f32>(0.0));
    }
    return FlatVarying(position, view_color(word & 0xffu));
}

@fragment
fn flat_fragment(v: FlatVarying) -> @location(0) vec4<f32> {
    return v.color;
}
