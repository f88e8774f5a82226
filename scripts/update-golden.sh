#!/usr/bin/env bash
# Regenerates the golden replay expectation after an intended change of the estimator.
# Say in the commit why the numbers moved.
#   scripts/update-golden.sh [BUILD_DIR]   (default: build/ci)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$repo/build/ci}
g=$repo/tests/data/golden/paper_exp2
"$build/bin/vmass-replay" --config "$g/config.yaml" --samples "$g/samples.csv" \
  --truth "$g/truth.csv" --out "$g/expected_estimate.csv"
echo "update-golden: rewrote $g/expected_estimate.csv"
# The CAN-log golden: its log and estimate travel packed (tests/data/golden/paper_exp2_can).
c=$repo/tests/data/golden/paper_exp2_can
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && cmake -E tar xf "$c/golden_can.tar.xz")
"$build/bin/vmass-replay" --config "$c/config.yaml" --log "$work/drive.log" \
  --out "$work/expected_estimate.csv" >/dev/null
(cd "$work" && cmake -E tar cJf "$c/golden_can.tar.xz" drive.log expected_estimate.csv)
echo "update-golden: rewrote $c/golden_can.tar.xz"
