//! Test inputs as bytes, shared by every crate's tests (issue 40: they were written once per test
//! file): fixture paths, binary STL records, zip packages (3MF) and gzip members.

use std::io::Write;
use std::path::PathBuf;

/// A file under `fixtures/`.
pub fn fixture(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures")
        .join(relative)
}

/// A binary STL: `header` padded to 80 bytes, the declared triangle count `declared` (which a
/// hostile file sets apart from the records that follow), then a record per triangle with a zero
/// normal and attribute.
pub fn binary_stl(
    header: &[u8],
    declared: u32,
    triangles: impl IntoIterator<Item = [[f32; 3]; 3]>,
) -> Vec<u8> {
    let mut bytes = header.to_vec();
    bytes.resize(80, b' ');
    bytes.extend(declared.to_le_bytes());
    for triangle in triangles {
        bytes.extend([0u8; 12]);
        for v in triangle {
            bytes.extend(v.iter().flat_map(|c| c.to_le_bytes()));
        }
        bytes.extend([0u8; 2]);
    }
    bytes
}

/// A zip package of these parts, each stored or deflated by `method`; `None` where the writer
/// refuses a part (a fuzzer's mutated name).
pub fn try_zip(parts: &[(&str, &[u8])], method: zip::CompressionMethod) -> Option<Vec<u8>> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(method)
        .large_file(true);
    for (name, bytes) in parts {
        zip.start_file(*name, options).ok()?;
        zip.write_all(bytes).ok()?;
    }
    Some(zip.finish().ok()?.into_inner())
}

/// A zip package of these parts (see [`try_zip`]), deflated.
pub fn zip_deflated(parts: &[(&str, &[u8])]) -> Vec<u8> {
    try_zip(parts, zip::CompressionMethod::Deflated).expect("a zip package in memory")
}

/// `bytes` as one gzip member at `level` (0 to 9).
pub fn gzip(bytes: &[u8], level: u32) -> Vec<u8> {
    let mut encoder = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::new(level));
    encoder.write_all(bytes).expect("gzip into memory");
    encoder.finish().expect("gzip into memory")
}

/// Writes a gzip bomb to `path`: `head` and then `zero_mib` MiB of zeros, streamed (a few KB on
/// disk, never the whole in memory), at `level`.
pub fn gzip_bomb(path: &std::path::Path, head: &[u8], zero_mib: usize, level: u32) {
    let file = std::fs::File::create(path).expect("create the bomb");
    let mut gz = flate2::write::GzEncoder::new(file, flate2::Compression::new(level));
    gz.write_all(head).expect("write");
    let block = vec![0u8; 1 << 20];
    for _ in 0..zero_mib {
        gz.write_all(&block).expect("write");
    }
    gz.finish().expect("finish");
}
