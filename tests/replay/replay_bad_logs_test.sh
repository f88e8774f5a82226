#!/bin/sh
# Logs from a hostile hand, end to end through vmass-replay and vmass-can:
#   - a line dropped by any reader is counted (an ASC channel above 255 is a corrupt line);
#   - a log none of whose lines can be read is bad input (exit 2), with how many lines were
#     dropped and the first one's number and reason (--log; a failed row with --logs);
#   - a log dated before 1970 (ASC 1969) replays as its twin dated 2024;
#   - --log-list is read bounded (/dev/zero refused); a FIFO named in --logs is refused, one in
#     a folder skipped with a warning and counted;
#   - a write that fails (/dev/full) is exit 1 naming the path;
#   - a DBC with CR-only line endings loads like its LF twin.
#   replay_bad_logs_test.sh VMASS_REPLAY VMASS_SIM VMASS_CAN DBC_DIR OUT_DIR
set -u
replay=$1
sim=$2
can=$3
dbc_dir=$4
out=$5
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out/fleet" || exit 1
"$sim" --scenario paper_exp2 --seed 1 --out "$out/s1" >/dev/null || fail "vmass-sim"
config="$out/s1/config.yaml"
head -n 3000 "$out/s1/drive.log" >"$out/short.log"

# An ASC twin of the short log, dated `date`: one line per frame, channel 1.
asc() {
  { printf 'date %s\nbase hex  timestamps absolute\n' "$1"
    sed -e 's/^(\([0-9.]*\)) can0 \([0-9A-F]*\)#\([0-9A-F]*\)$/\1 \2 \3/' "$out/short.log" |
      awk '{ n = length($3) / 2; s = ""; for (i = 0; i < n; i++) s = s " " substr($3, 2 * i + 1, 2)
             printf "   %.6f %s  %s             Rx   d %d%s\n", $1, ch, $2, n, s }' ch="$2"
    echo "End TriggerBlock"; } >"$3"
}
asc "Wed Jan 10 10:55:25.123 am 2024" 1 "$out/d2024.asc"
asc "Wed Dec 31 23:00:00.000 1969" 1 "$out/d1969.asc"
asc "Wed Jan 10 10:55:25.123 am 2024" 300 "$out/ch300.asc"

# 1. Channel 300: every frame line counted as corrupt, with its reason; no frame: exit 2.
"$replay" --config "$config" --log "$out/ch300.asc" >/dev/null 2>"$out/ch300.err"
[ $? -eq 2 ] || fail "ASC channel 300: expected exit 2: $(cat "$out/ch300.err")"
grep -q "0 frames, 3000 corrupt lines" "$out/ch300.err" || fail "channel 300 not counted: $(cat "$out/ch300.err")"
grep -q "ch300.asc: no frames: 3000 of 3003 lines could not be read; the first, line 3: channel above 255" \
  "$out/ch300.err" || fail "no-frames reason: $(cat "$out/ch300.err")"

# 3. Times of 9e15 s, negative times, garbage: exit 2 with the first line and why.
sed 's/^(/(900000/' "$out/short.log" >"$out/huge.log"
sed 's/^(/(-/' "$out/short.log" >"$out/negative.log"
printf '(1.000000) can0 XYZ#00\n(garbage\n' >"$out/garbage.log"
for name in huge negative garbage; do
  "$replay" --config "$config" --log "$out/$name.log" >/dev/null 2>"$out/$name.err"
  [ $? -eq 2 ] || fail "$name: expected exit 2: $(cat "$out/$name.err")"
done
grep -q "huge.log: no frames: 3000 of 3000 lines could not be read; the first, line 1: more than 12 digits of seconds in the timestamp" \
  "$out/huge.err" || fail "huge times: $(cat "$out/huge.err")"
grep -q "negative.log: no frames: 3000 of 3000 lines could not be read; the first, line 1: negative time (before 1970)" \
  "$out/negative.err" || fail "negative times: $(cat "$out/negative.err")"
grep -q "garbage.log: no frames: " "$out/garbage.err" || fail "garbage: $(cat "$out/garbage.err")"
"$can" decode --dbc "$out/s1/vehicle.dbc" "$out/huge.log" >/dev/null 2>"$out/decode_huge.err"
[ $? -eq 2 ] || fail "vmass-can decode of a log without frames: expected exit 2"
grep -q "huge.log: no frames: 3000 of 3000 lines" "$out/decode_huge.err" ||
  fail "vmass-can decode: $(cat "$out/decode_huge.err")"

# 4. Dated 1969: the same estimate as dated 2024 (the time column aside).
"$replay" --config "$config" --log "$out/d2024.asc" --out "$out/d2024.csv" >/dev/null 2>&1 ||
  fail "ASC 2024"
"$replay" --config "$config" --log "$out/d1969.asc" --out "$out/d1969.csv" >"$out/d1969.txt" 2>&1 ||
  fail "ASC 1969: $(cat "$out/d1969.txt")"
cut -d, -f2- "$out/d2024.csv" >"$out/d2024.cut"
cut -d, -f2- "$out/d1969.csv" >"$out/d1969.cut"
cmp -s "$out/d2024.cut" "$out/d1969.cut" || fail "1969 differs from 2024: $(diff "$out/d2024.cut" "$out/d1969.cut" | head -5)"
[ "$(grep -c inputs_invalid "$out/d1969.csv")" -le 1 ] || fail "1969: ticks with inputs_invalid"

# 5. Bounded list, FIFOs.
# Refused before a byte is read; the timeout bounds a regression that would read on (no
# `ulimit -v`: AddressSanitizer's shadow memory needs terabytes of address space).
timeout 5 "$replay" --config "$config" --log-list /dev/zero >/dev/null 2>"$out/zero.err"
[ $? -eq 2 ] || fail "--log-list /dev/zero: expected exit 2: $(cat "$out/zero.err")"
grep -q "/dev/zero: cannot read the list of logs: is a character device" "$out/zero.err" ||
  fail "--log-list /dev/zero: $(cat "$out/zero.err")"
mkfifo "$out/pipe.log" || fail "mkfifo"
timeout 20 "$replay" --config "$config" --logs "$out/pipe.log" >/dev/null 2>"$out/fifo.err"
[ $? -eq 2 ] || fail "FIFO in --logs: expected exit 2: $(cat "$out/fifo.err")"
grep -q "pipe.log: is a FIFO (named pipe): a log named here must be a regular file or a folder" \
  "$out/fifo.err" || fail "FIFO in --logs: $(cat "$out/fifo.err")"
cp "$out/short.log" "$out/fleet/a.log"
mkfifo "$out/fleet/b.log" || fail "mkfifo"
cp "$out/huge.log" "$out/fleet/c.log"
timeout 60 "$replay" --config "$config" --logs "$out/fleet" >"$out/fleet.csv" 2>"$out/fleet.err"
[ $? -eq 1 ] || fail "a folder with a log without frames: expected exit 1: $(cat "$out/fleet.err")"
grep -q "warning: $out/fleet/b.log: skipped: is a FIFO (named pipe)" "$out/fleet.err" ||
  fail "FIFO in a folder not named: $(cat "$out/fleet.err")"
grep -q "2 logs (1 failed, 1 skipped)" "$out/fleet.err" || fail "summary: $(cat "$out/fleet.err")"
grep -q "^$out/fleet/c.log,,.*c.log: no frames: 3000 of 3000 lines" "$out/fleet.csv" ||
  fail "row of a log without frames: $(cat "$out/fleet.csv")"

# 6. Failed writes: --out, an --out-dir CSV, standard output.
"$replay" --config "$config" --log "$out/short.log" --out /dev/full >/dev/null 2>"$out/full.err"
[ $? -eq 1 ] || fail "--out /dev/full: expected exit 1"
grep -q "/dev/full: write failed" "$out/full.err" || fail "--out /dev/full: $(cat "$out/full.err")"
mkdir -p "$out/csv" && ln -s /dev/full "$out/csv/a.csv"
"$replay" --config "$config" --logs "$out/fleet/a.log" --out-dir "$out/csv" >"$out/full2.csv" 2>"$out/full2.err"
[ $? -eq 1 ] || fail "--out-dir on /dev/full: expected exit 1"
grep -q "^$out/fleet/a.log,,,.*csv/a.csv: write failed" "$out/full2.csv" ||
  fail "--out-dir on /dev/full: $(cat "$out/full2.csv")"
[ -c /dev/full ] || fail "/dev/full was removed"
"$replay" --config "$config" --logs "$out/fleet/a.log" >/dev/full 2>"$out/full3.err"
[ $? -eq 1 ] || fail "table on /dev/full: expected exit 1"
"$can" decode --dbc "$out/s1/vehicle.dbc" "$out/short.log" >/dev/full 2>"$out/full4.err"
[ $? -eq 1 ] || fail "vmass-can decode on /dev/full: expected exit 1"

# 2. A DBC with CR-only line endings: the messages and signals of its LF twin.
for name in toyota_prius_2010_pt vw_mqb; do
  tr -d '\r' <"$dbc_dir/$name.dbc" >"$out/$name.lf.dbc"
  tr '\n' '\r' <"$out/$name.lf.dbc" >"$out/$name.cr.dbc"
  "$can" check --dbc "$out/$name.lf.dbc" >"$out/$name.lf.txt" 2>&1
  lf_rc=$?
  "$can" check --dbc "$out/$name.cr.dbc" >"$out/$name.cr.txt" 2>&1
  [ $? -eq $lf_rc ] || fail "$name: CR-only exits differently from LF"
  sed "s/$name.cr.dbc/$name.lf.dbc/g" "$out/$name.cr.txt" | cmp -s - "$out/$name.lf.txt" ||
    fail "$name: CR-only differs: $(sed "s/$name.cr.dbc/$name.lf.dbc/g" "$out/$name.cr.txt" | diff - "$out/$name.lf.txt" | head -5)"
  grep -qi "message" "$out/$name.lf.txt" || fail "$name: no messages listed"
done
echo "ok"
