#!/bin/sh
# vmass-replay over many logs: a folder and a list give one table row per log in the order
# named; each row is what --log alone reports for that log, whatever --jobs; --out-dir holds
# each log's estimate CSV, byte for byte what --log --out writes; JSON lines carry the same
# values; a missing log is a usage error (2), a log that cannot be written a failure (1).
#   replay_many_logs_test.sh VMASS_REPLAY VMASS_SIM OUT_DIR
set -u
replay=$1
sim=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }
# A JSON member's value, printf-formatted (JSON writes 1659.0 where the table shows 1659.000).
json_field() {
  /usr/bin/python3 -c 'import json, sys; print(sys.argv[1] % json.load(sys.stdin)[sys.argv[2]])' "$@"
}

rm -rf "$out" && mkdir -p "$out/fleet" || exit 1
"$sim" --scenario paper_exp2 --seed 1 --out "$out/s1" >/dev/null || fail "vmass-sim seed 1"
"$sim" --scenario load_step --seed 2 --out "$out/s2" >/dev/null || fail "vmass-sim seed 2"
cp "$out/s1/drive.log" "$out/fleet/b_exp2.log"
cp "$out/s2/drive.log" "$out/fleet/a_load_step.log"
head -n 20000 "$out/s1/drive.log" >"$out/fleet/c_short.log"
printf '(garbage\n' >>"$out/fleet/c_short.log"
touch "$out/fleet/notes.txt"  # not a log: a folder gives its *.log files only
config="$out/s1/config.yaml"

"$replay" --config "$config" --logs "$out/fleet" --jobs 1 >"$out/j1.csv" 2>"$out/j1.err" ||
  fail "--logs --jobs 1: $(cat "$out/j1.err")"
"$replay" --config "$config" --logs "$out/fleet" --jobs 2 --out-dir "$out/csv" >"$out/j2.csv" ||
  fail "--logs --jobs 2"
cmp -s "$out/j1.csv" "$out/j2.csv" || fail "the table depends on --jobs: $(diff "$out/j1.csv" "$out/j2.csv")"
[ "$(wc -l <"$out/j1.csv")" -eq 4 ] || fail "expected a header and 3 rows: $(cat "$out/j1.csv")"
head -n 1 "$out/j1.csv" | grep -q '^log,frames,corrupt_lines,duration_s,ticks,estimator,status,' ||
  fail "header: $(head -n 1 "$out/j1.csv")"
sed -n 2p "$out/j1.csv" | grep -q "^$out/fleet/a_load_step.log," || fail "rows not sorted by name"
sed -n 4p "$out/j1.csv" | grep -q "^$out/fleet/c_short.log,20000,1," ||
  fail "frames and corrupt lines of the short log: $(sed -n 4p "$out/j1.csv")"
grep -q "3 logs (0 failed, 0 skipped)" "$out/j1.err" || fail "no run line: $(cat "$out/j1.err")"

# Each row is what --log alone says, and each CSV what --log --out writes.
for name in a_load_step b_exp2 c_short; do
  log="$out/fleet/$name.log"
  "$replay" --config "$config" --log "$log" --json --out "$out/$name.single.csv" \
    >"$out/$name.json" 2>/dev/null || fail "--log $name"
  mass=$(json_field %.3f mass_kg <"$out/$name.json")
  used=$(json_field %d pairs_used <"$out/$name.json")
  accepted=$(json_field %d pairs_accepted <"$out/$name.json")
  grep "^$log," "$out/j1.csv" | grep -q ",$mass,.*,$used,$accepted," ||
    fail "$name: row differs from --log (mass $mass, pairs $used/$accepted): $(grep "^$log," "$out/j1.csv")"
  cmp -s "$out/$name.single.csv" "$out/csv/$name.csv" || fail "$name: --out-dir CSV differs"
done

# A list, and JSON lines with the same values.
printf '# logs\n%s\n\n%s\n' "$out/fleet/b_exp2.log" "$out/fleet/c_short.log" >"$out/list.txt"
"$replay" --config "$config" --log-list "$out/list.txt" --json >"$out/list.jsonl" ||
  fail "--log-list"
[ "$(wc -l <"$out/list.jsonl")" -eq 2 ] || fail "expected 2 JSON lines: $(cat "$out/list.jsonl")"
b_mass=$(grep "^$out/fleet/b_exp2.log," "$out/j1.csv" | cut -d, -f9)
[ "$(head -n 1 "$out/list.jsonl" | json_field %s log)" = "$out/fleet/b_exp2.log" ] &&
  [ "$(head -n 1 "$out/list.jsonl" | json_field %.3f mass_kg)" = "$b_mass" ] ||
  fail "JSON line differs from the CSV row ($b_mass): $(head -n 1 "$out/list.jsonl")"
grep -q '"error": *null}$' "$out/list.jsonl" || fail "no null error: $(cat "$out/list.jsonl")"

# Errors: a missing log (2, named), a CSV that cannot be written (1, the others still run),
# options of one input with many.
"$replay" --config "$config" --logs "$out/fleet" "$out/missing.log" >/dev/null 2>"$out/e1.err"
[ $? -eq 2 ] || fail "missing log: expected exit 2"
grep -q "missing.log: no such log or folder" "$out/e1.err" || fail "missing log not named"
mkdir -p "$out/csv2/b_exp2.csv"  # a folder where b's CSV goes
"$replay" --config "$config" --logs "$out/fleet" --out-dir "$out/csv2" >"$out/e2.csv" 2>/dev/null
[ $? -eq 1 ] || fail "unwritable CSV: expected exit 1"
grep -q "b_exp2.log,,.*cannot write" "$out/e2.csv" || fail "error not in the table: $(cat "$out/e2.csv")"
[ -s "$out/csv2/a_load_step.csv" ] || fail "the other logs were not written"
"$replay" --config "$config" --logs "$out/fleet" --truth "$out/s1/truth.csv" >/dev/null 2>&1
[ $? -eq 2 ] || fail "--truth with --logs: expected exit 2"
"$replay" --config "$config" --log "$out/fleet/b_exp2.log" --jobs 2 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--jobs with --log: expected exit 2"
echo "ok"
