#!/bin/sh
# Given vmassd's stderr connected to "the journal" (JOURNAL_STREAM set to that file's
# device:inode, as systemd does), every line it writes starts with an sd-daemon priority prefix
# (<3> error, <4> warning, <6> info), carries no program name, the first names the version, and
# a config error is one line, and so is a stop during start-up;
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
# (vmass-sim's config leaves the tick rate at its default: the bad one is added; written next
# to the config, so that its DBC is found and the tick rate is the only error.)
sed 's/^  type: \(bayes\|rls\).*/&\n  tick_rate_hz: -5/' "$out/d/config.yaml" >"$out/d/bad.yaml"
grep -q '^  tick_rate_hz: -5$' "$out/d/bad.yaml" || fail "no estimator.type line to add the tick rate to"
: >"$out/error.txt"
stream=$(stat -c '%d:%i' "$out/error.txt")
JOURNAL_STREAM=$stream "$vmassd" --config "$out/d/bad.yaml" --replay "$out/d/drive.log" \
  --lcm-url memq:// 2>>"$out/error.txt"
rc=$?
[ $rc -eq 2 ] || fail "a config error exited $rc, not 2 (RestartPreventExitStatus=2)"
# The version first, then the error in one line.
[ "$(wc -l <"$out/error.txt")" -eq 2 ] || fail "config error not one line: $(cat "$out/error.txt")"
tail -1 "$out/error.txt" | grep -q '^<3>.*tick_rate_hz' || fail "config error: $(cat "$out/error.txt")"
# Stopped during start-up (blocked opening a FIFO without a writer): the journal's form too.
mkfifo "$out/fifo.log" || fail "mkfifo"
: >"$out/stop.txt"
stream=$(stat -c '%d:%i' "$out/stop.txt")
JOURNAL_STREAM=$stream "$vmassd" --config "$out/d/config.yaml" --replay "$out/fifo.log" \
  --lcm-url memq:// 2>>"$out/stop.txt" &
pid=$!
sleep 0.5
kill -TERM $pid
wait $pid
rc=$?
[ $rc -eq 0 ] || fail "stopped during start-up: exit $rc"
tail -1 "$out/stop.txt" | grep -q '^<6>stopped during start-up$' ||
  fail "start-up stop not in the journal's form: $(cat "$out/stop.txt")"
grep -v -E '^<[2-7]>' "$out/stop.txt" && fail "start-up stop: lines without a priority prefix"
# Not under systemd: the usual form.
"$vmassd" --config "$out/d/bad.yaml" --lcm-url memq:// 2>"$out/plain.txt"
grep -q '^vmassd error: ' "$out/plain.txt" || fail "terminal form: $(cat "$out/plain.txt")"
echo "ok: $lines journal lines, each with its priority"
