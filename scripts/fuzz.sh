#!/usr/bin/env bash
# Builds the libFuzzer targets (the `fuzz` preset: clang-14, ASan + UBSan) and runs each for
# SECONDS (default 600: the long run; CI's smoke run gives 20). Each target starts from its seed
# corpus, fuzz/corpus/<target> (read only), and grows a working corpus in out/fuzz/corpus/<target>
# (kept between runs). Exits non-zero when any target crashed, leaked, timed out or hit a
# sanitizer report; the input that did it is saved as out/fuzz/artifacts/<target>-crash-<sha1>
# (rerun it: build/fuzz/bin/<target> out/fuzz/artifacts/<file>). Prints each target's executions,
# executions per second and coverage (edges, features).
#   scripts/fuzz.sh [SECONDS] [TARGET...]       (from anywhere; default: every target)
#   VMASS_FUZZ_JOBS=N  build jobs (default: nproc)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"

seconds=${1:-600}
shift || true
all=(fuzz_dbc_parser fuzz_candump_line fuzz_decoder fuzz_config fuzz_state)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all[@]}")
for t in "${targets[@]}"; do
  case " ${all[*]} " in
    *" $t "*) ;;
    *) echo "fuzz: no target '$t' (one of: ${all[*]})" >&2; exit 2 ;;
  esac
done

cmake --preset fuzz > /dev/null
cmake --build --preset fuzz -j "${VMASS_FUZZ_JOBS:-$(nproc)}"

out=out/fuzz
mkdir -p "$out/artifacts"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
failed=()
printf '%-18s %8s %12s %9s %8s %8s  %s\n' target seconds execs exec/s edges features result
for t in "${targets[@]}"; do
  mkdir -p "$out/corpus/$t"
  log=$out/$t.log
  rc=0
  # -timeout: one input taking longer is a hang (reported as a failure, like a crash).
  "build/fuzz/bin/$t" -max_total_time="$seconds" -timeout=25 -print_final_stats=1 \
    -artifact_prefix="$out/artifacts/$t-" "$out/corpus/$t" "fuzz/corpus/$t" > "$log" 2>&1 || rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -Eo 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  edges=$(echo "$cov" | awk '{print $2}')
  features=$(echo "$cov" | awk '{print $4}')
  result=ok
  if [ "$rc" -ne 0 ]; then
    result="FAILED (exit $rc): see $log"
    failed+=("$t")
  fi
  printf '%-18s %8s %12s %9s %8s %8s  %s\n' "$t" "$seconds" "${execs:--}" "${rate:--}" \
    "${edges:--}" "${features:--}" "$result"
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: ${failed[*]} failed; reproducers:" >&2
  ls -1 "$out"/artifacts/ >&2 || true
  for t in "${failed[@]}"; do grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error)' "$out/$t.log" >&2 || true; done
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, no crash"
