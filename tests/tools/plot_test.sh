#!/bin/sh
# vmass-plot on what people have: two runs of one drive (RLS and Bayes) overlaid against the
# truth, and an LCM log of vmassd over the same drive (read with LCM's own log reader):
#   - the mass axis is scaled to the data (the truth inside, tighter than +-10 %: the estimates
#     padded by the median 95 % half-width, which since estimator v2 holds the model's own
#     uncertainty, about +-7 % on this drive), an error
#     panel is drawn with the truth, rows without an estimate are skipped and counted
#   - the LCM log's estimates, exported to CSV, are byte-identical to vmass-replay's CSV, and its
#     status CSV carries vmassd's version
#   - a file that is neither is refused, naming it
#   plot_test.sh BIN_DIR VERSION OUT_DIR
set -u
bin=$1
version=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
"$bin/vmass-sim" --scenario paper_exp2 --seed 1 --noise eps3 --out d >/dev/null || fail "vmass-sim"
for est in bayes rls; do
  "$bin/vmass-replay" --config d/config.yaml --log d/drive.log --estimator $est \
    --out $est.csv >/dev/null 2>&1 || fail "vmass-replay $est"
done
"$bin/vmass-plot" --estimates bayes.csv rls.csv --labels bayes rls --truth d/truth.csv \
  --out runs.png >plot.txt 2>&1 || fail "vmass-plot: $(cat plot.txt)"
head -c 8 runs.png | od -c | grep -q "P   N   G" || fail "runs.png is not a PNG"
empty=$(awk -F, 'NR > 1 && $2 == "" { n++ } END { print n + 0 }' bayes.csv)
[ "$empty" -gt 0 ] || fail "the drive has no row before the first estimate: the test tests nothing"
grep -q "bayes: .* rows drawn, $empty without an estimate skipped" plot.txt ||
  fail "rows without an estimate not skipped: $(cat plot.txt)"
grep -q "runs.png: 2 runs, mass axis .* error panel +-" plot.txt || fail "$(cat plot.txt)"
truth=$(awk -F, 'NR == 2 { print $2 }' d/truth.csv)
sed -n 's/.*mass axis \[\([0-9.]*\), \([0-9.]*\)\] kg.*/\1 \2/p' plot.txt | {
  read -r lo hi
  awk -v lo="$lo" -v hi="$hi" -v t="$truth" \
    'BEGIN { exit !(lo < t && t < hi && hi - lo < 0.2 * t) }' ||
    fail "mass axis [$lo, $hi] not scaled to the data around the truth $truth"
} || exit 1
echo "ok: two runs overlaid; $(grep 'mass axis' plot.txt)"

# vmassd over the same drive, recorded by LCM's file provider (what lcm-logger writes).
"$bin/vmassd" --config d/config.yaml --replay d/drive.log --speed max --no-restore \
  --lcm-url 'file://run.lcmlog?mode=w' 2>vmassd.err || fail "vmassd: $(cat vmassd.err)"
"$bin/vmass-plot" --estimates run.lcmlog --csv-dir csv --out lcm.png >lcm.txt 2>&1 ||
  fail "vmass-plot on an LCM log: $(cat lcm.txt)"
grep -q "run.lcmlog: 20001 estimates, [1-9][0-9]* status messages" lcm.txt ||
  fail "LCM log not read: $(cat lcm.txt)"
cmp -s csv/run_estimates.csv bayes.csv || fail "the LCM log's estimates differ from vmass-replay's"
awk -F, -v v="$version" 'NR > 1 && $4 != v { exit 1 }' csv/run_status.csv ||
  fail "status rows without version $version"
echo "ok: LCM log plotted; its estimates are vmass-replay's, byte for byte"

# The status CSV carries what status_t says of the drive: its last row's pair-term fit is the
# one vmass-replay's summary gives for the same drive.
"$bin/vmass-replay" --config d/config.yaml --log d/drive.log --json >summary.json 2>/dev/null ||
  fail "vmass-replay --json"
/usr/bin/python3 - csv/run_status.csv summary.json <<'PY' || fail "status CSV's pair-term fit"
import csv, json, sys
last = list(csv.DictReader(open(sys.argv[1])))[-1]
fit = json.load(open(sys.argv[2]))["pair_term_fit"]
want = {"pair_fit_applies": 1, "pair_fit_pairs": fit["pairs"],
        "pair_fit_rotating_error": fit["rotating_error"],
        "pair_fit_rotating_error_std": fit["rotating_error_std"],
        "pair_fit_shift_kg": fit["mass_shift_kg"], "pair_fit_shift_std_kg": fit["mass_std_kg"]}
bad = {k: (last[k], v) for k, v in want.items() if abs(float(last[k]) - v) > 1e-3 * max(1, abs(v))}
if bad or int(last["pair_fit_pairs"]) < 100:
    sys.exit(f"status CSV against vmass-replay: {bad or last['pair_fit_pairs']}")
if not 0 < float(last["learnt_scale_std"]) < 0.2 or float(last["learnt_scale"]) != 1.0:
    sys.exit(f"a first drive's learnt scale: {last['learnt_scale']} +- {last['learnt_scale_std']}")
print(f"ok: status CSV's pair-term fit is vmass-replay's ({last['pair_fit_pairs']} pairs)")
PY

"$bin/vmass-plot" --estimates d/vehicle.dbc --out bad.png >bad.txt 2>&1 &&
  fail "a DBC was plotted"
grep -q "vehicle.dbc: missing columns" bad.txt || fail "refusal: $(cat bad.txt)"
echo "ok"
