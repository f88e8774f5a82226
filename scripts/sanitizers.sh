#!/usr/bin/env bash
# CI's sanitizer runs (docs/reliability.md): every test under AddressSanitizer + UBSan (the
# `asan` preset: clang-14, -O1), then the daemon's service tests under ThreadSanitizer (`tsan`,
# -O1). The qemu tests (label vcan) are left out: they would not finish under emulation and
# sanitizers. A report fails the test that produced it. Suppressions are for third-party code
# only, each with its reason (tests/service/tsan.supp); UBSan needs none.
#   scripts/sanitizers.sh [asan-build|asan-test|tsan-build|tsan-test]...   (default: all four)
#   (after scripts/install-deps.sh)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
jobs=$(nproc)

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$repo/tests/service/tsan.supp}

steps=("$@")
[ ${#steps[@]} -gt 0 ] || steps=(asan-build asan-test tsan-build tsan-test)
for step in "${steps[@]}"; do
  case "$step" in
    asan-build)
      cmake --preset asan > /dev/null
      cmake --build --preset asan -j "$jobs" ;;
    asan-test)
      ctest --preset asan -j "$jobs" -LE 'vcan|python' ;;
    tsan-build)
      cmake --preset tsan > /dev/null
      cmake --build --preset tsan -j "$jobs" --target vmass_service_tests ;;
    tsan-test)
      ctest --preset tsan -j "$jobs" -L service ;;
    *)
      echo "sanitizers: unknown step '$step' (asan-build, asan-test, tsan-build, tsan-test)" >&2
      exit 2 ;;
  esac
done
