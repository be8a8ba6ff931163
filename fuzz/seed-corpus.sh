#!/usr/bin/env bash
# Copies the fixtures into fuzz/corpus/<target>/ as libFuzzer's starting inputs, and bakes three of
# them into assets for the `asset` target, uncompressed and compact (format 5's coded sections).
# Run from anywhere; safe to run again.
set -euo pipefail
cd "$(dirname "$0")"
fixtures=../fixtures
mkdir -p corpus/{obj,ply,stl,threemf,gltf,glb,asset}
cp "$fixtures"/shapes/*.obj "$fixtures"/broken/*.obj "$fixtures"/hostile/*.obj corpus/obj/
cp "$fixtures"/shapes/*.ply "$fixtures"/broken/*.ply "$fixtures"/hostile/*.ply corpus/ply/
cp "$fixtures"/shapes/*.stl corpus/stl/
cp "$fixtures"/shapes/*.3mf corpus/threemf/
cp "$fixtures"/shapes/*.gltf "$fixtures"/broken/*.gltf "$fixtures"/hostile/*.gltf corpus/gltf/
cp "$fixtures"/shapes/*.glb "$fixtures"/broken/*.glb corpus/glb/
for mesh in shapes/cube.obj shapes/cube-marked-le.ply shapes/two-materials.glb; do
    cargo run --quiet --release --manifest-path ../Cargo.toml --bin chamfer -- \
        bake "$fixtures/$mesh" -o "corpus/asset/$(basename "$mesh").chamfer" >/dev/null
    cargo run --quiet --release --manifest-path ../Cargo.toml --bin chamfer -- \
        bake "$fixtures/$mesh" --compact -o "corpus/asset/$(basename "$mesh").compact.chamfer" >/dev/null
done
