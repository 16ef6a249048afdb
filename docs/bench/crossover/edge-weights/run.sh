#!/bin/sh
# The denoiser's edge weights swept per estimator on the training scene (docs/src/measured/denoiser-history.md,
# "The denoiser tuned per estimator"): concourse, still, 384×256, the map's seeds and knob,
# each estimator at its best depth (two) with one φ moved at a time — the luminance gate
# halved and doubled (default 4), the normal exponent a quarter (default 128), the depth
# reach four times (default 1). Usage: run.sh (OUT and BIN as ../map/run.sh).
set -e
export OUT=${OUT:-docs/bench/crossover/edge-weights}
base='denoise_iterations=2'
configs=""
for est in ris+denoise restir-denoised; do
  for phi in "" ";denoise_phi_luminance=2" ";denoise_phi_luminance=8" \
      ";denoise_phi_normal=32" ";denoise_phi_depth=4"; do
    configs="$configs${configs:+,}$est[$base$phi]"
  done
done
export CONFIGS="$configs"
"$(dirname "$0")/../map/run.sh" "concourse static"
