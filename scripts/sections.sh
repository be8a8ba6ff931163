#!/usr/bin/env bash
# Renders docs/images/sections/: a section drawing of fixtures/cad/cube_gears.3mf (cut at y = 65, the cut
# faces hatched, the cut outline wide, hidden lines dashed in grey beyond the plane) as SVG and PDF, and
# the PDF rendered to PNG for the docs (pdftoppm, Debian's poppler-utils), and the same cut rendered in real
# time by chamfer render (caps hatched on screen, cut outline). Usage: scripts/sections.sh [chamfer]
set -euo pipefail
cd "$(dirname "$0")/.."
chamfer=${1:-target/release/chamfer}
out=docs/images/sections
mkdir -p "$out"
flags=(--section 0,1,0,65 --hidden --hidden-color 0.55,0.55,0.55 --hidden-weight 0.18 --azimuth 20
    --elevation 30 --width 1200 --height 700)
for format in svg pdf; do
    "$chamfer" draw fixtures/cad/cube_gears.3mf -o "$out/cube-gears-section.$format" "${flags[@]}"
done
pdftoppm -png -r 200 -singlefile "$out/cube-gears-section.pdf" "$out/cube-gears-section"
"$chamfer" render fixtures/cad/cube_gears.3mf -o "$out/cube-gears-render.png" --section 0,1,0,65 \
    --cap-hatch-spacing 8 --cap-hatch-width 2 --azimuth 20 --elevation 30 --width 1200 --height 700 --distance 170
