#!/usr/bin/env bash
# The fleet layer's benchmark (docs/performance.md, "A fleet on Dask"): vmass.fleet on a
# LocalCluster of 1 and 2 workers against vmass-replay --logs with 1 and 2 jobs, over the same
# logs of an hour each (the hour of scripts/performance-suite.sh: paper_exp2 repeated to 60
# min), results written by the workers. Needs a build with the tools and the package installed
# in PYTHON (ctest -L python installs it in build/<preset>/tests/python/wheel/venv).
#   scripts/fleet-benchmark.sh [BUILD_DIR] [PYTHON] [LOGS] [RUNS]
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$repo/build/ci}
python=${2:-$build/tests/python/wheel/venv/bin/python}
logs=${3:-16}
runs=${4:-3}
work=$repo/build/fleet-bench
rm -rf "$work" && mkdir -p "$work"
"$build/bin/vmass-sim" --scenario paper_exp2 --out "$work/exp2" >/dev/null
for k in $(seq 0 17); do
  awk -v k="$k" '{ t = substr($1, 2, length($1) - 2) + k * 200.1
    printf "(%017.6f) %s %s\n", t, $2, $3 }' "$work/exp2/drive.log"
done >"$work/hour.log"
"$python" "$repo/tools/vmass_bench/fleet_bench.py" "$build/bin" "$work/hour.log" \
  "$work/exp2/config.yaml" "$work" --logs "$logs" --runs "$runs"
