#!/bin/sh
# The crossover map's bounds read exactly (docs/src/measured/denoiser.md, "The crossover map at 384×256"):
# the still cells whose preset was already at the baseline's best error at 8 candidates
# (marked ≤), swept from 1 candidate up, same settings otherwise. Usage: run.sh [FILTER].
# Then `restir-viewer bench-map docs/bench/crossover/low-candidates`.
set -e
BIN=${BIN:-target/release/restir-viewer}
OUT=${OUT:-docs/bench/crossover/low-candidates}
CONFIGS='ris+denoise,restir-denoised,restir-pairwise+denoise'
for scene in dynamic:moving-occluder dynamic:blinking-lights detail; do
  case "$scene" in *"${1:-}"*) ;; *) continue ;; esac
  spp=2048
  case "$scene" in dynamic:*) spp=256 ;; esac
  dir="$OUT/$(echo "$scene" | tr ':' '-')-384x256-static"
  [ -f "$dir/equal_error.csv" ] && continue
  start=$(date +%s)
  "$BIN" bench --scene "builtin:$scene" --size 384x256 --frames 8 --warmup 8 --seeds 4 \
    --reference-spp $spp --camera static --configs "$CONFIGS" \
    --knob light_candidates=1,2,4,8 --quiet --out "$dir"
  echo "$scene static $(( $(date +%s) - start )) s" >> "$OUT/run-times.txt"
done
