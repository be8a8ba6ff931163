//! Edge cluster bounds ([`clusters`](super::super::clusters)) in 16 bytes instead of 48, each
//! widened so that it still holds what it held: the centre on a 16-bit grid over the asset's box
//! (the radius grows by the distance the centre moved), the radius in whole units rounded up, the
//! cone's axis as a 16-bit octahedral code (the half-angle grows by the angle the axis moved) and
//! the half-angle in 65534ths of π rounded up (65535: the faces may look any way). The flags are not
//! stored: the loader takes the union of its edges' flags, which is exact and cheap.
//!
//! Storing them instead of computing them at load is what keeps a compact file's load below the
//! uncompressed file's (computing them is about half of the whole decode). The bake computes the
//! bounds from the positions the loader will see, so a quantized asset's clusters bound its own
//! edges, and the widening keeps every cluster conservative: a quantized bound never culls an edge
//! the exact bound would draw.
//!
//! Section layout: `u32` count, a [`Grid`] (origin and step, 6 × `f32`), the radius unit (`f32`),
//! then the records `[u16; 3]` centre, `u16` radius, `[i16; 2]` axis, `u16` half-angle, `u16` zero,
//! through meshoptimizer's vertex codec.

use glam::DVec3;

use super::super::clusters::{CLUSTER_EDGES, EdgeCluster, round_down};
use super::super::{EdgeFlags, attribute_flags};
use super::quantize::{Grid, decode_octahedral, encode_octahedral};

const GRID_BITS: u32 = 16;
const AXIS_BITS: u32 = 16;
/// The half-angle code of a cone that holds every direction.
const OPEN: u16 = u16::MAX;
/// Half-angle steps in π.
const ANGLE_STEPS: f64 = (u16::MAX - 1) as f64;
/// Bytes of one record.
pub(crate) const RECORD_BYTES: usize = 16;
/// Bytes before the records: the grid and the radius unit.
pub(crate) const PREFIX_BYTES: usize = 28;

/// The records of `clusters` of an asset whose positions lie in `min..=max`, after
/// [`PREFIX_BYTES`] of grid and unit; `None` if a bound cannot be held (it never is for clusters
/// of positions inside the box).
pub(crate) fn encode(
    clusters: &[EdgeCluster],
    min: [f32; 3],
    max: [f32; 3],
) -> Option<(Vec<u8>, Vec<[u16; 8]>)> {
    let grid = Grid::spanning(GRID_BITS, min, max);
    let diagonal = DVec3::from(max.map(f64::from)).distance(DVec3::from(min.map(f64::from)));
    let unit = match (diagonal / f64::from(u16::MAX) * (1.0 + 1e-6)) as f32 {
        u if u > 0.0 && u.is_finite() => u,
        _ => 1.0,
    };
    let mut prefix = grid.to_bytes().to_vec();
    prefix.extend(unit.to_le_bytes());
    let records = clusters
        .iter()
        .map(|c| record(c, &grid, unit))
        .collect::<Option<Vec<_>>>()?;
    Some((prefix, records))
}

fn record(c: &EdgeCluster, grid: &Grid, unit: f32) -> Option<[u16; 8]> {
    let q = grid.quantize(c.center);
    let center = DVec3::from(c.center.map(f64::from));
    let moved = DVec3::from(grid.position(q).map(f64::from)).distance(center);
    let needed = f64::from(c.radius) + moved;
    // Whole units, rounded up so that the f32 product the loader computes still holds `needed`.
    let units = (needed / f64::from(unit)).ceil();
    if !(0.0..=f64::from(u16::MAX)).contains(&units) {
        return None;
    }
    let radius = [units as u16, (units as u16).saturating_add(1)]
        .into_iter()
        .find(|&r| f64::from(f32::from(r) * unit) >= needed)?;
    let (axis, angle) = if c.cos_angle <= -1.0 {
        ([0, 0], OPEN)
    } else {
        let code = encode_octahedral(c.axis, AXIS_BITS);
        let old = DVec3::from(c.axis.map(f64::from));
        let new = DVec3::from(decode_octahedral(code, AXIS_BITS).map(f64::from));
        let turned = old.cross(new).length().atan2(old.dot(new)) + 1e-6;
        let half = f64::from(c.cos_angle).clamp(-1.0, 1.0).acos() + turned;
        let mut steps = (half / std::f64::consts::PI * ANGLE_STEPS).ceil();
        while half_angle(steps as u16) < half && steps < ANGLE_STEPS {
            steps += 1.0;
        }
        if steps >= ANGLE_STEPS {
            ([0, 0], OPEN)
        } else {
            (code, steps as u16)
        }
    };
    Some([
        q[0],
        q[1],
        q[2],
        radius,
        axis[0] as u16,
        axis[1] as u16,
        angle,
        0,
    ])
}

fn half_angle(steps: u16) -> f64 {
    f64::from(steps) * std::f64::consts::PI / ANGLE_STEPS
}

/// The clusters of `prefix` ([`PREFIX_BYTES`]) and `records` (decoded, [`RECORD_BYTES`] each),
/// their flags from `edge_attributes` (one cluster per [`CLUSTER_EDGES`] of them). `Err` says what
/// is wrong.
pub(crate) fn decode(
    prefix: &[u8; PREFIX_BYTES],
    records: &[u8],
    edge_attributes: &[u32],
) -> Result<Vec<EdgeCluster>, String> {
    let (grid, unit) = prefix
        .split_first_chunk::<24>()
        .map_or((None, 0.0), |(grid, unit)| {
            (
                Grid::from_bytes(GRID_BITS, grid),
                f32::from_le_bytes([unit[0], unit[1], unit[2], unit[3]]),
            )
        });
    let Some(grid) = grid.filter(|_| unit.is_finite() && unit > 0.0) else {
        return Err("grid or radius unit not finite, or negative".into());
    };
    let limit = (1i32 << (AXIS_BITS - 1)) - 1;
    let mut clusters = Vec::with_capacity(records.len() / RECORD_BYTES);
    for (index, (r, edges)) in records
        .chunks_exact(RECORD_BYTES)
        .zip(edge_attributes.chunks(CLUSTER_EDGES))
        .enumerate()
    {
        let word = |k: usize| u16::from_le_bytes([r[2 * k], r[2 * k + 1]]);
        let axis = [word(4) as i16, word(5) as i16];
        if axis.iter().any(|&a| i32::from(a).abs() > limit) || word(7) != 0 {
            return Err(format!(
                "cluster {index}: axis code or padding out of range"
            ));
        }
        let center = grid.position([word(0), word(1), word(2)]);
        if !center.iter().all(|v| v.is_finite()) {
            return Err(format!("cluster {index}: centre not finite"));
        }
        let mut flags = EdgeFlags::default();
        for &w in edges {
            flags |= attribute_flags(w);
        }
        let radius = f32::from(word(3)) * unit;
        if !radius.is_finite() {
            return Err(format!("cluster {index}: radius not finite"));
        }
        let (axis, cos_angle) = match word(6) {
            OPEN => ([0.0; 3], -1.0),
            steps => (
                decode_octahedral(axis, AXIS_BITS),
                round_down(half_angle(steps).cos()),
            ),
        };
        clusters.push(EdgeCluster::new(center, radius, axis, cos_angle, flags));
    }
    Ok(clusters)
}
