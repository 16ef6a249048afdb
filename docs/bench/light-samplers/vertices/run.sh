#!/usr/bin/env bash
# The light sampler at every vertex (docs/src/measured/many-lights.md, "At every
# vertex"): on the city, GI and PT with the light BVH at their path vertices against the
# power table there, and the 1-spp reference estimator (path-2b) with each. The references
# sample with the tree (reference_light_bvh=true), which render/tests/vertex_light_sampler.rs
# holds to the table's. Jitter off: one reference per scene. Usage: run.sh [N ...]
set -euo pipefail
cd "$(dirname "$0")/../../../.."
viewer=target/release/restir-viewer
configs="path-2b[reference_light_bvh=false],path-2b,restir+gi-pairwise@bvh[bvh_at_vertices=false],restir+gi-pairwise@bvh,restir+gi-pairwise@bvh[light_candidates=8;bvh_at_vertices=false],restir+gi-pairwise@bvh[light_candidates=8],restir+pt@bvh[bvh_at_vertices=false],restir+pt@bvh"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(131072 1048576)
for n in "${sizes[@]}"; do
    $viewer bench --scene "builtin:city:$n" --size 96x64 --frames 16 --warmup 8 --seeds 3 \
        --reference-spp 1024 --set jitter=false --set reference_light_bvh=true \
        --configs "$configs" --out "docs/bench/light-samplers/vertices/city-$n"
done
