#!/usr/bin/env bash
# From a run-fresh-clone.sh log (OUT_DIR/test.log): binaries.csv (the build, then each test
# binary's wall seconds from its "Running" line to its result, and the total) and
# tests.csv (each test's seconds as libtest's --report-time printed them).
set -euo pipefail
cd "$1"
awk '
    /BUILD_DONE/ { printf "build,%.1f\n", $1; last = $1 }
    / Running / { name = ($3 == "unittests") ? $4 : $3; start = $1 }
    /test result:/ && name != "" { printf "%s,%.1f\n", name, $1 - start; name = "" }
    $1 ~ /^[0-9.]+$/ { end = $1 }
    END { printf "total,%.1f\n", end }
' test.log | sed '1i binary,seconds' > binaries.csv
awk '
    / Running / { bin = ($3 == "unittests") ? $4 : $3 }
    / \.\.\. ok <[0-9.]+s>$/ { t = $NF; gsub(/[<>s]/, "", t); printf "%s,%s,%s\n", bin, $3, t }
' test.log | sed '1i binary,test,seconds' > tests.csv
