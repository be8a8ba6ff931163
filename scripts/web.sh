#!/usr/bin/env bash
# Builds the web page (web/: the bake and the runtime compiled to wasm32, issue 26) into
# target/web/ and serves it on 127.0.0.1, printing its URL. `scripts/web.sh build` only builds
# (the browser tests use that). Needs what scripts/setup.sh installs (the wasm32 target, clang and
# llvm-ar for meshoptimizer's encoders, the wasm-bindgen CLI).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
target=${CARGO_TARGET_DIR:-target}
out="$target/web"

# meshoptimizer's C++ (the compact encoders) built for wasm32: clang, llvm-ar and the math
# functions its stripped-down wasm headers lack (web/meshopt-wasm32.h).
export CC_wasm32_unknown_unknown=clang
export AR_wasm32_unknown_unknown=llvm-ar
export CFLAGS_wasm32_unknown_unknown="-include $root/web/meshopt-wasm32.h"
cargo build --release --locked --target wasm32-unknown-unknown -p chamfer-web
rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --target web --no-typescript --out-dir "$out/pkg" \
    "$target/wasm32-unknown-unknown/release/chamfer_web.wasm"
cp -r web/www/. "$out/"
# The bundled model the page opens when it is given none.
cp fixtures/meshes/fandisk.obj "$out/fandisk.obj"
echo "web: built $out ($(du -k "$out/pkg/chamfer_web_bg.wasm" | cut -f1) KiB of wasm)"

if [[ "${1:-serve}" == build ]]; then
    exit 0
fi
port=${PORT:-8137}
echo "web: serving http://127.0.0.1:$port/ (Ctrl-C stops)"
exec python3 -m http.server --bind 127.0.0.1 --directory "$out" "$port"
