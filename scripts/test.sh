#!/usr/bin/env bash
# Installs everything, checks the format, builds with warnings as errors, runs clang-tidy and
# every test, a 20 s smoke run of each fuzz target, then the suite under AddressSanitizer + UBSan
# and the service tests under ThreadSanitizer (what CI runs; about 30 minutes on 2 cores).
#   scripts/test.sh            (from anywhere; run as root or with sudo rights for apt)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"

bash scripts/install-deps.sh
bash scripts/install-python-deps.sh

bash scripts/check-format.sh              # clang-format: every C++ file formatted
cmake --preset ci
cmake --build --preset ci -j "$(nproc)"
bash scripts/check-tidy.sh build/ci       # clang-tidy: bug-finding checks, functions <= 80 lines
ctest --preset ci -j "$(nproc)"           # includes core_purity and the exit-code convention
bash scripts/fuzz.sh 20                   # libFuzzer smoke run: 20 s per target (docs/fuzzing.md)
bash scripts/sanitizers.sh                # ASan + UBSan on the suite, TSan on the service tests
