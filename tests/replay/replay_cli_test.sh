#!/bin/sh
# vmass-replay tells the truth: a truth file is read only when --truth names it; a truth in
# another time base than the input's is refused (exit 2, the file named); the table labels the
# prior and reports pairs used and accepted apart; --json carries the same.
#   replay_cli_test.sh VMASS_REPLAY GOLDEN_DIR OUT_DIR
set -u
replay=$1
golden=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }
# A JSON member's value, printf-formatted (JSON writes 1659.0 where the table shows 1659.000).
json_field() {
  /usr/bin/python3 -c 'import json, sys; print(sys.argv[1] % json.load(sys.stdin)[sys.argv[2]])' "$@"
}

rm -rf "$out" && mkdir -p "$out" || exit 1
cp "$golden/config.yaml" "$golden/samples.csv" "$golden/truth.csv" "$out/" || exit 1

# truth.csv beside the input is not read unasked.
"$replay" --config "$out/config.yaml" --samples "$out/samples.csv" >"$out/plain.txt" ||
  fail "replay without --truth"
grep -q "true mass" "$out/plain.txt" && fail "truth.csv read without --truth: $(cat "$out/plain.txt")"
grep -q "^prior  *[0-9.]* kg (static prior, eq. 3)" "$out/plain.txt" ||
  fail "prior not labelled: $(cat "$out/plain.txt")"
grep -q "^pairs used .*(in the estimate)" "$out/plain.txt" || fail "no pairs used line"
grep -q "^pairs accepted .*(by the supervisor)" "$out/plain.txt" || fail "no pairs accepted line"

# Named, in the same time base: compared.
"$replay" --config "$out/config.yaml" --samples "$out/samples.csv" --truth "$out/truth.csv" \
  --json >"$out/truth.json" || fail "replay with --truth"
for key in true_mass_kg initial_mass_kg prior reason pairs_accepted longitudinal lateral; do
  grep -q "\"$key\": *" "$out/truth.json" || fail "--json has no $key: $(cat "$out/truth.json")"
done
[ "$(json_field %.3f true_mass_kg <"$out/truth.json")" = 1659.000 ] ||
  fail "truth not used: $(cat "$out/truth.json")"
# After the flush every accepted pair is in the estimate.
used=$(json_field %d pairs_used <"$out/truth.json")
accepted=$(json_field %d pairs_accepted <"$out/truth.json")
[ "$used" = "$accepted" ] || fail "pairs used $used != accepted $accepted after the flush"

# The same drive with epoch times (as a candump log from a car carries): the truth starting at
# 0 s is refused, naming the file, before anything is written.
awk -F, 'NR == 1 { print; next } { $1 = sprintf("%.2f", $1 + 1700000000); print }' OFS=, \
  "$out/samples.csv" >"$out/epoch.csv"
"$replay" --config "$out/config.yaml" --samples "$out/epoch.csv" --truth "$out/truth.csv" \
  --out "$out/epoch_estimate.csv" >"$out/epoch.txt" 2>"$out/epoch.err"
rc=$?
[ $rc -eq 2 ] || fail "epoch input with a 0-based truth: exit $rc, expected 2"
grep -q "$out/truth.csv: not the truth of $out/epoch.csv: its times (0.000 to 59.990 s)" \
  "$out/epoch.err" || fail "refusal does not name the file and the spans: $(cat "$out/epoch.err")"
[ -s "$out/epoch.txt" ] && fail "a summary was printed for a refused truth"
[ -e "$out/epoch_estimate.csv" ] && fail "an estimate CSV was left for a refused run"
# Without the truth the epoch input replays fine.
"$replay" --config "$out/config.yaml" --samples "$out/epoch.csv" >/dev/null ||
  fail "epoch input without truth"
echo "ok"
