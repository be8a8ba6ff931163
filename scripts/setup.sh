#!/usr/bin/env bash
# Installs what building and testing all of Chamfer needs on a fresh Debian/Ubuntu machine: what the CLI needs
# (setup-cli.sh), then clang/llvm and the wasm32 target (the web page's build), Chromium (its tests), Node.js
# (the glTF-Validator), wasm-bindgen-cli and the Python venv with the package built into it.
# Sourced by test.sh; safe to run again (installs only what is missing).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup-cli.sh"

# clang and llvm (llvm-ar) compile meshoptimizer's encoders for the web page's wasm32 build; chromium
# runs the page's tests (headless, WebGPU on its own SwiftShader); qpdf checks the section drawings'
# PDFs (preprocess/tests/draw.rs).
apt_install_missing clang llvm chromium qpdf

# Node.js and npm, for the Khronos glTF-Validator (scripts/validate-gltf.sh), only when npm is missing
# (a nodesource nodejs already brings npm and must not be mixed with Debian's npm package).
command -v npm >/dev/null || apt_install_missing nodejs npm

# The web page's target (web/, issue 26).
if [[ ! -d "$(rustup run "$toolchain" rustc --print target-libdir --target wasm32-unknown-unknown 2>/dev/null)" ]]; then
    echo "setup: adding the wasm32-unknown-unknown target to Rust $toolchain"
    rustup target add --toolchain "$toolchain" wasm32-unknown-unknown
fi
# The wasm-bindgen CLI of exactly the version web/Cargo.toml pins (its output must match the crate's).
wasm_bindgen_version=0.2.130
if [[ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $wasm_bindgen_version" ]]; then
    echo "setup: installing wasm-bindgen-cli $wasm_bindgen_version"
    # Not --locked: its lock file names a webpki-roots version the registry no longer has.
    cargo install -q wasm-bindgen-cli --version "$wasm_bindgen_version" --bin wasm-bindgen
fi

# The Python package (python/, issue 27): a virtual environment .venv/ with what building and testing it
# needs (python/requirements-test.txt, installed only when missing), then the package built by maturin from
# this tree (release; the library without the wgpu renderer) and installed into it as a wheel (not
# under test.sh, see below).
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [[ ! -x "$root/.venv/bin/python" ]]; then
    echo "setup: creating $root/.venv"
    if ! python3 -m venv "$root/.venv" 2>/dev/null; then
        sudo=""
        [[ $(id -u) -ne 0 ]] && sudo="sudo"
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq python3-venv >/dev/null
        python3 -m venv "$root/.venv"
    fi
fi
if ! "$root/.venv/bin/python" - "$root/python/requirements-test.txt" <<'PY'
import sys
from importlib import metadata
for line in open(sys.argv[1]):
    requirement = line.split("#")[0].strip()
    if requirement:
        name, version = requirement.split("==")
        try:
            if metadata.version(name.split("[")[0]) != version:
                sys.exit(1)
        except metadata.PackageNotFoundError:
            sys.exit(1)
PY
then
    echo "setup: installing the Python test requirements into .venv"
    "$root/.venv/bin/python" -m pip install -q --disable-pip-version-check -r "$root/python/requirements-test.txt"
fi
# test.sh builds and installs the package from its sdist instead (what PyPI users get): it sets
# CHAMFER_SETUP_WHEEL=no, so the same crates are not compiled twice.
if [[ "${CHAMFER_SETUP_WHEEL:-yes}" == no ]]; then
    return 0 2>/dev/null || exit 0
fi
echo "setup: building the Python package (maturin)"
rm -rf "$root/target/wheels/tree"
"$root/.venv/bin/maturin" build --release --locked -q -m "$root/python/Cargo.toml" -o "$root/target/wheels/tree"
"$root/.venv/bin/python" -m pip install -q --disable-pip-version-check --no-deps --force-reinstall "$root"/target/wheels/tree/chamfer-*.whl
