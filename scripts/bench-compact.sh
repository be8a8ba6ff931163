#!/usr/bin/env bash
# Compact assets (BENCHMARKS.md "Compact assets (issue 24)"): bunny-loop2, fandisk and the generated
# 2 M-triangle torus baked uncompressed, compact and compact lossless (bytes per section, encode and
# load times against the uncompressed file's, read from a warm page cache, in one run), and the same
# meshes through gltfpack -cc (npm, pinned) as the size anchor: a packed mesh with no edge data.
# gltfpack reads glTF, so each mesh is first written as a GLB by trimesh (pinned, under the target
# folder). Nothing is installed into the repository.
#
#     scripts/bench-compact.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-15}
target=${CARGO_TARGET_DIR:-target}
tools=$target/bench-peers
out=$target/bench
mkdir -p "$out" "$tools"
if ! PYTHONPATH=$tools/py python3 -c "import trimesh; assert trimesh.__version__ == '5.2.0'" 2>/dev/null; then
    python3 -m pip install --quiet --target "$tools/py" trimesh==5.2.0 numpy==2.4.6
fi
if [ ! -x "$tools/npm/node_modules/.bin/gltfpack" ]; then
    npm install --silent --no-audit --no-fund --prefix "$tools/npm" gltfpack@1.3.0 >/dev/null
fi
cargo build --release --locked -p chamfer-preprocess --examples
torus=$("$target/release/examples/bench_bake" --write-torus 2000000)
meshes=(fixtures/meshes/bunny-loop2.ply.gz fixtures/meshes/fandisk.obj "$torus")
"$target/release/examples/bench_compact" --runs "$runs" "${meshes[@]}"

echo "### gltfpack -cc of the same meshes (mesh only: positions, normals, indices)"
echo
echo "| mesh | triangles | GLB in (trimesh) | gltfpack -cc | B/triangle |"
echo "|---|---:|---:|---:|---:|"
for mesh in "${meshes[@]}"; do
    name=$(basename "$mesh"); stem=${name%%.*}
    glb=$out/$stem.trimesh.glb; packed=$out/$stem.gltfpack.glb
    PYTHONPATH=$tools/py python3 - "$mesh" "$glb" <<'PY'
import gzip, io, sys
import trimesh
path, glb = sys.argv[1], sys.argv[2]
data = open(path, "rb").read()
kind = path.removesuffix(".gz").rsplit(".", 1)[-1]
if path.endswith(".gz"):
    data = gzip.decompress(data)
mesh = trimesh.load(io.BytesIO(data), file_type=kind, process=False, force="mesh")
mesh.export(glb)
print(len(mesh.faces), file=open(glb + ".triangles", "w"))
PY
    "$tools/npm/node_modules/.bin/gltfpack" -i "$glb" -o "$packed" -cc >/dev/null
    triangles=$(cat "$glb.triangles")
    in_bytes=$(stat -c %s "$glb"); packed_bytes=$(stat -c %s "$packed")
    printf '| %s | %s | %s | %s | %.2f |\n' "$name" "$triangles" "$in_bytes" "$packed_bytes" \
        "$(echo "$packed_bytes / $triangles" | bc -l)"
done
