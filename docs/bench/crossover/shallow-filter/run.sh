#!/bin/sh
# A ReSTIR tuned for the denoiser (docs/src/measured/denoiser-history.md, "The denoiser tuned per estimator"): with
# temporal reuse taking out part of the noise, does the preset need fewer à-trous
# iterations than RIS? Denoised RIS at its own best depth (two) against the preset at one
# and two, on the cells where the map is closest to the goal. Same settings as the map.
# Usage: run.sh [FILTER] (a substring of "scene camera").
set -e
export OUT=${OUT:-docs/bench/crossover/shallow-filter}
export CONFIGS='ris+denoise[denoise_iterations=2],restir-denoised[denoise_iterations=1],restir-denoised[denoise_iterations=2],ris+denoise[denoise_iterations=1]'
for filter in "detail static" "blinking-lights static" "concourse static"; do
  case "$filter" in *"${1:-}"*) ;; *) continue ;; esac
  "$(dirname "$0")/../map/run.sh" "$filter"
done
