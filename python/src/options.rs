//! Bake options from Python keyword arguments, made from the bake's schema (issue 40,
//! `chamfer_preprocess::BakeSettings`): each keyword is an entry of its "bake" group, read as the
//! entry's kind, and the same keywords give the same asset as the same `chamfer bake` flags
//! (tests/test_bake.py checks every entry). `None` leaves an option at its default; the schema
//! checks conflicts, the library the ranges.

use chamfer_preprocess::{BakeOptions, BakeSettings};
use chamfer_runtime::camera::Orbit;
use chamfer_runtime::schema::{Entry, Kind, Schema, Value};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt};

use crate::errors;

/// The schema's group Python's bake functions take.
const GROUP: &str = "bake";

/// The Python type of a kind, for messages and the command line (`python -m chamfer.dask`).
const fn python_type(kind: Kind) -> &'static str {
    match kind {
        Kind::Number => "float",
        Kind::Count => "int",
        Kind::Flag => "bool",
        Kind::Numbers => "list",
    }
}

/// The options the keyword arguments `kwargs` name, checked; an unknown keyword, a value of the
/// wrong type, two conflicting options or a value out of range raises `OptionsError`.
pub fn from_kwargs(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<BakeOptions> {
    let mut settings = BakeSettings::default();
    let given = set_keywords(&mut settings, GROUP, kwargs, None)?;
    BakeSettings::check_names(&given).map_err(|e| errors::options(e.to_string()))?;
    settings.bake_options().map_err(|e| match e {
        chamfer_preprocess::SettingsError::Options(e) => errors::from_library(e.into()),
        other => errors::options(other.to_string()),
    })
}

/// The compact encoding the keywords `kwargs` ask for (the schema's "encoding" group, `chamfer
/// bake`'s `--compact`, `--position-bits`, ...), checked; `None` for the uncompressed format.
pub fn encoding_from_kwargs(
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Option<chamfer_runtime::asset::CompactOptions>> {
    let mut settings = BakeSettings::default();
    let given = set_keywords(&mut settings, "encoding", kwargs, None)?;
    BakeSettings::check_names(&given).map_err(|e| errors::options(e.to_string()))?;
    settings
        .compact_options()
        .map_err(|e| errors::options(e.to_string()))
}

/// The orbit camera the view keywords of `kwargs` set (the view schema, `chamfer.VIEW_SCHEMA`),
/// checked, and the other keywords (the bake options) in a new dict.
pub fn view_from_kwargs<'py>(
    py: Python<'py>,
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<(Orbit, Bound<'py, PyDict>)> {
    let (orbit, others) = group_from_kwargs::<Orbit>(py, "view", kwargs)?;
    orbit.check().map_err(|e| errors::options(e.to_string()))?;
    Ok((orbit, others))
}

/// The settings the keywords of `kwargs` in `group` of `S`'s schema set, their combinations
/// checked (the struct's own check is the caller's), and the other keywords in a new dict.
pub fn group_from_kwargs<'py, S: Schema>(
    py: Python<'py>,
    group: &str,
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<(S, Bound<'py, PyDict>)> {
    let mut settings = S::default();
    let others = PyDict::new(py);
    let given = set_keywords(&mut settings, group, kwargs, Some(&others))?;
    S::check_names(&given).map_err(|e| errors::options(e.to_string()))?;
    Ok((settings, others))
}

/// Sets into `settings` the keywords of `kwargs` that are entries of `group`, each read as its
/// entry's kind (`None` leaves one at its default), and returns the names given; a flag given
/// False is not given, as its flag left off the command line. Other keywords go into `others`
/// when it is given, and raise `OptionsError` when it is not.
fn set_keywords<S: Schema>(
    settings: &mut S,
    group: &str,
    kwargs: Option<&Bound<'_, PyDict>>,
    others: Option<&Bound<'_, PyDict>>,
) -> PyResult<Vec<&'static str>> {
    let mut given = Vec::new();
    let Some(kwargs) = kwargs else {
        return Ok(given);
    };
    for (key, value) in kwargs.iter() {
        let name: String = key.extract()?;
        let Some(entry) = S::entry(&name).ok().filter(|entry| entry.group == group) else {
            match others {
                Some(others) => {
                    others.set_item(key, value)?;
                    continue;
                }
                None => {
                    return Err(errors::options(format!(
                        "unknown option {name:?} (chamfer.OPTIONS lists the options)"
                    )));
                }
            }
        };
        if value.is_none() {
            continue;
        }
        let value = read(entry, &value)?;
        entry
            .set(settings, value)
            .map_err(|e| errors::options(e.to_string()))?;
        if value != Value::Flag(false) {
            given.push(entry.name);
        }
    }
    Ok(given)
}

/// `value` read as `entry`'s kind.
fn read<S: Schema>(entry: &Entry<S>, value: &Bound<'_, PyAny>) -> PyResult<Value> {
    let wrong = || {
        let type_name = value
            .get_type()
            .name()
            .map_or_else(|_| "?".to_owned(), |n| n.to_string());
        errors::options(format!(
            "option {} must be {}, not {type_name}",
            entry.name,
            match entry.kind {
                Kind::Number => "a number",
                Kind::Count => "a non-negative integer",
                Kind::Flag => "True or False",
                Kind::Numbers => "a sequence of numbers",
            }
        ))
    };
    // bool is a subclass of int in Python: True is no number of degrees.
    let is_bool = value.is_instance_of::<PyBool>();
    match entry.kind {
        Kind::Number if !is_bool => {
            if !(value.is_instance_of::<PyFloat>() || value.is_instance_of::<PyInt>()) {
                return Err(wrong());
            }
            let number: f64 = value.extract().map_err(|_| wrong())?;
            Ok(Value::Number(number as f32))
        }
        Kind::Count if !is_bool && value.is_instance_of::<PyInt>() => {
            Ok(Value::Count(value.extract().map_err(|_| wrong())?))
        }
        Kind::Flag if is_bool => Ok(Value::Flag(value.extract()?)),
        // Any sequence of numbers (a list, a tuple, a numpy array), not a string.
        Kind::Numbers if !value.is_instance_of::<pyo3::types::PyString>() => {
            let numbers: Vec<f64> = value.extract().map_err(|_| wrong())?;
            let numbers: Vec<f32> = numbers.into_iter().map(|x| x as f32).collect();
            chamfer_runtime::schema::Numbers::new(&numbers)
                .map(Value::Numbers)
                .ok_or_else(|| {
                    errors::options(format!(
                        "option {} takes at most {} numbers, not {}",
                        entry.name,
                        chamfer_runtime::schema::Numbers::CAPACITY,
                        numbers.len()
                    ))
                })
        }
        _ => Err(wrong()),
    }
}

/// The option table for Python (`chamfer.OPTIONS`): `(name, type, help)` triples, the help
/// ending with the default.
pub fn table() -> Vec<(&'static str, &'static str, String)> {
    BakeSettings::ENTRIES
        .iter()
        .filter(|entry| entry.group == GROUP)
        .map(|entry| {
            let mut help = entry.help(str::to_owned);
            match entry.default() {
                Some(Value::Flag(_)) | None => {}
                Some(default) => help.push_str(&format!(" [default: {default}]")),
            }
            (entry.name, python_type(entry.kind), help)
        })
        .collect()
}

/// The bake's whole schema for Python (`chamfer.BAKE_SCHEMA`): a list of dicts, one per entry
/// (name, kind, group, value_name, help, default, example, range, conflicts, requires), the
/// "encoding" group's entries being the keywords of `Asset.encode` and `Asset.save`.
pub fn schema(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    json(py, BakeSettings::schema_json())
}

/// The view schema for Python (`chamfer.VIEW_SCHEMA`), as [`schema`]: the camera keywords of
/// `draw_svg`, `chamfer draw`'s and `chamfer render`'s camera flags.
pub fn view_schema(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    json(py, Orbit::schema_json())
}

/// A schema's table for Python (`chamfer.SECTION_SCHEMA`, `chamfer.DRAWING_STYLE_SCHEMA`), as
/// [`schema`].
pub fn schema_of<S: Schema>(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    json(py, S::schema_json())
}

fn json(py: Python<'_>, value: serde_json::Value) -> PyResult<Bound<'_, PyAny>> {
    py.import("json")?
        .call_method1("loads", (value.to_string(),))
}
