#!/usr/bin/env bash
# Set-up plus every test of the workspace (unit, integration, CLI, doc tests). CI runs exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
cargo test --workspace --release --locked
