//! The decoders against meshoptimizer's reference encoder and decoder, and the ring and edge codes.

use super::*;

fn reference_vertices<Vertex: bytemuck::Pod>(data: &[u8]) -> Vec<u8> {
    let vertices: &[Vertex] = bytemuck::cast_slice(data);
    meshopt::encode_vertex_buffer(vertices).expect("encode")
}

fn reference_vertices_v0<Vertex: bytemuck::Pod>(data: &[u8]) -> Vec<u8> {
    let vertices: &[Vertex] = bytemuck::cast_slice(data);
    meshopt::encode_vertex_buffer_level(vertices, 2, Some(0)).expect("encode")
}

/// Bytes with runs, noise, constant columns and slow ramps: every group width and channel mode.
fn mixed_bytes(len: usize, seed: u32) -> Vec<u8> {
    let mut x = seed.wrapping_mul(2_654_435_761).max(1);
    (0..len)
        .map(|i| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            match (i / 997) % 5 {
                0 => 0,
                1 => (i / 7) as u8,
                2 => (x & 3) as u8,
                3 => (x >> 8) as u8,
                _ => ((i % 16) as u8).wrapping_mul(17) ^ (x & 1) as u8,
            }
        })
        .collect()
}

/// The vertex decoder's bytes for `count` vertices of `stride` bytes.
fn decode_bytes(
    encoded: &[u8],
    count: usize,
    stride: usize,
) -> Result<Vec<u8>, vertex_codec::CodecError> {
    vertex_codec::fits(encoded, count, stride)?;
    let mut out = vec![0u8; count * stride];
    vertex_codec::decode_into(encoded, &mut out, stride)?;
    Ok(out)
}

#[test]
fn the_vertex_decoder_reads_what_the_reference_encoder_writes() {
    for (count, seed) in [
        (1usize, 1u32),
        (15, 2),
        (16, 3),
        (17, 4),
        (255, 5),
        (256, 6),
        (257, 7),
        (5000, 8),
    ] {
        for stride in [4usize, 8, 12, 16] {
            let data = mixed_bytes(count * stride, seed + stride as u32);
            for encoded in [
                match stride {
                    4 => reference_vertices::<[u8; 4]>(&data),
                    8 => reference_vertices::<[u8; 8]>(&data),
                    12 => reference_vertices::<[u8; 12]>(&data),
                    _ => reference_vertices::<[u8; 16]>(&data),
                },
                match stride {
                    4 => reference_vertices_v0::<[u8; 4]>(&data),
                    8 => reference_vertices_v0::<[u8; 8]>(&data),
                    12 => reference_vertices_v0::<[u8; 12]>(&data),
                    _ => reference_vertices_v0::<[u8; 16]>(&data),
                },
            ] {
                let decoded = decode_bytes(&encoded, count, stride)
                    .unwrap_or_else(|e| panic!("{count} × {stride}: {e:?}"));
                assert_eq!(decoded, data, "{count} vertices of {stride} bytes");
            }
        }
    }
}

#[test]
fn the_vertex_decoder_refuses_what_the_reference_decoder_refuses() {
    let data = mixed_bytes(300 * 8, 9);
    let encoded = reference_vertices::<[u8; 8]>(&data);
    // Every truncation, a wrong count and flipped bytes: the same verdict as meshoptimizer's.
    for cut in (0..encoded.len()).step_by(7) {
        let ours = decode_bytes(&encoded[..cut], 300, 8);
        let theirs = meshopt::decode_vertex_buffer::<[u8; 8]>(&encoded[..cut], 300);
        assert_eq!(ours.is_ok(), theirs.is_ok(), "cut at {cut}");
    }
    // (A count within the last block's group of 16 decodes the same bytes: the stream does not
    // store the count, only the caller does.)
    for count in [0usize, 100, 256, 1 << 30] {
        assert!(decode_bytes(&encoded, count, 8).is_err(), "count {count}");
    }
    for at in (0..encoded.len()).step_by(3) {
        let mut bad = encoded.clone();
        bad[at] ^= 0x5a;
        let ours = decode_bytes(&bad, 300, 8);
        let theirs = meshopt::decode_vertex_buffer::<[u8; 8]>(&bad, 300);
        assert_eq!(ours.is_ok(), theirs.is_ok(), "byte {at} flipped");
        if let (Ok(a), Ok(b)) = (ours, theirs) {
            assert_eq!(
                a,
                bytemuck::cast_slice::<[u8; 8], u8>(&b),
                "byte {at} flipped"
            );
        }
    }
}

/// A grid of `n × n` quads, triangles in rows, vertices numbered by first use (as the bake's
/// order makes them), with a few triangles out of order.
fn grid_triangles(n: u32) -> Vec<u32> {
    let mut t = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let v = |dx: u32, dy: u32| (y + dy) * (n + 1) + x + dx;
            t.extend([v(0, 0), v(1, 0), v(1, 1), v(0, 0), v(1, 1), v(0, 1)]);
        }
    }
    let len = t.len();
    t.swap(3, len - 3);
    t
}

#[test]
fn the_index_decoder_reads_what_the_reference_encoder_writes() {
    for n in [1u32, 2, 7, 40] {
        let triangles = grid_triangles(n);
        let vertices = ((n + 1) * (n + 1)) as usize;
        let encoded = meshopt::encode_index_buffer(&triangles, vertices).expect("encode");
        let decoded = index_codec::decode(&encoded, triangles.len() / 3).expect("decode");
        let reference =
            meshopt::decode_index_buffer::<u32>(&encoded, triangles.len()).expect("decode");
        assert_eq!(decoded, reference, "{n} × {n} grid");
        // The codec may rotate a triangle's corners, never change its winding.
        for (d, t) in decoded.chunks(3).zip(triangles.chunks(3)) {
            assert!(
                (0..3).any(|r| (0..3).all(|k| d[k] == t[(k + r) % 3])),
                "{d:?} is not {t:?}"
            );
        }
        // Encoding what was decoded rotates nothing more.
        let again = meshopt::encode_index_buffer(&decoded, vertices).expect("encode");
        assert_eq!(again, encoded);
    }
    // Random triangles: free vertices, deltas both ways, resets.
    let noise = mixed_bytes(3 * 999, 11);
    let random: Vec<u32> = noise
        .chunks(3)
        .map(|c| u32::from(c[0]) * 3 + u32::from(c[1] & 3))
        .collect();
    let random: Vec<u32> = random
        .chunks_exact(3)
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .flatten()
        .copied()
        .collect();
    let encoded = meshopt::encode_index_buffer(&random, 800).expect("encode");
    let reference = meshopt::decode_index_buffer::<u32>(&encoded, random.len()).expect("decode");
    assert_eq!(
        index_codec::decode(&encoded, random.len() / 3).expect("decode"),
        reference
    );
}

#[test]
fn the_index_decoder_refuses_what_the_reference_decoder_refuses() {
    let triangles = grid_triangles(12);
    let encoded = meshopt::encode_index_buffer(&triangles, 169).expect("encode");
    let count = triangles.len();
    for cut in 0..encoded.len() {
        let ours = index_codec::decode(&encoded[..cut], count / 3);
        let theirs = meshopt::decode_index_buffer::<u32>(&encoded[..cut], count);
        assert_eq!(ours.is_ok(), theirs.is_ok(), "cut at {cut}");
    }
    for at in 0..encoded.len() {
        let mut bad = encoded.clone();
        bad[at] ^= 0xa5;
        let ours = index_codec::decode(&bad, count / 3);
        let theirs = meshopt::decode_index_buffer::<u32>(&bad, count);
        assert_eq!(ours.is_ok(), theirs.is_ok(), "byte {at} flipped");
        if let (Ok(a), Ok(b)) = (ours, theirs) {
            assert_eq!(a, b, "byte {at} flipped");
        }
    }
    assert!(index_codec::decode(&encoded, 1 << 30).is_err());
}

/// The quad 0 1 2 3 as triangles [0, 1, 2] and [0, 2, 3], its five edges by face a and then by
/// `v0`, and their corner bits.
fn quad() -> ([u32; 6], [u32; 20], edges::VertexCorners) {
    let triangles = [0, 1, 2, 0, 2, 3];
    let all = [
        0, 1, 2, 0, // corner 0: boundary
        1, 2, 0, 1, // corner 1: boundary
        2, 0, 1, 3, // corner 2: the diagonal, v3 from the second triangle
        2, 3, 0, 2, // corner 4
        3, 0, 2, 3, // corner 5
    ];
    let corners = edges::VertexCorners::new(&triangles, 4);
    (triangles, all, corners)
}

fn decode_edges(
    bits: &[u8],
    count: usize,
    triangles: &[u32],
    corners: &edges::VertexCorners,
) -> Result<Vec<u32>, String> {
    let bits = edges::CornerBits::new(bits, triangles, count)?;
    let mut out = vec![0; 4 * count];
    edges::decode_range(&bits, triangles, corners, 0..triangles.len() / 3, &mut out);
    Ok(out)
}

#[test]
fn rings_round_trip_through_their_orders() {
    let (triangles, all, corners) = quad();
    let bits = edges::encode(&all, &triangles, &corners).expect("codable");
    let bits = edges::CornerBits::new(&bits, &triangles, 5).expect("bits");
    // Ends (2 * edge + end) per vertex: 0: 0, 5, 9; 1: 1, 2; 2: 3, 4, 6; 3: 7, 8.
    let mut at = Vec::new();
    bits.ends_at(0, &corners, &mut at);
    assert_eq!(at, [0, 5, 9]);
    bits.ends_at(2, &corners, &mut at);
    assert_eq!(at, [3, 4, 6]);
    let mut next: Vec<u32> = (0..10).collect();
    (next[0], next[9], next[5]) = (9, 5, 0);
    (next[1], next[2]) = (2, 1);
    (next[3], next[6], next[4]) = (6, 4, 3);
    (next[7], next[8]) = (8, 7);
    let heads = [5, 2, 3, 7];
    let (code, code_bits) = rings::encode(&next, &heads, &bits, &corners).expect("codable");
    // 2 + 1 bits at vertex 0, 1 at vertex 1, 2 + 1 at vertex 2, 1 at vertex 3.
    assert_eq!(code_bits, 8);
    assert_eq!(
        rings::decode(&code, code_bits, &bits, &corners, 10),
        Ok((next.clone(), heads.to_vec()))
    );
    // Two cycles at one vertex, a missing head or heads out of order cannot be coded.
    let mut split = next.clone();
    (split[3], split[6], split[4]) = (3, 4, 6);
    assert!(rings::encode(&split, &heads, &bits, &corners).is_none());
    assert!(rings::encode(&next, &[5, 2, 3], &bits, &corners).is_none());
    assert!(rings::encode(&next, &[2, 5, 3, 7], &bits, &corners).is_none());
    // A rank past the ends left, and a code with bits to spare, are refused.
    assert!(rings::decode(&[0xff; 8], 8, &bits, &corners, 10).is_err());
    assert!(rings::decode(&code, code_bits + 1, &bits, &corners, 10).is_err());
}

#[test]
fn edges_are_one_bit_per_face_a_corner() {
    let (triangles, all, corners) = quad();
    let bits = edges::encode(&all, &triangles, &corners).expect("codable");
    assert_eq!(bits, vec![0b0011_0111]);
    assert_eq!(
        decode_edges(&bits, 5, &triangles, &corners),
        Ok(all.to_vec())
    );
    // The same mesh with its first triangle rotated, as the index codec may: the same edges.
    let rotated = [1, 2, 0, 0, 2, 3];
    let rotated_corners = edges::VertexCorners::new(&rotated, 4);
    let bits = edges::encode(&all, &rotated, &rotated_corners).expect("codable");
    assert_eq!(
        decode_edges(&bits, 5, &rotated, &rotated_corners),
        Ok(all.to_vec())
    );
    // The diagonal dropped (coplanar): still codable.
    let kept: Vec<u32> = all
        .chunks(4)
        .enumerate()
        .filter(|(e, _)| *e != 2)
        .flat_map(|(_, e)| e.to_vec())
        .collect();
    let bits = edges::encode(&kept, &triangles, &corners).expect("codable");
    assert_eq!(decode_edges(&bits, 4, &triangles, &corners), Ok(kept));
    // Out of order, or a v3 the rule does not give: not codable.
    let mut swapped = all.to_vec();
    swapped[..8].rotate_left(4);
    assert!(edges::encode(&swapped, &triangles, &corners).is_none());
    let mut wrong = all.to_vec();
    wrong[11] = 2;
    assert!(edges::encode(&wrong, &triangles, &corners).is_none());
    // A count that disagrees with the bits, bits past the last corner or too few bytes are refused.
    assert!(decode_edges(&[0b0011_0111], 4, &triangles, &corners).is_err());
    assert!(decode_edges(&[0b1011_0111], 6, &triangles, &corners).is_err());
    assert!(decode_edges(&[], 0, &triangles, &corners).is_err());
}

#[test]
fn quantized_positions_and_normals_stay_within_their_stated_bounds() {
    let grid = Grid::spanning(16, [-1.0, 0.0, 10.0], [3.0, 0.5, 10.0]);
    let bound = grid.error_bound();
    for i in 0..1000 {
        let t = i as f32 / 999.0;
        let p = [-1.0 + 4.0 * t, 0.5 * (1.0 - t) * t * 4.0, 10.0];
        let q = grid.position(grid.quantize(p));
        for k in 0..3 {
            assert!(
                (q[k] - p[k]).abs() <= bound,
                "{p:?} -> {q:?}, bound {bound}"
            );
        }
    }
    for bits in [8u32, 12, 16] {
        let bound = quantize::octahedral_error_bound(bits);
        let mut worst = 0.0f32;
        for i in 0..2000 {
            // A spiral over the whole sphere.
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / 2000.0;
            let r = (1.0 - z * z).sqrt();
            let a = i as f32 * 2.399_963;
            let n = [r * a.cos(), r * a.sin(), z];
            let d = quantize::decode_octahedral(quantize::encode_octahedral(n, bits), bits);
            let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            assert!((length - 1.0).abs() < 1e-6);
            // The angle from the cross product, in f64: acos of an f32 dot is off by 5e-4 near 1.
            let (a, b) = (n.map(f64::from), d.map(f64::from));
            let cross = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            let sine = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
            let cosine = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            worst = worst.max(sine.atan2(cosine) as f32);
        }
        assert!(worst <= bound, "{bits} bits: {worst} rad > {bound}");
        assert!(
            worst > bound / 20.0,
            "{bits} bits: the bound {bound} is far above {worst}"
        );
    }
}
