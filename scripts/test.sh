#!/usr/bin/env bash
# Installs everything, checks the format, builds with the release flags and the tests (no
# compiler warning allowed), runs clang-tidy and every test (the qemu ones too), a fuzz smoke
# run of each target, then the suite under AddressSanitizer + UBSan and the service tests under
# ThreadSanitizer: what CI runs, after scripts/demo.sh. Prints each stage's wall time at its end.
#   scripts/test.sh            (from anywhere; run as root or with sudo rights for apt)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
source scripts/stage-clock.sh
jobs=$(nproc)
# Sanitizer and fuzz builds carry line tables (-g1): without this, ccache would key them on
# the directory of the clone, and a fresh clone would compile everything again.
export CCACHE_NOHASHDIR=1

# ctest_logged LOG ARGS...: ctest, its output also in LOG; the qemu tests' times go to the table.
ctest_logged() {
  local log=$1 rc=0
  shift
  mkdir -p "$(dirname "$log")"
  ctest "$@" 2>&1 | tee "$log" || rc=$?
  stage_notes+=("$(grep -E 'Test +#[0-9]+: service_vm_checks ' "$log" |
    sed -E 's/.*: ([a-z_]+) \.+ *([^ ]+) +([0-9.]+) sec.*/  qemu: \1 \3 s (\2)/')")
  return "$rc"
}

stage install bash scripts/install-deps.sh
stage "install (python)" bash scripts/install-python-deps.sh
stage format bash scripts/check-format.sh       # clang-format: every C++ file formatted
stage build bash scripts/build-checked.sh ci    # the release flags + tests; a warning fails it
stage tidy bash scripts/check-tidy.sh build/ci  # clang-tidy: bug-finding checks, functions <= 80 lines
# Every test; the qemu ones (label vcan, one VM at a time) start first and the others run beside
# them. Their own times are listed after the stage table.
stage ctest ctest_logged build/ci-ctest.log --preset ci -j "$jobs" -LE python
# The Python package (label python): its wheel compiles the libraries again, so it runs after
# the qemu tests rather than beside them (a starved VM delays the bus's frames).
stage python ctest --preset ci -j "$jobs" -L python
# Each fuzz target from its corpus, with a seed and a run count fixed by the commit
# (docs/fuzzing.md): a failure here is this commit's, and it replays.
stage fuzz bash scripts/fuzz.sh --smoke
stage "asan build" bash scripts/sanitizers.sh asan-build
stage "asan tests" bash scripts/sanitizers.sh asan-test
stage "tsan build" bash scripts/sanitizers.sh tsan-build
stage "tsan tests" bash scripts/sanitizers.sh tsan-test
