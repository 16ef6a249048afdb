#!/usr/bin/env bash
# ReGIR fed by the tree (docs/src/measured/many-lights.md, "Light samplers at scale", "ReGIR fed by the tree"):
# ReSTIR (pairwise) on the city with its candidates from the tiles, from ReGIR filled from
# the power table and from the light BVH (32 slots per cell, and 8), and from the BVH
# itself. References sample with the tree (reference_light_bvh=true). Usage: run.sh [N ...]
set -euo pipefail
cd "$(dirname "$0")/../../../.."
viewer=target/release/restir-viewer
configs="restir-pairwise@tiles,restir-pairwise@regir,restir-pairwise@regir[regir_build_from_bvh=true],restir-pairwise@regir[regir_slots=8],restir-pairwise@regir[regir_build_from_bvh=true;regir_slots=8],restir-pairwise@bvh"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(1048576)
for n in "${sizes[@]}"; do
    $viewer bench --scene "builtin:city:$n" --size 96x64 --frames 16 --warmup 4 --seeds 3 \
        --reference-spp 1024 --set jitter=false --set reference_light_bvh=true \
        --configs "$configs" --out "docs/bench/light-samplers/regir-from-bvh/city-$n"
done
