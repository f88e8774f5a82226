// A drive between two long stops whose challenger ended undecided, still excluding the belief,
// where a change is the likelier reading, is held: when a later drive reads the belief's load
// again and not the held one's, the belief returns to what it was without it. Mixed in, two
// loads make a mass of neither (Pipeline::hold_interlude, Pipeline::judge_interlude).
#include <cmath>

#include <gtest/gtest.h>

#include "synthetic_drive.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {
namespace {

constexpr double kSoloKg = 1600.0;
constexpr double kCoupledKg = 2000.0;

void stand(Pipeline* pipeline, const testing::LongitudinalDrive& drive, const VehicleParams& v,
           double t0_s, double t1_s) {
  Sample stop = testing::longitudinal_samples(drive, v, t0_s, t0_s + 0.01, 0.0, 0.0)[0];
  for (double t = t0_s; t < t1_s; t += 0.01) {
    stop.time_us = from_seconds(t);
    pipeline->step(stop);
  }
}

void drive(Pipeline* pipeline, const testing::LongitudinalDrive& d, const VehicleParams& v,
           double t0_s, double t1_s) {
  for (const Sample& s : testing::longitudinal_samples(d, v, t0_s, t1_s, 15.0, 0.0)) {
    pipeline->step(s);
  }
}

// A car without a load sensor drives solo, stops, drives 400 kg heavier with a challenger that
// can never decide (decide_sigma out of reach, as a loaded tractor's wide one), stops again,
// drives solo again. Returns the belief's mass at the end.
double belief_after_a_round_trip(bool heavier_in_the_middle) {
  PipelineParams p;
  p.vehicle = testing::test_vehicle();
  p.vehicle.max_mass_kg = 2300.0;
  p.suspension.has_sensor = false;
  p.estimator.load_change.decide_sigma = 1e6;
  Pipeline pipeline(p);
  testing::LongitudinalDrive solo;
  solo.mass_kg = kSoloKg;
  solo.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  solo.accel_noise_std_mps2 = 0.02;
  solo.force_noise_std_n = 60.0;
  testing::LongitudinalDrive middle = solo;
  middle.mass_kg = heavier_in_the_middle ? kCoupledKg : kSoloKg;
  middle.seed = 2;
  testing::LongitudinalDrive solo_again = solo;
  solo_again.seed = 3;
  drive(&pipeline, solo, p.vehicle, 0.0, 150.0);
  stand(&pipeline, solo, p.vehicle, 150.0, 160.0);
  drive(&pipeline, middle, p.vehicle, 160.0, 400.0);
  const Estimate in_the_middle = pipeline.estimate();
  if (heavier_in_the_middle) {
    EXPECT_EQ(in_the_middle.reason, StatusReason::kLoadChangeSuspected);
  } else {
    EXPECT_NE(in_the_middle.reason, StatusReason::kLoadChangeSuspected);
  }
  stand(&pipeline, solo, p.vehicle, 400.0, 410.0);
  drive(&pipeline, solo_again, p.vehicle, 410.0, 650.0);
  // The next long stop: the solo drive since tells the heavier load is gone.
  stand(&pipeline, solo, p.vehicle, 650.0, 660.0);
  drive(&pipeline, solo_again, p.vehicle, 660.0, 661.0);
  EXPECT_NE(pipeline.estimate().reason, StatusReason::kLoadChangeSuspected);
  return pipeline.regressor().state().mass_kg;
}

// Given the heavier drive in the middle, the belief after it is the solo load's, as close to it
// as when the middle drive was solo too. With the middle drive mixed in, it read 38 kg heavy with
// 2.5 times the spread, and the last drive's challenger suspected a change that did not happen.
TEST(UndecidedSegment, AnUndecidedDriveThatExcludedTheBeliefLeavesIt) {
  const double mixed_free = belief_after_a_round_trip(true);
  const double all_solo = belief_after_a_round_trip(false);
  EXPECT_NEAR(mixed_free, kSoloKg, 15.0);
  EXPECT_NEAR(all_solo, kSoloKg, 15.0);
}

}  // namespace
}  // namespace vmass
