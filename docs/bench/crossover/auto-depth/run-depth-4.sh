#!/bin/sh
# The depth the probe chose for denoised RIS on many-lights:65536 (four à-trous iterations)
# was not in the map's folders: each estimator at four, on the map's still cell (settings,
# seeds and knob of ../map/run.sh), so its error can be read beside three (../map) and two
# (../map-tuned). RIS writes ./many-lights-65536-384x256-static, the preset
# ./preset-depth-4/many-lights-65536-384x256-static, both in one run ./both-at-4/.
set -e
here=$(dirname "$0")
OUT=${OUT:-docs/bench/crossover/auto-depth}
OUT=$OUT CONFIGS='ris+denoise[denoise_iterations=4]' \
  "$here/../map/run.sh" "many-lights:65536 static"
OUT=$OUT/preset-depth-4 CONFIGS='restir-denoised[denoise_iterations=4]' \
  "$here/../map/run.sh" "many-lights:65536 static"
# Both in one run, for the cost comparison (the two runs above ran apart, at other loads).
OUT=$OUT/both-at-4 CONFIGS='ris+denoise[denoise_iterations=4],restir-denoised[denoise_iterations=4]' \
  "$here/../map/run.sh" "many-lights:65536 static"
