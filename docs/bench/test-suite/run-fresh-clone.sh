#!/usr/bin/env bash
# The test command of README.md timed from a fresh clone: `git clone` of this repository's
# HEAD into ../fresh (beside it, as CI checks it out, so ../shared resolves alike), an empty
# target folder and an empty Mesa shader cache, then `.ci/setup && cargo test --workspace`
# (built first with --no-run so the build and the tests are timed apart; libtest's
# --report-time, through RUSTC_BOOTSTRAP, gives each test's seconds).
# Usage: run-fresh-clone.sh OUT_DIR. Writes OUT_DIR/test.log, binaries.csv (each test binary's
# wall seconds, the build as "build") and tests.csv (each test's seconds).
set -uo pipefail
out=$(realpath -m "$1")
repo=$(realpath "$(dirname "$0")/../../..")
fresh=$(realpath -m "$repo/../fresh")
mkdir -p "$out"
rm -rf "$fresh" && git clone -q "$repo" "$fresh" && cd "$fresh"
export MESA_SHADER_CACHE_DIR=$(mktemp -d)
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
export RUSTC_BOOTSTRAP=1
stamp() { perl -MTime::HiRes=time -ne 'BEGIN{$|=1; $t0=time} printf "%7.1f %s", time-$t0, $_'; }
{
    .ci/setup && cargo test --workspace --no-run && echo "BUILD_DONE"
    cargo test --workspace --no-fail-fast -- -Z unstable-options --report-time
    echo "RC $?"
} 2>&1 | stamp > "$out/test.log"
rm -rf "$MESA_SHADER_CACHE_DIR"
"$repo/docs/bench/test-suite/summarise.sh" "$out"
