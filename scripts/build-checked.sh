#!/usr/bin/env bash
# Configures and builds a preset from scratch, and fails when the compiler printed a warning.
# The ci preset compiles with the release flags, without -Werror, so that it shares ccache's
# objects with the release build the demo made; ccache replays a cached object's warnings, and
# the build starts clean, so every warning of every object shows here.
#   scripts/build-checked.sh PRESET      (default: ci)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
preset=${1:-ci}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
cmake --preset "$preset" > /dev/null
cmake --build --preset "$preset" --target clean > /dev/null
rc=0
cmake --build --preset "$preset" -j "$(nproc)" 2>&1 | tee "$log" || rc=$?
[ "$rc" = 0 ] || exit "$rc"
if grep -q "warning:" "$log"; then
  echo "build-checked: the compiler warned (warnings are errors here):" >&2
  grep -A3 "warning:" "$log" >&2
  exit 1
fi
echo "build-checked: $preset built, no warning"
