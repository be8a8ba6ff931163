#!/usr/bin/env bash
# Installs what building and testing Chamfer needs on a fresh Debian/Ubuntu machine: a C toolchain,
# the Vulkan loader and Mesa's software Vulkan driver (lavapipe, for headless wgpu), Node.js (the glTF-Validator)
# and Rust.
# Sourced by demo.sh and test.sh; safe to run again (installs only what is missing).
set -euo pipefail
# Mesa's device-select layer prints harmless XDG_RUNTIME_DIR warnings without this.
export NODEVICE_SELECT=1

# clang and llvm (llvm-ar) compile meshoptimizer's encoders for the web page's wasm32 build; chromium
# runs the page's tests (headless, WebGPU on its own SwiftShader).
apt_packages=(build-essential pkg-config curl ca-certificates libvulkan1 mesa-vulkan-drivers clang llvm chromium)

missing=()
for p in "${apt_packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
    sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    echo "setup: installing ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# Node.js and npm, for the Khronos glTF-Validator (scripts/validate-gltf.sh), only when npm is missing
# (a nodesource nodejs already brings npm and must not be mixed with Debian's npm package).
if ! command -v npm >/dev/null; then
    sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    echo "setup: installing nodejs npm"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq nodejs npm >/dev/null
fi

if ! command -v cargo >/dev/null; then
    if [[ -x "$HOME/.cargo/bin/cargo" ]]; then
        export PATH="$HOME/.cargo/bin:$PATH"
    else
        echo "setup: installing Rust (rustup, stable)"
        curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal
        export PATH="$HOME/.cargo/bin:$PATH"
    fi
fi

# The repository's toolchain (rust-toolchain.toml: 1.97.1, which Bevy 0.20 needs) with the wasm32
# target of the web page (web/, issue 26), installed once.
toolchain=$(sed -n 's/^channel = "\(.*\)"/\1/p' "$(dirname "${BASH_SOURCE[0]}")/../rust-toolchain.toml")
if ! rustup run "$toolchain" rustc --print target-libdir --target wasm32-unknown-unknown >/dev/null 2>&1 \
    || [[ ! -d "$(rustup run "$toolchain" rustc --print target-libdir --target wasm32-unknown-unknown)" ]]; then
    echo "setup: installing Rust $toolchain (rust-toolchain.toml)"
    rustup toolchain install "$toolchain" --profile minimal --component rustfmt,clippy \
        --target wasm32-unknown-unknown
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
# this tree (release; the library without the wgpu renderer) and installed into it as a wheel.
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
echo "setup: building the Python package (maturin)"
rm -rf "$root/target/wheels/tree"
"$root/.venv/bin/maturin" build --release --locked -q -m "$root/python/Cargo.toml" -o "$root/target/wheels/tree"
"$root/.venv/bin/python" -m pip install -q --disable-pip-version-check --no-deps --force-reinstall "$root"/target/wheels/tree/chamfer-*.whl
