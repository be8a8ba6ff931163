// The runtime's simple lit mesh pass: crease-split normals, one light, Blinn's model plus ambient or
// glTF's metallic-roughness model (brdf.wgsl), lit on both sides so open meshes read correctly from
// behind.

struct MeshFrame {
    mvp: mat4x4<f32>,
    light: PunctualLight,
    // The base colour.
    color: vec4<f32>,
    // Share of the (diffuse) colour lit regardless of the light.
    ambient: f32,
    // Specular reflectance and exponent (Blinn).
    specular: f32,
    shininess: f32,
    // SHADE_PBR: metallic-roughness shading with `surface` (else Blinn); SHADE_ENVIRONMENT: plus the
    // image-based light of `environment`.
    pbr: u32,
    // The camera in model space: a point (w = 1) or a direction towards the viewer (w = 0).
    eye: vec4<f32>,
    // PBR: metallic, α = roughness².
    surface: vec4<f32>,
    // The section planes in the instance's model space (section.wgsl).
    section: array<vec4<f32>, SECTION_PLANES>,
}

fn view_section(k: u32) -> vec4<f32> {
    return mesh.section[k];
}

@group(0) @binding(0) var<uniform> mesh: MeshFrame;
@group(0) @binding(1) var<storage, read> environment: array<vec4<f32>>;

struct MeshVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) model_position: vec3<f32>,
}

@vertex
fn mesh_vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> MeshVarying {
    return MeshVarying(mesh.mvp * vec4<f32>(position, 1.0), normal, position);
}

@fragment
fn mesh_fragment(v: MeshVarying, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    if section_cuts(v.model_position) {
        discard;
    }
    let n = normalize(select(-v.normal, v.normal, front));
    let to_light = towards_light(mesh.light, v.model_position);
    let light = light_radiance(mesh.light, v.model_position);
    let to_viewer = normalize(mesh.eye.xyz - v.model_position * mesh.eye.w);
    let ambient = mesh.ambient;
    if (mesh.pbr & SHADE_PBR) != 0u {
        let m = Pbr(mesh.color.rgb, mesh.surface.x, mesh.surface.y);
        var lit = light * pbr_radiance(m, n, to_light, to_viewer) + ambient * uniform_environment(m, dot(n, to_viewer));
        if (mesh.pbr & SHADE_ENVIRONMENT) != 0u {
            lit += environment_light(m, n, to_viewer);
        }
        return vec4<f32>(lit, mesh.color.a);
    }
    let diffuse = max(dot(n, to_light), 0.0);
    let specular = mesh.specular * pow(max(dot(n, half_vector(to_light, to_viewer)), 0.0), mesh.shininess);
    return vec4<f32>(mesh.color.rgb * (ambient + (1.0 - ambient) * diffuse * light) + specular * light, mesh.color.a);
}
