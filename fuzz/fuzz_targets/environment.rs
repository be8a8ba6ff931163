#![no_main]

// A Radiance .hdr environment (issue 29) decodes or is refused, never panics.
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = chamfer_preprocess::environment::environment_from_bytes(
        std::path::Path::new("input.hdr"),
        data,
    );
});
