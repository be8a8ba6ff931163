#!/usr/bin/env bash
# Bake speed against peers (BENCHMARKS.md "Bake speed (issue 15)"): whole-process `chamfer bake` of
# bunny-loop2 against trimesh and three.js, our weld against meshoptimizer's vertex remap, the
# stage table (and, with BASE=path/to/an/older/chamfer, the same for that build, in the same run).
# Peers are pinned and installed under the target folder, never into the repository.
#
#     scripts/bench-peers.sh [ROUNDS]          BASE=/tmp/chamfer-main scripts/bench-peers.sh 5
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-5}
target=${CARGO_TARGET_DIR:-target}
tools=$target/bench-peers
if ! PYTHONPATH=$tools/py python3 -c "import trimesh, meshoptimizer; assert trimesh.__version__ == '5.2.0'" 2>/dev/null; then
    python3 -m pip install --quiet --target "$tools/py" trimesh==5.2.0 meshoptimizer==0.2.30a0 numpy==2.4.6
fi
if ! grep -qs '"version": "0.187.0"' "$tools/node/node_modules/three/package.json"; then
    mkdir -p "$tools/node"
    npm install --prefix "$tools/node" --no-save --no-audit --no-fund --loglevel=error three@0.187.0
fi
cargo build --release --locked -p chamfer-preprocess --bin chamfer --example bench_weld_remap
mkdir -p "$target/bench"
mesh=$target/bench/bunny-loop2.ply
[ -s "$mesh" ] || gunzip -c fixtures/meshes/bunny-loop2.ply.gz > "$mesh"
base=()
[ -n "${BASE:-}" ] && base=(--base "$BASE")
PYTHONPATH=$tools/py python3 scripts/bench-peers.py all --rounds "$rounds" \
    --chamfer "$target/release/chamfer" "${base[@]}" \
    --three "$tools/node/node_modules/three" \
    --weld-bench "$target/release/examples/bench_weld_remap" "$mesh"
