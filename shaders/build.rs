//! Makes one string constant per `.wgsl` file of this folder, named after the file (`fins.wgsl` ->
//! `FINS`) and documented with the file's leading comment, plus `ALL`: adding a shader file is all
//! it takes to reach the runtime.

use std::fmt::Write;
use std::path::Path;

fn main() {
    let dir = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    println!("cargo:rerun-if-changed={dir}");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("the shaders folder")
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| path.extension().is_some_and(|e| e == "wgsl"))
        .collect();
    files.sort();
    let mut code = String::new();
    let mut all = String::from(
        "/// Every file, by name (for tooling and tests).\npub const ALL: &[(&str, &str)] = &[\n",
    );
    for path in &files {
        println!("cargo:rerun-if-changed={}", path.display());
        let source = std::fs::read_to_string(path).expect("a readable .wgsl file");
        let file = path
            .file_name()
            .and_then(|n| n.to_str())
            .expect("a UTF-8 file name");
        let name = file.trim_end_matches(".wgsl").to_uppercase();
        for line in source.lines().take_while(|l| l.starts_with("//")) {
            let text = line.trim_start_matches('/');
            writeln!(code, "#[doc = {:?}]", text).expect("writing to a String");
        }
        writeln!(
            code,
            "pub const {name}: &str = include_str!({:?});",
            Path::new(&dir).join(file).display().to_string()
        )
        .expect("writing to a String");
        writeln!(all, "    ({file:?}, {name}),").expect("writing to a String");
    }
    all.push_str("];\n");
    code.push_str(&all);
    std::fs::write(Path::new(&out).join("files.rs"), code).expect("writing OUT_DIR/files.rs");
}
