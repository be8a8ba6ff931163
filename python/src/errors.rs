//! The package's exceptions: one base class, [`ChamferError`], and one subclass per kind of
//! problem, each raised with the library's message (which names the file and what is wrong) and the
//! file as its `path` attribute (`None` where no file is involved).

use std::path::{Path, PathBuf};

use chamfer_preprocess::Error;
use chamfer_runtime::asset::DecodeError;
use pyo3::PyTypeInfo;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

pyo3::create_exception!(
    chamfer,
    ChamferError,
    PyException,
    "Base class of every error chamfer raises; `path` names the file (or None)."
);
pyo3::create_exception!(
    chamfer,
    ReadError,
    ChamferError,
    "An input could not be read: missing, not a regular file, or a file it refers to was refused."
);
pyo3::create_exception!(
    chamfer,
    WriteError,
    ChamferError,
    "An output could not be written, or would replace an input or another output."
);
pyo3::create_exception!(
    chamfer,
    FormatError,
    ChamferError,
    "A file is not valid in its format (truncated, wrong header, ...), or its extension names no format chamfer reads."
);
pyo3::create_exception!(
    chamfer,
    UnsupportedError,
    FormatError,
    "A valid file uses something chamfer does not support (a required glTF extension, ...)."
);
pyo3::create_exception!(
    chamfer,
    MeshError,
    ChamferError,
    "The mesh loaded but cannot be baked (NaN positions, indices out of range, no triangles, ...)."
);
pyo3::create_exception!(
    chamfer,
    LimitError,
    ChamferError,
    "A file asks for more than the limits allow (max_triangles, max_vertices, max_instances, max_input_bytes, max_joints)."
);
pyo3::create_exception!(
    chamfer,
    OptionsError,
    ChamferError,
    "A bake, draw or batch option is unknown, of the wrong type or out of range."
);
pyo3::create_exception!(
    chamfer,
    ArrayError,
    ChamferError,
    "An array given to bake_arrays has the wrong dtype or shape, or indices that cannot be vertex numbers."
);
pyo3::create_exception!(
    chamfer,
    AssetError,
    ChamferError,
    "A file is not a valid .chamfer asset (wrong magic, unsupported version, inconsistent sections)."
);

/// The exception of `class` with `message`, its `path` attribute set.
fn raise<E: PyTypeInfo>(path: Option<&Path>, message: String) -> PyErr {
    Python::attach(|py| {
        let error = PyErr::new::<E, _>(message);
        let path = path.map(|p| p.display().to_string());
        // Setting an attribute on a fresh exception instance cannot fail in practice; if it did,
        // the exception would still carry its message, which names the file.
        let _ = error.value(py).setattr("path", path);
        error
    })
}

/// The library's error as the exception of its kind.
pub fn from_library(error: Error) -> PyErr {
    let message = error.to_string();
    match &error {
        Error::Read { path, .. } | Error::NotAFile { path, .. } | Error::Reference { path, .. } => {
            raise::<ReadError>(Some(path), message)
        }
        Error::Write { path, .. } | Error::OutputIsInput { path } => {
            raise::<WriteError>(Some(path), message)
        }
        Error::OutputClash { output, .. } => raise::<WriteError>(Some(output), message),
        Error::Parse { path, .. } | Error::UnknownFormat { path } => {
            raise::<FormatError>(Some(path), message)
        }
        Error::Unsupported { path, .. } => raise::<UnsupportedError>(Some(path), message),
        Error::Mesh { path, .. } => raise::<MeshError>(Some(path), message),
        Error::LimitExceeded { path, .. } => raise::<LimitError>(Some(path), message),
        Error::Options(_) => raise::<OptionsError>(None, message),
        // A variant added to the library later: still a ChamferError with its message.
        _ => raise::<ChamferError>(None, message),
    }
}

/// The library's error from writing `output`: a FIFO or device named as the output is a
/// WriteError (elsewhere NotAFile is about an input, a ReadError).
pub fn from_library_writing(error: Error, output: &Path) -> PyErr {
    match &error {
        Error::NotAFile { path, .. } if path == output => {
            raise::<WriteError>(Some(path), error.to_string())
        }
        _ => from_library(error),
    }
}

/// Why work done with the interpreter released failed; turned into the exception once it is held
/// again.
pub enum Failure {
    /// The library's error.
    Library(Error),
    /// The file is not a valid asset.
    Decode(PathBuf, DecodeError),
}

impl From<Error> for Failure {
    fn from(error: Error) -> Self {
        Self::Library(error)
    }
}

impl From<Failure> for PyErr {
    fn from(failure: Failure) -> Self {
        match failure {
            Failure::Library(e) => from_library(e),
            Failure::Decode(path, e) => from_decode(&path, e),
        }
    }
}

/// `path` is not a valid asset.
pub fn from_decode(path: &Path, error: DecodeError) -> PyErr {
    raise::<AssetError>(
        Some(path),
        format!("{}: not a valid .chamfer asset: {error}", path.display()),
    )
}

/// An option is wrong; `message` says which and why.
pub fn options(message: String) -> PyErr {
    raise::<OptionsError>(None, message)
}

/// An array given for the mesh `name` is wrong; `message` says which and why.
pub fn array(name: &str, message: String) -> PyErr {
    raise::<ArrayError>(Some(Path::new(name)), format!("{name}: {message}"))
}

/// Something the package's own code should have ruled out: a ChamferError with `message`,
/// never a crash.
pub fn internal(message: String) -> PyErr {
    raise::<ChamferError>(None, format!("{message} (please report this)"))
}

/// Registers the exception classes in the module.
pub fn register(module: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = module.py();
    module.add("ChamferError", py.get_type::<ChamferError>())?;
    module.add("ReadError", py.get_type::<ReadError>())?;
    module.add("WriteError", py.get_type::<WriteError>())?;
    module.add("FormatError", py.get_type::<FormatError>())?;
    module.add("UnsupportedError", py.get_type::<UnsupportedError>())?;
    module.add("MeshError", py.get_type::<MeshError>())?;
    module.add("LimitError", py.get_type::<LimitError>())?;
    module.add("OptionsError", py.get_type::<OptionsError>())?;
    module.add("ArrayError", py.get_type::<ArrayError>())?;
    module.add("AssetError", py.get_type::<AssetError>())?;
    Ok(())
}
