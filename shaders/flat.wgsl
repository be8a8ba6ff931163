// Flat-coloured geometry of the techniques that pull their vertices in the vertex shader: the colour
// of the edge's class, or nowhere for edges not drawn.

struct FlatVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) color: vec4<f32>,
    // The model-space point the section planes test (w = 1), or w = 0 for what they do not cut.
    @location(1) section_point: vec4<f32>,
}

// Vertex `position` of flat geometry in the colour of `word`, standing for model-space `point`.
fn flat_vertex(word: u32, position: vec4<f32>, point: vec3<f32>) -> FlatVarying {
    if word == NOT_DRAWN {
        return FlatVarying(NOWHERE, vec4<f32>(0.0), vec4<f32>(0.0));
    }
    return FlatVarying(position, view_color(word & 0xffu), vec4<f32>(point, 1.0));
}

// True if a fragment of flat geometry is cut away by the section.
fn flat_cut(section_point: vec4<f32>) -> bool {
    return section_point.w > 0.5 && section_cuts(section_point.xyz);
}

@fragment
fn flat_fragment(v: FlatVarying) -> @location(0) vec4<f32> {
    if flat_cut(v.section_point) {
        discard;
    }
    return v.color;
}
