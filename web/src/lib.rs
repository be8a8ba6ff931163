//! Chamfer in a web page (issue 26): the bake and the wgpu runtime compiled to `wasm32-unknown-unknown`
//! with wasm-bindgen, for the static page in `web/www` (`scripts/web.sh` builds and serves it).
//!
//! - [`bake`](crate::bake::bake) runs in the page's Web Worker: a dropped file's bytes and its companion
//!   files in, the asset's bytes (compact if asked) and its `inspect` report out; the same file and
//!   options give the same bytes as `chamfer bake`.
//! - [`draw_svg`](crate::bake::draw_svg) makes `chamfer draw`'s hidden-line SVG of an asset.
//! - `Viewer` (wasm32 only) draws an asset into a `<canvas>` on WebGPU with the runtime's renderers,
//!   as `chamfer render` draws it (same camera, styles and pixels for the same settings).
//!
//! What the page sends is JSON ([`settings`]); its defaults are the commands' defaults.

pub mod bake;
pub mod settings;
#[cfg(target_arch = "wasm32")]
mod viewer;

/// Runs when the module is instantiated (in the page and in its worker): panics print their message.
#[cfg(target_arch = "wasm32")]
#[wasm_bindgen::prelude::wasm_bindgen(start)]
fn start() {
    console_error_panic_hook::set_once();
}
