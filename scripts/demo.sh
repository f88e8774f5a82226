#!/usr/bin/env bash
# The main job on the bundled default: installs, builds (release), simulates the paper's
# experiment 2 drive (accelerating, braking, cornering) as a CAN log of the demo vehicle and runs
# the estimator over the log, printing the summary and writing a plot; then runs the daemon,
# vmassd, over the same log at 20x real time, publishing on LCM, with vmass-monitor showing its
# live estimate (the live view in a terminal, a report every 2 s otherwise), and stops it with
# SIGTERM.
#   scripts/demo.sh [OUT_DIR]      (default: out/demo)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"

# The live part: vmassd in the background, vmass-monitor in the foreground until it has seen
# 16000 estimates (160 s of the 200 s drive, ~8 s), then SIGTERM to the daemon.
live() {
  local bin=$1 out=$2 url=$3
  "$bin/vmassd" --config "$out/config.yaml" --replay "$out/drive.log" --speed 20 --no-restore \
    --lcm-url "$url" 2> "$out/vmassd.log" &
  local daemon=$! rc=0
  local monitor=("$bin/vmass-monitor" --config "$out/config.yaml" --lcm-url "$url"
                 --count 16000 --timeout 30)
  if [ -t 1 ]; then "${monitor[@]}" || rc=$?; else "${monitor[@]}" --plain --interval 2 || rc=$?; fi
  kill -TERM "$daemon" 2> /dev/null || true
  wait "$daemon" || rc=$?
  grep -E "vmassd running|stopped:" "$out/vmassd.log" || cat "$out/vmassd.log"
  return "$rc"
}
if [ "${1:-}" = "--live" ]; then  # internal: the live part (inside a private network namespace)
  shift
  live "$@"
  exit
fi

out=${1:-out/demo}

bash scripts/install-deps.sh
cmake --preset release -DVMASS_BUILD_TESTS=OFF >/dev/null
cmake --build --preset release -j "$(nproc)"

bin=build/release/bin
mkdir -p "$out"
"$bin/vmass-sim" --scenario paper_exp2 --seed 1 --noise eps3 --out "$out"
# The estimator reads the drive from CAN: the candump log, decoded with vehicle.dbc through the
# config's can: mapping (samples.csv holds the same drive as CSV: --samples instead of --log).
"$bin/vmass-replay" --config "$out/config.yaml" --log "$out/drive.log" \
  --truth "$out/truth.csv" --out "$out/estimate.csv" --plot "$out/estimate.png"
echo "demo: estimate CSV $out/estimate.csv, plot $out/estimate.png"

# The daemon on the same drive, live on LCM (UDP multicast with ttl=0: never leaves the host).
# As root, vmassd and vmass-monitor share a private network namespace (loopback up, multicast
# routed to it), which works on hosts without a multicast route; otherwise the host's network.
url="udpm://239.255.76.67:7667?ttl=0"
echo "demo: vmassd --replay $out/drive.log --speed 20 --lcm-url '$url', vmass-monitor:"
if [ "$(id -u)" = 0 ] && unshare -n true 2> /dev/null; then
  unshare -n bash -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec bash "$@"' \
    demo "$repo/scripts/demo.sh" --live "$bin" "$out" "$url"
elif ip route get 239.255.76.67 > /dev/null 2>&1; then
  bash "$repo/scripts/demo.sh" --live "$bin" "$out" "$url"
else
  echo "demo: no multicast route here (and no root for a private namespace): vmassd writes its"
  echo "      LCM output to $out/vmassd.lcm instead (lcm-logplayer can play it)"
  "$bin/vmassd" --config "$out/config.yaml" --replay "$out/drive.log" --speed max --no-restore \
    --lcm-url "file://$out/vmassd.lcm?mode=w"
fi
