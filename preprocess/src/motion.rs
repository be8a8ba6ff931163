//! Skins and morph targets from the loaded vertices to the welded ones (issue 41).
//!
//! A loader gives joints, weights and morph deltas per *input* vertex; the asset keeps them per
//! topology vertex. Welding uses the bind pose, so corners that coincide there are one vertex:
//! each topology vertex takes the data of the first input vertex welded into it, and the bake
//! counts the welded vertices whose data differ (their seam would open in motion, the edges follow
//! the first).

use chamfer_runtime::asset::Motion;
use chamfer_runtime::rig::{INFLUENCES, Rig};

/// Motion per loaded vertex, as a loader reads it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InputMotion {
    /// Per input vertex, four joints of [`Rig::joints`]; empty when nothing is skinned.
    pub joints: Vec<[u16; INFLUENCES]>,
    /// Per input vertex, their weights (summing to 1, or all 0 for a vertex no joint moves).
    pub weights: Vec<[f32; INFLUENCES]>,
    /// Per morph target, the input vertices it moves and by how much (any order).
    pub targets: Vec<Vec<(u32, [f32; 3])>>,
    /// Nodes, joints, morph weights and animations.
    pub rig: Rig,
}

impl InputMotion {
    /// True when the file moves nothing.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty() && self.targets.is_empty() && self.rig.is_empty()
    }
}

/// `input` per topology vertex: `input_vertex_map[i]` is input vertex `i`'s topology vertex, of
/// `vertices`. Returns the motion and how many input vertices were welded into a vertex whose
/// first input vertex has other joints, weights or morph deltas.
pub fn attach(input: InputMotion, input_vertex_map: &[u32], vertices: usize) -> (Motion, usize) {
    if input.is_empty() {
        return (Motion::default(), 0);
    }
    let first = first_inputs(input_vertex_map, vertices);
    let mut differ = vec![false; input_vertex_map.len()];
    let (mut joints, mut weights) = (Vec::new(), Vec::new());
    if !input.joints.is_empty() {
        let of = |v: usize| first[v] as usize;
        joints = (0..vertices).map(|v| input.joints[of(v)]).collect();
        weights = (0..vertices).map(|v| input.weights[of(v)]).collect();
        for (i, &v) in input_vertex_map.iter().enumerate() {
            let r = of(v as usize);
            differ[i] |= input.joints[i] != input.joints[r] || input.weights[i] != input.weights[r];
        }
    }
    let mut morph_starts = Vec::with_capacity(input.targets.len());
    let (mut morph_vertices, mut morph_deltas) = (Vec::new(), Vec::new());
    // Each input vertex's delta in the target at hand (zero elsewhere), reset after each target.
    let mut moved = vec![[0.0f32; 3]; input_vertex_map.len()];
    for target in input.targets {
        morph_starts.push(morph_vertices.len() as u32);
        // A delta of a vertex that is not its topology vertex's first is not kept; it differs from
        // the first's unless that one moves by the same amount.
        let mut kept: Vec<(u32, [f32; 3])> = Vec::with_capacity(target.len());
        for &(i, delta) in &target {
            let v = input_vertex_map[i as usize];
            if first[v as usize] == i {
                kept.push((v, delta));
            }
            moved[i as usize] = delta;
        }
        for (i, &v) in input_vertex_map.iter().enumerate() {
            differ[i] |= moved[i] != moved[first[v as usize] as usize];
        }
        for &(i, _) in &target {
            moved[i as usize] = [0.0; 3];
        }
        kept.sort_unstable_by_key(|&(v, _)| v);
        for (v, delta) in kept {
            morph_vertices.push(v);
            morph_deltas.push(delta);
        }
    }
    let motion = Motion {
        joints,
        weights,
        morph_starts,
        morph_vertices,
        morph_deltas,
        rig: input.rig,
    };
    (motion, differ.iter().filter(|&&d| d).count())
}

/// Per topology vertex (`input_vertex_map[i]` is input vertex `i`'s, of `vertices`), a number
/// shared by the vertices that always move together: the same joints and weights and no morph
/// target (each vertex a morph target moves is a group of its own).
pub fn rigid_groups(input: &InputMotion, input_vertex_map: &[u32], vertices: usize) -> Vec<u32> {
    let mut morphed = vec![false; vertices];
    for &(i, _) in input.targets.iter().flatten() {
        morphed[input_vertex_map[i as usize] as usize] = true;
    }
    let first = first_inputs(input_vertex_map, vertices);
    let mut groups = std::collections::HashMap::new();
    // Groups are numbered in order of appearance; a morphed vertex is one of its own.
    let mut next = 0u32;
    let mut new_group = || {
        next += 1;
        next - 1
    };
    (0..vertices)
        .map(|v| {
            if morphed[v] {
                return new_group();
            }
            let i = first[v] as usize;
            let skin = match input.joints.get(i) {
                Some(joints) => (*joints, input.weights[i].map(f32::to_bits)),
                None => ([0; INFLUENCES], [0; INFLUENCES]),
            };
            *groups.entry(skin).or_insert_with(&mut new_group)
        })
        .collect()
}

/// The first input vertex welded into each of the `vertices` topology vertices.
fn first_inputs(input_vertex_map: &[u32], vertices: usize) -> Vec<u32> {
    let mut first = vec![u32::MAX; vertices];
    for (i, &v) in input_vertex_map.iter().enumerate().rev() {
        first[v as usize] = i as u32;
    }
    first
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welded_vertices_take_their_first_input_vertex_and_differences_are_counted() {
        let rig = Rig {
            morph_weights: vec![0.0],
            morph_names: vec![String::new()],
            ..Rig::default()
        };
        let input = InputMotion {
            joints: vec![[0; 4], [1, 0, 0, 0], [1, 0, 0, 0]],
            weights: vec![[1.0, 0.0, 0.0, 0.0]; 3],
            // Input vertex 2 is welded into vertex 0 (first input vertex 1) and moves like it.
            targets: vec![vec![
                (2, [1.0, 0.0, 0.0]),
                (1, [1.0, 0.0, 0.0]),
                (0, [0.0, 2.0, 0.0]),
            ]],
            rig,
        };
        let (motion, differ) = attach(input, &[1, 0, 0], 2);
        assert_eq!(motion.joints, [[1, 0, 0, 0], [0; 4]]);
        assert_eq!(motion.morph_vertices, [0, 1]);
        assert_eq!(motion.morph_deltas, [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]]);
        assert_eq!(differ, 0);
        let input = InputMotion {
            joints: vec![[0; 4], [1, 0, 0, 0], [2, 0, 0, 0]],
            weights: vec![[1.0, 0.0, 0.0, 0.0]; 3],
            targets: Vec::new(),
            rig: Rig::default(),
        };
        assert_eq!(attach(input, &[1, 0, 0], 2).1, 1);
    }

    #[test]
    fn vertices_share_a_group_only_when_they_always_move_together() {
        let input = InputMotion {
            joints: vec![[0; 4], [0; 4], [1, 0, 0, 0], [0; 4]],
            weights: vec![[1.0, 0.0, 0.0, 0.0]; 4],
            // Input vertex 3 is morphed: its topology vertex is a group of its own.
            targets: vec![vec![(3, [0.0, 1.0, 0.0])]],
            rig: Rig::default(),
        };
        let groups = rigid_groups(&input, &[0, 1, 2, 3], 4);
        assert_eq!(groups[0], groups[1], "same joints and weights");
        assert_ne!(groups[0], groups[2], "another joint");
        assert!(groups[3] != groups[0] && groups[3] != groups[2], "morphed");
    }
}
