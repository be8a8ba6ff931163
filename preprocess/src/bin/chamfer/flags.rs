//! clap flags made from a schema (issue 40): each entry of a group becomes `--kebab-name`, with its
//! help (other entries spelled as flags), value name, default, conflicts and requirements. What the
//! command line gives is set into the schema's struct; the rest keeps the struct's defaults.

use chamfer_preprocess::BakeSettings;
use chamfer_preprocess::draw::style::DrawingStyle;
use chamfer_runtime::camera::Orbit;
use chamfer_runtime::render::{DisplaySettings, StyleSettings, Technique};
use chamfer_runtime::rig::AnimationSettings;
use chamfer_runtime::schema::{Entry, Kind, Numbers, Schema, Value, flag};
use chamfer_runtime::section::{CutSettings, Section};
use clap::error::ErrorKind;
use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches, value_parser};

/// The flags of `group`'s entries added to `command`.
fn augment<S: Schema>(command: Command, group: &str) -> Command {
    S::ENTRIES
        .iter()
        .filter(|entry| entry.group == group)
        .fold(command, |command, entry| command.arg(arg(entry)))
}

fn arg<S: Schema>(entry: &Entry<S>) -> Arg {
    let arg = typed_arg(
        entry.name.to_owned(),
        entry.kind,
        entry.value_name,
        entry.help(flag),
        entry.default().map(|d| d.to_string()),
    )
    .conflicts_with_all(entry.conflicts.iter().copied());
    entry
        .requires
        .iter()
        .fold(arg, |arg, &needed| arg.requires(needed))
}

/// The flag `--{id in kebab-case}` taking a value of `kind` (a number may be negative: a range
/// refuses it where it must not be), with its help and, for a value, the default it states.
fn typed_arg(
    id: String,
    kind: Kind,
    value_name: &str,
    mut help: String,
    default: Option<String>,
) -> Arg {
    let arg = Arg::new(id.clone()).long(flag(&id).trim_start_matches('-').to_owned());
    let arg = match kind {
        Kind::Flag => return arg.action(ArgAction::SetTrue).help(help),
        Kind::Number => arg
            .value_parser(value_parser!(f32))
            .allow_negative_numbers(true),
        Kind::Count => arg.value_parser(value_parser!(u64)),
        Kind::Numbers => arg
            .value_parser(|text: &str| text.parse::<Numbers>())
            .allow_hyphen_values(true),
    };
    if let Some(default) = default {
        help.push_str(&format!(" [default: {default}]"));
    }
    arg.action(ArgAction::Set)
        .value_name(value_name.to_owned())
        .help(help)
}

/// Sets into `settings` the values of `group`'s flags that `matches` holds, and returns their
/// names (a flag given at its default value included).
fn read<S: Schema>(
    matches: &ArgMatches,
    group: &str,
    settings: &mut S,
) -> Result<Vec<&'static str>, clap::Error> {
    let mut given = Vec::new();
    for entry in S::ENTRIES.iter().filter(|entry| entry.group == group) {
        let value = match entry.kind {
            Kind::Number => matches
                .get_one::<f32>(entry.name)
                .copied()
                .map(Value::Number),
            Kind::Count => matches
                .get_one::<u64>(entry.name)
                .copied()
                .map(Value::Count),
            Kind::Flag => matches.get_flag(entry.name).then_some(Value::Flag(true)),
            Kind::Numbers => matches
                .get_one::<Numbers>(entry.name)
                .copied()
                .map(Value::Numbers),
        };
        if let Some(value) = value {
            entry
                .set(settings, value)
                .map_err(|e| clap::Error::raw(ErrorKind::ValueValidation, e))?;
            given.push(entry.name);
        }
    }
    Ok(given)
}

/// Flags for the entries of one group of a schema.
macro_rules! group_flags {
    ($(#[$meta:meta])* $name:ident($schema:ty), $group:literal) => {
        $(#[$meta])*
        /// The settings, and the names of the entries given on the command line.
        #[derive(Clone, Default)]
        pub struct $name(pub $schema, pub Vec<&'static str>);

        impl FromArgMatches for $name {
            fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
                let mut settings = <$schema>::default();
                let given = read(matches, $group, &mut settings)?;
                Ok(Self(settings, given))
            }

            fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
                let given = read(matches, $group, &mut self.0)?;
                self.1.extend(given);
                Ok(())
            }
        }

        impl Args for $name {
            fn augment_args(command: Command) -> Command {
                augment::<$schema>(command, $group)
            }

            fn augment_args_for_update(command: Command) -> Command {
                augment::<$schema>(command, $group)
            }
        }
    };
}

group_flags!(
    /// The bake options as flags (`chamfer bake`, `demo`, `annotate`, `draw`, `render`).
    BakeFlags(BakeSettings),
    "bake"
);
group_flags!(
    /// How the asset is stored (`chamfer bake`, `demo`).
    EncodingFlags(BakeSettings),
    "encoding"
);
group_flags!(
    /// The orbit camera as flags (`chamfer render`, `draw`).
    ViewFlags(Orbit),
    "view"
);
group_flags!(
    /// The look's numbers as flags (`chamfer render`, `demo`).
    StyleFlags(StyleSettings),
    "style"
);
group_flags!(
    /// Section planes as flags (`chamfer render`, `draw`).
    SectionFlags(Section),
    "section"
);
group_flags!(
    /// How a render shows the section's cut faces and outline (`chamfer render`).
    CutFlags(CutSettings),
    "section"
);
group_flags!(
    /// Display modes: faces, hidden edges, distance fade (`chamfer render`).
    DisplayFlags(DisplaySettings),
    "display"
);
group_flags!(
    /// The pose of an animated asset: an animation at a time, morph weights (`chamfer render`).
    AnimationFlags(AnimationSettings),
    "animation"
);
group_flags!(
    /// The line roles' styles and the hatch as flags (`chamfer draw`).
    DrawingStyleFlags(DrawingStyle),
    "drawing_style"
);

impl BakeFlags {
    /// The options, checked.
    pub fn to_options(&self) -> anyhow::Result<chamfer_preprocess::BakeOptions> {
        Ok(self.0.bake_options()?)
    }
}

impl EncodingFlags {
    /// The compact options, checked; `None` for the uncompressed format.
    pub fn to_options(&self) -> anyhow::Result<Option<chamfer_runtime::asset::CompactOptions>> {
        Ok(self.0.compact_options()?)
    }
}

/// The techniques' own parameters as flags, `--{prefix}-{name}` (`--hybrid-step`), one per entry of
/// each table of [`Technique::parameter_tables`]: what the command line gives, set over the chosen
/// technique's preset by [`TechniqueFlags::apply`].
#[derive(Clone, Default)]
pub struct TechniqueFlags(Vec<(&'static str, &'static str, Value)>);

/// A parameter's flag id and its long name: `hybrid_step`, `hybrid-step`.
fn parameter_id(prefix: &str, name: &str) -> String {
    format!("{prefix}_{name}")
}

impl TechniqueFlags {
    /// `technique` with the given parameters set and checked; a parameter the technique does not
    /// have is refused, naming the techniques that have it.
    pub fn apply(&self, mut technique: Technique) -> anyhow::Result<Technique> {
        let name = technique.name();
        for &(prefix, entry, value) in &self.0 {
            let spelled = flag(&parameter_id(prefix, entry));
            match technique.parameters_mut() {
                Some(parameters) if parameters.prefix() == prefix => {
                    parameters
                        .set(entry, value)
                        .map_err(|e| anyhow::anyhow!("{spelled}: {e}"))?
                }
                _ => anyhow::bail!(
                    "{spelled} is a parameter of --technique {}, not of {name}",
                    users(prefix).join(", ")
                ),
            }
        }
        if let Some(parameters) = technique.parameters() {
            let prefix = parameters.prefix();
            parameters
                .check()
                .map_err(|e| anyhow::anyhow!(e.spelled(|n| flag(&parameter_id(prefix, n)))))?;
        }
        Ok(technique)
    }
}

/// The techniques whose parameter table is `prefix`'s.
fn users(prefix: &str) -> Vec<&'static str> {
    Technique::presets()
        .filter(|p| {
            p.technique
                .parameters()
                .is_some_and(|t| t.prefix() == prefix)
        })
        .map(|p| p.name)
        .collect()
}

impl FromArgMatches for TechniqueFlags {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut flags = Self::default();
        flags.update_from_arg_matches(matches)?;
        Ok(flags)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        for table in Technique::parameter_tables() {
            for name in table.names() {
                let id = parameter_id(table.prefix(), name);
                let value = match table.kind(name) {
                    Some(Kind::Flag) => matches.get_flag(&id).then_some(Value::Flag(true)),
                    Some(Kind::Count) => matches.get_one::<u64>(&id).copied().map(Value::Count),
                    Some(Kind::Numbers) => {
                        matches.get_one::<Numbers>(&id).copied().map(Value::Numbers)
                    }
                    _ => matches.get_one::<f32>(&id).copied().map(Value::Number),
                };
                if let Some(value) = value {
                    self.0.push((table.prefix(), name, value));
                }
            }
        }
        Ok(())
    }
}

impl Args for TechniqueFlags {
    fn augment_args(command: Command) -> Command {
        let mut command = command;
        for table in Technique::parameter_tables() {
            let schema = table.schema_json();
            let techniques = users(table.prefix()).join(", ");
            for (name, entry) in table
                .names()
                .into_iter()
                .zip(schema.as_array().into_iter().flatten())
            {
                let text = |key: &str| entry[key].as_str().unwrap_or_default().to_owned();
                let kind = table.kind(name).unwrap_or(Kind::Number);
                let default = (kind != Kind::Flag).then(|| "the technique's own".to_owned());
                command = command.arg(typed_arg(
                    parameter_id(table.prefix(), name),
                    kind,
                    &text("value_name"),
                    format!("--technique {techniques}: {}", text("help")),
                    default,
                ));
            }
        }
        command
    }

    fn augment_args_for_update(command: Command) -> Command {
        Self::augment_args(command)
    }
}
