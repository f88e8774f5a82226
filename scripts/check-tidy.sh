#!/usr/bin/env bash
# clang-tidy over every library and tool source (.clang-tidy: checks that find real bugs, and
# no function over 80 lines). Needs a configured build for compile_commands.json.
#   scripts/check-tidy.sh [BUILD_DIR]     (default: build/ci)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$repo/build/ci}
cd "$repo"
if [ ! -f "$build/compile_commands.json" ]; then
  echo "check-tidy: $build/compile_commands.json missing: configure first (cmake --preset ci)" >&2
  exit 2
fi
mapfile -t files < <(git ls-files 'src/*.cpp' 'tools/*.cpp')
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# One file per clang-tidy process, as many processes as cores; any finding is an error.
if ! printf '%s\n' "${files[@]}" |
    xargs -P "$(nproc)" -n 1 clang-tidy -p "$build" --quiet >"$log" 2>/dev/null; then
  grep -E -A3 "(error|warning):" "$log" >&2 || cat "$log" >&2
  echo "check-tidy: findings above (.clang-tidy lists the checks)" >&2
  exit 1
fi
echo "check-tidy: ${#files[@]} files clean"
