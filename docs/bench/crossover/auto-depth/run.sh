#!/bin/sh
# The à-trous depth `denoise_auto_depth` chooses (docs/src/measured/denoiser.md, "Choosing the depth per
# scene"), on the still cells of the crossover map at 384×256: each scene, each denoised
# estimator, each candidate count of the map's knob and each of its four seeds. A choice
# needs no reference: its probe reads the noisy history alone. Its error is the error of
# the fixed depth it chose (the history does not depend on the depth, so the frames after
# the probe are those of `denoise_iterations` = the choice, bit for bit), which the map's
# folders measured: ../shallow-filter (1 and 2), ../map-tuned (2), ../map (3).
# Writes choices.csv. Usage: run.sh (BIN overrides the binary).
set -e
BIN=${BIN:-target/release/restir-viewer}
OUT=$(dirname "$0")
tmp=$(mktemp -d)
echo "scene,estimator,light_candidates,seed,depth,held_out_0,held_out_1,held_out_2,held_out_3,held_out_4,held_out_5,pixels" > "$OUT/choices.csv"
for scene in detail concourse dynamic:blinking-lights many-lights:65536; do
  for estimator in ris+denoise restir-denoised; do
    case $estimator in
      ris+denoise) args="--mode ris --set denoise=true" ;;
      *) args="--preset restir-denoised" ;;
    esac
    for n in 8 16 32; do
      for seed in 0 1 2 3; do
        # Frame 1 has no history; the probe keeps frame 7 (6 warm frames) and holds out frame 8.
        "$BIN" render --scene "builtin:$scene" --size 384x256 --frames 8 --seed $seed $args \
          --set light_candidates=$n --set denoise_auto_depth=true \
          --out "$tmp/frame.exr" --stats "$tmp/stats.json" > /dev/null 2>&1
        python3 - "$tmp/stats.json" "$scene,$estimator,$n,$seed" >> "$OUT/choices.csv" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["denoise_depth"]
print(sys.argv[2] + "," + str(d["iterations"]) + "," + ",".join("%.6g" % r for r in d["held_out_error"]) + "," + str(d["pixels"]))
PY
      done
    done
  done
done
rm -r "$tmp"
