//! The corners around each vertex: a compressed list, built once and shared by the steps that walk
//! around vertices (split normals, next-index rings).

/// The corners around each vertex, in triangle order (a counting sort).
pub(crate) struct VertexCorners {
    starts: Vec<u32>,
    corners: Vec<u32>,
}

impl VertexCorners {
    pub(crate) fn new(triangles: &[[u32; 3]], vertex_count: usize) -> Self {
        let mut starts = vec![0u32; vertex_count + 1];
        for &v in triangles.as_flattened() {
            starts[v as usize + 1] += 1;
        }
        for v in 0..vertex_count {
            starts[v + 1] += starts[v];
        }
        let mut cursor = starts.clone();
        let mut corners = vec![0u32; triangles.len() * 3];
        for (c, &v) in triangles.as_flattened().iter().enumerate() {
            corners[cursor[v as usize] as usize] = c as u32;
            cursor[v as usize] += 1;
        }
        Self { starts, corners }
    }

    /// The corners (`3 * triangle + k`) at vertex `v`, in triangle order.
    pub(crate) fn of(&self, v: u32) -> &[u32] {
        &self.corners[self.starts[v as usize] as usize..self.starts[v as usize + 1] as usize]
    }
}
