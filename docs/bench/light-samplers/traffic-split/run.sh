#!/usr/bin/env bash
# The scene's tree with the moving triangles kept apart (docs/src/measured/dynamic-scenes.md,
# "The moving triangles kept apart"): bench-bvh's CPU comparison on the city with cars and on the
# orbiting lights, then `render --stats` of the city at 2^17 and 2^20, two runs each,
# interleaved with a build from before the split (BASE=path to its restir-viewer; without
# it only the split runs). Run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/../../../.."
viewer=target/release/restir-viewer
out=docs/bench/light-samplers/traffic-split
for s in city-traffic:131072 city-traffic:1048576 dynamic:many-lights:65536; do
    $viewer bench-bvh --scene "builtin:$s" --times 0,0.5,1,2,3,4 --repeats 3 \
        > "$out/bench-bvh-${s//:/-}.md"
done
builds=("split=$viewer")
[ -n "${BASE:-}" ] && builds=("single=$BASE" "${builds[@]}")
for run in 1 2; do
    for n in 131072 1048576; do
        for b in "${builds[@]}"; do
            "${b#*=}" render --scene "builtin:city-traffic:$n" --size 96x64 --frames 61 --fps 30 \
                --set light_sampler=bvh --set light_bvh_gpu_refit=false --out /tmp/traffic.exr \
                --stats "$out/traffic-$n-${b%%=*}-run$run.json"
        done
    done
done
