// A standstill reading of the load as evidence of the lumped scale: the anchor's own regression
// on the drive's pairs (StaticAnchor), and how the belief takes anchors (LearntScale::add_anchor):
// their shared error never averaged away, a known mass preferred once there is one.
#include "vmass/core/static_anchor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "vmass/core/learnt_scale.hpp"

namespace vmass {
namespace {

constexpr double kPriorStd = 0.035;

TEST(StaticAnchorTest, TheAnchorsJoinTheDatasheetButTheirSharedErrorNeverAveragesAway) {
  LearntScale s(LearningParams{}, kPriorStd);
  const double x = std::log(1.04);
  const double own = 1e-4;
  const double common = 0.02;
  for (int i = 0; i < 20; ++i) EXPECT_EQ(s.add_anchor(x, own, common), ScaleEvidence::kTaken);
  EXPECT_TRUE(s.learnt());
  EXPECT_EQ(s.state().anchors, 20);
  EXPECT_EQ(s.state().evidence, 0);
  // Twenty drives' own errors average away; the shared 2 % does not.
  const double anchor_var = own / 20.0 + common * common;
  const double prior_var = kPriorStd * kPriorStd;
  EXPECT_NEAR(s.log_scale(), x * prior_var / (prior_var + anchor_var), 1e-9);
  EXPECT_NEAR(s.log_scale_var(), 1.0 / (1.0 / prior_var + 1.0 / anchor_var), 1e-12);
  EXPECT_GT(s.relative_std(), 0.8 * common);

  // A known mass measures kappa without the shared error: from then on it alone makes the belief.
  EXPECT_EQ(s.add_evidence(std::log(1.05), 1e-4), ScaleEvidence::kTaken);
  EXPECT_DOUBLE_EQ(s.log_scale(), s.state().log_scale);
  EXPECT_DOUBLE_EQ(s.log_scale_var(), s.state().log_scale_var);
  EXPECT_NEAR(s.log_scale(), std::log(1.05) * prior_var / (prior_var + 1e-4), 1e-9);
}

TEST(StaticAnchorTest, AnOutlierAnchorCountsLessAndNonsenseIsRefused) {
  LearntScale s(LearningParams{}, kPriorStd);
  for (int i = 0; i < 5; ++i) s.add_anchor(std::log(1.03), 1e-4, 0.005);
  const double settled = s.log_scale();
  // A drive whose reading was 15 % off (a load at the tailgate): taken as if at outlier_sigma.
  EXPECT_EQ(s.add_anchor(std::log(1.03 * 1.15), 1e-4, 0.005), ScaleEvidence::kDownweighted);
  EXPECT_LT(s.log_scale() - settled, 0.01);
  EXPECT_EQ(s.state().anchors, 6);
  const LearntScaleState before = s.state();
  EXPECT_EQ(s.add_anchor(std::nan(""), 1e-4, 0.0), ScaleEvidence::kRefused);
  EXPECT_EQ(s.add_anchor(0.01, 0.0, 0.0), ScaleEvidence::kRefused);
  EXPECT_EQ(s.add_anchor(0.01, 1e-4, -0.01), ScaleEvidence::kRefused);
  EXPECT_EQ(s.add_anchor(0.3, 1e-4, 0.0), ScaleEvidence::kRefused);  // beyond max_abs_log_scale
  EXPECT_EQ(s.state().anchors, before.anchors);
  EXPECT_EQ(s.state().anchor_weight, before.anchor_weight);
}

TEST(StaticAnchorTest, RestoreRefusesAnchorsItCouldNotHold) {
  LearntScale s(LearningParams{}, kPriorStd);
  LearntScaleState bad;
  bad.log_scale_var = 1e-3;
  bad.anchors = 2;  // anchors without weight
  EXPECT_FALSE(s.restore(bad));
  bad.anchor_weight = 100.0;
  bad.anchor_weighted_log_scale = 40.0;  // a mean of 0.4: beyond the bound
  EXPECT_FALSE(s.restore(bad));
  bad.anchor_weighted_log_scale = 2.0;
  bad.anchor_weighted_common_std = -1.0;
  EXPECT_FALSE(s.restore(bad));
  bad.anchor_weighted_common_std = 2.0;
  EXPECT_TRUE(s.restore(bad));
  EXPECT_NEAR(s.log_scale(), 0.02 * (1e-3) / (1e-3 + 0.01 + 0.02 * 0.02) * 1.0, 1e-3);
}

// The anchor's regression reads the pairs alone: a car whose force reads 4 % high, a reading of
// 1600 +- 50 kg of which 40 kg is the kerb's.
TEST(StaticAnchorTest, ItsRegressionReadsThePairsAgainstTheReading) {
  BayesParams bayes;
  bayes.noise_std_guess_n = 30.0;
  StaticAnchor anchor(bayes);
  LearningParams learning;
  learning.drive_error_std_fraction = 0.01;
  AnchorObservation seen;
  EXPECT_FALSE(anchor.observation(learning, &seen));  // not begun
  const MassPrior reading{1600.0, 50.0, 0.0, 300.0};
  const MassPrior vague{1600.0, 480.0, 0.0, 300.0};
  anchor.begin(reading, 40.0, 1.0, vague);
  EXPECT_FALSE(anchor.observation(learning, &seen));  // no pair yet
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 30.0);
  std::uniform_real_distribution<double> accel(-1.0, 1.0);
  for (int i = 0; i < 600; ++i) {
    RegressionPair pair;
    pair.delta_accel_mps2 = accel(rng);
    pair.y_n = 1.04 * 1600.0 * pair.delta_accel_mps2 + noise(rng);
    anchor.add(pair);
  }
  ASSERT_TRUE(anchor.observation(learning, &seen));
  EXPECT_NEAR(seen.log_scale, std::log(1.04), 3e-3);
  EXPECT_DOUBLE_EQ(seen.common_std, 40.0 / 1600.0);
  // Its own part: the reading's 30 kg beyond the kerb's, the model floor, the regression's.
  EXPECT_GT(seen.variance, std::pow(30.0 / 1600.0, 2) + 1e-4);
  EXPECT_LT(seen.variance, std::pow(30.0 / 1600.0, 2) + 1e-4 + 1e-5);

  // A saved state gives the evidence back; it takes no more pairs.
  StaticAnchor restored(bayes);
  restored.hold(seen);
  RegressionPair other;
  other.delta_accel_mps2 = 1.0;
  other.y_n = 3000.0;
  restored.add(other);
  AnchorObservation held;
  ASSERT_TRUE(restored.observation(learning, &held));
  EXPECT_EQ(held.log_scale, seen.log_scale);
  restored.end();
  EXPECT_FALSE(restored.observation(learning, &held));
}

}  // namespace
}  // namespace vmass
