#!/bin/sh
# The crossover map at 384×256 (docs/src/measured/denoiser.md, "The crossover map"): every scene, still
# and panning, 4 seeds, each configuration over light_candidates = 8, 16, 32. Each
# (scene, camera) is an independent job: run any subset, on any machine, in any order;
# each writes its own folder and a finished one is skipped. Then `restir-viewer bench-map
# docs/bench/crossover/map` writes map.md and map.csv. Usage: run.sh [FILTER] (a substring
# of "scene camera"); OUT, CONFIGS, SEEDS, SIZE, KNOB and BIN override the folder, the
# configurations (the first is the baseline), the seed count (4), the size (384x256), the
# light_candidates values (8,16,32) and the binary.
set -e
BIN=${BIN:-target/release/restir-viewer}
OUT=${OUT:-docs/bench/crossover/map}
CONFIGS=${CONFIGS:-'ris+denoise,restir-denoised,restir-pairwise+denoise'}
# Still cells first, then panning; animated scenes and moving cameras take a reference per
# frame (256 spp each), a still one 2048 spp.
for job in "concourse static" "many-lights:65536 static" "city:131072 static" \
    "detail static" "concourse pan:0.5" "dynamic:moving-occluder static" \
    "dynamic:blinking-lights static" "many-lights:65536 pan:0.5" "city:131072 pan:0.5" \
    "detail pan:0.5" "dynamic:moving-occluder pan:0.5" "dynamic:blinking-lights pan:0.5"; do
  case "$job" in *"${1:-}"*) ;; *) continue ;; esac
  scene=${job% *}; cam=${job#* }
  spp=2048
  case "$job" in dynamic:*|*pan:*) spp=256 ;; esac
  # The city samples with the light BVH at the swept candidate count. Named, not left to
  # auto: auto's BVH draws at most AUTO_BVH_CANDIDATES (4 when this ran, 8 now), which would void the sweep.
  extra=""
  case "$job" in city:*) extra="--set light_sampler=bvh" ;; esac
  size=${SIZE:-384x256}
  dir="$OUT/$(echo "$scene" | tr ':' '-')-$size-$(echo "$cam" | tr ':' '-')"
  [ -f "$dir/equal_error.csv" ] && continue
  start=$(date +%s)
  "$BIN" bench --scene "builtin:$scene" --size $size --frames 8 --warmup 8 --seeds ${SEEDS:-4} \
    --reference-spp $spp --camera $cam --configs "$CONFIGS" $extra \
    --knob light_candidates=${KNOB:-8,16,32} --quiet --out "$dir"
  echo "$scene $cam $(( $(date +%s) - start )) s" >> "$OUT/run-times.txt"
done
