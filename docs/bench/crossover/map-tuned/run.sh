#!/bin/sh
# The crossover map with the denoiser tuned per estimator (docs/src/measured/denoiser-history.md, "The denoiser
# tuned per estimator"): on the training scene (concourse at 384×256) both denoised RIS and
# the restir-denoised preset reach their lowest error with two à-trous iterations, so here
# each runs with its own best, on the cells of ../map/run.sh (same sizes, seeds, knob).
# Usage: run.sh [FILTER ...] (substrings of "scene camera"; every cell without one).
set -e
export OUT=${OUT:-docs/bench/crossover/map-tuned}
export CONFIGS='ris+denoise[denoise_iterations=2],restir-denoised[denoise_iterations=2]'
[ $# -gt 0 ] || set -- ""
for filter in "$@"; do
  "$(dirname "$0")/../map/run.sh" "$filter"
done
