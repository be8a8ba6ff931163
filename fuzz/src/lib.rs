//! What every fuzz target checks (the same properties as `preprocess/tests/fuzz.rs`): loading
//! never panics, a loaded mesh bakes or is refused, every baked asset decodes, and every decoded
//! asset re-encodes to the same content.

use std::path::Path;

use chamfer_preprocess::{BakeOptions, Companions, Limits, bake, bake_with_companions, load};
use chamfer_runtime::asset::Asset;

/// Small limits, so an input that asks for a lot is refused quickly instead of baked slowly.
fn limits() -> Limits {
    Limits::DEFAULT
        .with_max_input_bytes(1 << 24)
        .with_max_vertices(1 << 18)
        .with_max_triangles(1 << 18)
        .with_max_instances(1 << 12)
}

/// Loads `data` as the file `name` (whose extension picks the loader) in a folder that does not
/// exist, so references to other files are never resolved; bakes it if it loads.
pub fn load_and_bake(name: &str, data: &[u8]) {
    let path = Path::new("/nonexistent-chamfer-fuzz-folder").join(name);
    let limits = limits();
    let Ok(loaded) = load::load_bytes(&path, data, &limits) else {
        return;
    };
    let Ok(baked) = bake(loaded.mesh, name, &BakeOptions::DEFAULT.with_limits(limits)) else {
        return;
    };
    if let Err(e) = Asset::decode(&baked.asset.encode_to_vec()) {
        panic!("a baked asset does not decode: {e}");
    }
}

/// Decodes `data` as an asset; if it decodes, its re-encoding decodes to the same content.
pub fn decode(data: &[u8]) {
    if let Ok(mut asset) = Asset::decode(data) {
        let mut again = Asset::decode(&asset.encode_to_vec()).expect("re-encoded asset decodes");
        asset.header.sections.clear();
        again.header.sections.clear();
        assert_eq!(again, asset, "re-encoding changed the asset");
    }
}

/// Bakes `data` as the web page bakes a dropped file named `name`: inflated in memory if the name
/// ends in `.gz`, the files it refers to looked up among none in memory (never on disk). A refusal
/// must name the file; a baked asset must decode.
pub fn bake_dropped(name: &str, data: &[u8]) {
    let options = BakeOptions::DEFAULT.with_limits(limits());
    match bake_with_companions(Path::new(name), data, Companions::Memory(&[]), &options) {
        Ok(baked) => {
            if let Err(e) = Asset::decode(&baked.asset.encode_to_vec()) {
                panic!("a baked asset does not decode: {e}");
            }
        }
        Err(e) => assert!(e.to_string().contains(name), "{e}"),
    }
}
