#!/usr/bin/env bash
# A reference with n light samples per vertex (docs/src/measured/many-lights.md,
# "At every vertex"): the 1-spp reference estimator on the city with the power table, with
# the light BVH, and with the BVH drawing 8 light samples per vertex, at 1 and 2 bounces.
# Per-frame MSE of one sample is what N samples divide by N: the ratio of two rows' MSE is
# how many of one row's samples one of the other's is worth. References of 1024 spp with the
# tree, jitter off. Usage: run.sh [N ...]
set -euo pipefail
cd "$(dirname "$0")/../../../.."
viewer=${BIN:-target/release/restir-viewer}
configs="path-2b[max_bounces=1;reference_light_bvh=false],path-2b[max_bounces=1],path-2b[max_bounces=1;reference_light_samples=8],path-2b[reference_light_bvh=false],path-2b,path-2b[reference_light_samples=8]"
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(131072 1048576)
for n in "${sizes[@]}"; do
    $viewer bench --scene "builtin:city:$n" --size 96x64 --frames 16 --warmup 2 --seeds 3 \
        --reference-spp 1024 --set jitter=false --set reference_light_bvh=true \
        --configs "$configs" --quiet --out "docs/bench/light-samplers/reference-light-samples/city-$n"
done
# The references themselves: a 4096-spp one with the table and a 512-spp one with the tree
# and 8 light samples per vertex, each with its own noise (results.csv,
# reference_noise_luma_rmse: half against half).
for n in "${sizes[@]}"; do
    $viewer bench --scene "builtin:city:$n" --size 96x64 --frames 1 --warmup 0 --configs nee \
        --reference-spp 4096 --set jitter=false --quiet \
        --out "docs/bench/light-samplers/reference-light-samples/reference-table-4096-city-$n"
    $viewer bench --scene "builtin:city:$n" --size 96x64 --frames 1 --warmup 0 --configs nee \
        --reference-spp 512 --set jitter=false --set reference_light_bvh=true \
        --set reference_light_samples=8 --quiet \
        --out "docs/bench/light-samplers/reference-light-samples/reference-tree-8-512-city-$n"
done
