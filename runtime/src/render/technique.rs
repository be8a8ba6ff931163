//! The one switch between edge techniques: [`Technique`], set in [`EdgeStyle::technique`].
//!
//! Each variant is drawn by its own module in `techniques/` with its own shader file; the core
//! knows only what each technique declares it needs (a stencil buffer, per-asset data, a pass after
//! the application's).
//!
//! [`EdgeStyle::technique`]: super::EdgeStyle::technique

/// Which technique draws the edges. [`Technique::Joined`] is the default and the one the asset is
/// made for; the others are the seeds' alternatives, kept so they can be chosen and compared.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub enum Technique {
    /// Compacted edges with gap-free joins (thesis §10, §13): per frame a compute pass classifies
    /// every edge and appends the drawn ones to a list that drives an indirect draw; joins cut
    /// overlapping quads apart and fill outer gaps with round caps, so no pixel is covered twice.
    /// Honours every [`EdgeStyle`](super::EdgeStyle) field.
    #[default]
    Joined,
}

impl Technique {
    /// Every technique with its default parameters, in the order of [`Technique::names`].
    pub fn all() -> Vec<Self> {
        vec![Self::Joined]
    }

    /// The technique's name, as `chamfer render --technique` takes it.
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Joined => "joined",
        }
    }

    /// Every technique's name.
    pub fn names() -> Vec<&'static str> {
        Self::all().iter().map(Self::name).collect()
    }

    /// The technique called `name`, with its default parameters.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::all().into_iter().find(|t| t.name() == name)
    }

    /// A one-line description: what it is and which seed section it follows.
    pub const fn summary(&self) -> &'static str {
        match self {
            Self::Joined => {
                "compacted edges with gap-free joins and round caps (thesis §10, §13; the default)"
            }
        }
    }
}
