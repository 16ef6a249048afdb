#!/bin/sh
# The crossover map with each scene at its own à-trous depth (docs/src/measured/denoiser.md, "Each scene at
# its depth, the cost over seeds"): the depth that is best for both estimators there
# (../auto-depth: one iteration on detail, two on concourse and the dynamic scenes, four on
# many-lights:65536; the city's three were not swept), the cells, seeds and knob of
# ../map/run.sh. Each bench keeps every seed's frame times, so `bench-map` states each
# cost ratio with its interval over the seeds. Run it with the machine otherwise idle.
# Usage: run.sh [FILTER ...] (substrings of "scene camera"; every cell without one).
set -e
here=$(dirname "$0")
export OUT=${OUT:-docs/bench/crossover/best-depth}
[ $# -gt 0 ] || set -- ""
for filter in "$@"; do
  for entry in "dynamic:moving-occluder 2" "concourse 2" "dynamic:blinking-lights 2" \
      "detail 1" "many-lights:65536 4" "city:131072 3"; do
    scene=${entry% *}; depth=${entry#* }
    for cam in static pan:0.5; do
      case "$scene $cam" in *"$filter"*) ;; *) continue ;; esac
      CONFIGS="ris+denoise[denoise_iterations=$depth],restir-denoised[denoise_iterations=$depth]" \
        "$here/../map/run.sh" "$scene $cam"
    done
  done
done
