#!/usr/bin/env bash
# GI's own light candidates at its secondary vertex (docs/src/measured/many-lights.md, "At
# every vertex"): ReSTIR GI on the city with the power table at the vertex (32 candidates,
# DI's count) against the light BVH there with 32, 8 and 4 (`gi_light_candidates`); DI keeps
# its 32 from the tree.
# References sample with the tree. Usage: run.sh [N ...]
set -euo pipefail
cd "$(dirname "$0")/../../../.."
viewer=target/release/restir-viewer
configs="restir+gi-pairwise@bvh[bvh_at_vertices=false],restir+gi-pairwise@bvh,restir+gi-pairwise@bvh[gi_light_candidates=8],restir+gi-pairwise@bvh[gi_light_candidates=4]"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(131072 1048576)
for n in "${sizes[@]}"; do
    $viewer bench --scene "builtin:city:$n" --size 96x64 --frames 16 --warmup 8 --seeds 3 \
        --reference-spp 1024 --set jitter=false --set reference_light_bvh=true \
        --configs "$configs" --out "docs/bench/light-samplers/gi-candidates/city-$n"
done
