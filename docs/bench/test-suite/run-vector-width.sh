#!/usr/bin/env bash
# Lavapipe's SIMD width against the test suite's two costs: a cold compile and a frame.
# Each row: one command timed with an empty (cold) or filled (warm) shader cache, at
# LP_NATIVE_VECTOR_WIDTH 128 and 256, alternating. Needs `cargo test --workspace --no-run`
# and `cargo build` first; run from the repository root. Writes vector-width.csv.
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=docs/bench/test-suite/vector-width.csv
bin=$(ls -t target/debug/deps/integration-* | grep -v '\.d$' | head -n 1)
cache=$(mktemp -d)
secs() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -n 1; }
echo "what,cache,width,seconds" > "$out"
for round in 1 2; do
  for width in 128 256; do
    for t in glass_fresnel::a_smooth_pane_reflects_the_same_in_every_frame \
             bias_matrix::the_default_restir_is_unbiased_and_a_dropped_one_over_m_is_caught; do
      rm -rf "$cache"/*
      (cd render && echo "$t,cold,$width,$(secs env LP_NATIVE_VECTOR_WIDTH=$width MESA_SHADER_CACHE_DIR="$cache" "../$bin" "$t" --exact)") >> "$out"
      (cd render && echo "$t,warm,$width,$(secs env LP_NATIVE_VECTOR_WIDTH=$width MESA_SHADER_CACHE_DIR="$cache" "../$bin" "$t" --exact)") >> "$out"
    done
    rm -rf "$cache"/*
    render=(env LP_NATIVE_VECTOR_WIDTH=$width MESA_SHADER_CACHE_DIR="$cache"
            target/debug/restir-viewer render --scene builtin:concourse --size 320x240)
    "${render[@]}" --frames 2 --out "$cache/first.png" > /dev/null
    echo "concourse 320x240 30 frames,warm,$width,$(secs "${render[@]}" --frames 30 --out "$cache/frames.png")" >> "$out"
  done
done
rm -rf "$cache"
