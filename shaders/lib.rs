//! The WGSL sources of Chamfer's renderer, one file per pass or technique, as string constants.
//!
//! This crate is the one place the shaders live; `chamfer-runtime` assembles each pipeline's module
//! from these pieces (shared definitions first, then the pass) and prepends the constants it shares
//! with the Rust side, so a constant is never written twice. Each file's constant is named after it
//! (`fins.wgsl` is [`FINS`]) and documented with the file's own leading comment; `build.rs` makes
//! them, so a new shader file needs no line here.
//!
//! ```
//! // Each file is a constant, and `ALL` lists them by file name (for tools that check or bundle WGSL).
//! assert!(chamfer_shaders::COMMON.contains("struct Frame"));
//! let (name, source) = chamfer_shaders::ALL.iter().find(|(n, _)| *n == "common.wgsl").unwrap();
//! assert_eq!((*name, *source), ("common.wgsl", chamfer_shaders::COMMON));
//! ```

include!(concat!(env!("OUT_DIR"), "/files.rs"));
