//! Resolving glTF buffers: the GLB binary chunk, base64 `data:` URIs, or files beside the `.gltf`
//! (regular files inside its folder after following links, see [`crate::load::files`]).

use std::borrow::Cow;
use std::path::{Component, Path};

use base64::Engine;
use gltf::json;

use crate::Limits;
use crate::load::files::{Companions, RefusedReference, read_reference};

/// The bytes of every buffer, each at least as long as its declared `byteLength`. Only the first
/// buffer may be the GLB binary chunk (as the specification says), so a file listing a thousand
/// buffers without a `uri` does not make a thousand copies of it.
pub(super) fn load<'a>(
    root: &json::Root,
    blob: Option<&'a [u8]>,
    path: &Path,
    companions: Companions<'_>,
    limits: &Limits,
) -> Result<Vec<Cow<'a, [u8]>>, String> {
    root.buffers
        .iter()
        .enumerate()
        .map(|(i, buffer)| {
            let data = match buffer.uri.as_deref() {
                None if i == 0 => blob.map(Cow::Borrowed).ok_or_else(|| {
                    format!("buffer {i} has no uri and the file has no binary chunk")
                })?,
                None => {
                    return Err(format!(
                        "buffer {i} has no uri (only buffer 0 may be the GLB binary chunk)"
                    ));
                }
                Some(uri) if uri.starts_with("data:") => Cow::Owned(
                    decode_data_uri(uri)
                        .ok_or_else(|| format!("buffer {i}: malformed or non-base64 data URI"))?,
                ),
                Some(uri) => {
                    let relative = relative_path(uri).map_err(|e| format!("buffer {i}: {e}"))?;
                    let bytes = read_reference(path, &relative, limits.max_input_bytes, companions)
                        .map_err(|e| match e {
                            RefusedReference::Missing => {
                                format!("buffer {i}: uri '{uri}' names a file that does not exist")
                            }
                            RefusedReference::Refused(problem) => {
                                format!("buffer {i}: uri '{uri}' {problem}")
                            }
                        })?;
                    Cow::Owned(bytes)
                }
            };
            if (data.len() as u64) < buffer.byte_length.0 {
                return Err(format!(
                    "buffer {i} declares {} bytes but holds {}",
                    buffer.byte_length.0,
                    data.len()
                ));
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
pub(crate) fn relative_path(uri: &str) -> Result<std::path::PathBuf, String> {
    if uri.is_empty() {
        return Err("uri is empty (it must name a file beside the glTF, or be a data: URI)".into());
    }
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
            "",
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
