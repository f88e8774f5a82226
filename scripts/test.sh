#!/usr/bin/env bash
# Installs everything, builds with warnings as errors and runs every test (what CI runs).
#   scripts/test.sh            (from anywhere; run as root or with sudo rights for apt)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"

bash scripts/install-deps.sh
bash scripts/install-python-deps.sh

cmake --preset ci
cmake --build --preset ci -j "$(nproc)"
ctest --preset ci -j "$(nproc)"
