#!/usr/bin/env bash
# Fails when a C++ source or header of the repository is not clang-formatted (.clang-format,
# Debian 12's clang-format 14). Fix with: clang-format -i $(git ls-files '*.cpp' '*.hpp')
#   scripts/check-format.sh            (from anywhere)
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if ! clang-format --dry-run --Werror "${files[@]}"; then
  echo "check-format: the files above are not clang-formatted" >&2
  echo "  fix: clang-format -i \$(git ls-files '*.cpp' '*.hpp')" >&2
  exit 1
fi
echo "check-format: ${#files[@]} files formatted"
