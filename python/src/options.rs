//! Bake options from Python keyword arguments: one table, [`OPTIONS`], maps each keyword to the
//! `BakeOptions::with_*` setter it calls, so a new option of the library is one entry here (and one
//! line in the stub's `BakeOptions` TypedDict). The names are the `chamfer bake` flags with `_` for `-`,
//! and the same keywords give the same asset as the same flags (tests/test_bake.py checks it).
//! `None` leaves an option at its default; the library's `validate` checks the ranges.

use chamfer_preprocess::{BakeOptions, Radius, Stitch, WeldTolerance};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt};

use crate::errors;

/// How an option's value is read from Python and which setter takes it.
#[derive(Clone, Copy)]
pub enum Setter {
    /// A real number (a Python float or int), as f32.
    Number(fn(BakeOptions, f32) -> BakeOptions),
    /// A count (a non-negative Python int).
    Count(fn(BakeOptions, u64) -> BakeOptions),
    /// `True` or `False` (nothing else: `"no"` would be truthy).
    Flag(fn(BakeOptions, bool) -> BakeOptions),
}

impl Setter {
    /// The Python type, for messages and the command line (`python -m chamfer.dask`).
    pub const fn kind(self) -> &'static str {
        match self {
            Self::Number(_) => "float",
            Self::Count(_) => "int",
            Self::Flag(_) => "bool",
        }
    }
}

/// Every option: keyword, setter, help (the `chamfer bake` flag's).
pub const OPTIONS: &[(&str, Setter, &str)] = &[
    (
        "weld_epsilon",
        Setter::Number(|o, d| o.with_weld(WeldTolerance::Absolute(d))),
        "Weld positions closer than this distance, in mesh units; 0 welds only identical positions (default: weld_rel).",
    ),
    (
        "weld_rel",
        Setter::Number(|o, f| o.with_weld(WeldTolerance::Relative(f))),
        "Weld positions closer than this fraction of the distance from the origin to the bounding box's farthest corner (default 1e-6).",
    ),
    (
        "coplanar_deg",
        Setter::Number(BakeOptions::with_coplanar_deg),
        "Drop interior edges whose faces are coplanar within this many degrees (default 0.01).",
    ),
    (
        "crease_deg",
        Setter::Number(BakeOptions::with_crease_deg),
        "Edges whose faces meet at this many degrees or more are creases (default 30).",
    ),
    (
        "radius",
        Setter::Number(|o, r| o.with_radius(Radius::Absolute(r))),
        "Give ridge creases (and marked edges without a radius) this chamfer radius, in mesh units; radii marked in the file win.",
    ),
    (
        "radius_rel",
        Setter::Number(|o, f| o.with_radius(Radius::Relative(f))),
        "Like radius, as a fraction of the bounding box's diagonal (e.g. 0.005).",
    ),
    (
        "radius_valleys",
        Setter::Flag(BakeOptions::with_radius_valleys),
        "Give valley creases the radius too (default False).",
    ),
    (
        "intersections",
        Setter::Flag(BakeOptions::with_intersections),
        "Also find intersection edges, where triangles cut through each other (default False).",
    ),
    (
        "stitch_rel",
        Setter::Number(|o, f| o.with_stitch(Stitch::Relative(f))),
        "Stitch the cracks between separately tessellated faces (CAD/BIM exports) within this fraction of the bounding box's diagonal (default 1e-4).",
    ),
    (
        "stitch_epsilon",
        Setter::Number(|o, d| o.with_stitch(Stitch::Absolute(d))),
        "Like stitch_rel, as a distance in mesh units.",
    ),
    (
        "no_stitch",
        Setter::Flag(|o, off| if off { o.with_stitch(Stitch::Off) } else { o }),
        "Do not stitch: every boundary edge the weld leaves stays a boundary (default False).",
    ),
    (
        "max_triangles",
        Setter::Count(|o, n| o.with_limits(o.limits.with_max_triangles(n))),
        "Refuse a mesh with more triangles than this (after fanning polygons and glTF instancing).",
    ),
    (
        "max_vertices",
        Setter::Count(|o, n| o.with_limits(o.limits.with_max_vertices(n))),
        "Refuse a mesh with more vertices than this (as loaded, before welding).",
    ),
    (
        "max_instances",
        Setter::Count(|o, n| o.with_limits(o.limits.with_max_instances(n))),
        "Refuse a glTF node graph (or 3MF build) that expands into more mesh instances than this.",
    ),
    (
        "max_input_bytes",
        Setter::Count(|o, n| o.with_limits(o.limits.with_max_input_bytes(n))),
        "Refuse a file (or a file it refers to) larger than this many bytes, after inflating .gz.",
    ),
];

/// Pairs of options that cannot both be given (as the CLI's flags conflict).
const CONFLICTS: [(&str, &str); 5] = [
    ("weld_epsilon", "weld_rel"),
    ("radius", "radius_rel"),
    ("stitch_epsilon", "stitch_rel"),
    ("no_stitch", "stitch_rel"),
    ("no_stitch", "stitch_epsilon"),
];

/// The options the keyword arguments `kwargs` name, checked; an unknown keyword, a value of the
/// wrong type, two conflicting options or a value out of range raises `OptionsError`.
pub fn from_kwargs(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<BakeOptions> {
    let mut options = BakeOptions::DEFAULT;
    let Some(kwargs) = kwargs else {
        return Ok(options);
    };
    let given = |name: &str| {
        kwargs
            .get_item(name)
            .ok()
            .flatten()
            .is_some_and(|v| !v.is_none())
    };
    for (a, b) in CONFLICTS {
        if given(a) && given(b) {
            return Err(errors::options(format!(
                "options {a} and {b} cannot both be given"
            )));
        }
    }
    for (key, value) in kwargs.iter() {
        let name: String = key.extract()?;
        let Some(&(_, setter, _)) = OPTIONS.iter().find(|(n, _, _)| *n == name) else {
            return Err(errors::options(format!(
                "unknown option {name:?} (see help(chamfer.bake) for the options)"
            )));
        };
        if value.is_none() {
            continue;
        }
        options = apply(options, &name, setter, &value)?;
    }
    options
        .validate()
        .map_err(|e| errors::from_library(e.into()))?;
    Ok(options)
}

/// `setter` applied to `value`, read as its kind.
fn apply(
    options: BakeOptions,
    name: &str,
    setter: Setter,
    value: &Bound<'_, PyAny>,
) -> PyResult<BakeOptions> {
    let wrong = || {
        let type_name = value
            .get_type()
            .name()
            .map_or_else(|_| "?".to_owned(), |n| n.to_string());
        errors::options(format!(
            "option {name} must be {}, not {type_name}",
            match setter {
                Setter::Number(_) => "a number",
                Setter::Count(_) => "a non-negative integer",
                Setter::Flag(_) => "True or False",
            }
        ))
    };
    // bool is a subclass of int in Python: True is no number of degrees.
    let is_bool = value.is_instance_of::<PyBool>();
    match setter {
        Setter::Number(set) if !is_bool => {
            if !(value.is_instance_of::<PyFloat>() || value.is_instance_of::<PyInt>()) {
                return Err(wrong());
            }
            let number: f64 = value.extract().map_err(|_| wrong())?;
            Ok(set(options, number as f32))
        }
        Setter::Count(set) if !is_bool && value.is_instance_of::<PyInt>() => {
            let count: u64 = value.extract().map_err(|_| wrong())?;
            Ok(set(options, count))
        }
        Setter::Flag(set) if is_bool => Ok(set(options, value.extract()?)),
        _ => Err(wrong()),
    }
}

/// The option table for Python: `(name, type, help)` triples.
pub fn table() -> Vec<(&'static str, &'static str, &'static str)> {
    OPTIONS
        .iter()
        .map(|&(name, setter, help)| (name, setter.kind(), help))
        .collect()
}
