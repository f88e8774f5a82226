// The probability that a long stop changed the load, and what the pipeline publishes with it
// when the drive since the stop neither decides a change nor agrees with the belief.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "synthetic_drive.hpp"
#include "vmass/core/constants.hpp"
#include "vmass/core/load_change_odds.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {
namespace {

TEST(LoadChangeOdds, IsBayesRuleBetweenTheReadingsErrorAndTheSpan) {
  // d = 2 s: the normal's likelihood exp(-2) against sqrt(2 pi) s / W, both halves of the prior.
  const double same = std::exp(-2.0);
  const double changed = std::sqrt(2.0 * kPi) * 100.0 / 2000.0;
  EXPECT_NEAR(load_change_probability(200.0, 100.0, 2000.0, 0.5), changed / (changed + same),
              1e-12);
  EXPECT_NEAR(load_change_probability(-200.0, 100.0, 2000.0, 0.5), changed / (changed + same),
              1e-12);
}

TEST(LoadChangeOdds, AgreementSpeaksForTheSameLoadAndAFarReadingForAChange) {
  EXPECT_LT(load_change_probability(0.0, 50.0, 2000.0, 0.5), 0.1);
  EXPECT_GT(load_change_probability(500.0, 50.0, 2000.0, 0.5), 0.999);
  // A reading as far, with errors as large, says less.
  EXPECT_LT(load_change_probability(500.0, 250.0, 2000.0, 0.5),
            load_change_probability(500.0, 50.0, 2000.0, 0.5));
  // A tiny std cannot overflow: the same load is then certain, or a change is.
  EXPECT_LT(load_change_probability(0.0, 1e-300, 2000.0, 0.5), 1e-100);
  EXPECT_NEAR(load_change_probability(1.0, 1e-300, 2000.0, 0.5), 1.0, 1e-12);
}

TEST(LoadChangeOdds, FollowsThePrior) {
  const double low = load_change_probability(150.0, 100.0, 2000.0, 0.1);
  const double mid = load_change_probability(150.0, 100.0, 2000.0, 0.5);
  const double high = load_change_probability(150.0, 100.0, 2000.0, 0.9);
  EXPECT_LT(low, mid);
  EXPECT_LT(mid, high);
}

TEST(LoadChangeOdds, WithoutEvidenceItIsThePrior) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(load_change_probability(nan, 100.0, 2000.0, 0.3), 0.3);
  EXPECT_EQ(load_change_probability(100.0, 0.0, 2000.0, 0.3), 0.3);
  EXPECT_EQ(load_change_probability(100.0, inf, 2000.0, 0.3), 0.3);
  EXPECT_EQ(load_change_probability(100.0, 100.0, -1.0, 0.3), 0.3);
}

// A car without a load sensor drives 150 s, stops for 10 s and drives on 120 kg heavier, with
// a challenger that can never decide (decide_sigma out of reach): the suspicion lasts.
std::vector<Estimate> suspected_estimates(double change_prior) {
  PipelineParams p;
  p.vehicle = testing::test_vehicle();
  p.vehicle.max_mass_kg = 2100.0;
  p.suspension.has_sensor = false;
  p.estimator.load_change.decide_sigma = 1e6;
  p.estimator.load_change.change_prior = change_prior;
  Pipeline pipeline(p);
  testing::LongitudinalDrive before;
  before.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  before.accel_noise_std_mps2 = 0.02;
  before.force_noise_std_n = 60.0;
  testing::LongitudinalDrive after = before;
  after.mass_kg = before.mass_kg + 120.0;
  after.seed = 2;
  for (const Sample& s : testing::longitudinal_samples(before, p.vehicle, 0.0, 150.0, 15.0, 0.0)) {
    pipeline.step(s);
  }
  Sample stop = testing::longitudinal_samples(before, p.vehicle, 150.0, 150.01, 0.0, 0.0)[0];
  for (double t = 150.0; t < 160.0; t += 0.01) {
    stop.time_us = from_seconds(t);
    pipeline.step(stop);
  }
  std::vector<Estimate> out;
  for (const Sample& s : testing::longitudinal_samples(after, p.vehicle, 160.0, 400.0, 15.0, 0.0)) {
    pipeline.step(s);
    out.push_back(pipeline.estimate());
  }
  return out;
}

// Given that suspicion, the published mass is the challenger's while it is undecided, whatever
// the prior; once it has its pairs the mass moves towards the belief as a change is thought less
// likely, and the interval spans both beliefs all along.
TEST(LoadChangeOdds, AnUndecidedSuspicionPublishesTheChallengerALastingOneWeighsBoth) {
  const std::vector<Estimate> unlikely = suspected_estimates(1e-6);
  const std::vector<Estimate> even = suspected_estimates(0.5);
  const std::vector<Estimate> likely = suspected_estimates(1.0 - 1e-6);
  ASSERT_EQ(unlikely.size(), likely.size());
  ASSERT_EQ(even.size(), likely.size());
  long suspected = 0, weighed = 0;
  for (std::size_t i = 0; i < likely.size(); ++i) {
    const Estimate& u = unlikely[i];
    const Estimate& e = even[i];
    const Estimate& l = likely[i];
    ASSERT_EQ(u.reason, l.reason);  // the prior moves the mass only
    if (l.reason != StatusReason::kLoadChangeSuspected) continue;
    ++suspected;
    EXPECT_EQ(u.ci_low_kg, l.ci_low_kg);
    EXPECT_EQ(u.ci_high_kg, l.ci_high_kg);
    if (u.mass_kg == l.mass_kg) continue;  // undecided: the challenger's, whatever the prior
    ++weighed;
    EXPECT_LT(u.mass_kg, e.mass_kg);  // the challenger reads the heavier load
    EXPECT_LT(e.mass_kg, l.mass_kg);
    EXPECT_GE(u.mass_kg, u.ci_low_kg);
    EXPECT_LE(l.mass_kg, l.ci_high_kg);
  }
  EXPECT_GT(suspected, 1000);  // 10 s of ticks at least
  EXPECT_GT(weighed, 100);
  EXPECT_LT(weighed, suspected);
}

}  // namespace
}  // namespace vmass
