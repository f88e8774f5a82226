#!/bin/bash
# Every check that needs a real SocketCAN stack, in one boot of tests/can/vcan_vm.sh's qemu VM
# (a boot costs 15-40 s of emulation): vmassd's two phases and the CAN layer's reader test
# (tests/can/vcan_integration.sh: classic, extended, remote and FD frames through vmass-can's
# SocketCAN reader, interface down/up and delete/re-create, compared with candump -L), each on
# its own interface and at the same time (phase 1 on vcan1, the reader test on vcan2, phase 2's
# drive on vcan0). The LCM output goes to LCM log files checked here afterwards with the
# generated Python types.
#
# 1. Counters and loss (Prius DBC, cansend): frames are received with kernel time stamps and
#    classified against the DBC; the interface going down, then being deleted and re-created, is
#    reported as input_lost on VMASS_STATUS while vmassd keeps running and re-opens it.
# 2. A simulated drive (vmass-sim paper_exp2, its first 60 s) played onto vcan0 with canplayer
#    while `vmassd --can vcan0` estimates, with `ip link set vcan0 down` / `up` between its two
#    30 s halves; candump records what the bus carried. vmassd must report input_lost while vcan0
#    is down, run with every input valid again after it is up, and decode every frame. Its
#    estimates must match vmass-replay --log:
#      a. on the recorded bus traffic, put on the daemon's own tick grid (tick k = row k): at
#         every tick |mass difference| <= 0.5 x the daemon's published mass_std_kg against the
#         nearest of replay ticks k-1..k+1, the final mass within 0.5 std too, and fewer than 20 %
#         of the frames applied late (a stamping bug; the count itself is the VM's scheduling);
#      b. on the original 60 s log: the final mass within 5 %.
#    Why not bit for bit: frame timing differs. canplayer sends each frame at its log time plus
#    its own scheduling delay (ms in the emulated VM), and vmassd ticks on its own grid, so a
#    frame lands in another tick than in the original log: that is (b), where the 1.5 s gap of
#    the down/up also drops the pairs it would have made (observed 0.01-0.33 %, and 3.05 % once
#    when the VM's canplayer delivered a bus that gave 127 pairs where the log gives 405, the
#    daemon agreeing with vmass-replay on that bus to 0.006 std in (a); the paper's errors are a
#    few %). (b) measures the playback as much as the daemon; (a) is the daemon's check. Comparing on the recorded traffic (a) removes that; what remains is
#    (i) frames the receive thread reads more than half a period after their kernel stamp (a
#    starved thread: the VM is emulated, p99 wake-up jitter 3-18 ms there), which the daemon
#    applies one tick late and counts ("input records late": 0 to 242 of 33600 in our runs),
#    and (ii) the daemon's re-stamp of a live frame into its tick clock, which differs from the
#    kernel stamp candump logs by the width of a clock-reading bracket (microseconds; more when
#    the thread is preempted inside it), and moves a frame lying that close to a tick boundary
#    to the neighbouring tick. Either can move an event (a pair, a completed Bayes batch) by a
#    tick, hence the k-1..k+1 window, widened by the ticks the daemon's worst tick-start jitter
#    spans (a late tick applies the frames of the ticks it missed: 109 overruns and 46 ms once). Observed worst 0.000-0.038 std with the tightest-bracket
#    re-stamp (0.32 std on the same tick only), final within 0.002 std; before it (one clock
#    pair per frame) up to 0.60 std on the same tick. The bound 0.5 std: daemon and offline
#    replay never disagree by a meaningful part of the estimate's own uncertainty.
# SIGTERM stops vmassd with exit 0 in both phases.
#
#   vmassd_vcan_test.sh VCAN_VM VMASSD PRIUS_DBC PYTHON_TYPES_DIR VMASS_SIM VMASS_REPLAY
#                       VMASS_CAN READER_TEST                         (boots its own VM)
# or in three parts, so that another VM's boot can carry the middle one (tests/service/vm_checks.sh):
#   vmassd_vcan_test.sh --prepare OUT VMASS_SIM                        (the drive, the config)
#   vmassd_vcan_test.sh --inside VMASSD PRIUS_DBC VMASS_CAN READER_TEST [OUT]   (inside the VM,
#                       with vcan0, vcan1 and vcan2 up; OUT default $VCAN_VM_OUT)
#   vmassd_vcan_test.sh --check OUT PYTHON_TYPES_DIR VMASS_REPLAY      (what the VM recorded)
set -euo pipefail

if [ "${1:-}" = "--inside" ]; then
  vmassd=$2 dbc=$3 vmass_can=$4 reader_test=$5 out=${6:-${VCAN_VM_OUT:-}}
  export VCAN_VM_OUT=$out  # the reader test writes there
  # vmassd logs "vmassd running" once its socket is open and its threads run (start-up in the
  # emulated VM, loading libraries over 9p, can take seconds).
  ready() {
    for _ in $(seq 300); do grep -q "vmassd running" "$1" 2>/dev/null && return 0; sleep 0.1; done
    echo "vmassd did not start:"; cat "$1"; return 1
  }
  # ------------------------------------------------------------------ phase 1 (vcan1)
  phase1() {
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
  inputs:
    speed: {message: SPEED, signal: SPEED}
lcm:
  status_period_s: 0.25
daemon:
  can_interface: vcan1
YAML
    "$vmassd" --config "$out/vmassd.yaml" --lcm-url "file://$out/out.lcm?mode=w" --no-restore \
      2> "$out/vmassd.log" &
    pid=$!
    ready "$out/vmassd.log"
    sleep 0.5
    send() { for _ in $(seq "$1"); do cansend vcan1 "$2"; done; }
    send 50 0B4#0000000000001000   # SPEED, in the DBC
    send 5 7FF#0102                # not in the DBC: the kernel filter (DBC ids) drops it
    send 3 0B4#0000                # too short
    sleep 1
    ip link set vcan1 down; sleep 1.5
    ip link set vcan1 up; sleep 1
    send 10 0B4#0000000000001000
    sleep 0.5
    ip link delete vcan1; sleep 1.5
    # Re-open backoff from the deletion: 0.1, 0.3, 0.7, 1.5, 3.1, 6.3 s: wait past it.
    ip link add dev vcan1 type vcan; ip link set vcan1 up; sleep 7
    send 10 0B4#0000000000001000
    sleep 1
    kill -TERM "$pid"
    rc=0; wait "$pid" || rc=$?
    echo "vmassd (phase 1) exit status $rc"
    return "$rc"
  }
  # Phase 1 and the reader test in the background while phase 2 plays the drive.
  phase1 > "$out/phase1.txt" 2>&1 &
  phase1_pid=$!
  sh "$reader_test" "$vmass_can" vcan2 > "$out/reader.txt" 2>&1 &
  reader_pid=$!

  # ------------------------------------------------------------------ phase 2
  # capture FILE: start candump on vcan0 into FILE and return once it records. A fixed sleep
  # was not enough on a loaded CI machine (the VM is emulated): candump bound its socket after
  # the drive had started and missed its first 84 frames. So a marker frame (an id outside the
  # DBC) is sent until it shows up in FILE; a large receive buffer keeps a starved candump from
  # dropping frames later.
  marker="7FF#CA"
  capture() {
    stdbuf -oL candump -L -r 8388608 vcan0 > "$1" &
    dump=$!
    for _ in $(seq 200); do
      cansend vcan0 "$marker"; sleep 0.05
      grep -q "$marker" "$1" && return 0
    done
    echo "candump did not start recording"; return 1
  }
  sim=$out/sim
  # candump writes to RAM: writing to the VM's shared folder is slow enough to lose frames.
  mkdir -p "$out/ram" && mount -t tmpfs -o size=64m tmpfs "$out/ram"
  "$vmassd" --config "$sim/config_vcan.yaml" --can vcan0 --no-restore \
    --lcm-url "file://$out/drive.lcm?mode=w" 2> "$out/vmassd_drive.log" &
  pid=$!
  ready "$out/vmassd_drive.log"
  sleep 0.5
  # candump stamps frames with the same kernel receive time as vmassd's socket.
  capture "$out/ram/captured1.log"
  canplayer -I "$sim/part1.log" vcan0=can0
  sleep 0.2; kill "$dump"; wait "$dump" || true
  ip link set vcan0 down; echo "vcan0 down"; sleep 1
  ip link set vcan0 up; echo "vcan0 up"
  sleep 0.5   # vmassd's reader notices (ENETDOWN is reported on its next read)
  capture "$out/ram/captured2.log"
  canplayer -I "$sim/part2.log" vcan0=can0
  sleep 2; kill "$dump"; wait "$dump" || true   # 2 s: the daemon's reader catches up
  kill -TERM "$pid"
  rc=0; wait "$pid" || rc=$?
  echo "vmassd (phase 2) exit status $rc"
  # The handshake markers are not part of the drive (vmassd's kernel filter drops their id).
  for f in captured1.log captured2.log; do grep -v "$marker" "$out/ram/$f" > "$out/$f" || true; done
  umount "$out/ram"
  rc1=0; wait "$phase1_pid" || rc1=$?
  rc_reader=0; wait "$reader_pid" || rc_reader=$?
  echo "--- phase 1 (vcan1)"; cat "$out/phase1.txt"
  echo "--- the SocketCAN reader test (vcan2), exit status $rc_reader"; cat "$out/reader.txt"
  [ "$rc" = 0 ] || exit "$rc"
  [ "$rc1" = 0 ] || exit "$rc1"
  exit "$rc_reader"
fi

# ------------------------------------------------------------------ before the VM
prepare() {
  local out=$1 sim_bin=$2
  # The drive: paper_exp2's first 60 s, in two halves of 30 s.
  "$sim_bin" --scenario paper_exp2 --seed 1 --out "$out/sim" > /dev/null
  awk '{ t = substr($1, 2, length($1) - 2) + 0; if (t < 60) print }' "$out/sim/drive.log" \
    > "$out/sim/drive60.log"
  awk '{ t = substr($1, 2, length($1) - 2) + 0; if (t < 30) print > P1; else print > P2 }' \
    P1="$out/sim/part1.log" P2="$out/sim/part2.log" "$out/sim/drive60.log"
  { cat "$out/sim/config.yaml"; printf 'lcm:\n  status_period_s: 0.25\n'; } \
    > "$out/sim/config_vcan.yaml"
}

# ------------------------------------------------------------------ after the VM
check() {
  local out=$1 pydir=$2 replay_bin=$3
  # ------------------------------------------------------------------ phase 1 checks
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
print("phase 1 states:", " ".join(dict.fromkeys(states)))
print("phase 1 final: received=%d decoded=%d unknown=%d malformed=%d reopens=%d ticks=%d "
      "estimates=%d" % (last.frames_received, last.frames_decoded, last.frames_unknown,
                        last.frames_malformed, last.source_reopens, last.ticks, estimates))
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
if last.source != "socketcan:vcan1": fails.append("source " + last.source)
if estimates < 500: fails.append("only %d estimates" % estimates)
for f in fails: print("FAIL:", f)
if fails:
    for s in statuses:
        print("  %6.2f s %-11s decoded=%d malformed=%d reopens=%d %s"
              % (s.uptime_s, s.state_name, s.frames_decoded, s.frames_malformed,
                 s.source_reopens, s.detail))
sys.exit(1 if fails else 0)
PY

  # ------------------------------------------------------------------ phase 2 checks
  # Reference a: the bus traffic as recorded, preceded by one frame of an id that is not in the DBC
  # at the daemon's tick 0, so that vmass-replay's ticks (T_0 = its first frame) fall on the
  # daemon's grid and its row k is the daemon's tick k.
  t0=$(python3 - "$out/drive.lcm" "$pydir" <<'PY'
import struct, sys
sys.path.insert(0, sys.argv[2])
import vmass
data = open(sys.argv[1], "rb").read()
pos = 0
while pos + 28 <= len(data):
    _, _, _, clen, dlen = struct.unpack(">IqqII", data[pos:pos + 28])
    channel = data[pos + 28:pos + 28 + clen].decode()
    if channel == "VMASS_ESTIMATE":
        e = vmass.mass_estimate_t.decode(data[pos + 28 + clen:pos + 28 + clen + dlen])
        print("%d %d" % (e.utime, e.tick))
        break
    pos += 28 + clen + dlen
PY
  )
  read -r first_utime first_tick <<< "$t0"
  t0_us=$((first_utime - first_tick * 10000))
  printf '(%d.%06d) vcan0 7FF#00\n' $((t0_us / 1000000)) $((t0_us % 1000000)) > "$out/aligned.log"
  cat "$out/captured1.log" "$out/captured2.log" >> "$out/aligned.log"
  "$replay_bin" --config "$out/sim/config_vcan.yaml" --log "$out/aligned.log" \
    --out "$out/aligned.csv" > "$out/aligned.txt" 2> "$out/aligned.err"
  "$replay_bin" --config "$out/sim/config_vcan.yaml" --log "$out/sim/drive60.log" \
    --out "$out/original.csv" > "$out/original.txt" 2> "$out/original.err"

  python3 - "$out" "$pydir" <<'PY'
import csv, math, re, struct, sys
out = sys.argv[1]
sys.path.insert(0, sys.argv[2])
import vmass
data = open(out + "/drive.lcm", "rb").read()
pos, statuses, estimates = 0, [], []
while pos + 28 <= len(data):
    _, _, _, clen, dlen = struct.unpack(">IqqII", data[pos:pos + 28])
    channel = data[pos + 28:pos + 28 + clen].decode()
    payload = data[pos + 28 + clen:pos + 28 + clen + dlen]
    pos += 28 + clen + dlen
    if channel == "VMASS_STATUS":
        statuses.append(vmass.status_t.decode(payload))
    elif channel == "VMASS_ESTIMATE":
        estimates.append(vmass.mass_estimate_t.decode(payload))
captured = sum(1 for f in ("/captured1.log", "/captured2.log") for _ in open(out + f))
aligned = list(csv.DictReader(open(out + "/aligned.csv")))
original = list(csv.DictReader(open(out + "/original.csv")))
last = statuses[-1]
states = [s.state_name for s in statuses]
print("phase 2 states:", " ".join(dict.fromkeys(states)))
print("phase 2 final: received=%d decoded=%d dropped=%d captured=%d ticks=%d overruns=%d "
      "skipped=%d jitter p50/p99/max %.0f/%.0f/%.0f us"
      % (last.frames_received, last.frames_decoded, last.frames_dropped, captured, last.ticks,
         last.tick_overruns, last.ticks_skipped, last.jitter_p50_us, last.jitter_p99_us,
         last.jitter_max_us))
fails = []
if last.state_name != "stopping": fails.append("final status is not 'stopping'")
if last.frames_decoded != captured:
    fails.append("decoded %d != %d frames on the bus" % (last.frames_decoded, captured))
if last.frames_dropped != 0: fails.append("%d frames dropped" % last.frames_dropped)
late = re.search(r"(\d+) input records late", open(out + "/vmassd_drive.log").read())
late = int(late.group(1)) if late else -1
print("late records: %d of %d" % (late, captured))
# How many records are late is the emulated VM's scheduling, not vmassd's correctness (which (a)
# checks): 0-242 of 33600 on an idle host, 897 with another two-thread job on it. Only a broken
# stamp (every record late) fails here.
if not 0 <= late < 0.2 * captured: fails.append("%d input records late" % late)
lost = [i for i, s in enumerate(statuses) if s.state_name == "input_lost"]
if not lost: fails.append("input_lost never reported while vcan0 was down")
else:
    after = statuses[lost[-1] + 1:]
    # The simulated bus carries wheel torque and brake pressure, so not their stand-ins.
    stand_ins = {"brake_switch", "engine_torque", "engine_speed"}
    def carried_valid(s):
        return all(v for n, v in zip(s.input_name, s.input_valid) if n not in stand_ins)
    if not any(s.state_name == "running" and carried_valid(s) for s in after):
        fails.append("not running with every input valid after vcan0 came back")

# a. Tick by tick against vmass-replay on the recorded traffic, on the daemon's grid. A record
# that lands in the neighbouring tick can move an event (a pair, a completed Bayes batch) by one
# tick, so each daemon tick is compared with the nearest of replay ticks k-1, k, k+1 (wider after
# late ticks, below).
by_tick = {e.tick: e for e in estimates}
# A tick that starts late by J applies the frames of the ticks it missed: an event can land up to
# ceil(J / 10 ms) ticks away (the emulated VM: 109 overruns, J = 46 ms in one CI run).
window = 1 + math.ceil(last.jitter_max_us / 10000.0)
compared, worst, worst_same, ratios = 0, (0.0, 0.0, -1), 0.0, []
for k, row in enumerate(aligned):
    e = by_tick.get(k)
    if e is None or not e.mass_known: continue
    compared += 1
    # An empty mass cell: vmass-replay had no estimate yet at that tick.
    near = [float(aligned[j]["mass_kg"]) for j in range(k - window, k + window + 1)
            if 0 <= j < len(aligned) and aligned[j]["mass_kg"]]
    if not near: near = [float("inf")]
    dm = min(abs(e.mass_kg - m) for m in near)
    std = max(e.mass_std_kg, 1e-9)
    same = float(row["mass_kg"]) if row["mass_kg"] else float("inf")
    worst_same = max(worst_same, abs(e.mass_kg - same) / std)
    ratios.append(dm / std)
    if dm / std > worst[0]: worst = (dm / std, dm, k)
ratios.sort()
final_k = len(aligned) - 1
fe = by_tick.get(final_k)
final_ratio = abs(fe.mass_kg - float(aligned[-1]["mass_kg"])) / fe.mass_std_kg if fe else 1e9
print("a. window +-%d ticks" % window)
print("a. recorded traffic: %d ticks compared; |dm| / std median %.3f, worst %.3f (%.3f kg at "
      "tick %d; same tick only: %.3f); final: daemon %.3f kg, vmass-replay %s kg (%.3f std); "
      "pairs daemon %d/%d, replay %s/%s"
      % (compared, ratios[len(ratios) // 2] if ratios else float("nan"), worst[0], worst[1],
         worst[2], worst_same, fe.mass_kg if fe else float("nan"), aligned[-1]["mass_kg"],
         final_ratio, fe.longitudinal_accepted if fe else -1, fe.lateral_accepted if fe else -1,
         aligned[-1]["longitudinal_pairs"], aligned[-1]["lateral_pairs"]))
if compared < 4000: fails.append("only %d ticks compared" % compared)
if worst[0] > 0.5:
    fails.append("tick %d differs by %.3f kg = %.2f std > 0.5 std" % (worst[2], worst[1], worst[0]))
# The final tick is held to the bound of every tick: a starved VM (1060 of 33600 frames applied
# late, 185 overruns, in one CI run) left the final 0.27 std from the replay, every tick within
# 0.42 std.
if final_ratio > 0.5: fails.append("final mass differs by %.2f std > 0.5 std" % final_ratio)

# b. Final mass against vmass-replay on the original 60 s log.
final_d = [e for e in estimates if e.mass_known][-1].mass_kg
final_o = float(original[-1]["mass_kg"])
rel = abs(final_d - final_o) / final_o
print("b. original log: daemon %.1f kg, vmass-replay %.1f kg, difference %.2f %%"
      % (final_d, final_o, 100 * rel))
print("   pairs: daemon %d, vmass-replay on the original log %s"
      % ([e for e in estimates if e.mass_known][-1].longitudinal_accepted,
         original[-1]["longitudinal_pairs"]))
if rel > 0.05: fails.append("final mass %.2f %% from vmass-replay on the original log" % (100 * rel))
for f in fails: print("FAIL:", f)
if fails:
    for s in statuses:
        print("  %6.2f s %-11s decoded=%d valid=%s %s"
              % (s.uptime_s, s.state_name, s.frames_decoded,
                 "".join("1" if v else "0" for v in s.input_valid), s.detail))
sys.exit(1 if fails else 0)
PY
}

case "${1:-}" in
  --prepare) prepare "$2" "$3"; exit ;;
  --check) check "$2" "$3" "$4"; exit ;;
esac
vcan_vm=$1 vmassd=$2 dbc=$3 pydir=$4 sim_bin=$5 replay_bin=$6 vmass_can=$7 reader_test=$8
out=$(mktemp -d /tmp/vmassd_vcan.XXXXXX)
trap 'rm -rf "$out"' EXIT
[ -z "${KEEP_VCAN_OUT:-}" ] || trap - EXIT
prepare "$out" "$sim_bin"
"$vcan_vm" --ifaces vcan0,vcan1,vcan2 --out "$out" --timeout 420 -- \
  "$0" --inside "$vmassd" "$dbc" "$vmass_can" "$reader_test"
check "$out" "$pydir" "$replay_bin"
