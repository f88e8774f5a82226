#!/usr/bin/env bash
# The accuracy suite, one command: installs what it needs, builds the release preset, runs the
# vehicle population (30 vehicles x every scenario x 3 seeds, both kinds of knowledge, vmass's
# estimators on their defaults and the baselines), the held-out vehicles, the ablation (each
# realism effect alone on one nominal car) and a few drives for plots, and regenerates
# docs/accuracy.md with docs/accuracy/*.png. About 35-45 minutes on 2 cores.
#
#   scripts/accuracy-suite.sh                     (from anywhere)
#   VEHICLES=7 SEEDS=1 scripts/accuracy-suite.sh  (a quick look; the report says what it ran)
#   DRIVES=10 LIVES=1: the lifetime mode's drives per life and lives per vehicle
#   TRUCKS=20 TRUCKS_HELD_OUT=10: the truck population's tractors (docs/accuracy-trucks.md)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
vehicles=${VEHICLES:-30}
held_out=${HELD_OUT:-14}
seeds=${SEEDS:-3}
jobs=${JOBS:-$(nproc)}

bash scripts/install-deps.sh
# The tree the binaries are built from (taken now: the old plots are removed before the report).
commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet 2>/dev/null || echo +local)"
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs" --target vmass-suite vmass-sim
bin=build/release/bin
out=build/accuracy
rm -rf "$out" && mkdir -p "$out/series"
start=$(date +%s)

"$bin/vmass-suite" --vehicles "$vehicles" --seeds "$seeds" --jobs "$jobs" --out "$out/population.jsonl"
"$bin/vmass-suite" --held-out --vehicles "$held_out" --seeds "$seeds" --jobs "$jobs" \
  --out "$out/held_out.jsonl"
"$bin/vmass-suite" --ablation auto --scenarios paper_exp2_eps1,urban,highway --seeds "$seeds" \
  --estimators rls,bayes,paper_lp --knowledge known_scale --jobs "$jobs" --out "$out/ablation.jsonl"
# A vehicle's Nth drive: each vehicle 10 drives in a row through the daemon's state file, loads
# changed while parked, beside the same drives fresh, and each also with a known mass declared
# on drive 1 (the true mass off by a ticket error drawn from its 0.5 % std) (a heavy truck's on drives 1 and 2: two loads, as issue 30 asks of trucks), the
# learnt scale carried (docs/accuracy.md, "lifetime mode").
"$bin/vmass-suite" --lifetime "${DRIVES:-10}" --lives "${LIVES:-1}" \
  --known-mass-drives 1 --truck-known-mass-drives 1,2 \
  --vehicles "$vehicles" --jobs "$jobs" --out "$out/lifetime.jsonl"
"$bin/vmass-suite" --lifetime "${DRIVES:-10}" --lives "${LIVES:-1}" \
  --known-mass-drives 1 --truck-known-mass-drives 1,2 \
  --held-out --vehicles "$held_out" --jobs "$jobs" --out "$out/lifetime_held_out.jsonl"
# New tyres before drive 6, declared by the workshop (vmass-ctl tyres-changed), with and without
# a known mass on drive 1.
"$bin/vmass-suite" --lifetime "${DRIVES:-10}" --lives "${LIVES:-1}" \
  --known-mass-drives 1 --truck-known-mass-drives 1,2 \
  --vehicles "$vehicles" --tyre-change-drive 6 --tyre-change-declared --estimators bayes --jobs "$jobs" \
  --out "$out/lifetime_tyres.jsonl"
# Engine torque and engine speed, with the gear number or with the ratio derived from the engine
# speed (issue 29): every combustion vehicle both ways, on the same drives, one seed, bayes.
for signal in engine_gear_index engine_speed_ratio; do
  "$bin/vmass-suite" --vehicles "$vehicles" --seeds 1 --estimators bayes --torque-signal "$signal" \
    --jobs "$jobs" --out "$out/torque_$signal.jsonl"
done
# The truck population (tractors, their own drives and held-out tractors): docs/accuracy-trucks.md.
"$bin/vmass-suite" --population trucks --vehicles "${TRUCKS:-20}" --seeds "$seeds" \
  --estimators rls,bayes --jobs "$jobs" --out "$out/trucks.jsonl"
"$bin/vmass-suite" --population trucks --held-out --vehicles "${TRUCKS_HELD_OUT:-10}" --seeds "$seeds" \
  --estimators rls,bayes --jobs "$jobs" --out "$out/trucks_held_out.jsonl"
# The tractors' lives (issue 30): two known masses at different loads (drives 1 and 2), another
# trailer coupled before drive 6.
"$bin/vmass-suite" --population trucks --lifetime "${DRIVES:-10}" --lives "${LIVES:-1}" \
  --known-mass-drives 1,2 --trailer-change-drive 6 --vehicles "${TRUCKS:-20}" --estimators bayes \
  --jobs "$jobs" --out "$out/trucks_trailer.jsonl"
"$bin/vmass-suite" --runs nominal:paper_exp2_eps3:1,nominal:paper_exp1_eps1:1,suv-18:urban:1,suv-4:heavy_rear_load:1 \
  --knowledge known_scale --series-dir "$out/series" --jobs "$jobs" --out "$out/series.jsonl"

rm -rf docs/accuracy
/usr/bin/python3 "$bin/vmass-accuracy-report" --population "$out/population.jsonl" \
  --held-out "$out/held_out.jsonl" --ablation "$out/ablation.jsonl" \
  --lifetime "$out/lifetime.jsonl" --lifetime-held-out "$out/lifetime_held_out.jsonl" \
  --tyre-lifetime "$out/lifetime_tyres.jsonl" \
  --series-dir "$out/series" --plots-dir docs/accuracy --out docs/accuracy.md \
  --torque-signals "$out/torque_engine_gear_index.jsonl" "$out/torque_engine_speed_ratio.jsonl" \
  --command "VEHICLES=$vehicles HELD_OUT=$held_out SEEDS=$seeds DRIVES=${DRIVES:-10} LIVES=${LIVES:-1} scripts/accuracy-suite.sh" \
  --commit "$commit" \
  --population-hash "$("$bin/vmass-suite" --population-hash)" \
  --seconds "$(( $(date +%s) - start ))"
/usr/bin/python3 "$bin/vmass-accuracy-report" --trucks "$out/trucks.jsonl" \
  --trucks-held-out "$out/trucks_held_out.jsonl" --trailer-lifetime "$out/trucks_trailer.jsonl" \
  --out docs/accuracy-trucks.md \
  --command "TRUCKS=${TRUCKS:-20} TRUCKS_HELD_OUT=${TRUCKS_HELD_OUT:-10} SEEDS=$seeds scripts/accuracy-suite.sh" \
  --commit "$commit"
echo "accuracy-suite: wrote docs/accuracy.md ($(( $(date +%s) - start )) s)"
