// Image-based light (issue 29): the environment prefiltered for the material's roughness and its
// irradiance (runtime/src/highlight/environment.rs), two equirectangular maps read bilinearly from
// `environment` (the specular map's texels, then the irradiance map's), combined by the split sum
// (brdf.wgsl, `environment_radiance`). Directions are in model space, as the lights'. Each module that
// includes it declares `environment` (draw.wgsl, mesh.wgsl).

fn environment_texel(first: u32, size: vec2<u32>, x: i32, y: i32) -> vec3<f32> {
    let width = i32(size.x);
    let column = u32(((x % width) + width) % width);
    let row = u32(clamp(y, 0, i32(size.y) - 1));
    return environment[first + row * size.x + column].rgb;
}

// A map's value in direction `d`: v from +Y (row 0) down, u from φ = −π with d = (sin θ sin φ, cos θ,
// −sin θ cos φ) (environment.rs, `direction`).
fn environment_map(first: u32, size: vec2<u32>, d: vec3<f32>) -> vec3<f32> {
    let theta = acos(clamp(d.y, -1.0, 1.0));
    let phi = atan2(d.x, -d.z);
    let p = vec2<f32>((phi + PI) / (2.0 * PI) * f32(size.x), theta / PI * f32(size.y)) - vec2<f32>(0.5);
    let cell = floor(p);
    let t = p - cell;
    let x = i32(cell.x);
    let y = i32(cell.y);
    let top = mix(environment_texel(first, size, x, y), environment_texel(first, size, x + 1, y), t.x);
    let bottom = mix(environment_texel(first, size, x, y + 1), environment_texel(first, size, x + 1, y + 1), t.x);
    return mix(top, bottom, t.y);
}

// What the environment sends towards the viewer from normal `n`.
fn environment_light(m: Pbr, n: vec3<f32>, to_viewer: vec3<f32>) -> vec3<f32> {
    let specular_size = vec2<u32>(ENV_SPECULAR_WIDTH, ENV_SPECULAR_HEIGHT);
    let specular = environment_map(0u, specular_size, reflect(-to_viewer, n));
    let irradiance = environment_map(specular_size.x * specular_size.y, vec2<u32>(ENV_IRRADIANCE_WIDTH, ENV_IRRADIANCE_HEIGHT), n);
    return environment_radiance(m, dot(n, to_viewer), irradiance, specular);
}
