//! The corners around each vertex of a triangle mesh: a compressed list (a counting sort), built
//! once and shared by what walks around vertices: the bake's split normals and next-index rings,
//! and the compact codec's edges and rings (one implementation for the bake and the decoder).

/// The corners (`3 * triangle + k`) at each vertex, in increasing order.
#[derive(Clone, Debug)]
pub struct VertexCorners {
    starts: Vec<u32>,
    corners: Vec<u32>,
}

impl VertexCorners {
    /// The corners of `triangles` (three vertex indices per triangle, flattened) at each of
    /// `vertex_count` vertices. Every index must be below `vertex_count` (panics otherwise), and
    /// there must be fewer than 2^32 corners: callers pass validated meshes.
    pub fn new(triangles: &[u32], vertex_count: usize) -> Self {
        let mut starts = vec![0u32; vertex_count + 1];
        for &v in triangles {
            starts[v as usize + 1] += 1;
        }
        for v in 0..vertex_count {
            starts[v + 1] += starts[v];
        }
        let mut cursor = starts.clone();
        let mut corners = vec![0u32; triangles.len()];
        for (c, &v) in triangles.iter().enumerate() {
            corners[cursor[v as usize] as usize] = c as u32;
            cursor[v as usize] += 1;
        }
        Self { starts, corners }
    }

    /// The corners at vertex `v`, in increasing order (so in triangle order).
    pub fn of(&self, v: u32) -> &[u32] {
        &self.corners[self.starts[v as usize] as usize..self.starts[v as usize + 1] as usize]
    }

    /// The number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.starts.len() - 1
    }
}
