//! The one switch between edge techniques: [`Technique`], set in [`EdgeStyle::technique`].
//!
//! Each variant is drawn by its own module in `techniques/` with its own shader file, which declares
//! what it needs ([`Technique::needs`]: per-asset data; a stencil buffer; a pass after the
//! application's). `docs/techniques.md` lists the four files a new technique touches.
//!
//! [`EdgeStyle::technique`]: super::EdgeStyle::technique

use super::{AssetExtras, techniques};
use crate::schema::{Kind, Schema, SchemaError, Value};

pub use super::techniques::{FinSettings, HybridDepth, SurfaceAngleSettings};

/// Which technique draws the edges. [`Technique::Joined`] is the default and the one the asset is
/// made for; the others are the seeds' alternatives, kept so they can be chosen and compared.
///
/// Every technique draws the classes, colours and width of the [`EdgeStyle`](super::EdgeStyle)
/// where it can; each variant says what it ignores.
///
/// In a scene ([`SceneRenderer`](super::SceneRenderer)), [`Joined`](Self::Joined),
/// [`McGuireHughes`](Self::McGuireHughes) and [`Fins`](Self::Fins) draw every instance of an asset
/// at once (a batch: a few passes per asset, whatever the number of its instances; the joined
/// technique also culls instances on the GPU). The others draw instance by instance: a uniform block
/// and a draw sequence (or a pass) per instance, instances out of view culled on the host.
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
    /// Draws instance by instance in a scene.
    HalfHex,
    /// Plug edges (thesis §9.3): the full quad plus a triangle at each end reaching to the projected
    /// vertex normal, edge and caps in one pass, for every class. Ignores `caps`,
    /// `half_quad_contours`, `highlight`. Needs [`AssetExtras::VERTEX_NORMALS`].
    /// Draws instance by instance in a scene.
    Plug,
    /// Half-hex contours and plug edges for the other classes: the combination the thesis
    /// recommends (§9.3, "quality roughly equivalent to McGuire and Hughes' edge/caps … only two
    /// passes"). Ignores `caps`, `half_quad_contours`, `highlight`. Needs
    /// [`AssetExtras::VERTEX_NORMALS`]. Draws instance by instance in a scene.
    HalfHexPlug,
    /// House edges (thesis §9.3): a base reaching below the edge under a roof through the projected
    /// normals; kept to show the artifacts the thesis warns of at sharp joints. Ignores `caps`,
    /// `half_quad_contours`, `highlight`. Needs [`AssetExtras::VERTEX_NORMALS`].
    /// Draws instance by instance in a scene.
    House,
    /// Fins (seed 003): silhouettes and creases found per frame, each drawn as a quad extruded from
    /// the edge along its front face's corner normals, with Listing 3's z-bias on crease fins. Shows
    /// the article's gap where a silhouette passes a hard edge, and z-fighting on near-90° valleys
    /// without the bias. Width is the fin's length along the normal (pixels at the vertex's depth,
    /// or world units); ignores `caps`, `half_quad_contours`, `depth_scaled`, `depth_bias_px` and
    /// `highlight`. Needs [`AssetExtras::FIN_CORNERS`].
    Fins(FinSettings),
    /// The barycentric thick wireframe (seed 001, final version): every triangle edge of the mesh at
    /// `width_px` whatever the triangle's shape, from per-corner edge coordinates computed in the
    /// vertex shader (no geometry shader). Drawn in the contour colour; ignores `classes` (all edges
    /// are one class), `caps`, `half_quad_contours`, `highlight`. With `feature_only` it needs
    /// [`AssetExtras::TRIANGLE_EDGES`]. Draws instance by instance in a scene.
    Wireframe {
        /// Only the asset's feature edges (boundaries, creases, marks), not the diagonals of flat or
        /// smooth regions.
        feature_only: bool,
        /// Anti-aliased inner border (a one-pixel ramp).
        smooth: bool,
        /// The seed's first, naive attempt: unit barycentrics with this threshold; its width follows
        /// the triangle's size and shape. For comparison.
        naive_threshold: Option<f32>,
    },
    /// A hardware contour method of the thesis' survey (§4): render state alone, no edge
    /// detection. See [`HardwareContour`] for each method and its limits. Draws contours (and for
    /// [`HardwareContour::Raskar`] creases) in their class colours; `width_px` where the method has
    /// a width; ignores `caps`, `half_quad_contours`, `highlight`.
    /// Draws instance by instance in a scene.
    Hardware(HardwareContour),
    /// Surface-angle contours (§7.1): pixels whose normal is within `threshold` of perpendicular to
    /// the view, |N·V| < threshold. Width follows curvature; flat faces fail (whole face or none).
    /// Ignores everything but the contour colour. Draws instance by instance in a scene.
    SurfaceAngle(SurfaceAngleSettings),
    /// The expanded inverted hull (§7.2): the mesh pushed out along its normals by `width_px`,
    /// front faces culled, in the contour colour. With the crease-split normals the hull tears at
    /// hard edges; `smooth_normals` pushes along smooth normals. Needs
    /// [`AssetExtras::VERTEX_NORMALS`]. Draws instance by instance in a scene.
    InvertedHull {
        /// Push along each topology vertex's smooth normal instead of the render normals.
        smooth_normals: bool,
    },
    /// The hybrid depth shader of seed 004: one post-process over the application's depth alone
    /// that gives edges, ambient shading or both, from the same code with the paper's parameters,
    /// multiplied over the scene's colour (or over this asset only). Runs in
    /// [`Prepared::finish`](super::Prepared::finish); works on whatever the depth holds, so its cost
    /// follows the resolution, not the mesh. Ignores every style field but `depth_scaled`... none:
    /// it has its own parameters. Known limits (§2, §4): a dark halo where depth jumps far
    /// (the bleach factor's reason), parameters to tune per scene.
    /// Draws instance by instance in a scene.
    Hybrid(HybridDepth),
    /// Image-space edges (thesis §5): Sobel, Prewitt, Scharr or Roberts' cross over the depth and a
    /// normal buffer, thresholded, drawn after the application's pass in the contour colour. Line
    /// thickness is `width_px` (the kernel's reach), scaled with depth if `depth_scaled`. Known
    /// limits (§5.6): missed and false edges, thresholds to tune, no control over style. Ignores
    /// `classes` (one colour), `caps`, `half_quad_contours`, `highlight`.
    /// Draws instance by instance in a scene.
    ImageSpace(ImageSpace),
}

/// An image-space gradient operator (thesis §5.1–5.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Operator {
    /// Sobel, 3×3 (1 2 1).
    Sobel,
    /// Prewitt, 3×3 (1 1 1).
    Prewitt,
    /// Scharr, 3×3 (3 10 3).
    Scharr,
    /// Roberts' cross, 2×2 (the least accurate).
    Roberts,
}

impl Operator {
    /// Every operator.
    pub const ALL: [Self; 4] = [Self::Sobel, Self::Prewitt, Self::Scharr, Self::Roberts];
}

/// Parameters of the image-space edges (thesis §5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageSpace {
    /// The gradient operator.
    pub operator: Operator,
    /// Edge where the depth gradient, relative to the pixel's depth, exceeds this; 0: depth unused.
    pub depth_threshold: f32,
    /// Edge where the normal gradient exceeds this; 0: no normal buffer.
    pub normal_threshold: f32,
}

impl ImageSpace {
    /// `operator` over depth (relative gradient 0.15) and normals (gradient 0.8).
    pub const fn new(operator: Operator) -> Self {
        Self {
            operator,
            depth_threshold: 0.15,
            normal_threshold: 0.8,
        }
    }
}

/// The hardware contour methods of the thesis' survey (§4), each a short pass configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum HardwareContour {
    /// §4.1, Rossignac and van Emmerik: the mesh into depth, then every triangle's wireframe,
    /// `width_px` thick, pushed back by a depth offset (`depth_bias_px`). Only edges that poke out
    /// past the silhouette show; joints between the thick lines gap.
    RossignacVanEmmerik,
    /// §4.1, Gooch and Gooch: back faces' wireframe with LessEqual over the front faces: a contour
    /// of at most one pixel at width 1; thicker lines, no offset.
    GoochWireframe,
    /// §4.2, Raskar and Cohen: back faces filled with LessEqual: contours of at most one pixel that
    /// flicker with depth quantization.
    BackFaces,
    /// §4.3: back faces filled and pulled towards the camera (`depth_bias_px`): thick, but the
    /// width follows the front surface's orientation and is uncontrollable.
    OffsetBackFaces,
    /// §4.4, "polygon fattening": each back face's edges pushed out by `width_px` on screen and the
    /// polygon closed again, so contours are evenly thick; the fan caps do not always fill the joint.
    FattenedBackFaces,
    /// §4.5, McReynolds and Blythe: the mesh four times one step off into the stencil, the edge
    /// colour where it counts 2 or 3. Outlines the whole silhouette (not inner contours); four
    /// extra draws of the mesh. Needs a stencil buffer; changes it.
    StencilShifted,
    /// §4.6, Akeley: front faces' wireframe inverting the stencil, the edge colour where it is 1.
    /// One pixel wide; misses back-facing boundaries; rasterization noise. Needs a stencil buffer.
    InvertedStencil,
    /// §4.7, Raskar: fattened back faces for contours; ridges as quads per front edge turned down
    /// by `crease_deg` about the edge (hidden by the next face unless it folds away more), valleys
    /// turned up and kept only between the front surface and a second depth buffer of the back
    /// faces. Z-fights where a fold equals the angle.
    Raskar {
        /// The fold, in degrees between face normals, from which an edge is a crease.
        crease_deg: f32,
    },
}

impl HardwareContour {
    /// Every method, with default parameters.
    pub const ALL: [Self; 8] = [
        Self::RossignacVanEmmerik,
        Self::GoochWireframe,
        Self::BackFaces,
        Self::OffsetBackFaces,
        Self::FattenedBackFaces,
        Self::StencilShifted,
        Self::InvertedStencil,
        Self::Raskar { crease_deg: 30.0 },
    ];

    /// The method's name, as `chamfer render --technique` takes it.
    pub const fn name(&self) -> &'static str {
        match self {
            Self::RossignacVanEmmerik => "rossignac-van-emmerik",
            Self::GoochWireframe => "gooch-wireframe",
            Self::BackFaces => "back-faces",
            Self::OffsetBackFaces => "offset-back-faces",
            Self::FattenedBackFaces => "fattened-back-faces",
            Self::StencilShifted => "stencil-shifted",
            Self::InvertedStencil => "inverted-stencil",
            Self::Raskar { .. } => "raskar",
        }
    }

    /// True if the method draws through the stencil buffer.
    pub const fn needs_stencil(&self) -> bool {
        matches!(self, Self::StencilShifted | Self::InvertedStencil)
    }
}

/// A technique as the front ends offer it: its name (`chamfer render --technique`, the page's list,
/// Bevy's viewer), a one-line summary (what it is and which seed section it follows) and its
/// parameters. Each technique module lists its own; [`Technique::all`] is their concatenation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// The name, kebab-case.
    pub name: &'static str,
    /// What it is and which seed section it follows.
    pub summary: &'static str,
    /// The technique and its default parameters.
    pub technique: Technique,
}

/// The preset among `presets` that is `technique`, else the first: a module whose presets differ by
/// their parameters names a technique with other parameters after its first preset (see the
/// modules that pick by a field instead).
pub(crate) fn preset_of(presets: &'static [Preset], technique: &Technique) -> &'static Preset {
    presets
        .iter()
        .find(|p| p.technique == *technique)
        .unwrap_or(&presets[0])
}

impl Technique {
    /// Every named technique, module by module, as the modules list them.
    pub fn presets() -> impl Iterator<Item = &'static Preset> {
        techniques::MODULES.iter().flat_map(|m| m.presets())
    }

    /// Every technique with its default parameters, in the order of [`Technique::names`].
    pub fn all() -> Vec<Self> {
        Self::presets().map(|p| p.technique).collect()
    }

    /// The preset this technique is, or is a variant of (its name and summary).
    pub fn preset(&self) -> &'static Preset {
        techniques::module(self).preset(self)
    }

    /// The technique's name, as `chamfer render --technique` takes it.
    pub fn name(&self) -> &'static str {
        self.preset().name
    }

    /// Every technique's name.
    pub fn names() -> Vec<&'static str> {
        Self::presets().map(|p| p.name).collect()
    }

    /// The technique called `name`, with its default parameters.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::presets()
            .find(|p| p.name == name)
            .map(|p| p.technique)
    }

    /// A one-line description: what it is and which seed section it follows.
    pub fn summary(&self) -> &'static str {
        self.preset().summary
    }

    /// What an asset must be uploaded with for this technique (see [`GpuAsset::for_techniques`]).
    ///
    /// [`GpuAsset::for_techniques`]: super::GpuAsset::for_techniques
    pub fn needs(&self) -> AssetExtras {
        techniques::module(self).needs(self)
    }

    /// True if the technique works after the application's pass, in
    /// [`Prepared::finish`](super::Prepared::finish), and reads its depth.
    pub fn is_post_process(&self) -> bool {
        techniques::module(self).is_post_process()
    }

    /// True if the technique draws hidden edges in their own style
    /// ([`EdgeStyle::display`](super::EdgeStyle::display)); the others ignore it.
    pub fn draws_hidden_edges(&self) -> bool {
        techniques::module(self).draws_hidden()
    }

    /// True if the technique needs a stencil aspect in the target's depth format.
    pub fn needs_stencil(&self) -> bool {
        techniques::module(self).needs_stencil(self)
    }

    /// The technique's own numbers, `None` for one that has none: the schema its module declares
    /// ([`FinSettings`], [`HybridDepth`], [`SurfaceAngleSettings`]), whatever its struct.
    pub fn parameters(&self) -> Option<&dyn Parameters> {
        match self {
            Self::Fins(p) => Some(p),
            Self::Hybrid(p) => Some(p),
            Self::SurfaceAngle(p) => Some(p),
            _ => None,
        }
    }

    /// The technique's own numbers, to set (see [`Technique::parameters`]).
    pub fn parameters_mut(&mut self) -> Option<&mut dyn Parameters> {
        match self {
            Self::Fins(p) => Some(p),
            Self::Hybrid(p) => Some(p),
            Self::SurfaceAngle(p) => Some(p),
            _ => None,
        }
    }

    /// Sets the technique's parameter `name` to `value`, refusing a technique without such a
    /// parameter (the error names the ones it has).
    pub fn set_parameter(&mut self, name: &str, value: Value) -> Result<(), SchemaError> {
        let technique = self.name();
        match self.parameters_mut() {
            Some(parameters) => parameters.set(name, value),
            None => Err(SchemaError::Unknown {
                name: name.to_owned(),
                known: format!("none: technique {technique} has no parameters"),
            }),
        }
    }

    /// Refuses parameters out of their ranges (a technique without parameters has none to refuse).
    pub fn check_parameters(&self) -> Result<(), SchemaError> {
        self.parameters().map_or(Ok(()), Parameters::check)
    }

    /// The parameter tables of every technique that has some, once per table (by
    /// [`Parameters::prefix`]), in the order of [`Technique::presets`]: what a front end builds
    /// its technique controls from.
    pub fn parameter_tables() -> Vec<&'static dyn Parameters> {
        let mut tables: Vec<&'static dyn Parameters> = Vec::new();
        for preset in Self::presets() {
            if let Some(table) = preset.technique.parameters() {
                if !tables.iter().any(|t| t.prefix() == table.prefix()) {
                    tables.push(table);
                }
            }
        }
        tables
    }
}

/// A technique's own numbers (issue 40): the [`Schema`] its module declares, behind one interface
/// so that a front end lists and sets them whatever the technique. Every schema whose entries
/// share one group is one; the group is the prefix its entries are spelled with where names are
/// flat (`hybrid`: `chamfer render --hybrid-step`).
pub trait Parameters: Sync {
    /// The entries' group: the prefix of their flat names.
    fn prefix(&self) -> &'static str;
    /// The entries' names, in the table's order.
    fn names(&self) -> Vec<&'static str>;
    /// The entry `name`'s kind (`None`: no such entry).
    fn kind(&self, name: &str) -> Option<Kind>;
    /// The entry `name`'s value (`None`: unset or no such entry).
    fn get(&self, name: &str) -> Option<Value>;
    /// Sets the entry `name` to `value`.
    fn set(&mut self, name: &str, value: Value) -> Result<(), SchemaError>;
    /// Refuses values out of their entries' ranges.
    fn check(&self) -> Result<(), SchemaError>;
    /// The table as JSON ([`Schema::schema_json`]), with each entry's `default` the value held
    /// here (a preset's parameters are the defaults of that technique).
    fn schema_json(&self) -> serde_json::Value;
}

impl<S: Schema + Sync> Parameters for S {
    fn prefix(&self) -> &'static str {
        S::ENTRIES.first().map_or("", |e| e.group)
    }

    fn names(&self) -> Vec<&'static str> {
        S::ENTRIES.iter().map(|e| e.name).collect()
    }

    fn kind(&self, name: &str) -> Option<Kind> {
        S::entry(name).ok().map(|e| e.kind)
    }

    fn get(&self, name: &str) -> Option<Value> {
        S::entry(name).ok()?.get(self)
    }

    fn set(&mut self, name: &str, value: Value) -> Result<(), SchemaError> {
        Schema::set(self, name, value)
    }

    fn check(&self) -> Result<(), SchemaError> {
        self.check_ranges()
    }

    fn schema_json(&self) -> serde_json::Value {
        S::ENTRIES
            .iter()
            .map(|entry| {
                let mut json = entry.to_json();
                json["default"] = entry
                    .get(self)
                    .map_or(serde_json::Value::Null, Value::to_json);
                json
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::Technique;

    /// Each module's presets name themselves, and no two share a name.
    #[test]
    fn every_preset_names_itself_once() {
        let names = Technique::names();
        for preset in Technique::presets() {
            assert_eq!(preset.technique.name(), preset.name);
            assert_eq!(preset.technique.summary(), preset.summary);
            assert_eq!(Technique::from_name(preset.name), Some(preset.technique));
            assert_eq!(
                names.iter().filter(|&&n| n == preset.name).count(),
                1,
                "{}",
                preset.name
            );
        }
        assert_eq!(names.len(), 27);
        assert_eq!(Technique::default(), Technique::all()[0]);
    }
}
