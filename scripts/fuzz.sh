#!/usr/bin/env bash
# Builds the libFuzzer targets (the `fuzz` preset: clang-14, ASan + UBSan) and runs each.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]   the long random run (default 600 s each, one after
#                                           the other): new seeds each time, and a working
#                                           corpus grown in out/fuzz/corpus/<target> (kept)
#   scripts/fuzz.sh --smoke                 CI's smoke run: every target, two at a time, from its
#                                           seed corpus fuzz/corpus/<target> (read only) for a
#                                           fixed number of executions (about 10 s each) with a
#                                           seed taken from the commit: the same commit runs
#                                           the same inputs, so a failure is this commit's and
#                                           replays, and an unrelated landing never meets a
#                                           finding that a random seed happened upon
#                                           (docs/fuzzing.md)
#
# Exits non-zero when any target crashed, leaked, timed out or hit a sanitizer report; the input
# that did it is saved as out/fuzz/artifacts/<target>-crash-<sha1> (rerun it:
# build/fuzz/bin/<target> out/fuzz/artifacts/<file>). Prints each target's executions,
# executions per second and coverage (edges, features).
#   VMASS_FUZZ_JOBS=N  build jobs (default: nproc)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"

all=(fuzz_dbc_parser fuzz_candump_line fuzz_decoder fuzz_config fuzz_state fuzz_blf)
# The smoke run's executions per target: about 10 s each on a 2-core CI machine.
declare -A smoke_runs=([fuzz_dbc_parser]=8000 [fuzz_candump_line]=200000 [fuzz_decoder]=150000
                       [fuzz_config]=25000 [fuzz_state]=200000 [fuzz_blf]=30000)
smoke=0
if [ "${1:-}" = "--smoke" ]; then
  smoke=1
  shift
  seconds=0
else
  seconds=${1:-600}
  shift || true
fi
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
# The smoke run's seed: the commit's first 8 hex digits (libFuzzer takes a 32-bit seed).
smoke_seed=$(( 16#$(git rev-parse --short=8 HEAD 2>/dev/null || echo 1) ))

# fuzz_one TARGET: runs it into $out/TARGET.log; exit status libFuzzer's.
fuzz_one() {
  local t=$1 limits work
  # -timeout: one input taking longer is a hang (reported as a failure, like a crash).
  if [ "$smoke" = 1 ]; then
    work=$(mktemp -d)  # new inputs go to a scratch corpus: the next smoke run starts the same
    limits=(-seed="$smoke_seed" -runs="${smoke_runs[$t]}")
  else
    work=$out/corpus/$t
    mkdir -p "$work"
    limits=(-max_total_time="$seconds")
  fi
  local rc=0
  "build/fuzz/bin/$t" "${limits[@]}" -timeout=25 -print_final_stats=1 \
    -artifact_prefix="$out/artifacts/$t-" "$work" "fuzz/corpus/$t" > "$out/$t.log" 2>&1 || rc=$?
  [ "$smoke" = 0 ] || rm -rf "$work"
  return "$rc"
}

report_one() {
  local t=$1 rc=$2 log=$out/$1.log
  local execs rate cov edges features result=ok
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -Eo 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  edges=$(echo "$cov" | awk '{print $2}')
  features=$(echo "$cov" | awk '{print $4}')
  [ "$rc" -eq 0 ] || result="FAILED (exit $rc): see $log"
  printf '%-18s %12s %9s %8s %8s  %s\n' "$t" "${execs:--}" "${rate:--}" "${edges:--}" \
    "${features:--}" "$result"
}

failed=()
declare -A status=()
if [ "$smoke" = 1 ]; then
  # Two at a time: libFuzzer runs on one core.
  pending=("${targets[@]}")
  while [ ${#pending[@]} -gt 0 ]; do
    batch=("${pending[@]:0:2}")
    pending=("${pending[@]:2}")
    pids=()
    for t in "${batch[@]}"; do fuzz_one "$t" & pids+=($!); done
    for i in "${!batch[@]}"; do
      rc=0
      wait "${pids[$i]}" || rc=$?
      status[${batch[$i]}]=$rc
    done
  done
else
  for t in "${targets[@]}"; do
    rc=0
    fuzz_one "$t" || rc=$?
    status[$t]=$rc
  done
fi
if [ "$smoke" = 1 ]; then
  echo "fuzz: smoke run, seed $smoke_seed"
else
  echo "fuzz: $seconds s per target"
fi
printf '%-18s %12s %9s %8s %8s  %s\n' target execs exec/s edges features result
for t in "${targets[@]}"; do
  report_one "$t" "${status[$t]}"
  [ "${status[$t]}" -eq 0 ] || failed+=("$t")
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: ${failed[*]} failed; reproducers:" >&2
  ls -1 "$out"/artifacts/ >&2 || true
  for t in "${failed[@]}"; do grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error)' "$out/$t.log" >&2 || true; done
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, no crash"
