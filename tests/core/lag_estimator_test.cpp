// Given pairs whose force fits the acceleration only at one lag, the LagEstimator finds that
// lag (to a fraction of a tick), not before it has the evidence, and a fixed lag overrides it.
#include "vmass/core/lag_estimator.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace vmass {
namespace {

constexpr double kRateHz = 100.0;
constexpr double kMassKg = 1500.0;

// y(L) = M da at the true lag; at other lags the force of other instants: M da of a shifted,
// decorrelating excitation (a sum of sines), plus a little noise.
struct LaggedPairs {
  double true_lag_ticks;
  std::mt19937_64 rng{3};
  std::normal_distribution<double> noise{0.0, 5.0};
  double accel(double t) const { return 0.6 * std::sin(2.1 * t) + 0.4 * std::sin(5.3 * t + 1.0); }

  void feed(LagEstimator* lag, double seconds) {
    std::vector<double> y(static_cast<std::size_t>(lag->max_lag_ticks()) + 1);
    for (double t = 0.0; t < seconds; t += 1.0 / kRateHz) {
      const double da = accel(t) - accel(t - 0.4);
      for (std::size_t l = 0; l < y.size(); ++l) {
        const double shift_s = (static_cast<double>(l) - true_lag_ticks) / kRateHz;
        y[l] = kMassKg * (accel(t - shift_s) - accel(t - shift_s - 0.4)) + noise(rng);
      }
      lag->add(da, y.data());
    }
  }
};

TEST(LagEstimator, FindsTheLagAtWhichThePairsFitBest) {
  LagEstimator lag(LagParams{}, kRateHz);
  ASSERT_EQ(lag.max_lag_ticks(), 15);
  LaggedPairs pairs{6.0};
  pairs.feed(&lag, 20.0);
  ASSERT_TRUE(lag.identified());
  EXPECT_NEAR(lag.lag_s(), 0.06, 0.005);
}

TEST(LagEstimator, AFractionalLagIsRefinedBetweenTicks) {
  LagEstimator lag(LagParams{}, kRateHz);
  LaggedPairs pairs{4.5};
  pairs.feed(&lag, 20.0);
  ASSERT_TRUE(lag.identified());
  EXPECT_NEAR(lag.lag_s(), 0.045, 0.004);
}

TEST(LagEstimator, NotIdentifiedBeforeItsEvidence) {
  LagParams p;
  p.min_evidence_s = 5.0;
  LagEstimator lag(p, kRateHz);
  LaggedPairs pairs{6.0};
  pairs.feed(&lag, 4.0);  // 4 s of pairs < 5 s
  EXPECT_FALSE(lag.identified());
  EXPECT_EQ(lag.lag_s(), 0.0);
  pairs.feed(&lag, 2.0);
  EXPECT_TRUE(lag.identified());
}

TEST(LagEstimator, BeforeItsEvidenceTheBestFitSoFarIsOfferedButNotUsed) {
  LagParams p;
  p.min_evidence_s = 5.0;
  LagEstimator lag(p, kRateHz);
  EXPECT_EQ(lag.best_lag_s(), 0.0);  // no pair yet
  LaggedPairs pairs{6.0};
  pairs.feed(&lag, 1.0);
  EXPECT_FALSE(lag.identified());
  EXPECT_EQ(lag.lag_s(), 0.0);
  EXPECT_NEAR(lag.best_lag_s(), 0.06, 0.01);
  std::vector<double> y(static_cast<std::size_t>(lag.max_lag_ticks()) + 1);
  for (std::size_t l = 0; l < y.size(); ++l) y[l] = 10.0 * static_cast<double>(l);
  EXPECT_NEAR(lag.y_at(y.data(), 0.045), 45.0, 1e-9);  // between ticks 4 and 5
  EXPECT_NEAR(lag.y_at(y.data(), 1.0), 150.0, 1e-9);   // clamped to the longest candidate
}

TEST(LagEstimator, AFixedLagIsUsedAsGiven) {
  LagParams p;
  p.fixed_lag_s = 0.03;
  LagEstimator lag(p, kRateHz);
  EXPECT_TRUE(lag.identified());
  EXPECT_DOUBLE_EQ(lag.lag_s(), 0.03);
  // Pairs do not move it, and y is read 3 ticks back.
  LaggedPairs pairs{6.0};
  pairs.feed(&lag, 20.0);
  EXPECT_DOUBLE_EQ(lag.lag_s(), 0.03);
  std::vector<double> y(static_cast<std::size_t>(lag.max_lag_ticks()) + 1);
  for (std::size_t l = 0; l < y.size(); ++l) y[l] = 10.0 * static_cast<double>(l);
  EXPECT_NEAR(lag.y_at_lag(y.data()), 30.0, 1e-9);
}

TEST(LagEstimator, ResetForgetsTheEvidence) {
  LagEstimator lag(LagParams{}, kRateHz);
  LaggedPairs pairs{6.0};
  pairs.feed(&lag, 20.0);
  ASSERT_TRUE(lag.identified());
  lag.reset();
  EXPECT_FALSE(lag.identified());
}

// Given a lag identified over 120 s of one load's pairs, after another load's first 10 s of
// pairs at another lag: kept as a prior, the old evidence lets the new lag through; kept whole
// (forgetting alone), it holds the old one. Still identified throughout: no pair waits.
TEST(LagEstimator, KeptAsAPriorTheOldLoadsLagSoonGivesWay) {
  auto lag_after_new_load = [](bool keep_as_prior) {
    LagEstimator lag(LagParams{}, kRateHz);
    LaggedPairs before{0.0};
    before.feed(&lag, 120.0);
    EXPECT_NEAR(lag.lag_s(), 0.0, 0.005);
    if (keep_as_prior) lag.keep_as_prior();
    EXPECT_TRUE(lag.identified());
    LaggedPairs after{6.0};
    after.feed(&lag, 10.0);
    return lag.lag_s();
  };
  EXPECT_NEAR(lag_after_new_load(true), 0.06, 0.01);
  EXPECT_LT(lag_after_new_load(false), 0.03);
}

TEST(LagEstimator, WithoutAnIdentifiedLagKeepAsPriorForgetsAll) {
  LagParams p;
  p.min_evidence_s = 5.0;
  LagEstimator lag(p, kRateHz);
  LaggedPairs pairs{6.0};
  pairs.feed(&lag, 4.0);
  ASSERT_FALSE(lag.identified());
  lag.keep_as_prior();
  pairs.feed(&lag, 4.0);  // 4 s again: the first 4 s no longer count
  EXPECT_FALSE(lag.identified());
}

}  // namespace
}  // namespace vmass
