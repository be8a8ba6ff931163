// Physically based shading shared by the mesh pass and the chamfer highlight (issue 29): glTF's
// metallic-roughness model (GGX distribution, height-correlated Smith visibility, Schlick Fresnel,
// Lambert diffuse weighted by 1 − F) and KHR_lights_punctual's lights. CPU twin:
// runtime/src/highlight/ggx.rs (`radiance`) and runtime/src/render/lighting.rs (`PunctualLight`).

// One light, in model space.
struct PunctualLight {
    // xyz: towards the light (w = 0) or the light's position (w = 1).
    position: vec4<f32>,
    // rgb: colour × intensity; a: 1 where it falls off as 1/d² (physically based point and spot
    // lights), 0 where it does not (seed 000's light).
    color: vec4<f32>,
    // A spot's axis (unit, the way it shines; zero for other lights); w: cos of its outer angle.
    spot: vec4<f32>,
    // x: cos of the spot's inner angle.
    cone: vec4<f32>,
}

fn towards_light(light: PunctualLight, p: vec3<f32>) -> vec3<f32> {
    let d = light.position.xyz - p * light.position.w;
    // A light placed on the shaded point itself: any direction (not NaN).
    return select(vec3<f32>(0.0, 0.0, 1.0), normalize(d), dot(d, d) > 1e-20);
}

// The unit half vector, or zero where light and viewer are opposite (as glam's normalize_or_zero).
fn half_vector(to_light: vec3<f32>, to_viewer: vec3<f32>) -> vec3<f32> {
    let s = to_light + to_viewer;
    return select(vec3<f32>(0.0), normalize(s), dot(s, s) > 1e-12);
}

// The light's colour arriving at `p`: distance falloff and the spot's cone (KHR_lights_punctual).
fn light_radiance(light: PunctualLight, p: vec3<f32>) -> vec3<f32> {
    var scale = 1.0;
    let offset = light.position.xyz - p;
    if light.position.w > 0.0 && light.color.a > 0.0 {
        scale = 1.0 / max(dot(offset, offset), 1e-12);
    }
    if dot(light.spot.xyz, light.spot.xyz) > 0.0 {
        let cos_angle = dot(-towards_light(light, p), light.spot.xyz);
        let t = clamp((cos_angle - light.spot.w) / max(light.cone.x - light.spot.w, 1e-4), 0.0, 1.0);
        scale *= t * t;
    }
    return light.color.rgb * scale;
}

// A metallic-roughness material: base colour, metallic, α = roughness².
struct Pbr {
    base: vec3<f32>,
    metallic: f32,
    alpha: f32,
}

fn pbr_f0(m: Pbr) -> vec3<f32> {
    return mix(vec3<f32>(0.04), m.base, m.metallic);
}

fn pbr_diffuse_color(m: Pbr) -> vec3<f32> {
    return m.base * (1.0 - m.metallic);
}

fn schlick(m: Pbr, v_dot_h: f32) -> vec3<f32> {
    let f0 = pbr_f0(m);
    return f0 + (vec3<f32>(1.0) - f0) * pow(1.0 - clamp(v_dot_h, 0.0, 1.0), 5.0);
}

// G / (4 N·L N·V), height-correlated Smith.
fn smith_visibility(n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let l = max(n_dot_l, 0.0);
    let v = max(n_dot_v, 0.0);
    let denominator = l * sqrt(v * v * (1.0 - a2) + a2) + v * sqrt(l * l * (1.0 - a2) + a2);
    return 0.5 / max(denominator, 1e-12);
}

fn ggx_distribution(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let c = max(n_dot_h, 0.0);
    let d = c * c * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

// Radiance towards the viewer from normal `n` under a light of radiance 1: ((1 − F) c_diff / π + F D Vis) (N·L)₊.
fn pbr_radiance(m: Pbr, n: vec3<f32>, to_light: vec3<f32>, to_viewer: vec3<f32>) -> vec3<f32> {
    let n_dot_l = dot(n, to_light);
    if n_dot_l <= 0.0 {
        return vec3<f32>(0.0);
    }
    let half = half_vector(to_light, to_viewer);
    let fresnel = schlick(m, dot(to_viewer, half));
    let specular = ggx_distribution(dot(n, half), m.alpha) * smith_visibility(n_dot_l, dot(n, to_viewer), m.alpha);
    return ((vec3<f32>(1.0) - fresnel) * pbr_diffuse_color(m) / PI + fresnel * specular) * n_dot_l;
}

// The split sum (Karis 2013): what an environment whose irradiance (over π) at the normal is
// `irradiance` and whose radiance prefiltered for the material's lobe along the reflection is
// `specular` sends towards the viewer: c_diff × irradiance plus `specular` × the lobe's directional
// albedo, by Karis' analytic fit of the DFG term (Unreal, "Physically Based Shading on Mobile", 2014).
fn environment_radiance(m: Pbr, n_dot_v: f32, irradiance: vec3<f32>, specular: vec3<f32>) -> vec3<f32> {
    let roughness = sqrt(m.alpha);
    let r = roughness * vec4<f32>(-1.0, -0.0275, -0.572, 0.022) + vec4<f32>(1.0, 0.0425, 1.04, -0.04);
    let a004 = min(r.x * r.x, exp2(-9.28 * max(n_dot_v, 0.0))) * r.x + r.y;
    let ab = vec2<f32>(-1.04, 1.04) * a004 + r.zw;
    return pbr_diffuse_color(m) * irradiance + (pbr_f0(m) * ab.x + ab.y) * specular;
}

// A uniform white environment of radiance 1: the PBR `ambient` share is its radiance.
fn uniform_environment(m: Pbr, n_dot_v: f32) -> vec3<f32> {
    return environment_radiance(m, n_dot_v, vec3<f32>(1.0), vec3<f32>(1.0));
}
