//! The crates as users get them: every published crate has the metadata crates.io shows, every
//! other member is kept off crates.io, and the README's dependency snippets name real crates,
//! versions and features (the build-script example's manifest holds its snippet line for line).
//!
//! `cargo package` itself (the tarballs build against each other) runs in `scripts/test.sh`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .expect("workspace root")
}

/// `cargo metadata --no-deps` of the workspace: its members by name.
fn members() -> HashMap<String, Value> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .args([
            "metadata",
            "--no-deps",
            "--format-version",
            "1",
            "--offline",
        ])
        .current_dir(root())
        .output()
        .expect("cargo metadata runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let metadata: Value = serde_json::from_slice(&output.stdout).expect("metadata JSON");
    metadata["packages"]
        .as_array()
        .expect("packages")
        .iter()
        .map(|p| (p["name"].as_str().expect("name").to_owned(), p.clone()))
        .collect()
}

/// `publish = false` is `"publish": []` in cargo's metadata.
fn published(package: &Value) -> bool {
    package["publish"].as_array().is_none_or(|r| !r.is_empty())
}

#[test]
fn published_crates_have_full_metadata_and_the_rest_stay_private() {
    let members = members();
    let mut published_names: Vec<&str> = members
        .iter()
        .filter(|(_, p)| published(p))
        .map(|(n, _)| n.as_str())
        .collect();
    published_names.sort();
    assert_eq!(
        published_names,
        [
            "chamfer-bevy",
            "chamfer-preprocess",
            "chamfer-runtime",
            "chamfer-shaders"
        ],
        "only the libraries users depend on are published"
    );
    for name in published_names {
        let package = &members[name];
        for field in ["description", "license", "repository", "rust_version"] {
            assert!(
                package[field].as_str().is_some_and(|v| !v.is_empty()),
                "{name}: no {field}"
            );
        }
        for field in ["keywords", "categories"] {
            let list = package[field].as_array().expect(field);
            assert!(
                (1..=5).contains(&list.len()),
                "{name}: {field} must have 1 to 5 entries, has {}",
                list.len()
            );
        }
        let manifest = Path::new(package["manifest_path"].as_str().expect("manifest"));
        let readme = package["readme"].as_str().expect("readme");
        let readme = manifest.parent().expect("crate dir").join(readme);
        assert!(readme.is_file(), "{name}: {} is missing", readme.display());
        for licence in ["LICENSE-MIT", "LICENSE-APACHE"] {
            let path = manifest.parent().expect("crate dir").join(licence);
            assert!(path.is_file(), "{name}: {} is missing", path.display());
        }
    }
}

/// One `name = ...` line of a README snippet that names a workspace crate.
struct Snippet {
    line: String,
    name: String,
    version: String,
    features: Vec<String>,
    default_features: bool,
}

fn quoted_after<'a>(text: &'a str, key: &str) -> Option<&'a str> {
    let rest = &text[text.find(key)? + key.len()..];
    let rest = rest.trim_start().strip_prefix('=')?.trim_start();
    let rest = rest.strip_prefix('"')?;
    Some(&rest[..rest.find('"')?])
}

fn parse_snippet(line: &str) -> Option<Snippet> {
    let (name, spec) = line.split_once('=')?;
    let name = name.trim();
    if !name.starts_with("chamfer-") {
        return None;
    }
    let spec = spec.trim();
    let version = match spec.strip_prefix('"') {
        Some(bare) => bare[..bare.find('"')?].to_owned(),
        None => quoted_after(spec, "version")?.to_owned(),
    };
    let features = spec
        .find("features = [")
        .map(|at| {
            let list = &spec[at + "features = [".len()..];
            list[..list.find(']').unwrap_or(0)]
                .split(',')
                .map(|f| f.trim().trim_matches('"').to_owned())
                .filter(|f| !f.is_empty())
                .collect()
        })
        .unwrap_or_default();
    Some(Snippet {
        line: line.to_owned(),
        name: name.to_owned(),
        version,
        features,
        default_features: !spec.contains("default-features = false"),
    })
}

/// The ```toml blocks of a Markdown file, each as its lines.
fn toml_blocks(markdown: &str) -> Vec<Vec<String>> {
    let mut blocks = Vec::new();
    let mut current: Option<Vec<String>> = None;
    for line in markdown.lines() {
        match (&mut current, line.trim_start()) {
            (None, l) if l.starts_with("```toml") => current = Some(Vec::new()),
            (Some(_), l) if l.starts_with("```") => blocks.extend(current.take()),
            (Some(block), _) => block.push(line.to_owned()),
            _ => {}
        }
    }
    blocks
}

/// A caret requirement `0.1` / `0.1.0` / `1` holds for `version` (the `MAJOR.MINOR.PATCH` rules of
/// cargo for the forms the README uses).
fn caret_matches(requirement: &str, version: &str) -> bool {
    let parse = |v: &str| -> Vec<u64> {
        v.split('.')
            .map(|p| p.parse().unwrap_or(u64::MAX))
            .collect()
    };
    let (req, have) = (parse(requirement), parse(version));
    let significant = req.iter().position(|&p| p != 0).unwrap_or(req.len() - 1);
    req.iter().enumerate().all(|(i, &r)| {
        if i <= significant {
            have.get(i) == Some(&r)
        } else {
            have.get(i).is_some_and(|&h| h >= r)
        }
    })
}

#[test]
fn caret_requirements_follow_cargo() {
    assert!(caret_matches("0.1", "0.1.0"));
    assert!(caret_matches("0.1.0", "0.1.3"));
    assert!(!caret_matches("0.2", "0.1.0"));
    assert!(!caret_matches("0.1.4", "0.1.3"));
    assert!(!caret_matches("1", "0.1.0"));
}

#[test]
fn readme_dependency_snippets_name_real_crates_versions_and_features() {
    let members = members();
    let mut checked = 0;
    for readme in ["README.md", "runtime/README.md", "preprocess/README.md"] {
        let text = std::fs::read_to_string(root().join(readme)).expect("README");
        for line in toml_blocks(&text).iter().flatten() {
            let Some(snippet) = parse_snippet(line.split('#').next().unwrap_or("")) else {
                continue;
            };
            let package = members
                .get(&snippet.name)
                .unwrap_or_else(|| panic!("{readme}: {} is not a workspace crate", snippet.name));
            assert!(
                published(package),
                "{readme}: {} is not published",
                snippet.name
            );
            let version = package["version"].as_str().expect("version");
            assert!(
                caret_matches(&snippet.version, version),
                "{readme}: {:?} asks for {}, the crate is {version}",
                snippet.line,
                snippet.version
            );
            for feature in &snippet.features {
                assert!(
                    package["features"].get(feature).is_some(),
                    "{readme}: {} has no feature {feature}",
                    snippet.name
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 3, "only {checked} snippet lines found");
}

#[test]
fn the_build_script_snippet_is_the_example_manifest() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let manifest =
        std::fs::read_to_string(root().join("examples/build-script/Cargo.toml")).expect("manifest");
    let block = toml_blocks(&readme)
        .into_iter()
        .find(|b| b.iter().any(|l| l.trim() == "[build-dependencies]"))
        .expect("the README's build.rs snippet");
    // Each snippet line sits in the same section of the example's manifest.
    let section_of = |text: &str, wanted: &str| -> Option<String> {
        let mut section = String::new();
        for line in text.lines() {
            if line.starts_with('[') {
                section = line.trim().to_owned();
            } else if line.trim() == wanted.trim() {
                return Some(section.clone());
            }
        }
        None
    };
    let mut section = String::new();
    for line in block.iter().filter(|l| !l.trim().is_empty()) {
        if line.starts_with('[') {
            section = line.trim().to_owned();
            continue;
        }
        assert_eq!(
            section_of(&manifest, line),
            Some(section.clone()),
            "README line {line:?} (in {section}) is not in examples/build-script/Cargo.toml's {section}"
        );
        let snippet = parse_snippet(line).expect("a chamfer crate");
        assert!(
            !snippet.default_features,
            "build scripts link the library alone"
        );
    }
}
