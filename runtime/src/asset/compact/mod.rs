//! The compact sections of format 5 (issue 24): what a shipped asset stores instead of the raw
//! arrays, and how they turn back into the same GPU-ready arrays.
//!
//! | coded section | replaces | payload (little-endian) |
//! |---|---|---|
//! | [`MeshIndicesCoded`](super::SectionKind::MeshIndicesCoded) | mesh indices | `u32` triangles, then meshoptimizer's index codec |
//! | [`TopologyPositionsCoded`](super::SectionKind::TopologyPositionsCoded) | topology positions | `u32` count, `u32` bits; for 1–16 bits a [`Grid`] (origin, step: 6 × `f32`) and `[u16; 4]` grid points, for 32 the `[f32; 3]` themselves; meshoptimizer's vertex codec |
//! | [`RenderNormalsCoded`](super::SectionKind::RenderNormalsCoded) | render normals | `u32` count, `u32` bits; for 2–16 bits `[i16; 2]` octahedral codes, for 32 the `[f32; 3]`; vertex codec |
//! | [`EdgeCorners`](super::SectionKind::EdgeCorners) | edge vertices | `u32` edges, then one bit per mesh corner (`edges.rs`) |
//! | [`EdgeAttributesCoded`](super::SectionKind::EdgeAttributesCoded) | edge attributes | `u32` count; vertex codec of the words |
//! | [`RingOrders`](super::SectionKind::RingOrders) | next ends and cap heads | `u64` bits of code, then the ring codes in whole `u64` words (`rings.rs`) |
//! | [`RenderVertexCountsCoded`](super::SectionKind::RenderVertexCountsCoded) | render vertex counts | `u32` count; vertex codec of the bytes, four per element |
//! | [`EdgeClustersCoded`](super::SectionKind::EdgeClustersCoded) | edge clusters | `u32` count, grid and radius unit; vertex codec of 16-byte bounds (`bounds.rs`) |
//!
//! Corner-relative edges need the mesh's topology triangles, which the render vertex counts give;
//! ring orders need corner-relative edges. A section the encoder cannot code (edges that do not
//! follow the bake's order, say) stays raw, so any asset can be written compact.
//!
//! The codecs are meshoptimizer's (zeux), whose reference encoder the bake calls through the
//! [`Codecs`] it is given; the decoders here are safe Rust (`vertex_codec.rs`, `index_codec.rs`).
//! `read.rs` decodes each section; `decode` puts them together, on two threads where it can.

mod bounds;
pub(crate) mod edges;
mod encode;
mod index_codec;
pub mod quantize;
pub(crate) mod read;
mod rings;
mod vertex_codec;

pub(crate) use encode::{encode, topology_triangles};
pub use quantize::Grid;

/// The stored value of `bits` that keeps the `f32` numbers themselves (lossless).
pub const LOSSLESS_BITS: u32 = 32;

/// How [`Asset::encode_compact`](super::Asset::encode_compact) stores the lossy sections.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompactOptions {
    /// Bits per axis of the topology positions' grid (1 to 16), or [`LOSSLESS_BITS`].
    pub position_bits: u32,
    /// The positions' largest error instead, in model units (issue 44): the grid gets the fewest
    /// bits per axis (1 to 16) whose error bound ([`Precision::position_error`]) is within it, and
    /// the positions stay exact where 16 bits are not enough. `position_bits` is then unused.
    pub position_error: Option<f32>,
    /// Bits per component of the normals' octahedral codes (2 to 16), or [`LOSSLESS_BITS`].
    pub normal_bits: u32,
}

impl Default for CompactOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl CompactOptions {
    /// 16 bits per axis for positions, 12 per component for normals.
    pub const DEFAULT: Self = Self {
        position_bits: 16,
        position_error: None,
        normal_bits: 12,
    };

    /// Every number lossless: the decoded asset equals the encoded one.
    pub const LOSSLESS: Self = Self {
        position_bits: LOSSLESS_BITS,
        position_error: None,
        normal_bits: LOSSLESS_BITS,
    };

    /// Why these options cannot be used, if they cannot.
    pub fn check(&self) -> Result<(), String> {
        if !(1..=16).contains(&self.position_bits) && self.position_bits != LOSSLESS_BITS {
            return Err(format!(
                "position bits must be 1 to 16, or {LOSSLESS_BITS} for lossless; got {}",
                self.position_bits
            ));
        }
        if let Some(error) = self.position_error.filter(|e| !(e.is_finite() && *e > 0.0)) {
            return Err(format!(
                "the position error must be a finite distance above 0; got {error}"
            ));
        }
        if !(2..=16).contains(&self.normal_bits) && self.normal_bits != LOSSLESS_BITS {
            return Err(format!(
                "normal bits must be 2 to 16, or {LOSSLESS_BITS} for lossless; got {}",
                self.normal_bits
            ));
        }
        Ok(())
    }
}

/// The precision a compact file stores its positions and normals with, read from its sections.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precision {
    /// Bits per axis of the positions' grid, or [`LOSSLESS_BITS`].
    pub position_bits: u32,
    /// The largest distance along an axis between a decoded position and the baked one (0 when
    /// lossless).
    pub position_error: f32,
    /// Bits per component of the normals' octahedral codes, or [`LOSSLESS_BITS`].
    pub normal_bits: u32,
    /// The largest angle, in radians, between a decoded normal and the baked one (0 when
    /// lossless).
    pub normal_error: f32,
}

impl Precision {
    /// What a file that is not compact (or a compact one without loss) stores: every number exact.
    pub const EXACT: Self = Self {
        position_bits: LOSSLESS_BITS,
        position_error: 0.0,
        normal_bits: LOSSLESS_BITS,
        normal_error: 0.0,
    };
}

/// The reference encoders of the two meshoptimizer codecs (the bake passes the `meshopt` crate's).
pub trait Codecs {
    /// `meshopt_encodeVertexBuffer` of `data`, vertices of `stride` bytes (a multiple of 4).
    fn encode_vertices(&self, data: &[u8], stride: usize) -> Vec<u8>;
    /// `meshopt_encodeIndexBuffer` of a triangle list whose indices are below `vertex_count`.
    fn encode_triangles(&self, indices: &[u32], vertex_count: usize) -> Vec<u8>;
}

#[cfg(test)]
mod tests;
