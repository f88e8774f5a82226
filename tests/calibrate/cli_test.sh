#!/bin/sh
# Command-line contract of vmass-calibrate: cli_test.sh CASE CALIBRATE_BIN WORK_DIR [SIM_BIN]
# Each case prints what it checked and exits non-zero on failure.
set -u
case_name=$1
tool=$2
work=$3
sim=${4:-}
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1

geometry="--wheelbase-m 2.7 --cg-to-front-axle-m 1.2"

# expect_error RC PATTERN ARGS...: the tool exits with RC and stderr contains PATTERN.
expect_error() {
  want_rc=$1
  pattern=$2
  shift 2
  "$tool" "$@" >out.txt 2>err.txt
  rc=$?
  if [ "$rc" -ne "$want_rc" ]; then
    echo "FAIL: exit $rc, want $want_rc: $*"; cat err.txt; exit 1
  fi
  if ! grep -q -- "$pattern" err.txt; then
    echo "FAIL: stderr lacks '$pattern': $*"; cat err.txt; exit 1
  fi
  echo "ok: exit $rc with '$pattern'"
}

good_steps() {
  printf 'added_mass_kg,rear_right_deflection_mm\n0,12.00\n100,19.26\n200,26.53\n300,33.79\n400,41.05\n' >"$1"
}

case "$case_name" in
  nan)
    printf 'added_mass_kg,rear_right_deflection_mm\n0,12\n100,nan\n200,26\n' >s.csv
    expect_error 2 "s.csv:3: rear_right_deflection_mm: NaN" --ballast s.csv $geometry ;;
  two_loads)
    printf 'added_mass_kg,rear_right_deflection_mm\n0,12\n0,12.1\n100,19\n' >s.csv
    expect_error 2 "at least three distinct loads" --ballast s.csv $geometry ;;
  not_increasing)
    printf 'added_mass_kg,rear_right_deflection_mm\n0,12\n100,19\n200,18\n' >s.csv
    expect_error 2 "does not increase with the load" --ballast s.csv $geometry ;;
  unknown_unit)
    printf 'added_mass_kg,rear_right_deflection_furlong\n0,12\n' >s.csv
    expect_error 2 "unknown unit 'furlong'" --ballast s.csv $geometry ;;
  number_with_unit)
    printf 'added_mass_kg,rear_right_deflection_mm\n0,12 mm\n' >s.csv
    expect_error 2 "'12 mm' is not a number" --ballast s.csv $geometry ;;
  absurd_mass)
    printf 'added_mass_kg,rear_right_deflection_mm\n0,12\n1e9,19\n2e9,26\n' >s.csv
    expect_error 2 "s.csv:3: added_mass_kg: 1e+09 kg is outside \\[-1000, 100000\\] kg" \
      --ballast s.csv $geometry ;;
  absurd_deflection)
    printf 'added_mass_kg,rear_right_deflection_m\n0,10\n100,15\n200,20\n' >s.csv
    expect_error 2 "s.csv:2: rear_right_deflection_m: 10 m is outside \\[-1, 1\\] m" \
      --ballast s.csv $geometry ;;
  decimal_comma)
    printf 'added_mass_kg,rear_right_deflection_mm\n0,12\n100,13,3\n200,14,6\n' >s.csv
    expect_error 2 "s.csv:3: 3 fields, the header has 2; decimal commas?" --ballast s.csv $geometry ;;
  byte_order_mark)
    printf '\357\273\277' >s.csv && good_steps body.csv && cat body.csv >>s.csv
    "$tool" --ballast s.csv $geometry >out.txt 2>err.txt || { echo "FAIL: exit $?"; cat err.txt; exit 1; }
    grep -q 'stiffness_n_per_m: 3' out.txt || { echo "FAIL: no stiffness"; cat out.txt; exit 1; }
    # Ceres's termination word is said in words, beside the word itself.
    grep -q '^  solver          converged: .*(Ceres CONVERGENCE, [0-9]* iterations)$' out.txt ||
      { echo "FAIL: no solver line"; cat out.txt; exit 1; }
    # The linear fit's correlation and covariance (SI), and whether a pair trades off.
    grep -q '^  correlation           stiffness  zero offset$' out.txt &&
      grep -q '^    zero offset \[m\]    [0-9.e+-]*   [0-9.e+-]*$' out.txt &&
      grep -q '^  trade-off' out.txt ||
      { echo "FAIL: no correlation/covariance section"; cat out.txt; exit 1; }
    ! grep -qi 'nan' out.txt || { echo "FAIL: NaN in the report"; cat out.txt; exit 1; }
    echo "ok: a UTF-8 byte order mark is ignored" ;;
  loader_would_refuse)
    # Within every input bound, but 0.005 mm per 50 t: a stiffness the config loader refuses.
    printf 'added_mass_kg,rear_right_deflection_mm\n0,12\n50000,12.005\n100000,12.01\n' >s.csv
    expect_error 1 "the config loader would refuse it (suspension.stiffness_n_per_m: .* (|x| <= 1e+10 N/m))" \
      --ballast s.csv $geometry --write-config w.yaml --json
    test ! -e w.yaml || { echo "FAIL: snippet written"; exit 1; }
    test ! -s out.txt || { echo "FAIL: a result was printed"; cat out.txt; exit 1; } ;;
  candump_log)
    printf '(1700000000.000000) can0 123#0011223344556677\n' >test.log
    expect_error 2 "is a CAN log: give --config FILE" --ballast test.log $geometry
    printf 'vehicle:\n  empty_mass_kg: 1500\n  wheelbase_m: 2.7\n  cg_to_front_axle_m: 1.2\n  wheel_radius_m: 0.31\n  brake_gain_n_per_pa: 0.0033\n  steering_ratio: 15.5\n  cornering_stiffness_front_n_per_rad: 150000\n  cornering_stiffness_rear_n_per_rad: 170000\nsuspension:\n  stiffness_n_per_m: 30000\n' >c.yaml
    expect_error 2 "c.yaml: can: required section is missing" --ballast test.log --config c.yaml \
      --masses 0:100:200 ;;
  series_needs_masses)
    printf 'time_s,rear_right_deflection_m\n0,0.012\n0.01,0.012\n' >t.csv
    expect_error 2 "give the ballast of each plateau with --masses" --ballast t.csv $geometry ;;
  no_geometry)
    good_steps s.csv
    expect_error 2 "vehicle.wheelbase_m" --ballast s.csv ;;
  plot_json_snippet)
    good_steps s.csv
    "$tool" --ballast s.csv $geometry --empty-mass-kg 1500 --plot p.png --write-config susp.yaml \
      --json >out.json 2>err.txt || { echo "FAIL: exit $?"; cat err.txt; exit 1; }
    head -c 8 p.png | od -An -c | grep -q 'P   N   G' || { echo "FAIL: no PNG"; exit 1; }
    grep -q '^suspension:' susp.yaml || { echo "FAIL: no snippet"; exit 1; }
    for key in stiffness_n_per_m stiffness_std_n_per_m zero_offset_mm linear_range_kg \
               '"progressive"' mass_check termination_meaning '"covariance_estimable":true' \
               '"correlation":{"stiffness_n_per_m":{"stiffness_n_per_m":1.0,"zero_offset_m":' \
               '"covariance":{"stiffness_n_per_m":{"stiffness_n_per_m":' '"trade_offs":'; do
      grep -q "$key" out.json || { echo "FAIL: JSON lacks $key"; exit 1; }
    done
    echo "ok: PNG, snippet and JSON written" ;;
  sim_end_to_end)
    "$sim" --scenario static_ballast --seed 4 --out sb >/dev/null || exit 1
    test -s sb/ballast.csv && test -s sb/suspension_truth.yaml || { echo "FAIL: sim files"; exit 1; }
    "$tool" --ballast sb/ballast.csv --config sb/config.yaml --json >csv.json || exit 1
    "$tool" --ballast sb/samples.csv --masses 0:100:800 --config sb/config.yaml --json \
      >series.json || exit 1
    grep -q '"detected": *true' csv.json && grep -q '"detected": *true' series.json ||
      { echo "FAIL: bump stop not detected"; exit 1; }
    grep -q '"linear_range_kg": *400\(\.0*\)\?,' csv.json || { echo "FAIL: linear range"; exit 1; }
    echo "ok: static_ballast calibrated from ballast.csv and from samples.csv" ;;
  sim_log)
    # The static test as the demo car's CAN log: the same curve as from its samples.csv.
    "$sim" --scenario static_ballast --seed 4 --out sb >/dev/null || exit 1
    "$tool" --ballast sb/drive.log --masses 0:100:800 --config sb/config.yaml --json \
      >log.json 2>log.err || { echo "FAIL: exit $?"; cat log.err; exit 1; }
    grep -q '"detected": *true' log.json || { echo "FAIL: bump stop not detected"; exit 1; }
    grep -q '"linear_range_kg": *400\(\.0*\)\?,' log.json || { echo "FAIL: linear range"; exit 1; }
    c=$(sed -n 's/^{"stiffness_n_per_m": *\([0-9.]*\),.*/\1/p' log.json)
    awk -v c="$c" 'BEGIN { exit !(c > 29700 && c < 30300) }' ||
      { echo "FAIL: stiffness '$c' not within 1 % of the simulated 30000 N/m"; exit 1; }
    "$tool" --ballast sb/drive.log --masses 0:100:800 --config sb/config.yaml >log.txt ||
      exit 1
    grep -q "note: log: .* deflection points" log.txt || { echo "FAIL: no log note"; exit 1; }
    echo "ok: static_ballast calibrated from drive.log: c = $c N/m" ;;
  *)
    echo "unknown case $case_name"; exit 2 ;;
esac
