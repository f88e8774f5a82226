# Sourced by scripts/demo.sh and scripts/test.sh: `stage NAME COMMAND...` runs COMMAND and
# records its wall time; at exit, pass or fail, a table of the stages' times is printed with
# what the machine is (cores, CPU limit, load, ccache's hits), so that every CI log and closing
# note shows where the time went.
stage_names=()
stage_seconds=()
stage_status=()
stage_notes=()  # lines printed under the table
stage_clock_start=$(date +%s)
command -v ccache > /dev/null && ccache --zero-stats > /dev/null

stage() {
  local name=$1
  shift
  local start rc=0
  start=$(date +%s)
  echo "=== stage: $name"
  "$@" || rc=$?
  stage_names+=("$name")
  stage_seconds+=($(($(date +%s) - start)))
  stage_status+=("$([ "$rc" = 0 ] && echo ok || echo "FAILED ($rc)")")
  return "$rc"
}

stage_table() {
  local total=$(($(date +%s) - stage_clock_start)) i
  echo
  echo "=== stage times ($(basename "$0"), $(git rev-parse --short HEAD 2>/dev/null || echo '?'))"
  for i in "${!stage_names[@]}"; do
    printf '%-20s %6d s  %s\n' "${stage_names[$i]}" "${stage_seconds[$i]}" "${stage_status[$i]}"
  done
  printf '%-20s %6d s\n' total "$total"
  local note
  for note in "${stage_notes[@]}"; do [ -z "$note" ] || echo "$note"; done
  local quota=none
  [ -r /sys/fs/cgroup/cpu.max ] && quota=$(cat /sys/fs/cgroup/cpu.max)
  echo "machine: $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)), cpu.max $quota, load $(cut -d' ' -f1-3 /proc/loadavg)"
  if command -v ccache > /dev/null; then
    echo "ccache: $(ccache --print-stats 2>/dev/null | awk -F'\t' '/^(direct_cache_hit|preprocessed_cache_hit|cache_miss)\t/ {printf "%s %s  ", $1, $2}')"
  fi
}
trap stage_table EXIT
