// The application's depth, single-sampled.
@group(0) @binding(16) var depth_texture: texture_depth_2d;

fn scene_depth(p: vec2<i32>) -> f32 {
    return textureLoad(depth_texture, p, 0);
}
