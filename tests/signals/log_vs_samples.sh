#!/bin/sh
# Given a simulated drive, when vmass-replay runs it from samples.csv and from drive.log (the
# demo car's CAN frames through the config's can: mapping), then both estimators end within
# 0.1 percentage point of each other over the same duration; a corrupt log line is reported
# with its line number and skipped; --samples and --log exclude each other.
#   log_vs_samples.sh VMASS_SIM VMASS_REPLAY OUT_DIR
set -u
sim=$1
replay=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }
field() { sed -n "s/.*\"$1\": *\([-0-9.e]*\).*/\1/p"; }

rm -rf "$out" && mkdir -p "$out" || exit 1
"$sim" --scenario paper_exp2 --seed 2 --noise eps1 --out "$out/d" >/dev/null || fail "vmass-sim"
for f in drive.log vehicle.dbc config.yaml samples.csv; do
  test -s "$out/d/$f" || fail "vmass-sim did not write $f"
done
grep -q '^can:' "$out/d/config.yaml" || fail "config.yaml has no can: section"

for est in bayes rls; do
  "$replay" --config "$out/d/config.yaml" --samples "$out/d/samples.csv" --estimator $est \
    --truth "$out/d/truth.csv" --json >"$out/samples_$est.json" || fail "--samples $est"
  "$replay" --config "$out/d/config.yaml" --log "$out/d/drive.log" --estimator $est \
    --truth "$out/d/truth.csv" --json >"$out/log_$est.json" 2>"$out/log_$est.err" || fail "--log $est"
  a=$(field error_percent <"$out/samples_$est.json")
  b=$(field error_percent <"$out/log_$est.json")
  da=$(field duration_s <"$out/samples_$est.json")
  db=$(field duration_s <"$out/log_$est.json")
  [ -n "$a" ] && [ -n "$b" ] || fail "no error_percent ($est)"
  echo "$est: final error --samples $a %, --log $b %, duration $da s / $db s"
  awk -v a="$a" -v b="$b" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 0.1) }' ||
    fail "$est: --log differs from --samples by more than 0.1 percentage point"
  [ "$da" = "$db" ] || fail "$est: durations differ"
  grep -q "0 corrupt lines" "$out/log_$est.err" || fail "$est: unexpected corrupt lines"
done

# A corrupt line in the middle: reported with its line number, counted, not fatal.
sed '1000a this is not a candump line' "$out/d/drive.log" >"$out/d/corrupt.log"
"$replay" --config "$out/d/config.yaml" --log "$out/d/corrupt.log" --json >"$out/corrupt.json" \
  2>"$out/corrupt.err" || fail "a corrupt line was fatal"
grep -q "corrupt.log:1001: " "$out/corrupt.err" || fail "corrupt line not reported: $(cat "$out/corrupt.err")"
grep -q "1 corrupt lines" "$out/corrupt.err" || fail "corrupt line not counted"

# Exactly one input.
"$replay" --config "$out/d/config.yaml" >/dev/null 2>&1 && fail "no input accepted"
"$replay" --config "$out/d/config.yaml" --samples "$out/d/samples.csv" --log "$out/d/drive.log" \
  >/dev/null 2>&1 && fail "--samples with --log accepted"
echo "ok"
