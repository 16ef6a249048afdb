#!/usr/bin/env bash
# GI's vertex sampler with DI at auto's default for the city
# (docs/src/measured/many-lights.md, "At every vertex"): as ../gi-candidates/run.sh, but DI draws the 4 tree candidates `auto` gives it
# instead of 32, so DI's initial pass no longer dominates the frame. The power table at the
# vertex with 32 and 8 candidates against the tree with 8 and 4. Usage: run.sh [N ...]
set -euo pipefail
cd "$(dirname "$0")/../../../.."
viewer=target/release/restir-viewer
di="light_candidates=4"
configs="restir+gi-pairwise@bvh[$di;bvh_at_vertices=false;gi_light_candidates=32],restir+gi-pairwise@bvh[$di;bvh_at_vertices=false;gi_light_candidates=8],restir+gi-pairwise@bvh[$di;gi_light_candidates=8],restir+gi-pairwise@bvh[$di;gi_light_candidates=4]"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(1048576)
for n in "${sizes[@]}"; do
    $viewer bench --scene "builtin:city:$n" --size 96x64 --frames 16 --warmup 8 --seeds 3 \
        --reference-spp 1024 --set jitter=false --set reference_light_bvh=true \
        --configs "$configs" --out "docs/bench/light-samplers/gi-candidates-auto-di/city-$n"
done
