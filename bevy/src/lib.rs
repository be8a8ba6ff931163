//! Chamfer in Bevy: add [`ChamferPlugin`], load a `.chamfer` asset (or a mesh file baked by Bevy's
//! asset processor with [`ChamferBake`]) and put [`ChamferEdges`] on any entity; every 3D camera
//! draws its edges in Bevy's own 3D pass.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use chamfer_bevy::{ChamferAsset, ChamferEdges, ChamferPlugin};
//!
//! fn setup(mut commands: Commands, assets: Res<AssetServer>) {
//!     let part: Handle<ChamferAsset> = assets.load("part.chamfer");
//!     commands.spawn((
//!         Mesh3d(assets.load("part.chamfer#mesh")),
//!         MeshMaterial3d::<StandardMaterial>::default(),
//!         ChamferEdges::new(part),
//!     ));
//! }
//! ```

mod asset;
mod bake;
mod render;
mod section;

use bevy::prelude::*;

pub use asset::{ChamferAsset, ChamferLoadError, ChamferLoader, render_mesh};
pub use bake::{BakeError, ChamferBake, bake_to_asset};
pub use chamfer_preprocess::schema::BakeSettings;
pub use chamfer_runtime::highlight::ggx::PbrMaterial;
pub use chamfer_runtime::render::{CapHatch, CapStyle, CutOutline, CutStyle};
pub use chamfer_runtime::render::{
    Display, DisplaySettings, DistanceFade, HiddenStyle, LinePattern,
};
pub use chamfer_runtime::render::{
    EdgeClasses, EdgeStyle, FinSettings, Highlight, HybridDepth, Light, Parameters, Shading,
    SurfaceAngleSettings, Technique,
};
pub use chamfer_runtime::section::{ClipPlanes, CutSettings, Plane, Section};
pub use render::{ChamferEdges, ChamferTimings};
pub use section::{ChamferSection, SectionExtension, SectionMaterial, SectionUniform};

/// Loads `.chamfer` assets, bakes mesh files in the asset processor ([`ChamferBake`]) and draws
/// [`ChamferEdges`] in every 3D camera.
#[derive(Default)]
pub struct ChamferPlugin;

impl Plugin for ChamferPlugin {
    fn build(&self, app: &mut App) {
        let processor = app
            .world()
            .get_resource::<bevy::asset::processor::AssetProcessor>()
            .cloned();
        app.init_asset::<ChamferAsset>()
            .init_asset_loader::<ChamferLoader>()
            .register_asset_processor(ChamferBake::new(processor));
        render::build(app);
        section::build(app);
    }
}
