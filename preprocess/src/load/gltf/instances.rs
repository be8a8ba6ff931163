//! Flattening a glTF node graph into the (mesh, world transform) pairs it draws, counted first.
//!
//! The specification asks for a strict tree, but a file is free to list a child twice or under two
//! parents: forty nodes that each list the next one twice draw 2⁴⁰ instances from 1.5 KB. So the
//! graph is walked once, each node once, to count how many node and primitive instances it would
//! expand into (a node reached again through its own subtree is a cycle and refused); only when
//! that count is within [`Limits::max_instances`] is it expanded. A node with
//! `EXT_mesh_gpu_instancing` counts its mesh's primitives once per instance (`gpu_instancing.rs`);
//! those instances are expanded once the buffers holding their transforms are read.

use std::path::Path;

use glam::Mat4;
use gltf::json;

use super::{gpu_instancing, local_transform};
use crate::limits::Limited;
use crate::{Error, Limits};

/// One node drawing its mesh: the mesh, the node's world transform, and how many GPU instances
/// of it the node draws (`None`: once, without `EXT_mesh_gpu_instancing`).
#[derive(Clone, Copy, Debug)]
pub(super) struct NodeMesh {
    pub mesh: usize,
    pub world: Mat4,
    /// The node, for its `EXT_mesh_gpu_instancing` accessors (`None` when the file has no scene).
    pub node: Option<usize>,
    pub gpu_instances: Option<u64>,
}

impl NodeMesh {
    /// How many times the node draws its mesh.
    pub fn copies(&self) -> u64 {
        self.gpu_instances.unwrap_or(1)
    }
}

/// Every node that draws a mesh, with its world transform: the default scene's node graph, or each
/// mesh once, untransformed, when the file has no scene. Refuses cycles and more instances (a node
/// drawn once per path from a scene root, plus each primitive of its mesh once per GPU instance)
/// than `limits` allow.
pub(super) fn mesh_instances(
    path: &Path,
    root: &json::Root,
    limits: &Limits,
) -> Result<Vec<NodeMesh>, Error> {
    let invalid = |message: String| Error::Parse {
        path: path.to_owned(),
        format: "glTF",
        message,
    };
    let scene = root
        .scene
        .map(|s| s.value())
        .or((!root.scenes.is_empty()).then_some(0));
    let Some(scene) = scene else {
        let primitives = root
            .meshes
            .iter()
            .fold(0u64, |n, m| n.saturating_add(m.primitives.len() as u64));
        limits.check(path, Limited::Instances, primitives)?;
        return Ok((0..root.meshes.len())
            .map(|mesh| NodeMesh {
                mesh,
                world: Mat4::IDENTITY,
                node: None,
                gpu_instances: None,
            })
            .collect());
    };
    let scene = root
        .scenes
        .get(scene)
        .ok_or_else(|| invalid(format!("default scene {scene} does not exist")))?;
    let roots: Vec<usize> = scene.nodes.iter().map(|n| n.value()).collect();
    let per_node = count_instances(root, &roots).map_err(invalid)?;
    let total = roots
        .iter()
        .fold(0u64, |n, &r| n.saturating_add(per_node[r]));
    limits.check(path, Limited::Instances, total)?;

    let mut instances = Vec::new();
    let mut stack: Vec<(usize, Mat4)> = roots.iter().map(|&n| (n, Mat4::IDENTITY)).collect();
    while let Some((index, parent)) = stack.pop() {
        let node = root
            .nodes
            .get(index)
            .ok_or_else(|| invalid(format!("node {index} does not exist")))?;
        let world = parent * local_transform(node);
        if let Some(m) = node.mesh {
            instances.push(NodeMesh {
                mesh: m.value(),
                world,
                node: Some(index),
                gpu_instances: gpu_instancing::count(root, node)
                    .map_err(|e| invalid(format!("node {index}: {e}")))?,
            });
        }
        for child in node.children.iter().flatten() {
            stack.push((child.value(), world));
        }
    }
    instances.reverse(); // depth-first in document order
    Ok(instances)
}

/// For every node reachable from `roots`, how many instances its subtree expands into: itself,
/// the primitives of its mesh (times its GPU instances), and its children's counts (saturating).
/// Each node is visited once.
fn count_instances(root: &json::Root, roots: &[usize]) -> Result<Vec<u64>, String> {
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        New,
        Open,
        Counted,
    }
    let mut state = vec![State::New; root.nodes.len()];
    let mut count = vec![0u64; root.nodes.len()];
    let node = |index: usize| {
        root.nodes
            .get(index)
            .ok_or_else(|| format!("node {index} does not exist"))
    };
    // An explicit stack: a chain of a hundred thousand nodes must not overflow the call stack.
    // `false` = enter the node, `true` = its children are counted, sum them.
    let mut stack: Vec<(usize, bool)> = roots.iter().map(|&r| (r, false)).collect();
    while let Some((index, children_done)) = stack.pop() {
        let n = node(index)?;
        if children_done {
            let primitives = n
                .mesh
                .and_then(|m| root.meshes.get(m.value()))
                .map_or(0, |m| m.primitives.len() as u64);
            // GPU instances count even when their mesh has no primitive: their transforms are read.
            let drawn =
                match gpu_instancing::count(root, n).map_err(|e| format!("node {index}: {e}"))? {
                    None => primitives,
                    Some(copies) => primitives.max(1).saturating_mul(copies),
                };
            let mut total = 1u64.saturating_add(drawn);
            for child in n.children.iter().flatten() {
                total = total.saturating_add(count[child.value()]);
            }
            count[index] = total;
            state[index] = State::Counted;
            continue;
        }
        match state[index] {
            State::Counted => continue,
            State::Open => return Err(format!("node {index} is part of a cycle")),
            State::New => {}
        }
        state[index] = State::Open;
        stack.push((index, true));
        for child in n.children.iter().flatten() {
            let child = child.value();
            node(child)?;
            match state[child] {
                State::Open => return Err(format!("node {child} is part of a cycle")),
                State::New => stack.push((child, false)),
                State::Counted => {}
            }
        }
    }
    Ok(count)
}
