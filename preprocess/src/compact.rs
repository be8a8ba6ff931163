//! The compact asset's encoders (format 5, issue 24): meshoptimizer's reference vertex and index
//! encoders through the `meshopt` crate, handed to
//! [`Asset::encode_compact`](chamfer_runtime::asset::Asset::encode_compact), which owns the format.

use chamfer_runtime::asset::{Asset, Codecs, CompactOptions};

/// meshoptimizer's encoders (compression level 2, its default; codec version 1).
#[derive(Clone, Copy, Debug, Default)]
pub struct Meshopt;

/// The vertex codec at its default level.
const LEVEL: i32 = 2;

impl Codecs for Meshopt {
    fn encode_vertices(&self, data: &[u8], stride: usize) -> Vec<u8> {
        fn encode<Vertex: bytemuck::Pod>(data: &[u8]) -> Vec<u8> {
            let vertices: &[Vertex] = bytemuck::cast_slice(data);
            meshopt::encode_vertex_buffer_level(vertices, LEVEL, None).unwrap_or_else(|e| {
                panic!("chamfer: meshopt vertex encoding failed ({e}); please report this")
            })
        }
        match stride {
            4 => encode::<[u8; 4]>(data),
            8 => encode::<[u8; 8]>(data),
            12 => encode::<[u8; 12]>(data),
            16 => encode::<[u8; 16]>(data),
            _ => panic!("chamfer: no vertex stride {stride} in the compact format"),
        }
    }

    fn encode_triangles(&self, indices: &[u32], vertex_count: usize) -> Vec<u8> {
        meshopt::encode_index_buffer(indices, vertex_count).unwrap_or_else(|e| {
            panic!("chamfer: meshopt index encoding failed ({e}); please report this")
        })
    }
}

/// Starts every triangle at the corner meshoptimizer's index codec would start it at (its winding
/// kept), so that a compact file's coded indices decode to exactly these (`indices` are triangles
/// of vertices below `vertex_count`). The codec's choice is its encoder's: run it and keep what it
/// decodes to. Leaves `indices` as they are if the codec fails (it does not, for such input).
pub(crate) fn rotate_as_the_codec(indices: &mut [u32], vertex_count: usize) {
    let Ok(stream) = meshopt::encode_index_buffer(indices, vertex_count) else {
        return;
    };
    if let Ok(decoded) = meshopt::decode_index_buffer::<u32>(&stream, indices.len()) {
        indices.copy_from_slice(&decoded);
    }
}

/// Writes `asset` raw ([`Asset::encode`]) or, with `compact`, as a compact file.
pub fn encode(
    asset: &Asset,
    compact: Option<&CompactOptions>,
    out: &mut impl std::io::Write,
) -> std::io::Result<()> {
    match compact {
        Some(options) => asset.encode_compact(options, &Meshopt, out),
        None => asset.encode(out),
    }
}
