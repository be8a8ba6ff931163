//! Reading glTF accessors, checked against their buffers: any component type (KHR_mesh_quantization
//! allows integer positions and normals), normalized or not, interleaved strides, and sparse
//! substitution. Nothing here can read out of bounds or allocate more than the file implies.

use std::borrow::Cow;

use gltf::json::{self, accessor::ComponentType, validation::Checked};

/// Accessors without a buffer view are all zeros (plus sparse values); more than this many
/// elements of nothing is an attack, not a mesh.
const MAX_IMPLICIT_ELEMENTS: u64 = 1 << 24;

pub(super) struct Accessors<'a> {
    pub root: &'a json::Root,
    pub buffers: &'a [Cow<'a, [u8]>],
}

impl Accessors<'_> {
    /// The element count an accessor declares, if it exists.
    pub fn count(&self, index: usize) -> Option<u64> {
        self.root.accessors.get(index).map(|a| a.count.0)
    }

    /// Reads a VECn accessor as floats (integers converted, normalized if the accessor says so).
    pub fn read_vectors<const N: usize>(&self, index: usize) -> Result<Vec<[f32; N]>, String> {
        let (values, components) = self.read(index)?;
        if components != N {
            return Err(format!(
                "accessor {index} has {components} components, expected {N}"
            ));
        }
        Ok(values
            .chunks_exact(N)
            .map(|c| std::array::from_fn(|k| c[k] as f32))
            .collect())
    }

    /// Reads an index accessor (unsigned byte, short or int scalars).
    pub fn read_indices(&self, index: usize) -> Result<Vec<u32>, String> {
        let accessor = self.get(index)?;
        let component = component_type(accessor, index)?;
        if !matches!(
            component,
            ComponentType::U8 | ComponentType::U16 | ComponentType::U32
        ) || accessor.normalized
        {
            return Err(format!(
                "accessor {index} cannot hold indices ({component:?})"
            ));
        }
        let (values, components) = self.read(index)?;
        if components != 1 {
            return Err(format!("index accessor {index} is not SCALAR"));
        }
        Ok(values.into_iter().map(|v| v as u32).collect())
    }

    fn get(&self, index: usize) -> Result<&json::Accessor, String> {
        self.root
            .accessors
            .get(index)
            .ok_or_else(|| format!("accessor {index} does not exist"))
    }

    /// All components of all elements, in f64 (exact for every glTF component type).
    fn read(&self, index: usize) -> Result<(Vec<f64>, usize), String> {
        let accessor = self.get(index)?;
        let component = component_type(accessor, index)?;
        let components = match accessor.type_ {
            Checked::Valid(t) => t.multiplicity(),
            Checked::Invalid => return Err(format!("accessor {index} has an invalid type")),
        };
        let count = accessor.count.0;
        let element_size = component.size() * components;
        let decode = |bytes: &[u8]| decode_component(bytes, component, accessor.normalized);

        let mut values = match accessor.buffer_view {
            Some(view) => {
                let (data, stride) = self.view(view.value(), element_size)?;
                let start = accessor.byte_offset.map_or(0, |o| o.0);
                // Offsets, strides and counts are the file's: any sum or product may overflow.
                let needed = if count == 0 {
                    Some(0)
                } else {
                    (count - 1)
                        .checked_mul(stride as u64)
                        .and_then(|b| b.checked_add(start))
                        .and_then(|b| b.checked_add(element_size as u64))
                };
                if needed.is_none_or(|n| n > data.len() as u64) {
                    return Err(format!(
                        "accessor {index} ({count} elements) runs past the end of its buffer view"
                    ));
                }
                let mut values = Vec::with_capacity(count as usize * components);
                for e in 0..count as usize {
                    let at = start as usize + e * stride;
                    let element = &data[at..at + element_size];
                    values.extend(element.chunks_exact(component.size()).map(decode));
                }
                values
            }
            None if count <= MAX_IMPLICIT_ELEMENTS => vec![0.0; count as usize * components],
            None => return Err(format!("accessor {index} has {count} elements and no data")),
        };
        if let Some(sparse) = &accessor.sparse {
            self.apply_sparse(
                index,
                sparse,
                component,
                accessor.normalized,
                components,
                count,
                &mut values,
            )?;
        }
        if values.iter().any(|v| !v.is_finite()) {
            return Err(format!("accessor {index} holds a NaN or infinite value"));
        }
        Ok((values, components))
    }

    /// The bytes of a buffer view and its element stride.
    fn view(&self, index: usize, element_size: usize) -> Result<(&[u8], usize), String> {
        let view = self
            .root
            .buffer_views
            .get(index)
            .ok_or_else(|| format!("buffer view {index} does not exist"))?;
        let buffer = self
            .buffers
            .get(view.buffer.value())
            .ok_or_else(|| format!("buffer view {index} refers to a missing buffer"))?;
        let start = view.byte_offset.map_or(0, |o| o.0);
        let end = start
            .checked_add(view.byte_length.0)
            .filter(|&e| e <= buffer.len() as u64);
        let end =
            end.ok_or_else(|| format!("buffer view {index} runs past the end of its buffer"))?;
        let stride = view.byte_stride.map_or(element_size, |s| s.0);
        if stride < element_size {
            return Err(format!(
                "buffer view {index} has stride {stride}, smaller than an element ({element_size} bytes)"
            ));
        }
        Ok((&buffer[start as usize..end as usize], stride))
    }

    #[allow(clippy::too_many_arguments)]
    fn apply_sparse(
        &self,
        index: usize,
        sparse: &json::accessor::sparse::Sparse,
        component: ComponentType,
        normalized: bool,
        components: usize,
        count: u64,
        values: &mut [f64],
    ) -> Result<(), String> {
        let n = sparse.count.0;
        let index_type = match sparse.indices.component_type {
            Checked::Valid(t) => t.0,
            Checked::Invalid => return Err(format!("accessor {index}: invalid sparse index type")),
        };
        let index_size = index_type.size();
        let (index_data, _) = self.view(sparse.indices.buffer_view.value(), index_size)?;
        let index_start = sparse.indices.byte_offset.0 as usize;
        let element_size = component.size() * components;
        let (value_data, _) = self.view(sparse.values.buffer_view.value(), element_size)?;
        let value_start = sparse.values.byte_offset.0 as usize;
        let fits = |start: usize, size: usize, len: usize| {
            (n as usize)
                .checked_mul(size)
                .and_then(|b| b.checked_add(start))
                .is_some_and(|end| end <= len)
        };
        if n > count
            || !fits(index_start, index_size, index_data.len())
            || !fits(value_start, element_size, value_data.len())
        {
            return Err(format!(
                "accessor {index}: sparse data ({n} entries) does not fit its buffer views"
            ));
        }
        for i in 0..n as usize {
            let at = index_start + i * index_size;
            let target =
                decode_component(&index_data[at..at + index_size], index_type, false) as u64;
            if target >= count {
                return Err(format!(
                    "accessor {index}: sparse index {target} is out of range ({count} elements)"
                ));
            }
            let source =
                &value_data[value_start + i * element_size..value_start + (i + 1) * element_size];
            for (k, bytes) in source.chunks_exact(component.size()).enumerate() {
                values[target as usize * components + k] =
                    decode_component(bytes, component, normalized);
            }
        }
        Ok(())
    }
}

fn component_type(accessor: &json::Accessor, index: usize) -> Result<ComponentType, String> {
    match accessor.component_type {
        Checked::Valid(t) => Ok(t.0),
        Checked::Invalid => Err(format!("accessor {index} has an invalid component type")),
    }
}

/// One little-endian component; normalized integers map to [0, 1] or [-1, 1] as the spec defines.
fn decode_component(bytes: &[u8], component: ComponentType, normalized: bool) -> f64 {
    let (value, max) = match component {
        ComponentType::I8 => (f64::from(bytes[0] as i8), 127.0),
        ComponentType::U8 => (f64::from(bytes[0]), 255.0),
        ComponentType::I16 => (f64::from(i16::from_le_bytes([bytes[0], bytes[1]])), 32767.0),
        ComponentType::U16 => (f64::from(u16::from_le_bytes([bytes[0], bytes[1]])), 65535.0),
        ComponentType::U32 => (
            f64::from(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
            4294967295.0,
        ),
        ComponentType::F32 => {
            return f64::from(f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]));
        }
    };
    if normalized {
        (value / max).max(-1.0)
    } else {
        value
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalized_integers_follow_the_spec() {
        assert_eq!(decode_component(&[0x81], ComponentType::I8, true), -1.0); // -127/127
        assert_eq!(decode_component(&[0x80], ComponentType::I8, true), -1.0); // -128 clamps
        assert_eq!(decode_component(&[255], ComponentType::U8, true), 1.0);
        assert_eq!(
            decode_component(&[0xff, 0x7f], ComponentType::I16, true),
            1.0
        );
        assert_eq!(
            decode_component(&[0x00, 0x80], ComponentType::I16, false),
            -32768.0
        );
        assert_eq!(
            decode_component(&1.5f32.to_le_bytes(), ComponentType::F32, true),
            1.5
        );
    }
}
