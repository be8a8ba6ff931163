#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| chamfer_fuzz::load_and_bake("input.3mf", data));
