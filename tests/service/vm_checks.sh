#!/bin/bash
# Every check that needs a kernel this machine does not have, in one boot of
# tests/service/systemd_vm.sh's qemu VM (a boot is 20-40 s of emulation, and the checks mostly
# wait on real-time playback): the systemd service test (vmassd_systemd_test.sh: installed,
# notify, watchdog restart with the state restored, clean stop; on can0) and the SocketCAN tests
# (vmassd_vcan_test.sh: vmassd's counters and interface loss, a drive played and compared with
# vmass-replay, the reader's own test; on vcan0-2), at the same time. Each keeps its own output
# folder and its own checks; this script fails when either does.
#
#   vm_checks.sh SYSTEMD_VM BUILD_DIR VMASS_SIM VMASSD PRIUS_DBC PYTHON_TYPES_DIR VMASS_REPLAY
#                VMASS_CAN READER_TEST
#   vm_checks.sh --inside BUILD_DIR OUT VMASSD PRIUS_DBC VMASS_CAN READER_TEST   (inside the VM)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

if [ "${1:-}" = "--inside" ]; then
  build=$2 out=$3 vmassd=$4 dbc=$5 vmass_can=$6 reader_test=$7
  "$here/vmassd_vcan_test.sh" --inside "$vmassd" "$dbc" "$vmass_can" "$reader_test" \
    "$out/vcan" > "$out/vcan_inside.txt" 2>&1 &
  vcan=$!
  rc_systemd=0
  "$here/vmassd_systemd_test.sh" --inside "$build" "$out/systemd/sim" || rc_systemd=$?
  rc_vcan=0
  wait "$vcan" || rc_vcan=$?
  echo "--- the SocketCAN checks inside the VM, exit status $rc_vcan"
  cat "$out/vcan_inside.txt"
  [ "$rc_systemd" = 0 ] || exit "$rc_systemd"
  exit "$rc_vcan"
fi

systemd_vm=$1 build=$2 sim_bin=$3 vmassd=$4 dbc=$5 pydir=$6 replay_bin=$7 vmass_can=$8
reader_test=$9
out=$(mktemp -d /tmp/vmass_vm_checks.XXXXXX)
trap 'rm -rf "$out"' EXIT
[ -z "${KEEP_VM_OUT:-}" ] || trap - EXIT
mkdir -p "$out/vcan" "$out/systemd"
"$here/vmassd_vcan_test.sh" --prepare "$out/vcan" "$sim_bin"
"$here/vmassd_systemd_test.sh" --prepare "$out/systemd/sim" "$sim_bin"
start=$(date +%s)
"$systemd_vm" --ifaces can0,vcan0,vcan1,vcan2 --out "$out" --timeout 540 -- \
  "$0" --inside "$build" "$out" "$vmassd" "$dbc" "$vmass_can" "$reader_test"
echo "vm_checks: the VM's part took $(($(date +%s) - start)) s"
"$here/vmassd_vcan_test.sh" --check "$out/vcan" "$pydir" "$replay_bin"
echo "vm_checks: systemd and SocketCAN checks passed"
