#!/usr/bin/env bash
# Documented check of `chamfer draw` in a real browser: draws the bundled fandisk with hidden lines and
# screenshots the SVG in headless Chromium (Debian's `chromium` package: apt-get install chromium).
# Usage: scripts/draw-in-chromium.sh [OUT_DIR]   (default: target/draw-check)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/draw-check}"
mkdir -p "$out"
cargo run --release --locked --bin chamfer -- draw fixtures/meshes/fandisk.obj -o "$out/fandisk.svg" \
  --hidden --width 800 --height 600
profile="$(mktemp -d)"
trap 'rm -rf "$profile"' EXIT
chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --user-data-dir="$profile" --window-size=820,620 \
  --screenshot="$out/fandisk-chromium.png" "file://$PWD/$out/fandisk.svg" 2>/dev/null
echo "screenshot: $out/fandisk-chromium.png"
