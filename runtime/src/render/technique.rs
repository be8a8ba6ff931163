//! The one switch between edge techniques: [`Technique`], set in [`EdgeStyle::technique`].
//!
//! Each variant is drawn by its own module in `techniques/` with its own shader file; the core
//! knows only what each technique declares it needs ([`Technique::needs`]: per-asset data; a stencil
//! buffer; a pass after the application's).
//!
//! [`EdgeStyle::technique`]: super::EdgeStyle::technique

use super::AssetExtras;

/// Which technique draws the edges. [`Technique::Joined`] is the default and the one the asset is
/// made for; the others are the seeds' alternatives, kept so they can be chosen and compared.
///
/// Every technique draws the classes, colours and width of the [`EdgeStyle`](super::EdgeStyle)
/// where it can; each variant says what it ignores.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub enum Technique {
    /// Compacted edges with gap-free joins (thesis §10, §13): per frame a compute pass classifies
    /// every edge and appends the drawn ones to a list that drives an indirect draw; joins cut
    /// overlapping quads apart and fill outer gaps with round caps, so no pixel is covered twice.
    /// Honours every style field.
    #[default]
    Joined,
    /// McGuire and Hughes' edges (thesis §8): every edge drawn as a quad whose vertices each
    /// classify it again (no compaction), full quads or half quads for contours, and two cap passes
    /// of triangles meeting along the projected vertex normals (§8.4) unless `caps` is
    /// [`CapMethod::None`](super::CapMethod::None). Its known flaw: caps on the wrong side where the
    /// projected normal does not follow the bend (§8.5). Ignores `highlight`; needs
    /// [`AssetExtras::VERTEX_NORMALS`].
    McGuireHughes,
    /// Half-hex edges (thesis §9.3): the half quad and both half caps in one pass, on the side the
    /// projected vertex normal points to. Contours only (other classes would flip sides); ignores
    /// `caps`, `half_quad_contours`, `highlight`. Needs [`AssetExtras::VERTEX_NORMALS`].
    HalfHex,
    /// Plug edges (thesis §9.3): the full quad plus a triangle at each end reaching to the projected
    /// vertex normal, edge and caps in one pass, for every class. Ignores `caps`,
    /// `half_quad_contours`, `highlight`. Needs [`AssetExtras::VERTEX_NORMALS`].
    Plug,
    /// Half-hex contours and plug edges for the other classes: the combination the thesis
    /// recommends (§9.3, "quality roughly equivalent to McGuire and Hughes' edge/caps … only two
    /// passes"). Ignores `caps`, `half_quad_contours`, `highlight`. Needs
    /// [`AssetExtras::VERTEX_NORMALS`].
    HalfHexPlug,
    /// House edges (thesis §9.3): a base reaching below the edge under a roof through the projected
    /// normals; kept to show the artifacts the thesis warns of at sharp joints. Ignores `caps`,
    /// `half_quad_contours`, `highlight`. Needs [`AssetExtras::VERTEX_NORMALS`].
    House,
    /// Fins (seed 003): silhouettes and creases found per frame, each drawn as a quad extruded from
    /// the edge along its front face's corner normals, with Listing 3's z-bias on crease fins. Shows
    /// the article's gap where a silhouette passes a hard edge, and z-fighting on near-90° valleys
    /// without the bias. Width is the fin's length along the normal (pixels at the vertex's depth,
    /// or world units); ignores `caps`, `half_quad_contours`, `depth_scaled`, `depth_bias_px` and
    /// `highlight`. Needs [`AssetExtras::FIN_CORNERS`].
    Fins {
        /// The fin's length in model units; `None`: `width_px` pixels at each vertex's depth.
        world_thickness: Option<f32>,
        /// How far crease fins move towards the camera, model units; `None`: 0.2 % of the model's
        /// bounding-box diagonal; `Some(0.0)`: no bias (the article's z-fighting).
        z_bias: Option<f32>,
    },
}

impl Technique {
    /// Every technique with its default parameters, in the order of [`Technique::names`].
    pub fn all() -> Vec<Self> {
        vec![
            Self::Joined,
            Self::McGuireHughes,
            Self::HalfHex,
            Self::Plug,
            Self::HalfHexPlug,
            Self::House,
            Self::Fins {
                world_thickness: None,
                z_bias: None,
            },
        ]
    }

    /// The technique's name, as `chamfer render --technique` takes it.
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Joined => "joined",
            Self::McGuireHughes => "mcguire-hughes",
            Self::HalfHex => "half-hex",
            Self::Plug => "plug",
            Self::HalfHexPlug => "half-hex-plug",
            Self::House => "house",
            Self::Fins { .. } => "fins",
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
            Self::McGuireHughes => {
                "McGuire-Hughes: every edge a quad classified per vertex, two cap passes (thesis §8)"
            }
            Self::HalfHex => "half-hex contours: half quad and caps in one pass (thesis §9.3)",
            Self::Plug => "plug edges: full quad and end caps in one pass (thesis §9.3)",
            Self::HalfHexPlug => "half-hex contours with plug edges for the rest (thesis §9.3)",
            Self::House => "house edges, for their artifacts (thesis §9.3)",
            Self::Fins { .. } => "fins extruded along the normals, with a z-bias (seed 003)",
        }
    }

    /// What an asset must be uploaded with for this technique (see [`GpuAsset::for_techniques`]).
    ///
    /// [`GpuAsset::for_techniques`]: super::GpuAsset::for_techniques
    pub const fn needs(&self) -> AssetExtras {
        match self {
            Self::Joined => AssetExtras::NONE,
            Self::McGuireHughes | Self::HalfHex | Self::Plug | Self::HalfHexPlug | Self::House => {
                AssetExtras::VERTEX_NORMALS
            }
            Self::Fins { .. } => AssetExtras::FIN_CORNERS,
        }
    }
}
