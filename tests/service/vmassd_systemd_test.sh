#!/bin/bash
# vmassd as a vehicle PC runs it: under real systemd (PID 1, inside tests/service/systemd_vm.sh's
# qemu VM), installed with `cmake --install --prefix /usr`, with the shipped unit and all its
# hardening (DynamicUser, StateDirectory, the syscall filter), its config in /etc/vmass/, and a
# simulated drive (vmass-sim paper_exp2) played onto can0 with canplayer:
#   1. `systemctl start vmassd` returns once it notified READY=1 (Type=notify); the service is
#      active and estimates arrive on LCM (vmass-monitor, multicast on loopback);
#   2. the state file appears in the state directory with the reference deflection of a
#      standstill (daemon.persist_interval_s: 5 here);
#   3. SIGSTOP to the daemon: no watchdog ping, so systemd kills it after WatchdogSec and
#      restarts it (NRestarts 1), and the new process restores the saved state;
#   4. `systemctl stop vmassd`: exit 0, the final state saved, the unit's result "success".
#
#   vmassd_systemd_test.sh SYSTEMD_VM BUILD_DIR VMASS_SIM                 (boots its own VM)
#   vmassd_systemd_test.sh --prepare SIM_DIR VMASS_SIM                   (the drive, for --inside)
#   vmassd_systemd_test.sh --inside BUILD_DIR SIM_DIR                    (inside the VM)
set -euo pipefail

if [ "${1:-}" = "--inside" ]; then
  build=$2 sim=$3
  fail() { echo "FAIL: $*"; journalctl -u vmassd -o cat --no-pager | tail -n 40; exit 1; }
  # poll SECONDS COMMAND...: true once COMMAND succeeds within SECONDS
  poll() {
    local s=$1; shift
    for _ in $(seq $((s * 4))); do "$@" > /dev/null 2>&1 && return 0; sleep 0.25; done
    return 1
  }
  cmake --install "$build" --prefix /usr > "$VMTEST_OUT/install.txt" 2>&1 \
    || { cat "$VMTEST_OUT/install.txt"; exit 1; }
  mkdir -p /etc/vmass
  cp "$sim/vehicle.dbc" /etc/vmass/
  { cat "$sim/config.yaml"
    printf 'lcm:\n  status_period_s: 0.5\ndaemon:\n  persist_interval_s: 5\n'; } \
    > /etc/vmass/vmassd.yaml
  systemctl daemon-reload
  systemctl start vmassd || fail "systemctl start vmassd"
  [ "$(systemctl is-active vmassd)" = active ] || fail "not active after start"
  echo "1. started: $(systemctl show -p MainPID --value vmassd) active"

  canplayer -I "$sim/drive90.log" can0=can0 &
  player=$!
  vmass-monitor --config /etc/vmass/vmassd.yaml --count 50 --plain --timeout 30 \
    > "$VMTEST_OUT/monitor.txt" 2>&1 || { cat "$VMTEST_OUT/monitor.txt"; fail "no estimates"; }
  echo "1. estimates on LCM: $(grep -c . "$VMTEST_OUT/monitor.txt") monitor lines"

  state=/var/lib/private/vmass/vmassd.state
  # A state the restarted daemon can restore: this car reads its load, so the state must carry
  # the reference deflection of a standstill (one saved before the first standstill window, on
  # a slow machine, has none and is refused on restore).
  poll 60 grep -qx "has_reference 1" "$state" || fail "no state file with a reference: $state"
  echo "2. state file saved: $(stat -c %s "$state") bytes"

  main=$(systemctl show -p MainPID --value vmassd)
  kill -STOP "$main"
  restarted() { [ "$(systemctl show -p NRestarts --value vmassd)" -ge 1 ] &&
                [ "$(systemctl is-active vmassd)" = active ]; }
  poll 40 restarted || fail "no watchdog restart after SIGSTOP"
  journalctl -u vmassd -o cat --no-pager | grep -q -i "watchdog timeout" \
    || fail "systemd did not report a watchdog timeout"
  poll 20 sh -c 'journalctl -u vmassd -o cat --no-pager | grep -q "^restored "' \
    || fail "the restarted daemon did not restore the state"
  echo "3. watchdog restart: pid $main -> $(systemctl show -p MainPID --value vmassd)," \
       "$(journalctl -u vmassd -o cat --no-pager | grep "^restored " | tail -n 1)"

  sleep 3
  systemctl stop vmassd
  kill "$player" 2> /dev/null || true
  result=$(systemctl show -p Result --value vmassd)
  status=$(systemctl show -p ExecMainStatus --value vmassd)
  stopped=$(journalctl -u vmassd -o cat --no-pager | grep "^stopped: " | tail -n 1)
  echo "4. stopped: result $result, exit $status; $stopped"
  [ "$result" = success ] && [ "$status" = 0 ] || fail "unclean stop"
  case "$stopped" in *"state saved"*) ;; *) fail "the final state was not saved" ;; esac
  echo "systemd test passed"
  exit 0
fi

# The drive's first 90 s, its opening standstill (0-5 s) played twice: 10 s at rest give the
# static window (3 s) room even when a loaded host starves the VM for seconds.
prepare() {
  local sim=$1 sim_bin=$2
  "$sim_bin" --scenario paper_exp2 --seed 2 --out "$sim" > /dev/null
  shift_log() {  # shift_log FROM TO OFFSET: the frames stamped in [FROM, TO), OFFSET s later
    awk -v from="$1" -v to="$2" -v off="$3" '{ t = substr($1, 2, length($1) - 2) + 0
      if (t >= from && t < to) { $1 = sprintf("(%.6f)", t + off); print } }' "$sim/drive.log"
  }
  { shift_log 0 5 0; shift_log 0 5 5; shift_log 5 90 5; } > "$sim/drive90.log"
}

if [ "${1:-}" = "--prepare" ]; then
  prepare "$2" "$3"
  exit
fi
systemd_vm=$1 build=$2 sim_bin=$3
out=$(mktemp -d /tmp/vmassd_systemd.XXXXXX)
trap 'rm -rf "$out"' EXIT
prepare "$out/sim" "$sim_bin"
"$systemd_vm" --ifaces can0 --out "$out" --timeout 480 -- "$0" --inside "$build" "$out/sim"
