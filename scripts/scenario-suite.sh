#!/usr/bin/env bash
# The scenario suite: simulates each scenario and runs both estimators over it, printing error,
# time to within 5/2/1 %, interval coverage and availability per block. Every estimator change
# is judged on this table, before and after.
#   scripts/scenario-suite.sh [BUILD_DIR] [SEED]     (default: build/release, seed 1)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$repo/build/release}
seed=${2:-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cases=("paper_exp1 eps1" "paper_exp2 eps1" "paper_exp2 eps2" "paper_exp2 eps3" "load_step eps1")
printf '%-11s %-5s %-6s %9s %8s %8s %8s %9s %7s %7s\n' scenario noise est "error_%" "t5%_s" "t2%_s" \
  "t1%_s" "coverage" "lon_av" "lat_av"
for c in "${cases[@]}"; do
  set -- $c
  dir=$work/$1_$2
  "$build/bin/vmass-sim" --scenario "$1" --noise "$2" --seed "$seed" --out "$dir" >/dev/null
  for est in rls bayes; do
    "$build/bin/vmass-replay" --config "$dir/config.yaml" --samples "$dir/samples.csv" \
      --truth "$dir/truth.csv" --estimator "$est" --json |
      /usr/bin/python3 -c '
import json, sys
r = json.loads(sys.stdin.read())
f = lambda v, d=2: "never" if v is None else f"{v:.{d}f}"
print(f"%-11s %-5s %-6s %9s %8s %8s %8s %9s %7s %7s" % (sys.argv[1], sys.argv[2], r["estimator"],
      f(r["error_percent"], 3), f(r["time_within_5_s"], 1), f(r["time_within_2_s"], 1),
      f(r["time_within_1_s"], 1), f(100 * r["coverage"], 1) if r["coverage"] is not None else "n/a",
      f(100 * r["longitudinal_availability"], 1), f(100 * r["lateral_availability"], 1)))
' "$1" "$2"
  done
done
