#!/usr/bin/env bash
# STL and 3MF in, and stitching (BENCHMARKS.md "STL and 3MF (issue 30)"): bunny-loop2 as a binary STL
# soup and as a 3MF, parsed by Chamfer, stl_io 0.11 (benches/stl-peer) and trimesh; whole-process bakes of
# the same mesh as PLY, STL and 3MF; a cube tessellated face by face baked with and without stitching.
# Peers are pinned and installed under the target folder, never into the repository.
#
#     scripts/bench-cad.sh [ROUNDS]
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-5}
target=${CARGO_TARGET_DIR:-target}
tools=$target/bench-peers
if ! PYTHONPATH=$tools/py python3 -c "import trimesh, lxml, networkx; assert trimesh.__version__ == '5.2.0'" 2>/dev/null; then
    python3 -m pip install --quiet --target "$tools/py" trimesh==5.2.0 numpy==2.4.6 lxml==6.0.2 networkx==3.5
fi
cargo build --release --locked -p chamfer-preprocess --bin chamfer
CARGO_TARGET_DIR=$target/stl-peer cargo build --release --locked --manifest-path benches/stl-peer/Cargo.toml
out=$target/bench/cad
mkdir -p "$out"
mesh=$target/bench/bunny-loop2.ply
[ -s "$mesh" ] || gunzip -c fixtures/meshes/bunny-loop2.ply.gz > "$mesh"
[ -s "$out/cracked.obj" ] && [ -s "$out/bunny-ascii.stl" ] || PYTHONPATH=$tools/py python3 scripts/bench-cad.py make "$mesh" "$out"
PYTHONPATH=$tools/py python3 scripts/bench-cad.py all --chamfer "$target/release/chamfer" \
    --peer "$target/stl-peer/release/chamfer-stl-peer" --rounds "$rounds" "$out" "$mesh"
