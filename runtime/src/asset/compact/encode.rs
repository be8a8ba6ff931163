//! Writing the coded sections of a compact file (the table in [`super`]): each section coded on
//! its own, from what the loader will decode of the sections before it, so that the corner bits
//! name the triangles as the index codec rotates them and the cluster bounds hold the quantized
//! positions.

use super::super::clusters::{self, cluster_count};
use super::super::join::join;
use super::super::{Asset, SectionKind};
use super::edges::{self, CornerBits, VertexCorners};
use super::quantize::{self, Grid};
use super::{Codecs, CompactOptions, LOSSLESS_BITS, bounds, index_codec, rings};

/// Assets at least this large are coded on two threads.
const PARALLEL_TRIANGLES: usize = 1 << 15;

/// The coded sections of `asset`, each replacing its raw twin; sections that cannot be coded (see
/// each encoder) are left out and stay raw. `render_counts` are the render vertex counts the file
/// stores (`None` when its render positions are stored instead).
pub(crate) fn encode(
    asset: &Asset,
    options: &CompactOptions,
    render_counts: Option<&[u8]>,
    codecs: &(dyn Codecs + Sync),
) -> Vec<(SectionKind, Vec<u8>)> {
    let parallel = asset.triangle_count() >= PARALLEL_TRIANGLES;
    let (mut coded, vertices) = join(
        parallel,
        || encode_mesh(asset, render_counts, codecs),
        || {
            let bits = position_bits(options, &asset.topology_positions);
            let (positions, seen) = encode_positions(asset, bits, codecs);
            let mut coded = vec![
                (SectionKind::TopologyPositionsCoded, positions),
                (
                    SectionKind::RenderNormalsCoded,
                    encode_normals(&asset.render_normals, options.normal_bits, codecs),
                ),
                (
                    SectionKind::EdgeAttributesCoded,
                    encode_words(&asset.edge_attributes, codecs),
                ),
            ];
            // Lossless files keep the exact clusters (raw): they decode to the asset itself.
            if *options != CompactOptions::LOSSLESS {
                coded.push(encode_clusters(asset, seen, codecs));
            }
            coded
        },
    );
    coded.extend(vertices);
    coded
}

/// The triangles, the render vertex counts, the edges as corner bits and the rings, each coded
/// when it can be.
fn encode_mesh(
    asset: &Asset,
    render_counts: Option<&[u8]>,
    codecs: &dyn Codecs,
) -> Vec<(SectionKind, Vec<u8>)> {
    let mut coded = Vec::new();
    let mut triangles = asset.mesh_indices.to_u32_vec();
    if !triangles.is_empty() {
        let stream = codecs.encode_triangles(&triangles, asset.render_normals.len());
        // The codec may rotate a triangle's corners: the edges are coded against the triangles
        // the loader will see. (A stream that did not decode would be a codec bug: the indices
        // then stay raw.)
        if let Ok(decoded) = index_codec::decode(&stream, triangles.len() / 3) {
            triangles = decoded;
            let mut bytes = count_prefix(triangles.len() / 3);
            bytes.extend(stream);
            coded.push((SectionKind::MeshIndicesCoded, bytes));
        }
    }
    let Some(counts) = render_counts else {
        return coded;
    };
    let mut padded = counts.to_vec();
    padded.resize(counts.len().next_multiple_of(4), 0);
    let mut bytes = count_prefix(counts.len());
    bytes.extend(codecs.encode_vertices(&padded, 4));
    coded.push((SectionKind::RenderVertexCountsCoded, bytes));

    let topology = topology_triangles(&triangles, counts);
    let vertex_count = asset.topology_positions.len();
    let corners = VertexCorners::new(&topology, vertex_count);
    let Some(bits) = edges::encode(&asset.edge_vertices.to_u32_vec(), &topology, &corners) else {
        return coded;
    };
    let mut bytes = count_prefix(asset.edge_count());
    bytes.extend(&bits);
    coded.push((SectionKind::EdgeCorners, bytes));
    if asset.next_ends.is_empty() {
        return coded;
    }
    let Ok(bits) = CornerBits::new(&bits, &topology, asset.edge_count()) else {
        return coded;
    };
    let code = rings::encode(
        &asset.next_ends.to_u32_vec(),
        &asset.cap_heads.to_u32_vec(),
        &bits,
        &corners,
    );
    if let Some((code, bits)) = code {
        let mut bytes = bits.to_le_bytes().to_vec();
        bytes.extend(code);
        coded.push((SectionKind::RingOrders, bytes));
    }
    coded
}

fn count_prefix(count: usize) -> Vec<u8> {
    (count as u32).to_le_bytes().to_vec()
}

/// The coded positions, and the positions the loader will decode from them. Positions whose box
/// is too wide for a grid of finite steps (beyond `f32`'s range) are kept exact.
/// The grid's bits per axis for `positions`: `options.position_bits`, or with a position error the
/// fewest whose grid keeps within it (its [`Grid::error_bound`], which the loader states), else
/// [`LOSSLESS_BITS`].
fn position_bits(options: &CompactOptions, positions: &[[f32; 3]]) -> u32 {
    let Some(error) = options.position_error else {
        return options.position_bits;
    };
    let (min, max) = extent(positions);
    (1..=16)
        .find(|&bits| Grid::spanning(bits, min, max).error_bound() <= error)
        .unwrap_or(LOSSLESS_BITS)
}

fn encode_positions(asset: &Asset, bits: u32, codecs: &dyn Codecs) -> (Vec<u8>, Vec<[f32; 3]>) {
    let positions = &asset.topology_positions;
    let (min, max) = extent(positions);
    let grid = Grid::spanning(bits.min(16), min, max);
    let points: Vec<[u16; 4]> = positions
        .iter()
        .map(|&p| {
            let [x, y, z] = grid.quantize(p);
            [x, y, z, 0]
        })
        .collect();
    let seen: Vec<[f32; 3]> = points
        .iter()
        .map(|&[x, y, z, _]| grid.position([x, y, z]))
        .collect();
    let gridded = bits != LOSSLESS_BITS
        && grid.step.iter().all(|s| s.is_finite())
        && seen.iter().flatten().all(|v| v.is_finite());
    let mut bytes = count_prefix(positions.len());
    if !gridded {
        bytes.extend(LOSSLESS_BITS.to_le_bytes());
        bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(positions), 12));
        return (bytes, positions.clone());
    }
    bytes.extend(bits.to_le_bytes());
    bytes.extend(grid.to_bytes());
    bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(&points), 8));
    (bytes, seen)
}

fn encode_normals(normals: &[[f32; 3]], bits: u32, codecs: &dyn Codecs) -> Vec<u8> {
    let mut bytes = count_prefix(normals.len());
    bytes.extend(bits.to_le_bytes());
    if bits == LOSSLESS_BITS {
        bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(normals), 12));
        return bytes;
    }
    let codes: Vec<[i16; 2]> = normals
        .iter()
        .map(|&n| quantize::encode_octahedral(n, bits))
        .collect();
    bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(&codes), 4));
    bytes
}

fn encode_words(words: &[u32], codecs: &dyn Codecs) -> Vec<u8> {
    let mut bytes = count_prefix(words.len());
    bytes.extend(codecs.encode_vertices(bytemuck::cast_slice(words), 4));
    bytes
}

/// The clusters of `asset` with its positions as the loader decodes them (`seen`): their bounds
/// coded, or raw when a bound cannot be coded (a box too small or too large for 16-bit units).
fn encode_clusters(
    asset: &Asset,
    seen: Vec<[f32; 3]>,
    codecs: &dyn Codecs,
) -> (SectionKind, Vec<u8>) {
    let (min, max) = extent(&seen);
    let view = Asset {
        topology_positions: seen,
        edge_vertices: asset.edge_vertices.clone(),
        edge_attributes: asset.edge_attributes.clone(),
        ..Asset::default()
    };
    let clusters = clusters::edge_clusters(&view);
    debug_assert_eq!(clusters.len(), cluster_count(asset.edge_count()));
    let Some((mut bytes, records)) = bounds::encode(&clusters, min, max) else {
        return (
            SectionKind::EdgeClusters,
            bytemuck::cast_slice(&clusters).to_vec(),
        );
    };
    let mut section = count_prefix(records.len());
    section.append(&mut bytes);
    section.extend(codecs.encode_vertices(bytemuck::cast_slice(&records), bounds::RECORD_BYTES));
    (SectionKind::EdgeClustersCoded, section)
}

/// The smallest box that holds `positions` (the origin's when there are none).
fn extent(positions: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    if positions.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    positions.iter().fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|k| lo[k].min(p[k])),
                std::array::from_fn(|k| hi[k].max(p[k])),
            )
        },
    )
}

/// The topology triangles: each render vertex of `triangles` replaced by the topology vertex whose
/// position it repeats (`counts[v]` render vertices per topology vertex, in order). Every index must
/// be below the counts' sum.
pub(crate) fn topology_triangles(triangles: &[u32], counts: &[u8]) -> Vec<u32> {
    let mut topology_of = Vec::with_capacity(counts.iter().map(|&c| usize::from(c)).sum());
    for (v, &count) in counts.iter().enumerate() {
        topology_of.extend(std::iter::repeat_n(v as u32, usize::from(count)));
    }
    triangles.iter().map(|&r| topology_of[r as usize]).collect()
}
