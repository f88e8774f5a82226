#!/bin/sh
# The suite's lifetime mode goes through the daemon's own state file: vmassd, replaying each
# drive of a life at full speed with --state-file (as under systemd, a day between drives),
# writes byte for byte the state file vmass-suite --lifetime wrote after the same drive, with
# and without the deflection sensor. So the lifetime tables measure what a vehicle's vmassd
# does on its Nth drive.
#
#   lifetime_daemon_test.sh VMASS_SUITE VMASSD WORK_DIR
set -u
suite=$1 vmassd=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "lifetime_daemon_test: FAIL: $*" >&2; exit 1; }

"$suite" --lifetime 3 --vehicle-ids suv-4 --knowledge known_scale --keep-dir "$work/keep" \
  --jobs 1 --out "$work/life.jsonl" 2> "$work/suite.err" || { cat "$work/suite.err"; fail "vmass-suite"; }
checked=0
for dir in "$work"/keep/*; do
  state=$work/$(basename "$dir").state
  for n in 1 2 3; do
    "$vmassd" --config "$dir/config.yaml" --replay "$dir/drive_$n.log" --speed max \
      --lcm-url memq:// --state-file "$state" 2> "$work/vmassd.log" ||
      { cat "$work/vmassd.log"; fail "vmassd on $(basename "$dir") drive $n"; }
    cmp "$state" "$dir/state_after_drive_$n" ||
      fail "$(basename "$dir") drive $n: vmassd's state file differs from the suite's"
    checked=$((checked + 1))
  done
  grep -q "restored bayes estimate" "$work/vmassd.log" || fail "$(basename "$dir"): not restored"
done
[ "$checked" -eq 6 ] || fail "$checked drives compared, expected 6 (suv-4 with and without its sensor)"
echo "lifetime_daemon_test: $checked drives, vmassd's state file identical to the suite's"
