#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| chamfer_fuzz::decode(data));
