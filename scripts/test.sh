#!/usr/bin/env bash
# Set-up plus every test of the workspace (unit, integration, CLI, doc tests), annotated glTF files through
# the Khronos glTF-Validator, the docs without warnings and the published crates packaged and built from
# their tarballs. CI runs exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each step's end is logged with the seconds since the start (BENCHMARKS.md keeps what each costs).
step() { echo "test.sh: $1 done at ${SECONDS} s" >&2; }
CHAMFER_SETUP_WHEEL=no source scripts/setup.sh
step set-up
cargo test --workspace --release --locked
step "cargo test"
# Annotated glTF / GLB files through the Khronos glTF-Validator (npm).
./scripts/validate-gltf.sh
step glTF-Validator
# The web page: built for wasm32 and driven in headless Chromium.
./scripts/test-web.sh
step "the page"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --release --locked
step docs
# Every crate users depend on, as crates.io would get it: cargo packs the workspace's crates into a
# local registry overlay so each tarball builds against the others' tarballs (dependencies from
# crates.io). --allow-dirty: a developer's uncommitted work is what gets checked (CI's clone is clean).
# The overlay's unpacked sources (under CARGO_HOME) and their builds are keyed by name and version only,
# so an earlier run's copies of our crates would be reused as they were: clear them first.
target=${CARGO_TARGET_DIR:-target}
rm -rf "${CARGO_HOME:-$HOME/.cargo}"/registry/src/*/chamfer-{shaders,runtime,preprocess}-[0-9]* "$target/package"
if [ -d "$target/debug/.fingerprint" ]; then
    find "$target/debug/.fingerprint" -maxdepth 1 -name 'chamfer-*' -exec rm -rf {} +
fi
# The tarballs build in the dev profile (target/debug), which nothing else here uses: without debug
# info, which no one reads there.
CARGO_PROFILE_DEV_DEBUG=false cargo package --workspace --locked --allow-dirty --exclude chamfer-tests --exclude chamfer-build-script-example \
    --exclude chamfer-python --exclude chamfer-web --exclude chamfer-bevy  # Python: PyPI (below); web: the page
# chamfer-bevy is packed too but not built from its tarball: that would compile Bevy a second time
# (13 min here, BENCHMARKS.md); the workspace build above is the same code.
cargo package --locked --allow-dirty --no-verify -p chamfer-bevy -p chamfer-runtime -p chamfer-preprocess \
    -p chamfer-shaders
step "cargo package"
# The Python package (python/, issue 27), as users get it: its sdist, a wheel built from that sdist (into the
# same target folder, so the dependencies the workspace build compiled are reused; set-up built none here)
# and installed into .venv, then its tests (pytest:
# the bindings against the chamfer binary cargo test built, and the Dask batch bakes on a LocalCluster).
rm -rf "$target/wheels/sdist"
.venv/bin/maturin sdist -m python/Cargo.toml -o "$target/wheels/sdist"
# The sdist unpacks outside the repository: the repository's toolchain by name, so the dependencies
# the workspace build compiled are reused.
PATH="$PWD/.venv/bin:$PATH" RUSTUP_TOOLCHAIN="$toolchain" CARGO_TARGET_DIR="$(cd "$target" && pwd)" .venv/bin/python -m pip wheel -q --disable-pip-version-check --no-deps \
    --no-build-isolation -w "$target/wheels/sdist" "$target"/wheels/sdist/chamfer-*.tar.gz
.venv/bin/python -m pip install -q --disable-pip-version-check --no-deps --force-reinstall "$target"/wheels/sdist/chamfer-*.whl
step "Python sdist and wheel"
.venv/bin/python -m pytest python/tests -q
step "Python tests"
