//! Option schemas (issue 40): one table per concept (the bake's options, ...) from which every front
//! end builds its own surface — clap's flags and their help, Python's keywords and `chamfer.OPTIONS`,
//! the page's controls, Bevy's `.meta` — so an option is declared once, next to the code that uses
//! it. [`schema!`](crate::schema!) writes the struct (typed fields, serde's derive for JSON and RON) and its table
//! ([`Schema::ENTRIES`]: each field's name, kind, default, range, help, conflicts and an example of a
//! value other than the default, which the cross-front-end tests set through each front end).

use std::fmt;

/// How an entry's value is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A real number (f32).
    Number,
    /// A non-negative integer (u64).
    Count,
    /// On or off; given means on.
    Flag,
    /// A list of up to [`Numbers::CAPACITY`] real numbers (a plane, a colour, a dash pattern),
    /// written `a,b,c` on the command line and as an array in JSON and Python.
    Numbers,
}

impl Kind {
    /// The kind's name in the schema's JSON and in messages: `number`, `count` or `flag`.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Number => "number",
            Self::Count => "count",
            Self::Flag => "flag",
            Self::Numbers => "numbers",
        }
    }
}

/// One entry's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A [`Kind::Number`].
    Number(f32),
    /// A [`Kind::Count`].
    Count(u64),
    /// A [`Kind::Flag`].
    Flag(bool),
    /// A [`Kind::Numbers`].
    Numbers(Numbers),
}

/// Up to [`Numbers::CAPACITY`] real numbers, held inline so a [`Value`] stays `Copy`. Which lengths
/// an entry takes is its struct's check (a plane is 4, a colour 3).
#[derive(Clone, Copy, PartialEq)]
pub struct Numbers {
    values: [f32; Numbers::CAPACITY],
    len: u8,
}

impl Numbers {
    /// The most numbers one value holds: six planes of four.
    pub const CAPACITY: usize = 24;
    /// No numbers.
    pub const EMPTY: Self = Self {
        values: [0.0; Self::CAPACITY],
        len: 0,
    };

    /// The numbers of `array`, for defaults and examples; `N` must be at most [`Self::CAPACITY`]
    /// (a compile error in a constant).
    pub const fn from_array<const N: usize>(array: [f32; N]) -> Self {
        assert!(N <= Self::CAPACITY, "more numbers than a value holds");
        let mut values = [0.0; Self::CAPACITY];
        let mut i = 0;
        while i < N {
            values[i] = array[i];
            i += 1;
        }
        Self {
            values,
            len: N as u8,
        }
    }

    /// These numbers, `None` when there are more than [`Self::CAPACITY`].
    pub fn new(numbers: &[f32]) -> Option<Self> {
        let mut values = [0.0; Self::CAPACITY];
        values.get_mut(..numbers.len())?.copy_from_slice(numbers);
        Some(Self {
            values,
            len: numbers.len() as u8,
        })
    }

    /// The numbers.
    pub fn as_slice(&self) -> &[f32] {
        &self.values[..usize::from(self.len)]
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl Default for Numbers {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl fmt::Debug for Numbers {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}

/// Comma-separated, as the command line takes them.
impl fmt::Display for Numbers {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, x) in self.as_slice().iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            write!(f, "{x}")?;
        }
        Ok(())
    }
}

/// Comma-separated numbers (spaces allowed); an empty text is no numbers.
impl std::str::FromStr for Numbers {
    type Err = String;
    fn from_str(text: &str) -> Result<Self, String> {
        let numbers = if text.trim().is_empty() {
            Vec::new()
        } else {
            text.split(',')
                .map(|part| {
                    part.trim()
                        .parse::<f32>()
                        .map_err(|_| format!("{:?} is not a number", part.trim()))
                })
                .collect::<Result<Vec<f32>, String>>()?
        };
        Self::new(&numbers).ok_or_else(|| {
            format!(
                "{} numbers given, at most {} are taken",
                numbers.len(),
                Self::CAPACITY
            )
        })
    }
}

impl serde::Serialize for Numbers {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.as_slice().serialize(serializer)
    }
}

impl<'de> serde::Deserialize<'de> for Numbers {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let numbers = Vec::<f32>::deserialize(deserializer)?;
        Self::new(&numbers).ok_or_else(|| {
            serde::de::Error::custom(format!("at most {} numbers are taken", Self::CAPACITY))
        })
    }
}

impl Value {
    /// The value as JSON (what the page's controls and Python's table show).
    pub fn to_json(self) -> serde_json::Value {
        match self {
            // Through f32's shortest text, so 1e-6 stays 1e-6 and not 9.999999974752427e-7.
            Self::Number(x) => x
                .to_string()
                .parse::<f64>()
                .ok()
                .and_then(serde_json::Number::from_f64)
                .map_or(serde_json::Value::Null, serde_json::Value::Number),
            Self::Count(n) => n.into(),
            Self::Flag(b) => b.into(),
            Self::Numbers(numbers) => numbers
                .as_slice()
                .iter()
                .map(|&x| Self::Number(x).to_json())
                .collect(),
        }
    }
}

impl Value {
    /// `json` read as a value of `kind` (what the page's settings and JSON tables give), `None`
    /// when it is not one.
    pub fn from_json(kind: Kind, json: &serde_json::Value) -> Option<Self> {
        match kind {
            Kind::Number => json.as_f64().map(|x| Self::Number(x as f32)),
            Kind::Count => json.as_u64().map(Self::Count),
            Kind::Flag => json.as_bool().map(Self::Flag),
            Kind::Numbers => {
                let numbers = json
                    .as_array()?
                    .iter()
                    .map(|x| x.as_f64().map(|x| x as f32))
                    .collect::<Option<Vec<f32>>>()?;
                Numbers::new(&numbers).map(Self::Numbers)
            }
        }
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Number(x) => write!(f, "{x}"),
            Self::Count(n) => write!(f, "{n}"),
            Self::Flag(b) => write!(f, "{b}"),
            Self::Numbers(numbers) => write!(f, "{numbers}"),
        }
    }
}

/// The upper bound of a range that has none but finiteness: the largest finite f32.
pub const FINITE: f64 = f32::MAX as f64;

/// The entry `name` spelled as a command-line flag: `weld_rel` is `--weld-rel`.
pub fn flag(name: &str) -> String {
    format!("--{}", name.replace('_', "-"))
}

/// A field type a schema can hold: its kind and its value (`None`: not set).
pub trait Field: Sized {
    /// How the field is written.
    const KIND: Kind;
    /// The value, `None` when the field is unset (an `Option` at `None`).
    fn value(&self) -> Option<Value>;
    /// The field holding `value`, `None` when `value` is of another kind.
    fn from_value(value: Value) -> Option<Self>;
}

macro_rules! field {
    ($ty:ty, $kind:ident) => {
        impl Field for $ty {
            const KIND: Kind = Kind::$kind;
            fn value(&self) -> Option<Value> {
                Some(Value::$kind(*self))
            }
            fn from_value(value: Value) -> Option<Self> {
                match value {
                    Value::$kind(x) => Some(x),
                    _ => None,
                }
            }
        }
        impl Field for Option<$ty> {
            const KIND: Kind = Kind::$kind;
            fn value(&self) -> Option<Value> {
                self.map(Value::$kind)
            }
            fn from_value(value: Value) -> Option<Self> {
                <$ty as Field>::from_value(value).map(Some)
            }
        }
    };
}
field!(f32, Number);
field!(u64, Count);
field!(bool, Flag);
field!(Numbers, Numbers);

/// One entry of a schema: a field of the struct `S`, described. Made by [`schema!`](crate::schema!); the function
/// fields are its accessors (use the methods).
pub struct Entry<S: 'static> {
    /// The field's name, snake_case: the JSON/RON key and Python keyword; the CLI flag is it in
    /// kebab-case.
    pub name: &'static str,
    /// How the value is written.
    pub kind: Kind,
    /// Which part of a front end takes it (e.g. `"bake"` or `"encoding"`).
    pub group: &'static str,
    /// The value's placeholder in the CLI's help (`DEG`, `N`, ...).
    pub value_name: &'static str,
    /// The field's doc comment, a line per element. Other entries are named in backticks
    /// (`` `weld_rel` ``), which each front end spells its own way ([`Entry::help`]).
    pub doc: &'static [&'static str],
    /// The values accepted lie within these bounds (the page's controls use them; the struct's
    /// own check decides, with the conditions a range cannot say).
    pub range: Option<(f64, f64)>,
    /// Entries that cannot be given together with this one.
    pub conflicts: &'static [&'static str],
    /// Entries this one needs given (`position_bits` needs `compact`).
    pub requires: &'static [&'static str],
    #[doc(hidden)]
    pub get: fn(&S) -> Option<Value>,
    #[doc(hidden)]
    pub set: fn(&mut S, Value) -> bool,
    #[doc(hidden)]
    pub example: fn(&mut S),
}

/// Why a value cannot be put into a schema's struct.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SchemaError {
    /// No entry has this name.
    #[error("unknown option {name:?} (the options are: {known})")]
    Unknown {
        /// The name given.
        name: String,
        /// The entries' names, comma-separated.
        known: String,
    },
    /// The value is of another kind than the entry's.
    #[error("option {name} must be a {}, not {given}", kind.name())]
    WrongKind {
        /// The entry.
        name: &'static str,
        /// Its kind.
        kind: Kind,
        /// What was given.
        given: String,
    },
    /// Two entries that exclude each other are both given.
    #[error("options {0} and {1} cannot both be given")]
    Conflict(&'static str, &'static str),
    /// An entry is given without one it needs.
    #[error("option {0} needs option {1}")]
    Requires(&'static str, &'static str),
    /// A value its struct's own check refuses, for a reason a range cannot say.
    #[error("option {name} {reason}")]
    Invalid {
        /// The entry.
        name: &'static str,
        /// Why, as a predicate: "must be 1 or 4, not 3".
        reason: String,
    },
    /// A number is not finite, or a value lies outside its entry's range.
    #[error("option {name} must be {}, not {given}", describe_range(*range))]
    OutOfRange {
        /// The entry.
        name: &'static str,
        /// Its range (`None`: any finite number).
        range: Option<(f64, f64)>,
        /// What was given.
        given: String,
    },
}

impl SchemaError {
    /// The message with the entry named as a front end spells it (the CLI: [`flag`]), for the
    /// errors that name one entry's value; the others read as their `Display`.
    pub fn spelled(&self, spell: impl Fn(&str) -> String) -> String {
        match self {
            Self::OutOfRange { name, range, given } => {
                format!(
                    "{} must be {}, not {given}",
                    spell(name),
                    describe_range(*range)
                )
            }
            Self::Invalid { name, reason } => format!("{} {reason}", spell(name)),
            other => other.to_string(),
        }
    }
}

fn describe_range(range: Option<(f64, f64)>) -> String {
    match range {
        Some((low, high)) if high >= FINITE => format!("at least {low}"),
        Some((low, high)) => format!("{low} to {high}"),
        None => "a finite number".into(),
    }
}

impl<S: Schema> Entry<S> {
    /// The entry's value in `settings` (`None`: unset).
    pub fn get(&self, settings: &S) -> Option<Value> {
        (self.get)(settings)
    }

    /// Sets the entry in `settings` to `value`, refused when of another kind.
    pub fn set(&self, settings: &mut S, value: Value) -> Result<(), SchemaError> {
        if (self.set)(settings, value) {
            Ok(())
        } else {
            Err(SchemaError::WrongKind {
                name: self.name,
                kind: self.kind,
                given: value.to_string(),
            })
        }
    }

    /// Sets the entry in `settings` to its example, a value other than the default.
    pub fn set_example(&self, settings: &mut S) {
        (self.example)(settings);
    }

    /// The entry's example, a value other than its default.
    pub fn example(&self) -> Option<Value> {
        let mut settings = S::default();
        self.set_example(&mut settings);
        self.get(&settings)
    }

    /// The entry's default (`None`: unset unless given).
    pub fn default(&self) -> Option<Value> {
        self.get(&S::default())
    }

    /// Whether `settings` gives the entry: holds a value other than its default (a flag: on).
    pub fn is_given(&self, settings: &S) -> bool {
        self.get(settings) != self.default()
    }

    /// The help text, with each entry named in backticks spelled by `spell` (the CLI: `--weld-rel`;
    /// Python: `weld_rel`).
    pub fn help(&self, spell: impl Fn(&str) -> String) -> String {
        let text = self
            .doc
            .iter()
            .map(|line| line.trim())
            .collect::<Vec<_>>()
            .join(" ");
        let mut out = String::with_capacity(text.len());
        let mut parts = text.split('`');
        out.push_str(parts.next().unwrap_or_default());
        while let Some(quoted) = parts.next() {
            if S::ENTRIES.iter().any(|e| e.name == quoted) {
                out.push_str(&spell(quoted));
            } else {
                out.push('`');
                out.push_str(quoted);
                out.push('`');
            }
            out.push_str(parts.next().unwrap_or_default());
        }
        out
    }

    /// The entry as JSON, for the page's controls and Python's table: name, kind, group,
    /// value_name, help (names as they are), default (null: unset), example, range, conflicts,
    /// requires.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "name": self.name,
            "kind": self.kind.name(),
            "group": self.group,
            "value_name": self.value_name,
            "help": self.help(str::to_owned),
            "default": self.default().map(Value::to_json),
            "example": self.example().map(Value::to_json),
            "range": self.range,
            "conflicts": self.conflicts,
            "requires": self.requires,
        })
    }
}

/// A struct described by a table of entries, made by [`schema!`](crate::schema!).
pub trait Schema: Default + Sized + 'static {
    /// The fields, in declaration order.
    const ENTRIES: &'static [Entry<Self>];

    /// The entry named `name`.
    fn entry(name: &str) -> Result<&'static Entry<Self>, SchemaError> {
        Self::ENTRIES
            .iter()
            .find(|e| e.name == name)
            .ok_or_else(|| SchemaError::Unknown {
                name: name.to_owned(),
                known: Self::ENTRIES
                    .iter()
                    .map(|e| e.name)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// Sets the entry `name` to `value`.
    fn set(&mut self, name: &str, value: Value) -> Result<(), SchemaError> {
        Self::entry(name)?.set(self, value)
    }

    /// Refuses given entries that conflict, or that lack an entry they need; an entry is given
    /// when it holds a value other than its default (see [`Schema::check_names`] where the names
    /// given are known).
    fn check_combinations(&self) -> Result<(), SchemaError> {
        let given: Vec<&str> = Self::ENTRIES
            .iter()
            .filter(|e| e.is_given(self))
            .map(|e| e.name)
            .collect();
        Self::check_names(&given)
    }

    /// Refuses `given`, the names of the entries a caller gave (a default given explicitly
    /// included), when two of them conflict or one lacks an entry it needs.
    fn check_names(given: &[&str]) -> Result<(), SchemaError> {
        for &name in given {
            let entry = Self::entry(name)?;
            if let Some(&other) = entry.conflicts.iter().find(|c| given.contains(c)) {
                return Err(SchemaError::Conflict(entry.name, other));
            }
            if let Some(&needed) = entry.requires.iter().find(|r| !given.contains(r)) {
                return Err(SchemaError::Requires(entry.name, needed));
            }
        }
        Ok(())
    }

    /// Refuses a number that is not finite and a value outside its entry's range (inclusive).
    /// Schemas whose library checks its values itself (the bake's) need not call it.
    fn check_ranges(&self) -> Result<(), SchemaError> {
        for entry in Self::ENTRIES {
            let numbers: Vec<f64> = match entry.get(self) {
                Some(Value::Number(x)) => vec![f64::from(x)],
                Some(Value::Count(n)) => vec![n as f64],
                Some(Value::Numbers(numbers)) => {
                    numbers.as_slice().iter().map(|&x| f64::from(x)).collect()
                }
                Some(Value::Flag(_)) | None => continue,
            };
            let inside = |x: f64| {
                x.is_finite()
                    && entry
                        .range
                        .is_none_or(|(low, high)| (low..=high).contains(&x))
            };
            if !numbers.into_iter().all(inside) {
                return Err(SchemaError::OutOfRange {
                    name: entry.name,
                    range: entry.range,
                    given: entry.get(self).map(|v| v.to_string()).unwrap_or_default(),
                });
            }
        }
        Ok(())
    }

    /// The entries `self` sets, as command-line flags in the table's order: `--name value`, a
    /// flag `--name` when on; unset entries and flags that are off are left out. What a drawing's
    /// description quotes, so the same view can be asked for again.
    fn to_flags(&self) -> Vec<String> {
        Self::ENTRIES
            .iter()
            .filter_map(|entry| match entry.get(self)? {
                Value::Flag(false) => None,
                Value::Flag(true) => Some(flag(entry.name)),
                value => Some(format!("{} {value}", flag(entry.name))),
            })
            .collect()
    }

    /// The table as JSON: an array of [`Entry::to_json`].
    fn schema_json() -> serde_json::Value {
        Self::ENTRIES.iter().map(Entry::to_json).collect()
    }
}

/// Declares a settings struct and its [`Schema`] table. Each field carries its doc comment (the
/// help of every front end), its type (a [`Field`]: `f32`, `u64`, `bool` or an `Option` of the
/// first two), its default, and in braces its group, CLI value name, range, an example value other
/// than the default, and the entries it conflicts with or requires:
///
/// ```
/// chamfer_runtime::schema! {
///     /// How to draw a line.
///     #[derive(Clone, Debug, PartialEq)]
///     pub struct Line {
///         /// Width in pixels.
///         width: f32 = 2.0, { group: "style", value: "PX", range: Some((0.0, 64.0)),
///             example: 3.0, conflicts: [], requires: [] },
///         /// Draw it dashed.
///         dashed: bool = false, { group: "style", value: "", range: None,
///             example: true, conflicts: [], requires: [] },
///     }
/// }
/// use chamfer_runtime::schema::{Schema, Value};
/// let mut line = Line::default();
/// line.set("width", Value::Number(4.0)).expect("a number");
/// assert_eq!(line.width, 4.0);
/// assert!(line.set("dashed", Value::Number(1.0)).is_err());
/// ```
#[macro_export]
macro_rules! schema {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            $(
                $(#[doc = $doc:literal])*
                $field:ident : $ty:ty = $default:expr, {
                    group: $group:literal,
                    value: $value_name:literal,
                    range: $range:expr,
                    example: $example:expr,
                    conflicts: [$($conflict:ident),* $(,)?],
                    requires: [$($required:ident),* $(,)?] $(,)?
                }
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        $vis struct $name {
            $( $(#[doc = $doc])* pub $field: $ty, )*
        }

        impl ::core::default::Default for $name {
            fn default() -> Self {
                Self { $( $field: $default, )* }
            }
        }

        impl $crate::schema::Schema for $name {
            const ENTRIES: &'static [$crate::schema::Entry<Self>] = &[$(
                $crate::schema::Entry {
                    name: stringify!($field),
                    kind: <$ty as $crate::schema::Field>::KIND,
                    group: $group,
                    value_name: $value_name,
                    doc: &[$($doc),*],
                    range: $range,
                    conflicts: &[$(stringify!($conflict)),*],
                    requires: &[$(stringify!($required)),*],
                    get: |s| $crate::schema::Field::value(&s.$field),
                    set: |s, v| match <$ty as $crate::schema::Field>::from_value(v) {
                        Some(x) => { s.$field = x; true }
                        None => false,
                    },
                    example: |s| s.$field = $example,
                },
            )*];
        }
    };
}

#[cfg(test)]
mod tests {
    use super::{Schema, SchemaError, Value};

    crate::schema! {
        /// A test schema.
        #[derive(Debug, PartialEq)]
        pub struct Sample {
            /// A length; see `fraction`.
            length: Option<f32> = None, { group: "a", value: "L", range: Some((0.0, 1.0)),
                example: Some(0.5), conflicts: [fraction], requires: [] },
            /// A `fraction` of it.
            fraction: f32 = 0.25, { group: "a", value: "F", range: None, example: 0.5,
                conflicts: [], requires: [] },
            /// Count things.
            count: u64 = 3, { group: "b", value: "N", range: None, example: 4,
                conflicts: [], requires: [on] },
            /// On.
            on: bool = false, { group: "b", value: "", range: None, example: true,
                conflicts: [], requires: [] },
        }
    }

    #[test]
    fn entries_read_and_write_their_fields() {
        let mut s = Sample::default();
        assert_eq!(Sample::ENTRIES.len(), 4);
        s.set("length", Value::Number(0.75)).expect("a number");
        assert_eq!(s.length, Some(0.75));
        assert!(matches!(
            s.set("length", Value::Flag(true)),
            Err(SchemaError::WrongKind { name: "length", .. })
        ));
        assert!(matches!(
            s.set("width", Value::Number(1.0)),
            Err(SchemaError::Unknown { .. })
        ));
        for entry in Sample::ENTRIES {
            let mut example = Sample::default();
            entry.set_example(&mut example);
            assert!(entry.is_given(&example), "{}", entry.name);
            assert_ne!(example, Sample::default());
        }
        assert_eq!(Sample::ENTRIES[1].default(), Some(Value::Number(0.25)));
        assert_eq!(Sample::ENTRIES[0].default(), None);
    }

    #[test]
    fn conflicts_and_requirements_are_checked() {
        let mut s = Sample::default();
        s.length = Some(1.0);
        assert_eq!(s.check_combinations(), Ok(()));
        s.fraction = 0.5;
        assert_eq!(
            s.check_combinations(),
            Err(SchemaError::Conflict("length", "fraction"))
        );
        let mut s = Sample {
            count: 5,
            ..Sample::default()
        };
        assert_eq!(
            s.check_combinations(),
            Err(SchemaError::Requires("count", "on"))
        );
        s.on = true;
        assert_eq!(s.check_combinations(), Ok(()));
        // A default given explicitly still conflicts.
        assert_eq!(
            Sample::check_names(&["fraction", "length"]),
            Err(SchemaError::Conflict("length", "fraction"))
        );
    }

    #[test]
    fn help_spells_other_entries_for_each_front_end() {
        let cli = Sample::ENTRIES[0].help(super::flag);
        assert_eq!(cli, "A length; see --fraction.");
        assert_eq!(Sample::ENTRIES[1].help(str::to_owned), "A fraction of it.");
        let json = Sample::schema_json();
        assert_eq!(json[0]["name"], "length");
        assert_eq!(json[0]["default"], serde_json::Value::Null);
        assert_eq!(json[1]["default"], 0.25);
        assert_eq!(json[1]["example"], 0.5);
        assert_eq!(json[2]["requires"][0], "on");
    }

    #[test]
    fn ranges_refuse_what_lies_outside_and_flags_quote_what_is_set() {
        let mut s = Sample::default();
        assert_eq!(s.check_ranges(), Ok(()));
        s.length = Some(1.5);
        assert!(matches!(
            s.check_ranges(),
            Err(SchemaError::OutOfRange { name: "length", .. })
        ));
        s.length = None;
        s.fraction = f32::NAN;
        let error = s.check_ranges().expect_err("not finite");
        assert_eq!(
            error.to_string(),
            "option fraction must be a finite number, not NaN"
        );
        s.fraction = 0.5;
        s.on = true;
        assert_eq!(s.to_flags(), ["--fraction 0.5", "--count 3", "--on"]);
        s.count = 0;
        s.length = Some(-1.0);
        let error = s.check_ranges().expect_err("below");
        assert_eq!(
            error.spelled(super::flag),
            "--length must be 0 to 1, not -1"
        );
    }
}
