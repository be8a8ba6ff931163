//! Writes a generated torus of `N × N` quads (`2 N²` triangles) as a binary little-endian PLY, for the
//! large-asset rows of BENCHMARKS.md (issue 14: a 10 M-triangle mesh must bake, load and render).
//!
//! ```text
//! cargo run --release -p chamfer-preprocess --example large_mesh -- 2240 /tmp/torus-10m.ply
//! ```
//! The tube's radius swings with 24 bumps around the ring, so contours are long and change with the
//! camera; every vertex is shared, so the bake welds nothing and keeps every edge.

use std::io::Write;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let n: u32 = args.next().ok_or("usage: large_mesh N OUT.ply")?.parse()?;
    let out = args.next().ok_or("usage: large_mesh N OUT.ply")?;
    if n < 3 || u64::from(n) * u64::from(n) > u64::from(u32::MAX / 2) {
        return Err("N must be at least 3 and 2 N² fit 32 bits".into());
    }
    let vertices = n * n;
    let triangles = 2 * n * n;
    let mut file = std::io::BufWriter::new(std::fs::File::create(&out)?);
    write!(
        file,
        "ply\nformat binary_little_endian 1.0\nelement vertex {vertices}\nproperty float x\nproperty float y\nproperty float z\nelement face {triangles}\nproperty list uchar int vertex_indices\nend_header\n"
    )?;
    let tau = std::f32::consts::TAU;
    for i in 0..n {
        let u = i as f32 / n as f32 * tau;
        let tube = 0.3 + 0.06 * (24.0 * u).sin();
        for j in 0..n {
            let v = j as f32 / n as f32 * tau;
            let r = 1.0 + tube * v.cos();
            for c in [r * u.cos(), tube * v.sin(), r * u.sin()] {
                file.write_all(&c.to_le_bytes())?;
            }
        }
    }
    let at = |i: u32, j: u32| (i % n) * n + (j % n);
    for i in 0..n {
        for j in 0..n {
            let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            for tri in [[a, d, c], [a, c, b]] {
                file.write_all(&[3])?;
                for v in tri {
                    file.write_all(&v.to_le_bytes())?;
                }
            }
        }
    }
    file.flush()?;
    println!("{out}: {vertices} vertices, {triangles} triangles");
    Ok(())
}
