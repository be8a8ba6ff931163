#!/usr/bin/env bash
# Installs what the main job (scripts/demo.sh: build the chamfer CLI, bake and render a mesh) needs on a fresh
# Debian/Ubuntu machine: a C toolchain, the Vulkan loader and Mesa's software Vulkan driver (lavapipe, for
# headless wgpu) and Rust with the repository's toolchain. Nothing the tests alone need (setup.sh adds that).
# Sourced by demo.sh and setup.sh; safe to run again (installs only what is missing).
set -euo pipefail
# Mesa's device-select layer prints harmless XDG_RUNTIME_DIR warnings without this.
export NODEVICE_SELECT=1

# Installs the Debian packages named that are missing (with sudo when not root).
apt_install_missing() {
    local missing=() p sudo=""
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    ((${#missing[@]})) || return 0
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    echo "setup: installing ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}
apt_install_missing build-essential pkg-config curl ca-certificates libvulkan1 mesa-vulkan-drivers

if ! command -v cargo >/dev/null; then
    if [[ -x "$HOME/.cargo/bin/cargo" ]]; then
        export PATH="$HOME/.cargo/bin:$PATH"
    else
        echo "setup: installing Rust (rustup, stable)"
        curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal
        export PATH="$HOME/.cargo/bin:$PATH"
    fi
fi

# The repository's toolchain (rust-toolchain.toml: 1.97.1, which Bevy 0.20 needs), installed once.
toolchain=$(sed -n 's/^channel = "\(.*\)"/\1/p' "$(dirname "${BASH_SOURCE[0]}")/../rust-toolchain.toml")
if ! rustup run "$toolchain" rustc --version >/dev/null 2>&1; then
    echo "setup: installing Rust $toolchain (rust-toolchain.toml)"
    rustup toolchain install "$toolchain" --profile minimal --component rustfmt,clippy
fi
