#!/usr/bin/env bash
# The web page's figures in BENCHMARKS.md (issue 26): builds the page and the CLI, then
# web/tests/bench.mjs in headless Chromium. RUNS=N changes the repetitions (default 5).
set -euo pipefail
cd "$(dirname "$0")/.."
target=${CARGO_TARGET_DIR:-target}
./scripts/test-web.sh --build-only
node web/tests/bench.mjs "$target/web" "$target/release/chamfer" "$target/web-bench" "$target/web-tools/node_modules"
