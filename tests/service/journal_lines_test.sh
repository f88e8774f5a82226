#!/bin/sh
# Given vmassd's stderr connected to "the journal" (JOURNAL_STREAM set to that file's
# device:inode, as systemd does), every line it writes starts with an sd-daemon priority prefix
# (<3> error, <4> warning, <6> info), carries no program name, the first names the version, and
# a config error is one line;
# without JOURNAL_STREAM the lines read "vmassd LEVEL: ...".
#   journal_lines_test.sh VMASSD VMASS_SIM OUT_DIR
set -u
vmassd=$1
sim=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" || exit 1
"$sim" --scenario paper_exp2 --seed 1 --noise eps1 --out "$out/d" >/dev/null || fail "vmass-sim"
# A recording played at full speed: start-up (version, can.inputs, warnings) to the last line.
: >"$out/journal.txt"
stream=$(stat -c '%d:%i' "$out/journal.txt")
JOURNAL_STREAM=$stream "$vmassd" --config "$out/d/config.yaml" --replay "$out/d/drive.log" \
  --speed max --no-restore --lcm-url memq:// 2>>"$out/journal.txt" || fail "vmassd exited $?"
lines=$(wc -l <"$out/journal.txt")
[ "$lines" -ge 5 ] || fail "only $lines lines: $(cat "$out/journal.txt")"
grep -v -E '^<[2-7]>' "$out/journal.txt" && fail "lines without a priority prefix"
grep -q 'vmassd info' "$out/journal.txt" && fail "program name and level in the journal"
head -1 "$out/journal.txt" | grep -q '^<6>vmassd [0-9.]* starting: config ' ||
  fail "the first line does not name the version"
grep -q '^<6>vmassd running (version ' "$out/journal.txt" || fail "no running line with version"
grep -q '^<6>can.inputs.speed <- ' "$out/journal.txt" || fail "can.inputs not one entry per input"
# A configuration error: exit 2, one line, priority 3.
sed 's/^  tick_rate_hz:.*/  tick_rate_hz: -5/' "$out/d/config.yaml" >"$out/bad.yaml"
: >"$out/error.txt"
stream=$(stat -c '%d:%i' "$out/error.txt")
JOURNAL_STREAM=$stream "$vmassd" --config "$out/bad.yaml" --replay "$out/d/drive.log" \
  --lcm-url memq:// 2>>"$out/error.txt"
rc=$?
[ $rc -eq 2 ] || fail "a config error exited $rc, not 2 (RestartPreventExitStatus=2)"
# The version first, then the error in one line.
[ "$(wc -l <"$out/error.txt")" -eq 2 ] || fail "config error not one line: $(cat "$out/error.txt")"
tail -1 "$out/error.txt" | grep -q '^<3>.*tick_rate_hz' || fail "config error: $(cat "$out/error.txt")"
# Not under systemd: the usual form.
"$vmassd" --config "$out/bad.yaml" --lcm-url memq:// 2>"$out/plain.txt"
grep -q '^vmassd error: ' "$out/plain.txt" || fail "terminal form: $(cat "$out/plain.txt")"
echo "ok: $lines journal lines, each with its priority"
