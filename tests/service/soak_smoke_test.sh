#!/bin/sh
# vmass-soak in small (12 simulated minutes, about 5.8 million frames at a full 1 Mbit/s bus):
# the generated stream reaches vmassd --replay /dev/stdin whole (every frame received, the
# drive's decoded, the filler counted unknown, nothing malformed or dropped), every tick runs,
# nothing fails to publish, and resident memory stays flat. The 24-hour run is a command
# (docs/reliability.md), not a test.
#   soak_smoke_test.sh VMASS_SOAK VMASSD VMASS_SIM WORKDIR
set -eu
soak=$1 vmassd=$2 sim=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
"$sim" --scenario paper_exp2 --seed 3 --out "$work/sim" > /dev/null
"$soak" --log "$work/sim/drive.log" --dbc "$work/sim/vehicle.dbc" --hours 0.2 \
  --daemon-log "$work/daemon.log" -- "$vmassd" --config "$work/sim/config.yaml" \
  --replay /dev/stdin --speed max --lcm-url memq:// --no-restore > "$work/report.json"
python3 - "$work/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print(json.dumps(r))
fails = []
def expect(ok, what):
    if not ok: fails.append(what)
expect(r["received"] == r["frames_written"], "received %d != written %d" % (r["received"], r["frames_written"]))
expect(r["decoded"] == r["drive_frames"], "decoded %d != drive frames %d" % (r["decoded"], r["drive_frames"]))
expect(r["unknown"] == r["filler_frames"], "unknown %d != filler %d" % (r["unknown"], r["filler_frames"]))
for k in ("malformed", "dropped", "publish_failures", "queue_drops", "overruns", "too_late", "jumps"):
    expect(r[k] == 0, "%s = %d" % (k, r[k]))
expect(abs(r["ticks"] - 0.2 * 360000) <= 2, "ticks %d, expected 72000" % r["ticks"])
expect(r["frames_written"] > 5_000_000, "only %d frames" % r["frames_written"])
expect(0 < r["rss_end_kb"] <= 1.5 * r["rss_start_kb"] + 2048, "memory grew")
for f in fails: print("FAIL:", f)
sys.exit(1 if fails else 0)
PY
