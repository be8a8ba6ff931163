#![no_main]

// The web page's bake: a dropped `.ply.gz`, inflated in memory, its companions in memory.
libfuzzer_sys::fuzz_target!(|data: &[u8]| chamfer_fuzz::bake_dropped("input.ply.gz", data));
