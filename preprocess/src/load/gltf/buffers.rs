//! Resolving glTF buffers: the GLB binary chunk, base64 `data:` URIs, or files beside the `.gltf`.

use std::path::{Component, Path};

use base64::Engine;
use gltf::json;

pub(super) enum BufferError {
    Read(std::io::Error),
    Invalid(String),
}

/// The bytes of every buffer, each at least as long as its declared `byteLength`.
pub(super) fn load(
    root: &json::Root,
    blob: Option<&[u8]>,
    path: &Path,
) -> Result<Vec<Vec<u8>>, BufferError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    root.buffers
        .iter()
        .enumerate()
        .map(|(i, buffer)| {
            let data = match buffer.uri.as_deref() {
                None => blob.map(<[u8]>::to_vec).ok_or_else(|| {
                    BufferError::Invalid(format!(
                        "buffer {i} has no uri and the file has no binary chunk"
                    ))
                })?,
                Some(uri) if uri.starts_with("data:") => decode_data_uri(uri).ok_or_else(|| {
                    BufferError::Invalid(format!("buffer {i}: malformed or non-base64 data URI"))
                })?,
                Some(uri) => std::fs::read(
                    dir.join(
                        relative_path(uri)
                            .map_err(|e| BufferError::Invalid(format!("buffer {i}: {e}")))?,
                    ),
                )
                .map_err(BufferError::Read)?,
            };
            if (data.len() as u64) < buffer.byte_length.0 {
                return Err(BufferError::Invalid(format!(
                    "buffer {i} declares {} bytes but holds {}",
                    buffer.byte_length.0,
                    data.len()
                )));
            }
            Ok(data)
        })
        .collect()
}

fn decode_data_uri(uri: &str) -> Option<Vec<u8>> {
    let (meta, payload) = uri.strip_prefix("data:")?.split_once(',')?;
    meta.ends_with(";base64").then_some(())?;
    base64::engine::general_purpose::STANDARD
        .decode(payload)
        .ok()
}

/// A URI that stays inside the `.gltf`'s folder: relative, no scheme, no `..`, percent-decoded.
fn relative_path(uri: &str) -> Result<std::path::PathBuf, String> {
    if uri.contains("://") || uri.starts_with('/') || uri.starts_with('\\') {
        return Err(format!("uri '{uri}' is not a relative file path"));
    }
    let decoded =
        percent_decode(uri).ok_or_else(|| format!("uri '{uri}' has a bad percent escape"))?;
    let path = Path::new(&decoded);
    if path
        .components()
        .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir))
    {
        return Err(format!("uri '{uri}' leaves the file's folder"));
    }
    Ok(path.to_owned())
}

fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_must_stay_beside_the_file() {
        assert!(relative_path("mesh%20data.bin").is_ok_and(|p| p == Path::new("mesh data.bin")));
        assert!(relative_path("sub/mesh.bin").is_ok());
        for bad in [
            "../secret.bin",
            "/etc/passwd",
            "http://example.com/a.bin",
            "a/../../b.bin",
            "%zz",
        ] {
            assert!(relative_path(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn data_uris_decode_base64_only() {
        assert_eq!(
            decode_data_uri("data:application/octet-stream;base64,AAEC"),
            Some(vec![0, 1, 2])
        );
        assert_eq!(decode_data_uri("data:application/octet-stream,AAEC"), None);
        assert_eq!(
            decode_data_uri("data:application/octet-stream;base64,@@"),
            None
        );
    }
}
