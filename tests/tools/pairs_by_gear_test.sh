#!/bin/sh
# The pair channel carries what a study of the rotating masses per gear needs (issue 30, step 3):
# vmassd over a pickup's urban drive (eight gears, known scale) with lcm.publish_pairs, recorded
# by LCM's file provider, exported by vmass-lcmlog-csv --pairs and read by pairs_by_gear.py:
#   - one pair record per tick and block; every candidate's m_rot is the config's for its gear
#   - each gear's effective mass is the true mass plus that m_rot within 10 % of the mass (the
#     config is right here, so a wrong term, gear or weight would show)
#   - a broken row is refused naming the file and line
#   pairs_by_gear_test.sh BIN_DIR SOURCE_DIR OUT_DIR
set -u
bin=$1
src=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
"$bin/vmass-sim" --vehicle pickup-10 --scenario urban --out d >/dev/null || fail "vmass-sim"
{ cat d/config.yaml; printf 'lcm:\n  publish_pairs: true\n'; } >d/pairs.yaml
"$bin/vmassd" --config d/pairs.yaml --replay d/drive.log --speed max --no-restore \
  --lcm-url 'file://run.lcmlog?mode=w' 2>vmassd.err || fail "vmassd: $(cat vmassd.err)"
"$bin/vmass-lcmlog-csv" run.lcmlog --pairs pairs.csv 2>csv.txt || fail "$(cat csv.txt)"
estimates=$(sed -n 's/.*: \([0-9]*\) estimates, .*/\1/p' csv.txt)
records=$(sed -n 's/.* \([0-9]*\) pair records.*/\1/p' csv.txt)
[ -n "$estimates" ] && [ "$estimates" -gt 0 ] && [ "$records" = $((2 * estimates)) ] ||
  fail "pair records: $(cat csv.txt)"

# Each candidate's m_rot against the config's rotating_mass_by_gear_kg (gear g is entry g).
by_gear=$(sed -n 's/.*rotating_mass_by_gear_kg: \[\(.*\)\].*/\1/p' d/config.yaml | tr -d ' ')
[ -n "$by_gear" ] || fail "the config has no rotating_mass_by_gear_kg"
awk -F, -v table="$by_gear" '
  BEGIN { n = split(table, m, ",") }
  NR > 1 && $2 == "longitudinal" {
    g = $11; rows++
    if (g < 1 || g > n) { print "gear " g " at " $1 " s"; bad++; next }
    if ($10 < m[g] * 0.9999 || $10 > m[g] * 1.0001) { print "m_rot " $10 " != " m[g]; bad++ }
  }
  END { if (rows == 0) print "no longitudinal pair"; exit bad > 0 || rows == 0 }' pairs.csv ||
  fail "m_rot per gear"

mass=$(awk -F, 'NR == 2 { print $2 }' d/truth.csv)
/usr/bin/python3 "$src/tools/vmass_suite/pairs_by_gear.py" pairs.csv --mass "$mass" >gears.txt ||
  fail "pairs_by_gear.py: $(cat gears.txt)"
awk -F'|' -v mass="$mass" '
  $2 ~ /^ *[0-9]+ *$/ { gears++; x = $7 + 0; if (x < -0.1 * mass || x > 0.1 * mass) bad++ }
  END { exit gears < 2 || bad > 0 }' gears.txt || fail "gears: $(cat gears.txt)"
grep -q "^line through the gears: effective = " gears.txt || fail "no line: $(cat gears.txt)"

head -1 pairs.csv >broken.csv && echo "1.00,longitudinal,accepted,1,oops" >>broken.csv
/usr/bin/python3 "$src/tools/vmass_suite/pairs_by_gear.py" broken.csv >broken.txt 2>&1 &&
  fail "a broken row was read"
grep -q "broken.csv:2: " broken.txt || fail "refusal: $(cat broken.txt)"
echo "ok: $(grep -c '^| [0-9]' gears.txt) gears; $(grep '^line' gears.txt)"
