//! numpy in and out. Out: read-only views of an asset's sections that share its memory (no copy;
//! the asset stays alive as long as a view does). In: a mesh's vertices and faces, checked for
//! dtype, shape and index range, converted to the library's `Mesh` arrays.

use glam::Vec3;
use numpy::ndarray::{ArrayView, IxDyn, ShapeBuilder};
use numpy::{Element, PyArray2, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors;

/// A read-only array of `shape` over `data` (C order), owned by `owner`, which must keep `data`
/// alive and unchanged for as long as it lives (a frozen asset does).
pub fn view<'py, T: Element>(
    owner: &Bound<'py, PyAny>,
    data: &[T],
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let array = ArrayView::from_shape(IxDyn(shape), data)
        .map_err(|e| errors::internal(format!("a section does not have its shape: {e}")))?;
    share(owner, &array)
}

/// A read-only one-dimensional array of every `step`-th element of `data`: a field of an
/// interleaved section (the flags in the low half of each attribute word).
pub fn strided<'py, T: Element>(
    owner: &Bound<'py, PyAny>,
    data: &[T],
    count: usize,
    step: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let array = ArrayView::from_shape(IxDyn(&[count]).strides(IxDyn(&[step])), data)
        .map_err(|e| errors::internal(format!("a section does not have its shape: {e}")))?;
    share(owner, &array)
}

fn share<'py, T: Element>(
    owner: &Bound<'py, PyAny>,
    array: &ArrayView<'_, T, IxDyn>,
) -> PyResult<Bound<'py, PyAny>> {
    // SAFETY: `owner` becomes the array's base object, so numpy keeps it alive while the array
    // lives; the memory belongs to `owner`'s frozen asset, which is never mutated or reallocated.
    let shared = unsafe { PyArrayDyn::borrow_from_array(array, owner.clone()) };
    // Python must not write into the asset either: clear the writeable flag. numpy refuses to set
    // it again on an array whose base exposes no writable buffer.
    let readonly = shared
        .try_readwrite()
        .map_err(|e| errors::internal(format!("cannot share a section: {e}")))?
        .make_nonwriteable();
    drop(readonly);
    Ok(shared.into_any())
}

/// `value` as a numpy array (`numpy.asarray`, no copy when it is one already).
fn as_array<'py>(value: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyUntypedArray>> {
    let py = value.py();
    let array = py
        .import("numpy")?
        .call_method1("asarray", (value,))?
        .cast_into::<PyUntypedArray>()?;
    Ok(array)
}

/// The `(N, 3)` array `value` named `what`, or ArrayError naming the mesh `name`.
fn rows_of_three<'py>(
    value: &Bound<'py, PyAny>,
    what: &str,
    name: &str,
) -> PyResult<Bound<'py, PyUntypedArray>> {
    let array =
        as_array(value).map_err(|e| errors::array(name, format!("{what} is not an array: {e}")))?;
    if array.ndim() != 2 || array.shape()[1] != 3 {
        return Err(errors::array(
            name,
            format!("{what} must have shape (N, 3), not {:?}", array.shape()),
        ));
    }
    Ok(array)
}

fn dtype_name(array: &Bound<'_, PyUntypedArray>) -> String {
    array
        .dtype()
        .str()
        .map_or_else(|_| "?".to_owned(), |s| s.to_string())
}

/// Vertex positions from an `(N, 3)` float32 or float64 array (float64 is rounded to float32, the
/// precision the library and the asset use).
pub fn positions(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<Vec3>> {
    let array = rows_of_three(value, "vertices", name)?;
    let borrow_error = |e| errors::array(name, format!("vertices cannot be read: {e}"));
    if let Ok(a) = array.cast::<PyArray2<f32>>() {
        let a = a.try_readonly().map_err(borrow_error)?;
        return Ok(a
            .as_array()
            .rows()
            .into_iter()
            .map(|r| Vec3::new(r[0], r[1], r[2]))
            .collect());
    }
    if let Ok(a) = array.cast::<PyArray2<f64>>() {
        let a = a.try_readonly().map_err(borrow_error)?;
        return Ok(a
            .as_array()
            .rows()
            .into_iter()
            .map(|r| Vec3::new(r[0] as f32, r[1] as f32, r[2] as f32))
            .collect());
    }
    Err(errors::array(
        name,
        format!(
            "vertices must be float32 or float64, not {}",
            dtype_name(&array)
        ),
    ))
}

/// Triangles from an `(M, 3)` integer array of any width; a negative index, or one too large for
/// 32 bits, raises ArrayError (indices past the last vertex are the bake's MeshError).
pub fn triangles(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<[u32; 3]>> {
    let array = rows_of_three(value, "faces", name)?;
    macro_rules! try_int {
        ($($t:ty),*) => {$(
            if let Ok(a) = array.cast::<PyArray2<$t>>() {
                return convert::<$t>(a, name);
            }
        )*};
    }
    try_int!(i64, i32, u32, u64, i16, u16, i8, u8);
    Err(errors::array(
        name,
        format!("faces must be integers, not {}", dtype_name(&array)),
    ))
}

fn convert<T>(array: &Bound<'_, PyArray2<T>>, name: &str) -> PyResult<Vec<[u32; 3]>>
where
    T: Element + Copy + std::fmt::Display,
    u32: TryFrom<T>,
{
    let array = array
        .try_readonly()
        .map_err(|e| errors::array(name, format!("faces cannot be read: {e}")))?;
    array
        .as_array()
        .rows()
        .into_iter()
        .enumerate()
        .map(|(row, r)| {
            let index = |k: usize| {
                u32::try_from(r[k]).map_err(|_| {
                    errors::array(
                        name,
                        format!("faces[{row}] has index {}, which is no vertex number", r[k]),
                    )
                })
            };
            Ok([index(0)?, index(1)?, index(2)?])
        })
        .collect()
}
