//! ASCII PLY element lines (Bourke's PLY format description: one element per line, its values in
//! the header's property order, a list as its count then its items) read into the loader's
//! property structs.
//!
//! ply-rs-bw's line grammar refuses `nan` and `inf` outright and then says only "Couldn't parse
//! element line.", or "Expected element of type 'List(UChar, UInt)'" for a short line. Here values
//! are Rust's number syntax (so a NaN position reaches the loader's check, which names it, and a
//! NaN in a property the loader skips is skipped, as in a binary file), and a wrong line says which
//! property and which value. Values after the last property are ignored, as ply-rs-bw does.

use ply_rs_bw::ply::{
    BeginList, ElementDef, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};

use super::ply_header::{scalar_name, type_name};

/// One element from its line. Errors name the property and the value.
pub(crate) fn read_element<E: PropertyAccess>(
    line: &str,
    element: &ElementDef,
) -> Result<E, String> {
    let mut tokens = line.split_ascii_whitespace();
    let mut value = E::new();
    let mut read = 0usize;
    for (name, property) in &element.properties {
        let described = || format!("property '{name}' ({})", type_name(&property.data_type));
        let mut next = || {
            let token = tokens.next().ok_or_else(|| {
                format!("the line ends before {}: it has {read} values", described())
            })?;
            read += 1;
            Ok::<_, String>(token)
        };
        let result = match &property.data_type {
            PropertyType::Scalar(scalar) => {
                let token = next()?;
                set_scalar(&mut value, name, scalar, token)
                    .map_err(|e| format!("{} {e}", described()))?
            }
            PropertyType::List(count_type, item) => {
                let token = next()?;
                let count: usize = parse_integer::<u32>(token, count_type)
                    .ok()
                    .and_then(|c| usize::try_from(c).ok())
                    .ok_or_else(|| {
                        format!(
                            "{} has the count '{token}', not a {} of 0 or more",
                            described(),
                            scalar_name(count_type)
                        )
                    })?;
                // The items are on the line: a count larger than the line cannot allocate.
                let items: Vec<&str> = (&mut tokens).take(count).collect();
                read += items.len();
                if items.len() < count {
                    return Err(format!(
                        "{} lists {count} values but the line has {} after the count",
                        described(),
                        items.len()
                    ));
                }
                set_list(&mut value, name, item, &items)
                    .map_err(|e| format!("{} {e}", described()))?
            }
        };
        if result == PropertyAccessResult::UnsupportedType {
            return Err(format!(
                "{} is not of a type this loader reads",
                described()
            ));
        }
    }
    Ok(value)
}

/// `token` as a value of the integer type `scalar`, widened to `T`.
fn parse_integer<T: TryFrom<i64>>(token: &str, scalar: &ScalarType) -> Result<T, String> {
    let (low, high) = match scalar {
        ScalarType::Char => (i64::from(i8::MIN), i64::from(i8::MAX)),
        ScalarType::UChar => (0, i64::from(u8::MAX)),
        ScalarType::Short => (i64::from(i16::MIN), i64::from(i16::MAX)),
        ScalarType::UShort => (0, i64::from(u16::MAX)),
        ScalarType::Int => (i64::from(i32::MIN), i64::from(i32::MAX)),
        ScalarType::UInt => (0, i64::from(u32::MAX)),
        ScalarType::Float | ScalarType::Double => (i64::MIN, i64::MAX),
    };
    token
        .parse::<i64>()
        .ok()
        .filter(|v| (low..=high).contains(v))
        .and_then(|v| T::try_from(v).ok())
        .ok_or_else(|| format!("is '{token}', not a {}", scalar_name(scalar)))
}

fn parse_float<T: std::str::FromStr>(token: &str, scalar: &ScalarType) -> Result<T, String> {
    token
        .parse()
        .map_err(|_| format!("is '{token}', not a {}", scalar_name(scalar)))
}

fn set_scalar<E: PropertyAccess>(
    value: &mut E,
    name: &str,
    scalar: &ScalarType,
    token: &str,
) -> Result<PropertyAccessResult, String> {
    Ok(match scalar {
        ScalarType::Char => value.set_char(name, parse_integer(token, scalar)?),
        ScalarType::UChar => value.set_uchar(name, parse_integer(token, scalar)?),
        ScalarType::Short => value.set_short(name, parse_integer(token, scalar)?),
        ScalarType::UShort => value.set_ushort(name, parse_integer(token, scalar)?),
        ScalarType::Int => value.set_int(name, parse_integer(token, scalar)?),
        ScalarType::UInt => value.set_uint(name, parse_integer(token, scalar)?),
        ScalarType::Float => value.set_float(name, parse_float(token, scalar)?),
        ScalarType::Double => value.set_double(name, parse_float(token, scalar)?),
    })
}

/// Hands a list to `value` the way it asks for it (filling its own vector or through its setter).
macro_rules! list {
    ($value:ident, $name:ident, $items:ident, $begin:ident, $set:ident, $parse:expr) => {{
        let parse = $parse;
        match $value.$begin($name, $items.len()) {
            BeginList::Fill(out) => {
                out.clear();
                for (k, token) in $items.iter().enumerate() {
                    out.push(parse(token).map_err(|e| format!("value {k} {e}"))?);
                }
                PropertyAccessResult::Set
            }
            BeginList::UseSetter => {
                let list = $items
                    .iter()
                    .enumerate()
                    .map(|(k, token)| parse(token).map_err(|e| format!("value {k} {e}")))
                    .collect::<Result<Vec<_>, String>>()?;
                $value.$set($name, list)
            }
            BeginList::UnsupportedType => PropertyAccessResult::UnsupportedType,
        }
    }};
}

fn set_list<E: PropertyAccess>(
    value: &mut E,
    name: &str,
    item: &ScalarType,
    items: &[&str],
) -> Result<PropertyAccessResult, String> {
    Ok(match item {
        ScalarType::Char => list!(
            value,
            name,
            items,
            begin_list_char,
            set_list_char,
            |t: &&str| parse_integer(t, item)
        ),
        ScalarType::UChar => list!(
            value,
            name,
            items,
            begin_list_uchar,
            set_list_uchar,
            |t: &&str| parse_integer(t, item)
        ),
        ScalarType::Short => list!(
            value,
            name,
            items,
            begin_list_short,
            set_list_short,
            |t: &&str| parse_integer(t, item)
        ),
        ScalarType::UShort => list!(
            value,
            name,
            items,
            begin_list_ushort,
            set_list_ushort,
            |t: &&str| parse_integer(t, item)
        ),
        ScalarType::Int => list!(
            value,
            name,
            items,
            begin_list_int,
            set_list_int,
            |t: &&str| parse_integer(t, item)
        ),
        ScalarType::UInt => list!(
            value,
            name,
            items,
            begin_list_uint,
            set_list_uint,
            |t: &&str| parse_integer(t, item)
        ),
        ScalarType::Float => list!(
            value,
            name,
            items,
            begin_list_float,
            set_list_float,
            |t: &&str| parse_float(t, item)
        ),
        ScalarType::Double => list!(
            value,
            name,
            items,
            begin_list_double,
            set_list_double,
            |t: &&str| parse_float(t, item)
        ),
    })
}

#[cfg(test)]
mod tests {
    use ply_rs_bw::ply::{Addable, DefaultElement, Property, PropertyDef};

    use super::*;

    fn element(properties: &[(&str, PropertyType)]) -> ElementDef {
        let mut element = ElementDef::new("face".into());
        for (name, data_type) in properties {
            element
                .properties
                .add(PropertyDef::new((*name).into(), data_type.clone()));
        }
        element
    }

    #[test]
    fn values_are_read_by_type_and_wrong_lines_name_the_property() {
        let face = element(&[
            ("flags", PropertyType::Scalar(ScalarType::UChar)),
            (
                "vertex_indices",
                PropertyType::List(ScalarType::UChar, ScalarType::UInt),
            ),
            ("quality", PropertyType::Scalar(ScalarType::Float)),
        ]);
        let read: DefaultElement = read_element("7 3 0 1 2 nan\n", &face).expect("reads");
        assert_eq!(read["flags"], Property::UChar(7));
        assert_eq!(read["vertex_indices"], Property::ListUInt(vec![0, 1, 2]));
        assert!(matches!(read["quality"], Property::Float(q) if q.is_nan()));
        for (line, expected) in [
            (
                "",
                "the line ends before property 'flags' (uchar): it has 0 values",
            ),
            (
                "7",
                "the line ends before property 'vertex_indices' (list uchar uint): it has 1 values",
            ),
            (
                "300 3 0 1 2 0",
                "property 'flags' (uchar) is '300', not a uchar",
            ),
            (
                "7 3 0 1",
                "property 'vertex_indices' (list uchar uint) lists 3 values but the line has 2 after the count",
            ),
            ("7 -1 0 1", "has the count '-1', not a uchar of 0 or more"),
            (
                "7 3 0 x 2 0",
                "property 'vertex_indices' (list uchar uint) value 1 is 'x', not a uint",
            ),
            (
                "7 3 0 1 2 1,5",
                "property 'quality' (float) is '1,5', not a float",
            ),
        ] {
            let error = read_element::<DefaultElement>(line, &face).expect_err(line);
            assert!(error.contains(expected), "{line:?}: {error}");
        }
    }
}
