//! Generated animated glTF files (issue 41) and their poses computed the obvious way, in f64, from
//! the numbers they were generated from (not from the file): a skinned cylinder of two bones that
//! bends 90°, and a cube whose top rises by a morph target.

use serde_json::json;

/// `bytes` filled with `fill` to a multiple of four (GLB chunks and buffer views are aligned so).
fn pad4(bytes: &mut Vec<u8>, fill: u8) {
    bytes.resize(bytes.len().next_multiple_of(4), fill);
}

/// A GLB file from its JSON document and its binary buffer.
pub fn glb(document: &serde_json::Value, buffer: &[u8]) -> Vec<u8> {
    let mut text = document.to_string().into_bytes();
    pad4(&mut text, b' ');
    let mut bin = buffer.to_vec();
    pad4(&mut bin, 0);
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// A binary buffer and the buffer views and accessors over it, built one array at a time.
#[derive(Default)]
pub struct Buffer {
    pub bytes: Vec<u8>,
    pub views: Vec<serde_json::Value>,
    pub accessors: Vec<serde_json::Value>,
}

impl Buffer {
    /// Appends `values` (little-endian, `component` a glTF component type) as one accessor of
    /// `count` elements of type `kind`; returns its index.
    pub fn add(
        &mut self,
        bytes: &[u8],
        component: u32,
        count: usize,
        kind: &str,
        extra: serde_json::Value,
    ) -> usize {
        pad4(&mut self.bytes, 0);
        self.views.push(json!({
            "buffer": 0, "byteOffset": self.bytes.len(), "byteLength": bytes.len()
        }));
        self.bytes.extend_from_slice(bytes);
        let mut accessor = json!({
            "bufferView": self.views.len() - 1, "componentType": component, "count": count, "type": kind
        });
        if let (Some(a), Some(e)) = (accessor.as_object_mut(), extra.as_object()) {
            a.extend(e.clone());
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// `values` as f32 of type `kind` (`n` numbers each).
    pub fn floats(&mut self, values: &[f32], n: usize, kind: &str) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.add(&bytes, 5126, values.len() / n, kind, json!({}))
    }

    /// Positions, with the min and max glTF requires.
    pub fn positions(&mut self, positions: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = positions
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        self.add(
            &bytes,
            5126,
            positions.len(),
            "VEC3",
            json!({"min": lo, "max": hi}),
        )
    }

    /// `u16` values of type `kind` (`n` numbers each).
    pub fn shorts(&mut self, values: &[u16], n: usize, kind: &str) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.add(&bytes, 5123, values.len() / n, kind, json!({}))
    }
}

/// The skinned cylinder's shape.
pub const CYLINDER_RADIUS: f64 = 0.25;
/// Its height; bone 1 starts halfway up.
pub const CYLINDER_HEIGHT: f64 = 2.0;
/// Around and along.
pub const CYLINDER_SEGMENTS: usize = 16;
/// Rings of vertices from bottom to top.
pub const CYLINDER_RINGS: usize = 9;
/// Bone 1's bend at the end of the animation, about z.
pub const BEND: f64 = std::f64::consts::FRAC_PI_2;
/// The animation's length in seconds.
pub const DURATION: f64 = 1.0;

/// How much a vertex at height `y` follows bone 1: 0 below 0.75, 1 above 1.25, linear between.
pub fn upper_weight(y: f64) -> f64 {
    ((y - 0.75) / 0.5).clamp(0.0, 1.0)
}

/// A closed cylinder along y (capped, a centre vertex per cap) skinned to two bones: bone 0 at the
/// origin, bone 1 its child at (0, 1, 0). Animation "bend" turns bone 1 about z from 0 to 90° over
/// a second with `interpolation` ("LINEAR", "STEP" or "CUBICSPLINE"; the spline's tangents are 0).
/// The mesh node is placed by a translation (`offset`) that skinning must ignore.
pub fn skinned_cylinder(interpolation: &str, offset: [f32; 3]) -> Vec<u8> {
    let (positions, triangles) = cylinder();
    let mut buffer = Buffer::default();
    let position = buffer.positions(&positions);
    let indices: Vec<u16> = triangles.iter().flatten().map(|&i| i as u16).collect();
    let index = buffer.shorts(&indices, 1, "SCALAR");
    let joints: Vec<u16> = positions.iter().flat_map(|_| [0, 1, 0, 0]).collect();
    let weights: Vec<f32> = positions
        .iter()
        .flat_map(|p| {
            let w = upper_weight(f64::from(p[1])) as f32;
            [1.0 - w, w, 0.0, 0.0]
        })
        .collect();
    let joint = buffer.shorts(&joints, 4, "VEC4");
    let weight = buffer.floats(&weights, 4, "VEC4");
    // Inverse bind matrices: the bones' rest world transforms are translations by 0 and (0,1,0).
    let mut ibm = glam::Mat4::IDENTITY.to_cols_array().to_vec();
    ibm.extend(glam::Mat4::from_translation(glam::Vec3::new(0.0, -1.0, 0.0)).to_cols_array());
    let inverse_binds = buffer.floats(&ibm, 16, "MAT4");
    let (times, rotations) = bend_keys(interpolation);
    let time = buffer.floats(&times, 1, "SCALAR");
    let rotation = buffer.floats(&rotations, 4, "VEC4");
    if let Some(a) = buffer.accessors[time].as_object_mut() {
        a.insert("min".into(), json!([0.0]));
        a.insert("max".into(), json!([DURATION]));
    }
    let document = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"name": "cylinder", "mesh": 0, "skin": 0, "translation": offset},
            {"name": "bone0", "children": [2]},
            {"name": "bone1", "translation": [0.0, 1.0, 0.0]}
        ],
        "meshes": [{"primitives": [{
            "attributes": {"POSITION": position, "JOINTS_0": joint, "WEIGHTS_0": weight},
            "indices": index
        }]}],
        "skins": [{"joints": [1, 2], "inverseBindMatrices": inverse_binds}],
        "animations": [{
            "name": "bend",
            "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}],
            "samplers": [{"input": time, "output": rotation, "interpolation": interpolation}]
        }],
        "buffers": [{"byteLength": buffer.bytes.len()}],
        "bufferViews": buffer.views,
        "accessors": buffer.accessors
    });
    glb(&document, &buffer.bytes)
}

/// Key times and rotations of the bend: two keys, 0° and 90° about z (with zero tangents for a
/// cubic spline).
fn bend_keys(interpolation: &str) -> (Vec<f32>, Vec<f32>) {
    let half = (BEND / 2.0) as f32;
    let (rest, bent) = ([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, half.sin(), half.cos()]);
    let times = vec![0.0, DURATION as f32];
    let rotations = if interpolation == "CUBICSPLINE" {
        [[0.0; 4], rest, [0.0; 4], [0.0; 4], bent, [0.0; 4]].concat()
    } else {
        [rest, bent].concat()
    };
    (times, rotations)
}

/// The cylinder's vertices and outward-wound triangles.
pub fn cylinder() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let (n, rings) = (CYLINDER_SEGMENTS, CYLINDER_RINGS);
    let mut positions = Vec::new();
    for r in 0..rings {
        let y = CYLINDER_HEIGHT * r as f64 / (rings - 1) as f64;
        for s in 0..n {
            let a = std::f64::consts::TAU * s as f64 / n as f64;
            positions.push([
                (CYLINDER_RADIUS * a.cos()) as f32,
                y as f32,
                (CYLINDER_RADIUS * a.sin()) as f32,
            ]);
        }
    }
    let (bottom, top) = (positions.len() as u32, positions.len() as u32 + 1);
    positions.push([0.0, 0.0, 0.0]);
    positions.push([0.0, CYLINDER_HEIGHT as f32, 0.0]);
    let at = |r: usize, s: usize| (r * n + s % n) as u32;
    let mut triangles = Vec::new();
    for r in 0..rings - 1 {
        for s in 0..n {
            let (a, b, c, d) = (at(r, s), at(r, s + 1), at(r + 1, s), at(r + 1, s + 1));
            triangles.push([a, c, b]);
            triangles.push([b, c, d]);
        }
    }
    for s in 0..n {
        triangles.push([bottom, at(0, s), at(0, s + 1)]);
        triangles.push([top, at(rings - 1, s + 1), at(rings - 1, s)]);
    }
    (positions, triangles)
}

/// Bone 1's angle at `time` for an animation of `interpolation` (a cubic spline with zero
/// tangents eases: smoothstep of the time).
pub fn bend_angle(interpolation: &str, time: f64) -> f64 {
    let s = (time / DURATION).clamp(0.0, 1.0);
    match interpolation {
        "STEP" if s < 1.0 => 0.0,
        "STEP" => BEND,
        "CUBICSPLINE" => {
            // The quaternion's components follow the Hermite basis, then it is normalized.
            let h = 3.0 * s * s - 2.0 * s * s * s;
            let half = BEND / 2.0;
            let (z, w) = (h * half.sin(), (1.0 - h) + h * half.cos());
            2.0 * z.atan2(w)
        }
        _ => BEND * s,
    }
}

/// Where the skinning formula puts a cylinder vertex `p` (model space, before the node's offset,
/// which skinning ignores) when bone 1 is turned by `angle` about z.
pub fn posed_cylinder_vertex(p: [f64; 3], angle: f64) -> [f64; 3] {
    let w = upper_weight(p[1]);
    let (s, c) = angle.sin_cos();
    let (x, y) = (p[0], p[1] - 1.0);
    let turned = [c * x - s * y, s * x + c * y + 1.0, p[2]];
    std::array::from_fn(|k| (1.0 - w) * p[k] + w * turned[k])
}

/// How far the morph cube's top rises at weight 1.
pub const RISE: f32 = 0.5;

/// A unit cube (24 vertices, flat normals) with one morph target that raises its top face by
/// [`RISE`]; animation "rise" takes the weight from 0 to 1 over a second, linearly. The mesh's
/// rest weight is `rest_weight`, and the target's deltas are stored sparse.
pub fn morph_cube(rest_weight: f32) -> Vec<u8> {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for axis in 0..3 {
        for side in [0.0f32, 1.0] {
            let base = positions.len() as u32;
            for (u, v) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                let mut p = [0.0f32; 3];
                p[axis] = side;
                p[(axis + 1) % 3] = u;
                p[(axis + 2) % 3] = v;
                positions.push(p);
            }
            let outward = side == 1.0;
            if outward {
                triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
            } else {
                triangles.extend([[base, base + 2, base + 1], [base, base + 3, base + 2]]);
            }
        }
    }
    let mut buffer = Buffer::default();
    let position = buffer.positions(&positions);
    let indices: Vec<u16> = triangles.iter().flatten().map(|&i| i as u16).collect();
    let index = buffer.shorts(&indices, 1, "SCALAR");
    // The target as a sparse accessor: no buffer view, only the top vertices' deltas.
    let top: Vec<u16> = (0..positions.len() as u16)
        .filter(|&i| positions[i as usize][1] == 1.0)
        .collect();
    let deltas: Vec<f32> = top.iter().flat_map(|_| [0.0, RISE, 0.0]).collect();
    let top_bytes: Vec<u8> = top.iter().flat_map(|v| v.to_le_bytes()).collect();
    let delta_bytes: Vec<u8> = deltas.iter().flat_map(|v| v.to_le_bytes()).collect();
    let top_view = view(&mut buffer, &top_bytes);
    let delta_view = view(&mut buffer, &delta_bytes);
    buffer.accessors.push(json!({
        "componentType": 5126, "count": positions.len(), "type": "VEC3",
        "min": [0.0, 0.0, 0.0], "max": [0.0, RISE, 0.0],
        "sparse": {
            "count": top.len(),
            "indices": {"bufferView": top_view, "componentType": 5123},
            "values": {"bufferView": delta_view}
        }
    }));
    let target = buffer.accessors.len() - 1;
    let time = buffer.floats(&[0.0, DURATION as f32], 1, "SCALAR");
    let weight = buffer.floats(&[0.0, 1.0], 1, "SCALAR");
    let document = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "cube", "mesh": 0}],
        "meshes": [{
            "primitives": [{
                "attributes": {"POSITION": position},
                "indices": index,
                "targets": [{"POSITION": target}]
            }],
            "weights": [rest_weight],
            "extras": {"targetNames": ["rise"]}
        }],
        "animations": [{
            "name": "rise",
            "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}],
            "samplers": [{"input": time, "output": weight}]
        }],
        "buffers": [{"byteLength": buffer.bytes.len()}],
        "bufferViews": buffer.views,
        "accessors": buffer.accessors
    });
    glb(&document, &buffer.bytes)
}

fn view(buffer: &mut Buffer, bytes: &[u8]) -> usize {
    pad4(&mut buffer.bytes, 0);
    buffer.views.push(json!({
        "buffer": 0, "byteOffset": buffer.bytes.len(), "byteLength": bytes.len()
    }));
    buffer.bytes.extend_from_slice(bytes);
    buffer.views.len() - 1
}
