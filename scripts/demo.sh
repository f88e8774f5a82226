#!/usr/bin/env bash
# The main job on the bundled default: installs, builds (release), simulates the paper's
# experiment 2 drive (accelerating, braking, cornering) as a CAN log of the demo vehicle and runs
# the estimator over the log, printing the summary and writing a plot.
#   scripts/demo.sh [OUT_DIR]      (default: out/demo)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
out=${1:-out/demo}

bash scripts/install-deps.sh
cmake --preset release -DVMASS_BUILD_TESTS=OFF >/dev/null
cmake --build --preset release -j "$(nproc)"

bin=build/release/bin
mkdir -p "$out"
"$bin/vmass-sim" --scenario paper_exp2 --seed 1 --noise eps3 --out "$out"
# The estimator reads the drive from CAN: the candump log, decoded with vehicle.dbc through the
# config's can: mapping (samples.csv holds the same drive as CSV: --samples instead of --log).
"$bin/vmass-replay" --config "$out/config.yaml" --log "$out/drive.log" \
  --truth "$out/truth.csv" --out "$out/estimate.csv" --plot "$out/estimate.png"
echo "demo: estimate CSV $out/estimate.csv, plot $out/estimate.png"
