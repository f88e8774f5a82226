#!/bin/bash
# vmassd on a real SocketCAN interface (vcan0, inside tests/can/vcan_vm.sh's qemu VM): frames are
# received with kernel time stamps and classified against the DBC; the interface going down and
# being deleted and re-created is reported as input_lost on VMASS_STATUS while vmassd keeps
# running and re-opens it; SIGTERM stops it with exit 0. The LCM output goes to an LCM log file
# that is checked here afterwards with the generated Python types.
#
#   vmassd_vcan_test.sh VCAN_VM VMASSD DBC PYTHON_TYPES_DIR      (outside: boots the VM)
#   vmassd_vcan_test.sh --inside VMASSD DBC                       (inside the VM)
set -euo pipefail

if [ "${1:-}" = "--inside" ]; then
  vmassd=$2 dbc=$3 out=$VCAN_VM_OUT
  cat > "$out/vmassd.yaml" <<YAML
vehicle:
  empty_mass_kg: 1500
  wheelbase_m: 2.7
  cg_to_front_axle_m: 1.2
  wheel_radius_m: 0.31
  brake_gain_n_per_pa: 0.0033
  steering_ratio: 15.5
  cornering_stiffness_front_n_per_rad: 150000
  cornering_stiffness_rear_n_per_rad: 170000
suspension:
  stiffness_n_per_m: 30000
can:
  dbc: $dbc
lcm:
  status_period_s: 0.25
daemon:
  can_interface: vcan0
YAML
  "$vmassd" --config "$out/vmassd.yaml" --lcm-url "file://$out/out.lcm?mode=w" --no-restore \
    2> "$out/vmassd.log" &
  pid=$!
  sleep 2
  send() { for _ in $(seq "$1"); do cansend vcan0 "$2"; done; }
  send 50 0B4#0000000000001000   # SPEED, in the DBC
  send 5 7FF#0102                # not in the DBC: the kernel filter (DBC ids) drops it
  send 3 0B4#0000                # too short
  sleep 1
  ip link set vcan0 down; sleep 1.5
  ip link set vcan0 up; sleep 1
  send 10 0B4#0000000000001000
  sleep 0.5
  ip link delete vcan0; sleep 1.5
  # Re-open backoff from the deletion: 0.1, 0.3, 0.7, 1.5, 3.1, 6.3 s: wait past it.
  ip link add dev vcan0 type vcan; ip link set vcan0 up; sleep 7
  send 10 0B4#0000000000001000
  sleep 1
  kill -TERM "$pid"
  rc=0; wait "$pid" || rc=$?
  echo "vmassd exit status $rc"
  exit "$rc"
fi

vcan_vm=$1 vmassd=$2 dbc=$3 pydir=$4
out=$(mktemp -d /tmp/vmassd_vcan.XXXXXX)
trap 'rm -rf "$out"' EXIT
[ -z "${KEEP_VCAN_OUT:-}" ] || trap - EXIT
"$vcan_vm" --out "$out" --timeout 300 -- "$0" --inside "$vmassd" "$dbc"
python3 - "$out/out.lcm" "$pydir" <<'PY'
import struct, sys
sys.path.insert(0, sys.argv[2])
import vmass
data = open(sys.argv[1], "rb").read()
pos, statuses, estimates = 0, [], 0
while pos + 28 <= len(data):
    sync, _, _, clen, dlen = struct.unpack(">IqqII", data[pos:pos + 28])
    assert sync == 0xEDA1DA01, "bad LCM log"
    channel = data[pos + 28:pos + 28 + clen].decode()
    payload = data[pos + 28 + clen:pos + 28 + clen + dlen]
    pos += 28 + clen + dlen
    if channel == "VMASS_STATUS":
        statuses.append(vmass.status_t.decode(payload))
    elif channel == "VMASS_ESTIMATE":
        estimates += 1
states = [s.state_name for s in statuses]
last = statuses[-1]
print("states:", " ".join(dict.fromkeys(states)))
print("final: received=%d decoded=%d unknown=%d malformed=%d reopens=%d ticks=%d estimates=%d"
      % (last.frames_received, last.frames_decoded, last.frames_unknown, last.frames_malformed,
         last.source_reopens, last.ticks, estimates))
fails = []
if "input_lost" not in states: fails.append("input_lost never reported")
lost_at = states.index("input_lost") if "input_lost" in states else len(states)
if "running" not in states[lost_at:]:
    fails.append("not running again after the interface came back")
if last.state_name != "stopping": fails.append("final status is not 'stopping'")
if last.frames_decoded != 70: fails.append("decoded %d != 70" % last.frames_decoded)
if last.frames_unknown != 0: fails.append("unknown %d != 0 (kernel filter)" % last.frames_unknown)
if last.frames_malformed != 3: fails.append("malformed %d != 3" % last.frames_malformed)
if last.source_reopens < 1: fails.append("no re-open after the interface was re-created")
if last.source != "socketcan:vcan0": fails.append("source " + last.source)
if estimates < 500: fails.append("only %d estimates" % estimates)
for f in fails: print("FAIL:", f)
if fails:
    for s in statuses:
        print("  %6.2f s %-11s decoded=%d malformed=%d reopens=%d %s"
              % (s.uptime_s, s.state_name, s.frames_decoded, s.frames_malformed,
                 s.source_reopens, s.detail))
sys.exit(1 if fails else 0)
PY
