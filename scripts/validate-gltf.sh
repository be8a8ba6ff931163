#!/usr/bin/env bash
# Annotates glTF, GLB and OBJ fixtures with every glTF edge dialect (extras.chamfer,
# EXT_mesh_primitive_edge_visibility, CESIUM_primitive_outline) and runs the Khronos glTF-Validator
# (npm package gltf-validator, pinned) on the results: no file may have an error. Run by test.sh.
# (fixtures/shapes/cube-quantized.gltf is left out: the fixture itself declares min/max that its
# quantized positions do not have, which the validator reports as errors of the input.)
set -euo pipefail
cd "$(dirname "$0")/.."
version=2.0.0-dev.3.10
target=${CARGO_TARGET_DIR:-target}
tools=$target/gltf-validator
if ! grep -qs "\"version\": \"$version\"" "$tools/node_modules/gltf-validator/package.json"; then
    mkdir -p "$tools"
    npm install --prefix "$tools" --no-save --no-audit --no-fund --loglevel=error "gltf-validator@$version"
fi
cargo build --release --locked --bin chamfer
chamfer=$target/release/chamfer
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
annotate() { "$chamfer" annotate "$1" -o "$out/$2" --gltf-edges extras,edge-visibility,outline --radius-rel 0.005; }
annotate fixtures/meshes/fandisk.obj fandisk.glb
annotate fixtures/meshes/fandisk.obj fandisk.gltf
annotate fixtures/meshes/suzanne.obj suzanne.glb
annotate fixtures/shapes/two-objects.obj two-objects.glb
annotate fixtures/shapes/two-materials.glb two-materials.glb
annotate fixtures/shapes/two-materials.gltf two-materials.gltf
annotate fixtures/shapes/pyramid-fans-mirrored.glb pyramid-fans-mirrored.glb
annotate fixtures/shapes/cube-marked-extras.glb cube-marked-extras.glb
node scripts/validate-gltf.mjs "$tools/node_modules/gltf-validator" "$out"/*
