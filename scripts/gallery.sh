#!/usr/bin/env bash
# Renders docs/images/techniques/: every edge technique of `chamfer render --technique` on the same
# four scenes with the same cameras (cube at 12 px, fandisk, bunny, two objects overlapping in depth),
# for docs/techniques.md. Usage: scripts/gallery.sh [path/to/chamfer]
set -euo pipefail
cd "$(dirname "$0")/.."
export NODEVICE_SELECT=1
chamfer=${1:-target/release/chamfer}
out=docs/images/techniques
mkdir -p "$out"
# The technique names, from the command's own list.
names=$("$chamfer" render --help | sed -n 's/.*\[possible values: \(.*\)\].*/\1/p' | grep -m1 joined | tr -d ',')
for technique in $names; do
    common=(--technique "$technique" --width 240 --height 200)
    "$chamfer" render fixtures/shapes/cube.obj -o "$out/cube-$technique.png" "${common[@]}" \
        --edge-width 12 >/dev/null
    "$chamfer" render fixtures/meshes/fandisk.obj -o "$out/fandisk-$technique.png" "${common[@]}" \
        --azimuth -120 --elevation 30 --edge-width 2 >/dev/null
    "$chamfer" render fixtures/meshes/stanford-bunny.obj -o "$out/bunny-$technique.png" \
        "${common[@]}" --edge-width 1.5 >/dev/null
    "$chamfer" render fixtures/shapes/two-objects.obj -o "$out/two-objects-$technique.png" \
        "${common[@]}" --azimuth 5 --elevation 15 --edge-width 2 >/dev/null
    echo "$technique"
done
# McGuire-Hughes without its cap passes: the joints' gaps (thesis §6.4).
"$chamfer" render fixtures/shapes/cube.obj -o "$out/cube-mcguire-hughes-nocaps.png" --technique mcguire-hughes \
    --caps none --width 240 --height 200 --edge-width 12 >/dev/null
