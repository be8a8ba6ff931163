#!/usr/bin/env bash
# The CLI's set-up (setup-cli.sh: C toolchain, Vulkan driver, Rust) plus the main job: bakes the bundled
# fandisk mesh and prints what the bake found.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup-cli.sh
cargo run --release --locked --bin chamfer -- demo "$@"
