#!/usr/bin/env bash
# The performance suite of issue 12, one command: builds the release binaries, runs every
# benchmark (each beside its baseline in the same run, medians of repeated runs) and writes
# docs/performance.md with the figures, the machine, its load and the commit.
#   scripts/performance-suite.sh [--quick] [--out FILE]   (from anywhere; ~10 min, --quick ~3)
#   scripts/performance-suite.sh --check                  (~1 min: the regression check below)
#
#   --check      the hour's replay (vmass-replay --out /dev/null) against a reference workload in
#                the same run, `wc -l` over the same file repeated until it takes at least a
#                second, CPU times, medians of 5 alternated runs; fails when the replay costs
#                more than three times the committed ratio (tools/vmass_bench/replay_ratio.txt),
#                which a machine's noise never does and a regression like the last (5x) does
#
#   micro        vmass-bench (Google Benchmark): decoding random vw_mqb frames in vmass-can's
#                path and the daemon's, with cantools_bench.py on the same frames (the ratio),
#                candump parsing, a pipeline tick, an RLS update, a Bayes batch, number formatting
#   replay       one hour of driving (the simulated paper_exp2 log repeated to 60 min) through
#                vmass-replay --out /dev/null, without --out and with --json, runs alternated
#                with `wc -l` on the same file (the ratio)
#   many logs    a folder of 200 logs through vmass-replay --logs with 1 job and with every core
#   daemon       vmassd at 100 Hz fed through --can-fd (the SocketCAN reader's fd seam) at a
#                realistic bus load by vmass-bench-daemon: CPU, resident memory, tick jitter
#
# Times are CPU time for the micro benchmarks and cantools, wall and CPU time of whole processes
# otherwise; the load average beside each says how busy the machine was.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
out_md=docs/performance.md
quick=0 check=0
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --check) check=1 ;;
    --out) out_md=$2; shift ;;
    *) echo "usage: scripts/performance-suite.sh [--quick] [--out FILE] | --check" >&2; exit 2 ;;
  esac
  shift
done
runs=5 daemon_s=60 reps=5
if [ "$quick" = 1 ]; then runs=3 daemon_s=20 reps=3; fi
jobs=$(nproc)

cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs" --target vmass-bench vmass-bench-daemon vmassd \
  vmass-replay vmass-sim >/dev/null
bin=$repo/build/release/bin
work=$repo/build/perf
rm -rf "$work"
mkdir -p "$work"

# The drive: paper_exp2 (200 s, 112,006 frames), and the hour: 18 copies shifted in time.
"$bin/vmass-sim" --scenario paper_exp2 --out "$work/exp2" >/dev/null
for k in $(seq 0 17); do
  awk -v k="$k" '{ t = substr($1, 2, length($1) - 2) + k * 200.1
    printf "(%017.6f) %s %s\n", t, $2, $3 }' "$work/exp2/drive.log"
done >"$work/hour.log"
mkdir -p "$work/fleet"
for i in $(seq -w 1 200); do ln -s ../exp2/drive.log "$work/fleet/drive$i.log"; done

load() { cut -d' ' -f1 /proc/loadavg; }
# "<wall seconds> <CPU seconds>" of a command (output discarded)
timed() {
  local TIMEFORMAT='%R %U %S' t
  t=$( { time "$@" >/dev/null 2>&1; } 2>&1)
  awk '{ printf "%s %.3f\n", $1, $2 + $3 }' <<<"$t"
}

# CPU seconds (user + sys) of a command, output discarded
cpu_s() {
  local TIMEFORMAT='%U %S' t
  t=$( { time "$@" >/dev/null 2>&1; } 2>&1)
  awk '{ printf "%.4f\n", $1 + $2 }' <<<"$t"
}
wc_passes() { for _ in $(seq "$1"); do wc -l "$work/hour.log"; done; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

if [ "$check" = 1 ]; then
  committed=$(awk '/^ratio / { print $2 }' tools/vmass_bench/replay_ratio.txt)
  passes=1
  while [ "$(awk -v t="$(cpu_s wc_passes "$passes")" 'BEGIN { print (t >= 1.0) }')" = 0 ]; do
    passes=$((passes * 2))
  done
  ratios=()
  for _ in 1 2 3 4 5; do
    reference=$(cpu_s wc_passes "$passes")
    replay=$(cpu_s "$bin/vmass-replay" --config "$work/exp2/config.yaml" --log "$work/hour.log" \
      --out /dev/null)
    ratios+=("$(awk -v r="$replay" -v w="$reference" -v n="$passes" 'BEGIN { printf "%.2f", r / (w / n) }')")
    echo "replay $replay s CPU, wc -l x $passes $reference s: ratio ${ratios[-1]}" >&2
  done
  ratio=$(printf '%s\n' "${ratios[@]}" | median)
  limit=$(awk -v c="$committed" 'BEGIN { print 3 * c }')
  echo "performance-suite --check: replay / wc -l = $ratio (median of 5; committed $committed, fails above $limit)"
  awk -v r="$ratio" -v l="$limit" 'BEGIN { exit !(r <= l) }' ||
    { echo "performance-suite --check: FAILED: the replay is slower than 3x its committed cost" >&2; exit 1; }
  exit 0
fi

echo "micro benchmarks ..." >&2
load_micro=$(load)
"$bin/vmass-bench" --frames-log "$work/frames.log" --benchmark_repetitions="$reps" \
  --benchmark_report_aggregates_only=true --benchmark_out="$work/micro.json" \
  --benchmark_out_format=json >"$work/micro.txt"
bash scripts/install-python-deps.sh >/dev/null  # cantools, in build/pyenv
build/pyenv/bin/python tools/vmass_bench/cantools_bench.py --dbc tests/data/dbc/vw_mqb.dbc \
  --log "$work/frames.log" --runs "$runs" >"$work/cantools.json"

echo "replay of one hour ..." >&2
load_replay=$(load)
cfg=$work/exp2/config.yaml
: >"$work/replay.txt"
for _ in $(seq "$runs"); do  # alternated, so that both see the same load
  echo "wc $(timed wc -l "$work/hour.log")" >>"$work/replay.txt"
  echo "out $(timed "$bin/vmass-replay" --config "$cfg" --log "$work/hour.log" --out /dev/null)" \
    >>"$work/replay.txt"
  echo "noout $(timed "$bin/vmass-replay" --config "$cfg" --log "$work/hour.log")" >>"$work/replay.txt"
  echo "json $(timed "$bin/vmass-replay" --config "$cfg" --log "$work/hour.log" --json)" \
    >>"$work/replay.txt"
done

echo "200 logs ..." >&2
load_fleet=$(load)
: >"$work/fleet.txt"
for _ in $(seq "$runs"); do
  echo "1 $(timed "$bin/vmass-replay" --config "$cfg" --logs "$work/fleet" --jobs 1)" >>"$work/fleet.txt"
  echo "$jobs $(timed "$bin/vmass-replay" --config "$cfg" --logs "$work/fleet" --jobs "$jobs")" \
    >>"$work/fleet.txt"
done

echo "daemon, 2 x ${daemon_s} s ..." >&2
# The bus as the daemon's socket sees it without kernel filters (2,500 frames/s of ids its DBC
# does not know beside the drive's 560), and with them (a CAN socket's filters drop those ids).
for filler in 2500 0; do
  "$bin/vmass-bench-daemon" --log "$work/exp2/drive.log" --dbc "$work/exp2/vehicle.dbc" \
    --filler-fps "$filler" --warmup 5 --seconds "$daemon_s" --daemon-log "$work/vmassd.log" -- \
    "$bin/vmassd" --config "$cfg" --can-fd 3 --no-restore \
    --lcm-url "file://$work/vmassd.lcm?mode=w" >"$work/daemon_$filler.json"
done

/usr/bin/python3 tools/vmass_bench/performance_report.py --work "$work" --out "$out_md" \
  --commit "$(git rev-parse --short HEAD)$(git diff --quiet HEAD || echo ' (with changes)')" \
  --loads "$load_micro" "$load_replay" "$load_fleet" --jobs "$jobs"
echo "performance-suite: wrote $out_md" >&2
