#!/bin/sh
# One interface of a multi-interface log (--interface NAME), in every tool that reads a log and
# in each text format: the golden drive on can1 (ASC channel 2, TRC bus 2) with noise frames of
# the same ids on can0 (channel 1, bus 1):
#   - vmass-replay --log ... --interface can1 gives the estimate CSV of the drive alone, and says
#     how many frames of other interfaces it skipped (never as corrupt lines); without the
#     option every frame comes through (the noise moves the estimate);
#   - an interface the log does not have: exit 2 naming the file, the interface and those the
#     log has with their frame counts; with --logs and --log-list a failed row;
#   - vmassd --replay, vmass-can decode and vmass-calibrate --ballast do the same;
#   - a name no interface can have is a usage error (exit 2) in every tool.
#   replay_interface_test.sh BIN_DIR GOLDEN_CAN_DIR OUT_DIR
set -u
bin=$1
golden=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" || exit 1
cd "$out" || exit 1
tar -xJf "$golden/golden_can.tar.xz" drive.log || fail "cannot extract the golden drive"
config=$golden/config.yaml
dbc=$golden/vehicle.dbc

# The drive on can1; the mixed log adds a noise frame on can0 after every third one, at its
# time and with its id.
sed 's/ can0 / can1 /' drive.log >drive1.log
awk '{ l = $0; sub(/ can0 /, " can1 ", l); print l
       if (NR % 3 == 0) { sub(/#.*/, "#FFFFFFFFFFFFFFFF"); print } }' drive.log >mixed.log
frames=$(wc -l <drive.log | tr -d ' ')
noise=$((frames / 3))

# candump -l to ASC (interface canN is channel N+1) and to TRC 2.1 (bus N+1), times kept.
to_asc() {
  { echo 'base hex  timestamps absolute'
    awk '{ t = substr($1, 2, length($1) - 2); ch = substr($2, 4) + 1; split($3, f, "#")
           id = length(f[1]) == 8 ? f[1] "x" : f[1]; n = length(f[2]) / 2; s = ""
           for (i = 0; i < n; i++) s = s " " substr(f[2], 2 * i + 1, 2)
           printf "   %s %d  %s             Rx   d %d%s\n", t, ch, id, n, s }' "$1"; } >"$2"
}
to_trc() {
  { printf ';$FILEVERSION=2.1\n;$COLUMNS=N,O,T,B,I,d,R,L,D\n'
    awk '{ t = substr($1, 2, length($1) - 2); ch = substr($2, 4) + 1; split($3, f, "#")
           id = length(f[1]) == 8 ? f[1] : substr("0000" f[1], length(f[1]) + 1)
           n = length(f[2]) / 2; s = ""
           for (i = 0; i < n; i++) s = s " " substr(f[2], 2 * i + 1, 2)
           printf "%7d %12.3f DT  %d %8s Rx -  %d   %s\n", NR, t * 1000, ch, id, n, s }' "$1"
  } >"$2"
}
for f in drive1 mixed; do
  to_asc $f.log $f.asc
  to_trc $f.log $f.trc
done

replay() { "$bin/vmass-replay" --config "$config" "$@"; }

# 1. Each format: --interface can1 gives the drive's own estimate; the noise is counted.
for ext in log asc trc; do
  replay --log drive1.$ext --out alone_$ext.csv >/dev/null 2>alone_$ext.err ||
    fail "$ext: the drive alone: $(cat alone_$ext.err)"
  replay --log mixed.$ext --interface can1 --out can1_$ext.csv >/dev/null 2>can1_$ext.err ||
    fail "$ext: --interface can1: $(cat can1_$ext.err)"
  cmp -s alone_$ext.csv can1_$ext.csv || fail "$ext: --interface can1 differs from the drive alone"
  grep -q "mixed.$ext (.*): $frames frames on can1, $noise frames of other interfaces skipped, 0 corrupt lines" \
    can1_$ext.err || fail "$ext: the report: $(cat can1_$ext.err)"
  replay --log mixed.$ext --out all_$ext.csv >/dev/null 2>all_$ext.err ||
    fail "$ext: without --interface: $(cat all_$ext.err)"
  grep -q "mixed.$ext (.*): $((frames + noise)) frames, 0 corrupt lines" all_$ext.err ||
    fail "$ext: without --interface every frame comes through: $(cat all_$ext.err)"
  cmp -s alone_$ext.csv all_$ext.csv && fail "$ext: the noise of can0 did not move the estimate"
  echo "ok: $ext: --interface can1 is the drive alone, $noise frames of can0 skipped"
done

# 2. An interface the log does not have: exit 2, the interfaces it has with their frames.
for ext in log asc trc; do
  replay --log mixed.$ext --interface can2 --out none.csv >/dev/null 2>none_$ext.err
  rc=$?
  [ $rc -eq 2 ] || fail "$ext: --interface can2: exit $rc, expected 2: $(cat none_$ext.err)"
  grep -q "vmass-replay: mixed.$ext: no frame on interface can2; the log has can1 ($frames frames), can0 ($noise frames)$" \
    none_$ext.err || fail "$ext: no frame on can2: $(cat none_$ext.err)"
  [ -e none.csv ] && fail "$ext: the estimate CSV of a log without a frame on can2 was kept"
done
echo "ok: an interface the log does not have: exit 2 with the interfaces it has"

# 3. Many logs: the interface of each; a log without it is a failed row, not fatal.
head -n 3000 drive.log >only_can0.log
replay --logs mixed.log only_can0.log --interface can1 --jobs 2 >fleet.csv 2>fleet.err
rc=$?
[ $rc -eq 1 ] || fail "--logs with a failed row: exit $rc, expected 1: $(cat fleet.err)"
grep -q "^mixed.log,$frames,0," fleet.csv || fail "--logs: the mixed log's row: $(cat fleet.csv)"
grep -q "^only_can0.log,.*,only_can0.log: no frame on interface can1; the log has can0 (3000 frames)$" \
  fleet.csv || fail "--logs: the failed row: $(cat fleet.csv)"
grep -q "interface can1: $((noise + 3000)) frames of other interfaces skipped" fleet.err ||
  fail "--logs: the frames skipped: $(cat fleet.err)"
printf 'mixed.log\nonly_can0.log\n' >logs.list
replay --log-list logs.list --interface can1 --jobs 1 >list.csv 2>list.err
cmp -s fleet.csv list.csv || fail "--log-list differs from --logs: $(cat list.csv)"
echo "ok: --logs and --log-list: the interface of each log, a failed row for a log without it"

# 4. vmassd --replay: the same ticks as the drive alone; an interface it lacks is exit 2.
run_vmassd() {
  "$bin/vmassd" --config "$config" --speed max --no-restore --lcm-url memq:// --replay "$@"
}
ticks=$(($(wc -l <alone_log.csv) - 1))
run_vmassd mixed.trc --interface can1 >/dev/null 2>vmassd.err || fail "vmassd: $(cat vmassd.err)"
grep -q "end of replay:mixed.trc; $ticks ticks" vmassd.err ||
  fail "vmassd did not play the $ticks ticks: $(cat vmassd.err)"
grep -q "mixed.trc: interface can1: $noise frames of other interfaces skipped" vmassd.err ||
  fail "vmassd: the frames skipped: $(cat vmassd.err)"
run_vmassd mixed.asc --interface vcan0 >/dev/null 2>vmassd_none.err
rc=$?
[ $rc -eq 2 ] || fail "vmassd --interface vcan0: exit $rc, expected 2"
grep -q "mixed.asc: no frame on interface vcan0; the log has can1 ($frames frames), can0 ($noise frames)" \
  vmassd_none.err || fail "vmassd: no frame on vcan0: $(cat vmassd_none.err)"
echo "ok: vmassd --replay --interface"

# 5. vmass-can decode: what it prints for the drive alone; an interface the log lacks is exit 2.
"$bin/vmass-can" decode --dbc "$dbc" drive1.log >alone.decoded 2>/dev/null || fail "decode"
"$bin/vmass-can" decode --dbc "$dbc" mixed.log --interface can1 >can1.decoded 2>decode.err ||
  fail "decode --interface can1: $(cat decode.err)"
cmp -s alone.decoded can1.decoded || fail "decode --interface can1 differs from the drive alone"
grep -q "$noise frames of other interfaces skipped" decode.err || fail "decode: $(cat decode.err)"
"$bin/vmass-can" decode --dbc "$dbc" --interface can2 <mixed.log >/dev/null 2>decode_none.err
rc=$?
[ $rc -eq 2 ] || fail "decode --interface can2 from stdin: exit $rc, expected 2"
grep -q "stdin: no frame on interface can2; the log has can1 ($frames frames), can0 ($noise frames)" \
  decode_none.err || fail "decode: no frame on can2: $(cat decode_none.err)"
echo "ok: vmass-can decode --interface"

# 6. vmass-calibrate --ballast: the fit of the static test alone.
"$bin/vmass-sim" --scenario static_ballast --seed 4 --out sb >/dev/null || fail "vmass-sim"
sed 's/ can0 / can1 /' sb/drive.log >sb1.log
awk '{ l = $0; sub(/ can0 /, " can1 ", l); print l
       if (NR % 3 == 0) { sub(/#.*/, "#FFFF"); print } }' sb/drive.log >sb_mixed.log
calibrate() { "$bin/vmass-calibrate" --masses 0:100:800 --config sb/config.yaml --json "$@"; }
calibrate --ballast sb1.log >alone.json 2>/dev/null || fail "calibrate the test alone"
calibrate --ballast sb_mixed.log --interface can1 >can1.json 2>calibrate.err ||
  fail "calibrate --interface can1: $(cat calibrate.err)"
cmp -s alone.json can1.json || fail "calibrate --interface can1 differs from the test alone"
calibrate --ballast sb_mixed.log --interface can5 >/dev/null 2>calibrate_none.err
rc=$?
[ $rc -eq 2 ] || fail "calibrate --interface can5: exit $rc, expected 2"
grep -q "sb_mixed.log: no frame on interface can5; the log has can1 (" calibrate_none.err ||
  fail "calibrate: no frame on can5: $(cat calibrate_none.err)"
echo "ok: vmass-calibrate --ballast --interface"

# 7. A name no interface can have: a usage error in every tool, before anything is read.
for name in '' 'can 1' 'can0123456789abc' 'can/1'; do
  for tool in "vmass-replay --config $config --log mixed.log" \
              "vmassd --config $config --replay mixed.log" \
              "vmass-can decode --dbc $dbc mixed.log" \
              "vmass-calibrate --config sb/config.yaml --ballast sb_mixed.log"; do
    # shellcheck disable=SC2086
    "$bin"/$tool --interface "$name" >/dev/null 2>usage.err
    rc=$?
    [ $rc -eq 2 ] || fail "$tool --interface '$name': exit $rc, expected 2"
    grep -q -- "--interface: .*an interface name has 1 to 15 characters" usage.err ||
      fail "$tool --interface '$name': $(cat usage.err)"
  done
done
echo "ok: a name no interface can have is a usage error (exit 2)"
