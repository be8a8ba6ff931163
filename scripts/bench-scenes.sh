#!/usr/bin/env bash
# Scenes in batches (BENCHMARKS.md "Scenes in batches (issue 28)"): bench_scene at 8, 1,000 and ~10,000
# instances (joined), McGuire–Hughes and fins at 1,000, each batched against one renderer per instance
# where that is affordable, and bench_render on the bunny and bunny-loop2. With OLD=DIR naming a folder
# of the same examples built from an earlier commit, the same runs of those first, as the baseline.
#
#     OLD=/tmp/old-examples scripts/bench-scenes.sh
set -euo pipefail
cd "$(dirname "$0")/.."
export NODEVICE_SELECT=1
target=${CARGO_TARGET_DIR:-target}
cargo build --release --locked -p chamfer-preprocess --example bench_scene --example bench_render
new=$target/release/examples
if [ -n "${OLD:-}" ]; then
    echo "## baseline: $OLD"
    "$OLD/bench_scene" --frames 5
    "$OLD/bench_render" --frames 9
fi
echo "## now"
"$new/bench_scene" --frames 5
"$new/bench_scene" --frames 5 --grid 2 --no-separate
"$new/bench_scene" --frames 3 --grid 22 --no-separate
"$new/bench_scene" --frames 5 --technique mcguire-hughes
"$new/bench_scene" --frames 5 --technique fins
"$new/bench_render" --frames 9
