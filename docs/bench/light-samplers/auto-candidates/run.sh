#!/bin/sh
# How many light-BVH candidates `auto` should draw (render/src/effects.rs,
# AUTO_BVH_CANDIDATES), chosen over seeds: ReSTIR (pairwise) on the night city with the
# tiles first, then the light BVH at 2, 4, 8, 16 and 32 candidates per pixel, and `auto`
# itself. results.md's equal-time table states each row's gain over the tiles with its 95 %
# interval over the seeds (docs/src/light-samplers.md, "Choosing"). Usage: run.sh [FILTER]
# (a substring of "N WxH"); SEEDS (12), BIN and OUT override.
set -e
BIN=${BIN:-target/release/restir-viewer}
OUT=${OUT:-docs/bench/light-samplers/auto-candidates}
bvh() { echo "restir-pairwise@bvh[light_candidates=$1]"; }
CONFIGS="restir-pairwise@tiles,$(bvh 2),$(bvh 4),$(bvh 8),$(bvh 16),restir-pairwise@bvh,restir-pairwise"
for job in "1048576 128x80" "1048576 96x64" "131072 128x80" "16384 128x80"; do
  case "$job" in *"${1:-}"*) ;; *) continue ;; esac
  n=${job% *}; size=${job#* }
  dir="$OUT/city-$n-$size"
  [ -f "$dir/results.csv" ] && continue
  start=$(date +%s)
  "$BIN" bench --scene "builtin:city:$n" --size "$size" --frames 16 --warmup 4 \
    --seeds "${SEEDS:-12}" --reference-spp 1024 --configs "$CONFIGS" --quiet --out "$dir"
  echo "city:$n $size $(( $(date +%s) - start )) s" >> "$OUT/run-times.txt"
done
