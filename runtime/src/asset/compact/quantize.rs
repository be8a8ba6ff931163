//! Lossy number formats of the compact asset: positions on a grid over their bounding box, unit
//! normals octahedral-encoded (Cigolle et al., "A Survey of Efficient Representations for
//! Independent Unit Vectors", JCGT 2014). Both are stated with their error bound.

/// A grid of `2^bits` steps per axis from `origin`: a position is stored as the nearest grid point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// Bits per axis, 1 to 16.
    pub bits: u32,
    /// The grid's first point (the bounding box's minimum corner).
    pub origin: [f32; 3],
    /// The distance between grid points along each axis.
    pub step: [f32; 3],
}

impl Grid {
    /// The grid of `bits` bits per axis spanning `min..=max`.
    pub fn spanning(bits: u32, min: [f32; 3], max: [f32; 3]) -> Self {
        let steps = ((1u32 << bits) - 1) as f32;
        Self {
            bits,
            origin: min,
            step: std::array::from_fn(|k| ((max[k] - min[k]) / steps).max(0.0)),
        }
    }

    /// The largest distance along any axis between a position in the box and its grid point
    /// (half a step, plus the rounding of the f32 arithmetic that rebuilds it).
    pub fn error_bound(&self) -> f32 {
        let extent =
            self.step.iter().fold(0.0f32, |m, &s| m.max(s)) * ((1u32 << self.bits) - 1) as f32;
        let origin = self.origin.iter().fold(0.0f32, |m, &o| m.max(o.abs()));
        self.step.iter().fold(0.0f32, |m, &s| m.max(s)) * 0.5
            + (origin + extent) * f32::EPSILON * 2.0
    }

    /// The grid coordinates of `p` (clamped into the grid).
    pub fn quantize(&self, p: [f32; 3]) -> [u16; 3] {
        let top = ((1u32 << self.bits) - 1) as f32;
        std::array::from_fn(|k| {
            if self.step[k] > 0.0 {
                ((p[k] - self.origin[k]) / self.step[k])
                    .round()
                    .clamp(0.0, top) as u16
            } else {
                0
            }
        })
    }

    /// The grid as stored: origin and step, six little-endian `f32`.
    pub fn to_bytes(&self) -> [u8; 24] {
        let mut bytes = [0u8; 24];
        for (k, v) in self.origin.iter().chain(&self.step).enumerate() {
            bytes[4 * k..4 * k + 4].copy_from_slice(&v.to_le_bytes());
        }
        bytes
    }

    /// The grid of `bits` stored as `bytes` ([`to_bytes`](Self::to_bytes)), if its numbers are
    /// finite and its steps not negative.
    pub fn from_bytes(bits: u32, bytes: &[u8; 24]) -> Option<Self> {
        let number = |k: usize| {
            f32::from_le_bytes([
                bytes[4 * k],
                bytes[4 * k + 1],
                bytes[4 * k + 2],
                bytes[4 * k + 3],
            ])
        };
        let grid = Self {
            bits,
            origin: std::array::from_fn(number),
            step: std::array::from_fn(|k| number(3 + k)),
        };
        let finite = grid.origin.iter().chain(&grid.step).all(|v| v.is_finite());
        (finite && grid.step.iter().all(|&s| s >= 0.0)).then_some(grid)
    }

    /// The position of grid point `q`.
    pub fn position(&self, q: [u16; 3]) -> [f32; 3] {
        std::array::from_fn(|k| self.origin[k] + f32::from(q[k]) * self.step[k])
    }
}

/// The octahedral code of unit vector `n` with `bits` bits per component (2 to 16), chosen among the
/// four nearest codes as the one that decodes closest to `n`.
pub fn encode_octahedral(n: [f32; 3], bits: u32) -> [i16; 2] {
    let scale = ((1i32 << (bits - 1)) - 1) as f32;
    let l1 = n[0].abs() + n[1].abs() + n[2].abs();
    let (mut x, mut y) = if l1 > 0.0 {
        (n[0] / l1, n[1] / l1)
    } else {
        (0.0, 0.0)
    };
    if n[2] < 0.0 {
        (x, y) = ((1.0 - y.abs()) * x.signum(), (1.0 - x.abs()) * y.signum());
    }
    let (fx, fy) = ((x * scale).floor(), (y * scale).floor());
    let mut best = [0i16; 2];
    let mut best_dot = f32::NEG_INFINITY;
    for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
        let code = [
            (fx + dx).clamp(-scale, scale) as i16,
            (fy + dy).clamp(-scale, scale) as i16,
        ];
        let d = decode_octahedral(code, bits);
        let dot = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        if dot > best_dot {
            (best, best_dot) = (code, dot);
        }
    }
    best
}

/// The unit vector of octahedral code `code` (components within ±(2^(bits-1) - 1)).
pub fn decode_octahedral(code: [i16; 2], bits: u32) -> [f32; 3] {
    let scale = ((1i32 << (bits - 1)) - 1) as f32;
    let (mut x, mut y) = (f32::from(code[0]) / scale, f32::from(code[1]) / scale);
    let z = 1.0 - x.abs() - y.abs();
    if z < 0.0 {
        (x, y) = ((1.0 - y.abs()) * x.signum(), (1.0 - x.abs()) * y.signum());
    }
    let length = (x * x + y * y + z * z).sqrt();
    [x / length, y / length, z / length]
}

/// The largest angle, in radians, between a unit vector and the decoding of its code with `bits`
/// bits: 5 code steps (the nearest of the four codes around a vector is within half a step's
/// diagonal in the square, which the octahedral map stretches by up to about 2.6 on the sphere;
/// measured below 4 steps over the sphere, see the tests).
pub fn octahedral_error_bound(bits: u32) -> f32 {
    5.0 / ((1i32 << (bits - 1)) - 1) as f32
}
