#!/usr/bin/env bash
# Set-up plus every test of the workspace (unit, integration, CLI, doc tests), annotated glTF files through
# the Khronos glTF-Validator, the docs without warnings and the published crates packaged and built from
# their tarballs. CI runs exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
cargo test --workspace --release --locked
# Annotated glTF / GLB files through the Khronos glTF-Validator (npm).
./scripts/validate-gltf.sh
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --release --locked
# Every crate users depend on, as crates.io would get it: cargo packs the workspace's crates into a
# local registry overlay so each tarball builds against the others' tarballs (dependencies from
# crates.io). --allow-dirty: a developer's uncommitted work is what gets checked (CI's clone is clean).
cargo package --workspace --locked --allow-dirty --exclude chamfer-tests --exclude chamfer-build-script-example
