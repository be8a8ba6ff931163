//! How edges look: classes, colours, width, depth bias, and which technique draws them.

use crate::asset::EdgeFlags;

use super::display::Display;
use super::layout::{CONTOUR_CLASS, INTERSECTION_CLASS, drawn::COLOR_COUNT};
use super::lighting::Highlight;
use super::technique::Technique;
use crate::section::ClipPlanes;

/// Which edge classes to draw; combine with `|`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EdgeClasses(pub u32);

impl EdgeClasses {
    /// Silhouette edges of this frame: one face towards the camera, one away (thesis §6.1).
    pub const CONTOUR: Self = Self(CONTOUR_CLASS);
    /// Edges with one face, and edges with more than two.
    pub const BOUNDARY: Self = Self((EdgeFlags::BOUNDARY.0 | EdgeFlags::NON_MANIFOLD.0) as u32);
    /// Convex creases.
    pub const RIDGE: Self = Self(EdgeFlags::RIDGE.0 as u32);
    /// Concave creases.
    pub const VALLEY: Self = Self(EdgeFlags::VALLEY.0 as u32);
    /// Edges marked in the source file, and material seams.
    pub const MARKED: Self = Self((EdgeFlags::MARKED.0 | EdgeFlags::MATERIAL.0) as u32);
    /// Where triangles cut through each other (baked with `--intersections`, thesis §2.2); drawn
    /// by [`Technique::Joined`] like creases, view-independent and depth tested.
    pub const INTERSECTION: Self = Self(INTERSECTION_CLASS);
    /// Both crease directions.
    pub const CREASE: Self = Self(Self::RIDGE.0 | Self::VALLEY.0);
    /// Every class.
    pub const ALL: Self = Self(
        Self::CONTOUR.0 | Self::BOUNDARY.0 | Self::CREASE.0 | Self::MARKED.0 | Self::INTERSECTION.0,
    );
    /// No class: nothing is drawn.
    pub const NONE: Self = Self(0);

    /// Each class by name, as `chamfer render --classes`, the page and its settings spell them:
    /// the one table of class names.
    pub const NAMED: [(&'static str, Self); 6] = [
        ("contour", Self::CONTOUR),
        ("boundary", Self::BOUNDARY),
        ("marked", Self::MARKED),
        ("ridge", Self::RIDGE),
        ("valley", Self::VALLEY),
        ("intersection", Self::INTERSECTION),
    ];

    /// Every class's name, in [`EdgeClasses::NAMED`]'s order.
    pub fn names() -> impl Iterator<Item = &'static str> {
        Self::NAMED.iter().map(|(name, _)| *name)
    }

    /// The classes named in `names`; `Err` with the first unknown name.
    pub fn from_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<Self, &'a str> {
        names.into_iter().try_fold(Self::NONE, |all, name| {
            Self::NAMED
                .iter()
                .find(|(known, _)| *known == name)
                .map(|(_, class)| all | *class)
                .ok_or(name)
        })
    }

    /// True if every class of `other` is in `self`.
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// True if any class of `other` is in `self`.
    pub const fn intersects(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }
}

impl std::ops::BitOr for EdgeClasses {
    type Output = Self;
    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

/// Straight-alpha RGBA colour per class. An edge in several classes takes the first of: contour,
/// boundary, marked, ridge, valley.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeColors {
    /// Silhouettes.
    pub contour: [f32; 4],
    /// Boundary and non-manifold edges.
    pub boundary: [f32; 4],
    /// Marked edges and material seams.
    pub marked: [f32; 4],
    /// Convex creases.
    pub ridge: [f32; 4],
    /// Concave creases.
    pub valley: [f32; 4],
    /// Intersection edges.
    pub intersection: [f32; 4],
}

impl EdgeColors {
    /// Every class in one colour.
    pub const fn all(color: [f32; 4]) -> Self {
        Self {
            contour: color,
            boundary: color,
            marked: color,
            ridge: color,
            valley: color,
            intersection: color,
        }
    }

    pub(crate) fn array(&self) -> [[f32; 4]; COLOR_COUNT as usize] {
        [
            self.contour,
            self.boundary,
            self.marked,
            self.ridge,
            self.valley,
            self.intersection,
        ]
    }
}

impl Default for EdgeColors {
    fn default() -> Self {
        Self {
            contour: [0.0, 0.0, 0.0, 1.0],
            boundary: [0.75, 0.1, 0.1, 1.0],
            marked: [0.95, 0.55, 0.05, 1.0],
            ridge: [0.08, 0.08, 0.1, 1.0],
            valley: [0.1, 0.25, 0.6, 1.0],
            intersection: [0.1, 0.55, 0.2, 1.0],
        }
    }
}

/// How the gaps and overlaps where drawn edges meet are resolved ([`Technique::Joined`] only).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CapMethod {
    /// One thread per drawn edge end walks its vertex's next-index ring (thesis §13): the work
    /// follows the drawn edges.
    #[default]
    NextIndex,
    /// One thread per vertex with two or more edges walks its ring from the cap buffer's head
    /// (thesis §10.5): the work follows the mesh. Up to 16 drawn edges per vertex are joined.
    CapBuffer,
    /// Plain quads: gaps at bends and double coverage where quads overlap (McGuire–Hughes
    /// without caps). For comparison.
    None,
}

/// How edges look; given to [`EdgeRenderer::prepare`](super::EdgeRenderer::prepare) each frame.
///
/// Every technique honours what it can of these fields; each [`Technique`] variant's docs say which
/// fields it ignores.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeStyle {
    /// Which technique draws the edges.
    pub technique: Technique,
    /// Classes to draw.
    pub classes: EdgeClasses,
    /// Colour per class.
    pub colors: EdgeColors,
    /// Line width in pixels.
    pub width_px: f32,
    /// Scale the width with depth (thesis §9.1): `width_px` at the model's centre, wider in front,
    /// narrower behind, never below `min_width_px`. Perspective cameras only.
    pub depth_scaled: bool,
    /// Lower bound of a depth-scaled width, pixels.
    pub min_width_px: f32,
    /// How far, in pixels' worth of world distance at the edge's depth, edges are pulled towards the
    /// camera for the depth test. `None`: `1 + 1.5 × width`, enough for faces up to about 55° from
    /// the view direction across the quad's half-width, far less than any real occluder's distance.
    pub depth_bias_px: Option<f32>,
    /// How edges join ([`Technique::Joined`]).
    pub caps: CapMethod,
    /// Draw contours as half quads outside the silhouette (thesis §8.3), full width.
    pub half_quad_contours: bool,
    /// Skip creases and marked edges whose two faces both look away (closed meshes hide them anyway).
    pub cull_back_facing: bool,
    /// Draw chamfer edges (those with a radius) as lit rounded strips (seed 000) instead of lines
    /// ([`Technique::Joined`]).
    pub highlight: Option<Highlight>,
    /// Skip the asset's edge clusters that cannot hold a drawn edge before classifying any edge
    /// ([`Technique::Joined`]; issue 14). The same edges are drawn either way; `false` classifies every
    /// edge, the baseline the cluster test is measured against.
    pub cluster_culling: bool,
    /// Section planes in world space (issue 43): every technique clips its edges to what they keep.
    /// An [`Instance`](super::Instance) may have its own.
    pub section: ClipPlanes,
    /// The hidden part of each drawn edge in a style of its own, and edges fading with distance
    /// (issue 42; [`Technique::Joined`], [`Technique::McGuireHughes`] and [`Technique::Fins`]).
    pub display: Display,
}

impl Default for EdgeStyle {
    fn default() -> Self {
        Self {
            technique: Technique::Joined,
            classes: EdgeClasses::ALL,
            colors: EdgeColors::default(),
            width_px: 2.0,
            depth_scaled: false,
            min_width_px: 1.0,
            depth_bias_px: None,
            caps: CapMethod::NextIndex,
            half_quad_contours: true,
            cull_back_facing: true,
            highlight: None,
            cluster_culling: true,
            section: ClipPlanes::NONE,
            display: Display::default(),
        }
    }
}

impl EdgeStyle {
    /// The width clamped to what a pass can draw.
    pub(crate) fn width(&self) -> f32 {
        if self.width_px.is_finite() {
            self.width_px.clamp(0.0, 4096.0)
        } else {
            0.0
        }
    }

    /// The depth bias in pixels.
    pub(crate) fn bias_px(&self) -> f32 {
        self.depth_bias_px
            .filter(|b| b.is_finite())
            .unwrap_or(1.0 + 1.5 * self.width())
    }
}

#[cfg(test)]
mod named_tests {
    use super::EdgeClasses;

    #[test]
    fn the_named_classes_are_all_the_classes_once() {
        let all = EdgeClasses::from_names(EdgeClasses::names()).expect("known");
        assert_eq!(all, EdgeClasses::ALL);
        assert_eq!(EdgeClasses::from_names(["ridge", "seam"]), Err("seam"));
        assert_eq!(EdgeClasses::from_names([]), Ok(EdgeClasses::NONE));
    }
}
