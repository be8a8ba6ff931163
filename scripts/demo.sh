#!/usr/bin/env bash
# Set-up plus the main job: bakes the bundled fandisk mesh and prints what the bake found.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
cargo run --release --locked --bin chamfer -- demo "$@"
