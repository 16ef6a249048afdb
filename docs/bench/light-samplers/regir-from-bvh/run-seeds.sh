#!/usr/bin/env bash
# ReGIR fed by the tree against the tiles with enough seeds for a verdict
# (docs/src/measured/many-lights.md, "ReGIR fed by the tree"): the tiles first, so results.md's equal-time table states every
# row's gain over them with its 95 % interval; the table-filled grid at 32 slots and the
# tree-filled one at 8, the two that read 1.47x in the three-seed run. SEEDS (default 30)
# and N (default 1048576) from the environment. Run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/../../../.."
viewer=target/release/restir-viewer
n=${N:-1048576}
seeds=${SEEDS:-30}
tree="regir_build_from_bvh=true"
configs="restir-pairwise@tiles,restir-pairwise@regir,restir-pairwise@regir[$tree;regir_slots=8]"
$viewer bench --scene "builtin:city:$n" --size 96x64 --frames 16 --warmup 4 --seeds "$seeds" \
    --reference-spp 1024 --set jitter=false --set reference_light_bvh=true \
    --configs "$configs" --out "docs/bench/light-samplers/regir-from-bvh/city-$n-seeds-$seeds"
