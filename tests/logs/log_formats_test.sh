#!/bin/sh
# The CAN logs people have, each written by an independent writer from one simulated drive
# (python-can writes ASC, BLF and TRC; asammdf writes MDF4 bus logging), read by every tool
# that reads a log, with the format found from the content alone (no extensions are used):
#   - vmass-replay --log gives the byte-identical estimate CSV the candump -l log gives
#   - vmass-can decode prints what it prints for the candump log (and for candump's screen
#     output of the same frames, as cantools decode reads it)
#   - vmass-calibrate --ballast gives the identical fit from an ASC and a BLF static test
#   - vmassd --replay plays an MDF4 log to its end
#   - a corrupt line (record) is reported as "file:line N" ("file:record N") and counted
#   - a converter without its Python package, an LCM log and an unknown file are refused (2)
#   log_formats_test.sh BIN_DIR PYTHON OUT_DIR
set -u
here=$(cd "$(dirname "$0")" && pwd)
bin=$1
python=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" || exit 1
cd "$out" || exit 1
"$python" -c "import can, asammdf" 2>/dev/null ||
  fail "$python lacks python-can or asammdf: run scripts/install-python-deps.sh"
"$bin/vmass-sim" --scenario paper_exp2 --seed 2 --noise eps1 --out d >/dev/null || fail "vmass-sim"
TZ=UTC "$python" "$here/write_logs.py" d/drive.log x || fail "write_logs.py"
cp d/drive.log x/drive.candump  # no extension tells the format
for f in drive.asc drive.blf drive.trc drive.mf4; do mv "x/$f" "x/${f%.*}_${f#*.}.bin"; done

replay() { "$bin/vmass-replay" --config d/config.yaml --log "$1" --out "$2" >/dev/null 2>"$2.err"; }
replay x/drive.candump candump.csv || fail "replay of the candump log: $(cat candump.csv.err)"
"$bin/vmass-can" decode --dbc d/vehicle.dbc x/drive.candump >candump.decoded 2>/dev/null ||
  fail "decode of the candump log"
for spec in asc:"Vector ASC":lines trc:"PEAK TRC":lines blf:"Vector BLF":records \
            mf4:"ASAM MDF4":records; do
  ext=${spec%%:*}
  rest=${spec#*:}
  name=${rest%%:*}
  unit=${rest#*:}
  replay "x/drive_$ext.bin" "$ext.csv" || fail "$ext: replay: $(cat "$ext.csv.err")"
  grep -q "drive_$ext.bin ($name): 112006 frames, 0 corrupt $unit" "$ext.csv.err" ||
    fail "$ext: format or counts: $(cat "$ext.csv.err")"
  cmp -s candump.csv "$ext.csv" || fail "$ext: the estimate differs from the candump log's"
  "$bin/vmass-can" decode --dbc d/vehicle.dbc "x/drive_$ext.bin" >"$ext.decoded" 2>/dev/null ||
    fail "$ext: decode"
  cmp -s candump.decoded "$ext.decoded" || fail "$ext: vmass-can decode differs"
  echo "ok: $name: replay and decode identical to candump -l"
done

# candump's screen output (what candump prints without -l), with times (-t a) and without.
awk '{ split($3, f, "#"); d = f[2]; s = ""; for (i = 1; i <= length(d); i += 2)
       s = s " " substr(d, i, 2); printf "%s  %s  %s   [%d] %s\n", $1, $2, f[1], length(d) / 2, s }' \
  x/drive.candump >x/screen_timed.txt
"$bin/vmass-can" decode --dbc d/vehicle.dbc x/screen_timed.txt >screen.decoded 2>screen.err ||
  fail "screen output: decode"
cmp -s candump.decoded screen.decoded || fail "screen output with times: decode differs"
cut -c 21- x/screen_timed.txt | "$bin/vmass-can" decode --dbc d/vehicle.dbc >untimed.decoded \
  2>untimed.err || fail "untimed screen output on stdin: decode"
grep -q "candump screen output, 112006 frames, 112006 decoded" untimed.err ||
  fail "untimed screen output: $(cat untimed.err)"
"$bin/vmass-replay" --config d/config.yaml --log x/screen_timed.txt >/dev/null 2>&1 ||
  fail "a screen log with times does not replay"
echo "ok: candump screen output decoded (and replayed when it has times)"

# Corrupt lines and records: reported with their place, counted, skipped.
sed '1000a\
   9.999999 1  123             Rx   d 8 01 02' x/drive_asc.bin >x/bad_asc.bin
replay x/bad_asc.bin bad_asc.csv || fail "a corrupt ASC line was fatal"
grep -q "bad_asc.bin:1001: fewer data bytes than the DLC says" bad_asc.csv.err ||
  fail "ASC corrupt line not reported: $(cat bad_asc.csv.err)"
grep -q "1 corrupt lines" bad_asc.csv.err || fail "ASC corrupt line not counted"
sed '30a\
      9       9.000 DT  1     0123 Rx -  8    01' x/drive_trc.bin >x/bad_trc.bin
replay x/bad_trc.bin bad_trc.csv || fail "a corrupt TRC line was fatal"
grep -q "bad_trc.bin:31: fewer data bytes than the length says" bad_trc.csv.err ||
  fail "TRC corrupt line not reported: $(cat bad_trc.csv.err)"
TZ=UTC "$python" "$here/write_logs.py" d/drive.log bad --bad-mdf-record 1000 >/dev/null ||
  fail "write_logs.py --bad-mdf-record"
replay bad/drive.mf4 bad_mf4.csv || fail "a corrupt MDF4 record was fatal"
grep -q "drive.mf4:record 1000: classic frame of 9 bytes" bad_mf4.csv.err ||
  fail "MDF4 corrupt record not reported: $(cat bad_mf4.csv.err)"
grep -q "112005 frames, 1 corrupt records" bad_mf4.csv.err || fail "MDF4 record not counted"
echo "ok: corrupt ASC and TRC lines and MDF4 records reported with their place and counted"

# The daemon replays MDF4 (through the converter) to its end.
"$bin/vmassd" --config d/config.yaml --replay x/drive_mf4.bin --speed max --no-restore \
  --lcm-url memq:// >vmassd.out 2>vmassd.err || fail "vmassd --replay MDF4: $(cat vmassd.err)"
grep -q "drive_mf4.bin: ASAM MDF4" vmassd.err || fail "vmassd does not name the format"
ticks=$(($(wc -l <candump.csv) - 1))  # one estimate row per tick
grep -q "end of replay:x/drive_mf4.bin; $ticks ticks" vmassd.err ||
  fail "vmassd did not play the $ticks ticks: $(cat vmassd.err)"
echo "ok: vmassd --replay of ASAM MDF4"

# A static ballast test as ASC and BLF: the same fit as from its candump log.
"$bin/vmass-sim" --scenario static_ballast --seed 4 --out sb >/dev/null || fail "vmass-sim ballast"
TZ=UTC "$python" "$here/write_logs.py" sb/drive.log sbx >/dev/null || fail "write_logs sb"
for log in sb/drive.log sbx/drive.asc sbx/drive.blf; do
  "$bin/vmass-calibrate" --ballast "$log" --masses 0:100:800 --config sb/config.yaml --json \
    >"$(basename "$log").json" 2>/dev/null || fail "vmass-calibrate --ballast $log"
done
cmp -s drive.log.json drive.asc.json || fail "calibration from ASC differs"
cmp -s drive.log.json drive.blf.json || fail "calibration from BLF differs"
echo "ok: vmass-calibrate --ballast from ASC and BLF identical to candump -l"

# Refusals: exit 2 with the reason.
VMASS_PYTHON=/usr/bin/python3 "$bin/vmass-replay" --config d/config.yaml --log x/drive_mf4.bin \
  >/dev/null 2>nopkg.err
rc=$?
if /usr/bin/python3 -c "import asammdf" 2>/dev/null; then
  echo "skip: /usr/bin/python3 has asammdf: the missing-package message is not tested"
else
  [ $rc -eq 2 ] || fail "MDF4 without asammdf: exit $rc"
  grep -q "reading MDF4 needs the Python package asammdf" nopkg.err ||
    fail "missing package not named: $(cat nopkg.err)"
fi
printf '\355\241\332\001\000\000\000\000' >run.lcmlog
"$bin/vmass-replay" --config d/config.yaml --log run.lcmlog >/dev/null 2>lcm.err
rc=$?
[ $rc -eq 2 ] && grep -q "run.lcmlog: an LCM log (lcm-logger), not CAN frames" lcm.err ||
  fail "an LCM log: exit $rc, $(cat lcm.err)"
"$bin/vmass-replay" --config d/config.yaml --log d/truth.csv >/dev/null 2>csv.err
[ $? -eq 2 ] && grep -q "not a CAN log vmass reads" csv.err || fail "a CSV as a log: $(cat csv.err)"
echo "ok: refusals"
