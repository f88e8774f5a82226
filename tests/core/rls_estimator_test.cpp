// RlsEstimator against independent answers: the regularised batch least-squares solution (QR of
// the stacked system with the prior as pseudo-observations), its exponentially weighted version,
// the steady state of forgetting, and the frequentist coverage of the 95% interval.
#include "vmass/core/rls_estimator.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "regression_test_data.hpp"

namespace vmass {
namespace {

constexpr double kZ975 = 1.959963984540054;  // standard normal 0.975 quantile (tables)

MassPrior test_prior() {
  MassPrior p;
  p.mass_kg = 1500.0;
  p.mass_std_kg = 300.0;
  p.mu_n = 0.0;
  p.mu_std_n = 500.0;
  return p;
}

using testing::make_pair;

std::vector<RegressionPair> synthetic_pairs(int n, double mass, double mu, double sigma,
                                            std::uint64_t seed) {
  return testing::synthetic_pairs(n, mass, mu, sigma, seed, 0.2, 1.0);
}

struct BatchSolution {
  Eigen::Vector2d theta;
  Eigen::Matrix2d p;
};

// argmin prior_w (theta - theta0)^T P0^-1 (theta - theta0) + sum_i c_i w_i (y_i - phi_i theta)^2
// / sigma^2, by Householder QR of the stacked, whitened rows (no normal equations); P is
// (A^T A)^-1 = R^-1 R^-T.
BatchSolution batch_least_squares(const Eigen::Vector2d& theta0, const Eigen::Matrix2d& p0,
                                  double prior_w, const std::vector<RegressionPair>& pairs,
                                  const std::vector<double>& c, double sigma) {
  const int n = static_cast<int>(pairs.size());
  Eigen::MatrixXd a(n + 2, 2);
  Eigen::VectorXd b(n + 2);
  // Pseudo-observations: U (theta - theta0) with U^T U = prior_w P0^-1.
  const Eigen::Matrix2d info0 = prior_w * p0.inverse();
  const Eigen::Matrix2d u = info0.llt().matrixU();
  a.topRows<2>() = u;
  b.head<2>() = u * theta0;
  for (int i = 0; i < n; ++i) {
    const double s = std::sqrt(c[i] * pairs[i].weight) / sigma;
    a(i + 2, 0) = s * pairs[i].delta_accel_mps2;
    a(i + 2, 1) = s;
    b(i + 2) = s * pairs[i].y_n;
  }
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  BatchSolution out;
  out.theta = qr.solve(b);
  const Eigen::Matrix2d r = qr.matrixQR().topRows<2>().triangularView<Eigen::Upper>();
  const Eigen::Matrix2d r_inv = r.inverse();
  out.p = r_inv * r_inv.transpose();
  return out;
}

void expect_close(const RlsEstimator& rls, const BatchSolution& ref, double tol) {
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(rls.theta()(i), ref.theta(i), tol * std::abs(ref.theta(i))) << "theta " << i;
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(rls.covariance()(i, j), ref.p(i, j), tol * std::sqrt(ref.p(i, i) * ref.p(j, j)))
          << "P(" << i << "," << j << ")";
    }
  }
}

// Eigenvalues of D^-1 P D^-1 with D = the bound's standard deviations.
Eigen::Vector2d whitened_eigenvalues(const RlsEstimator& rls) {
  const Eigen::Vector2d d = rls.covariance_bound().diagonal().cwiseSqrt();
  const Eigen::Matrix2d q =
      d.cwiseInverse().asDiagonal() * rls.covariance() * d.cwiseInverse().asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(q, Eigen::EigenvaluesOnly).eigenvalues();
}

TEST(RlsParams, ValidateNamesKeyAndBound) {
  EXPECT_EQ(RlsParams{}.validate(), "");
  RlsParams p;
  p.forgetting_factor = 0.5;
  EXPECT_EQ(p.validate(), "rls.forgetting_factor must be in (0.9, 1], got 0.5");
  p.forgetting_factor = 1.01;
  EXPECT_EQ(p.validate(), "rls.forgetting_factor must be in (0.9, 1], got 1.01");
  p.forgetting_factor = std::nan("");
  EXPECT_NE(p.validate().find("rls.forgetting_factor"), std::string::npos);
  p = RlsParams{};
  p.noise_std_n = 0.0;
  EXPECT_EQ(p.validate(), "rls.noise_std_n must be > 0, got 0");
  p.noise_std_n = std::numeric_limits<double>::infinity();
  EXPECT_NE(p.validate().find("rls.noise_std_n"), std::string::npos);
  p = RlsParams{};
  p.min_variance_fraction = 0.0;
  EXPECT_EQ(p.validate(), "rls.min_variance_fraction must be in (0, 1), got 0");
}

TEST(RlsEstimator, ResetPublishesThePriorWithGaussianInterval) {
  RlsEstimator rls(RlsParams{});
  rls.reset(test_prior());
  const RegressorState s = rls.state();
  EXPECT_EQ(s.mass_kg, 1500.0);
  EXPECT_EQ(s.mu_n, 0.0);
  EXPECT_DOUBLE_EQ(s.mass_std_kg, 300.0);
  EXPECT_DOUBLE_EQ(s.mu_std_n, 500.0);
  EXPECT_NEAR(s.ci_low_kg, 1500.0 - kZ975 * 300.0, 1e-9);
  EXPECT_NEAR(s.ci_high_kg, 1500.0 + kZ975 * 300.0, 1e-9);
  EXPECT_EQ(s.noise_std_n, 100.0);
  EXPECT_EQ(s.pairs_used, 0);
  EXPECT_EQ(rls.name(), "rls");
}

TEST(RlsEstimator, PredictIsPhiThetaAndPhiPPhiPlusNoise) {
  RlsParams params;
  params.noise_std_n = 80.0;
  RlsEstimator rls(params);
  rls.reset(test_prior());
  const PairPrediction pred = rls.predict(make_pair(0.0, 1.3, 2.0));
  EXPECT_DOUBLE_EQ(pred.y_n, 1500.0 * 1.3);
  // Independent: Var(M da + mu) + sigma^2 / w with M, mu independent under the prior.
  EXPECT_DOUBLE_EQ(pred.variance_n2, 1.3 * 1.3 * 300.0 * 300.0 + 500.0 * 500.0 + 80.0 * 80.0 / 2);
}

TEST(RlsEstimator, WithoutForgettingEqualsRegularisedBatchLeastSquares) {
  const double sigma = 80.0;
  RlsParams params;
  params.noise_std_n = sigma;
  RlsEstimator rls(params);
  const MassPrior prior = test_prior();
  rls.reset(prior);
  const std::vector<RegressionPair> pairs = synthetic_pairs(2000, 1800.0, 150.0, sigma, 42);
  const Eigen::Vector2d theta0(prior.mass_kg, prior.mu_n);
  const Eigen::Matrix2d p0 = rls.covariance_bound();
  std::vector<RegressionPair> used;
  for (const RegressionPair& pair : pairs) {
    ASSERT_TRUE(rls.update(pair));
    used.push_back(pair);
    const std::size_t n = used.size();
    if (n == 1 || n == 2 || n == 10 || n == 100 || n == 2000) {
      SCOPED_TRACE(n);
      expect_close(rls,
                   batch_least_squares(theta0, p0, 1.0, used, std::vector<double>(n, 1.0), sigma),
                   1e-9);
    }
  }
  EXPECT_EQ(rls.state().pairs_used, 2000);
  // And it found the truth (sanity, not the point of the test).
  EXPECT_NEAR(rls.theta()(0), 1800.0, 5.0 * std::sqrt(rls.covariance()(0, 0)));
}

TEST(RlsEstimator, WithForgettingEqualsExponentiallyWeightedBatch) {
  const double sigma = 60.0;
  const double lambda = 0.98;
  RlsParams params;
  params.noise_std_n = sigma;
  params.forgetting_factor = lambda;
  RlsEstimator rls(params);
  // A wide prior only sets the bound; the run starts from a restored, tighter, correlated state,
  // so that the bound stays inactive and the closed form applies exactly.
  MassPrior wide = test_prior();
  wide.mass_std_kg = 1000.0;
  wide.mu_std_n = 2000.0;
  rls.reset(wide);
  const Eigen::Vector2d theta_s(1600.0, 50.0);
  Eigen::Matrix2d p_s;
  p_s << 200.0 * 200.0, 0.3 * 200.0 * 300.0, 0.3 * 200.0 * 300.0, 300.0 * 300.0;
  ASSERT_TRUE(rls.restore(theta_s, p_s, 0));
  const std::vector<RegressionPair> pairs = synthetic_pairs(500, 2100.0, -80.0, sigma, 7);
  std::vector<RegressionPair> used;
  for (const RegressionPair& pair : pairs) {
    ASSERT_TRUE(rls.update(pair));
    used.push_back(pair);
    const int n = static_cast<int>(used.size());
    if (n == 1 || n == 3 || n == 50 || n == 500) {
      SCOPED_TRACE(n);
      // Pair i (1-based) of N carries lambda^(N-i+1); the prior lambda^N.
      std::vector<double> c(n);
      for (int i = 1; i <= n; ++i) c[i - 1] = std::pow(lambda, n - i + 1);
      expect_close(rls, batch_least_squares(theta_s, p_s, std::pow(lambda, n), used, c, sigma),
                   1e-9);
    }
  }
}

struct DegenerateCase {
  const char* name;
  double da;  // the same differenced acceleration on every pair
  double lambda;
};

class RlsDegenerate : public ::testing::TestWithParam<DegenerateCase> {};

TEST_P(RlsDegenerate, CovarianceStaysSymmetricPositiveDefiniteAndBounded) {
  const DegenerateCase c = GetParam();
  const double sigma = 80.0;
  RlsParams params;
  params.noise_std_n = sigma;
  params.forgetting_factor = c.lambda;
  RlsEstimator rls(params);
  const MassPrior prior = test_prior();
  rls.reset(prior);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, sigma);
  double max_whitened = 0.0;
  double min_whitened = 1.0;
  for (int i = 0; i < 100000; ++i) {
    ASSERT_TRUE(rls.update(make_pair(1800.0 * c.da + 150.0 + noise(rng), c.da, 1.0)));
    const Eigen::Matrix2d& p = rls.covariance();
    ASSERT_EQ(p(0, 1), p(1, 0)) << "update " << i;
    ASSERT_TRUE(p.allFinite() && rls.theta().allFinite()) << "update " << i;
    const Eigen::Vector2d ev = whitened_eigenvalues(rls);
    max_whitened = std::max(max_whitened, ev(1));
    min_whitened = std::min(min_whitened, ev(0));
    ASSERT_EQ(p.llt().info(), Eigen::Success) << "update " << i;
  }
  // P0 - P and P - fraction P0 stay positive semi-definite (to rounding).
  EXPECT_LE(max_whitened, 1.0 + 1e-12);
  EXPECT_GE(min_whitened, params.min_variance_fraction * (1.0 - 1e-9));
  const Eigen::Matrix2d& p = rls.covariance();
  EXPECT_LE(p(0, 0), 300.0 * 300.0 * (1.0 + 1e-12));
  EXPECT_LE(p(1, 1), 500.0 * 500.0 * (1.0 + 1e-12));
  if (c.da == 0.0) {
    // phi = [0, 1] says nothing about M: its estimate stays, only mu learns.
    EXPECT_NEAR(rls.theta()(0), 1500.0, 1e-9);
    EXPECT_NEAR(rls.theta()(1), 150.0, 5.0 * std::sqrt(p(1, 1)));
    if (c.lambda < 1.0) {
      // The unexcited variance saturates at the prior's; mu's settles where forgetting and one
      // pair per step balance: 1/p = lambda (1/p + 1/r)  =>  p = r (1 - lambda) / lambda.
      EXPECT_NEAR(p(0, 0), 300.0 * 300.0, 1e-6 * 300.0 * 300.0);
      const double r = sigma * sigma;
      EXPECT_NEAR(p(1, 1), r * (1.0 - c.lambda) / c.lambda, 1e-9 * r);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, RlsDegenerate,
                         ::testing::Values(DegenerateCase{"NoExcitationForgetting", 0.0, 0.98},
                                           DegenerateCase{"NoExcitation", 0.0, 1.0},
                                           DegenerateCase{"RepeatedForgetting", 0.7, 0.98},
                                           DegenerateCase{"Repeated", 0.7, 1.0}),
                         [](const ::testing::TestParamInfo<DegenerateCase>& param_info) {
                           return param_info.param.name;
                         });

TEST(RlsEstimator, NoUpdatesLeaveStateUnchanged) {
  RlsParams params;
  params.forgetting_factor = 0.95;
  RlsEstimator rls(params);
  rls.reset(test_prior());
  const Eigen::Matrix2d p_before = rls.covariance();
  const RegressorState before = rls.state();
  for (int i = 0; i < 10; ++i) (void)rls.predict(make_pair(100.0, 0.5, 1.0));
  const RegressorState after = rls.state();
  EXPECT_EQ(after.mass_kg, before.mass_kg);
  EXPECT_EQ(after.mu_n, before.mu_n);
  EXPECT_EQ(after.mass_std_kg, before.mass_std_kg);
  EXPECT_EQ(after.ci_low_kg, before.ci_low_kg);
  EXPECT_EQ(after.pairs_used, before.pairs_used);
  EXPECT_EQ(rls.covariance(), p_before);
}

TEST(RlsEstimator, ForgettingNeverInflatesBeyondThePrior) {
  RlsParams params;
  params.forgetting_factor = 0.91;
  RlsEstimator rls(params);
  rls.reset(test_prior());
  // Excite first so P is well inside the bound, then starve M of excitation for a long time.
  for (const RegressionPair& pair : synthetic_pairs(200, 1800.0, 150.0, 100.0, 11)) {
    ASSERT_TRUE(rls.update(pair));
  }
  EXPECT_LT(rls.covariance()(0, 0), 0.01 * 300.0 * 300.0);
  for (int i = 0; i < 5000; ++i) ASSERT_TRUE(rls.update(make_pair(150.0, 0.0, 1.0)));
  EXPECT_LE(whitened_eigenvalues(rls)(1), 1.0 + 1e-12);
  EXPECT_NEAR(rls.covariance()(0, 0), 300.0 * 300.0, 1e-6 * 300.0 * 300.0);
}

TEST(RlsEstimator, InvalidPairsAreIgnored) {
  RlsEstimator rls(RlsParams{});
  rls.reset(test_prior());
  for (const RegressionPair& pair : synthetic_pairs(20, 1800.0, 150.0, 100.0, 5)) {
    ASSERT_TRUE(rls.update(pair));
  }
  const Eigen::Vector2d theta = rls.theta();
  const Eigen::Matrix2d p = rls.covariance();
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const RegressionPair bad[] = {make_pair(nan, 1.0, 1.0),   make_pair(100.0, nan, 1.0),
                                make_pair(inf, 1.0, 1.0),   make_pair(100.0, -inf, 1.0),
                                make_pair(100.0, 1.0, 0.0), make_pair(100.0, 1.0, -2.0),
                                make_pair(100.0, 1.0, nan), make_pair(100.0, 1.0, inf)};
  for (const RegressionPair& pair : bad) {
    EXPECT_FALSE(rls.update(pair));
    const PairPrediction pred = rls.predict(pair);
    EXPECT_FALSE(std::isnan(pred.y_n));
    EXPECT_EQ(pred.variance_n2, inf);
  }
  EXPECT_EQ(rls.theta(), theta);
  EXPECT_EQ(rls.covariance(), p);
  EXPECT_EQ(rls.state().pairs_used, 20);
}

TEST(RlsEstimator, ExtremeFinitePairsNeverProduceNan) {
  RlsEstimator rls(RlsParams{});
  rls.reset(test_prior());
  const double big = std::numeric_limits<double>::max();
  const RegressionPair extreme[] = {make_pair(big, 1.0, 1.0),   make_pair(-big, 1.0, 1.0),
                                    make_pair(1.0, 1e300, 1.0), make_pair(1.0, 1.0, 1e-300),
                                    make_pair(1.0, 1.0, 1e300), make_pair(big, -1e200, 1e300)};
  for (const RegressionPair& pair : extreme) {
    (void)rls.update(pair);
    const RegressorState s = rls.state();
    ASSERT_TRUE(std::isfinite(s.mass_kg) && std::isfinite(s.mu_n) && std::isfinite(s.mass_std_kg) &&
                std::isfinite(s.ci_low_kg) && std::isfinite(s.ci_high_kg));
    ASSERT_EQ(rls.covariance().llt().info(), Eigen::Success);
  }
}

TEST(RlsEstimator, RestoreRoundTripsAndRejectsBadCovariance) {
  RlsEstimator rls(RlsParams{});
  rls.reset(test_prior());
  Eigen::Matrix2d p;
  p << 400.0, 10.0, 10.0, 900.0;
  ASSERT_TRUE(rls.restore(Eigen::Vector2d(1700.0, 20.0), p, 123));
  EXPECT_EQ(rls.covariance(), p);
  EXPECT_EQ(rls.state().pairs_used, 123);
  EXPECT_EQ(rls.state().mass_kg, 1700.0);
  Eigen::Matrix2d indefinite;
  indefinite << 400.0, 700.0, 700.0, 900.0;
  EXPECT_FALSE(rls.restore(Eigen::Vector2d(1.0, 2.0), indefinite, 1));
  Eigen::Matrix2d with_nan = p;
  with_nan(0, 1) = std::nan("");
  EXPECT_FALSE(rls.restore(Eigen::Vector2d(1.0, 2.0), with_nan, 1));
  EXPECT_FALSE(rls.restore(Eigen::Vector2d(std::nan(""), 2.0), p, 1));
  EXPECT_EQ(rls.theta(), Eigen::Vector2d(1700.0, 20.0));
  EXPECT_EQ(rls.covariance(), p);
  // A restored P beyond the bound is clipped to it.
  Eigen::Matrix2d too_wide;
  too_wide << 4.0 * 300.0 * 300.0, 0.0, 0.0, 500.0 * 500.0;
  ASSERT_TRUE(rls.restore(Eigen::Vector2d(1.0, 2.0), too_wide, 1));
  EXPECT_NEAR(rls.covariance()(0, 0), 300.0 * 300.0, 1e-6);
}

TEST(RlsEstimator, IntervalCoversTheTruthAtItsLevelWhenTheNoiseIsKnown) {
  // Given theta drawn from the Gaussian prior and Gaussian noise of the configured sigma, RLS is
  // the exact Gaussian posterior, so the 95% interval covers the true M in 95% of runs.
  const double sigma = 80.0;
  RlsParams params;
  params.noise_std_n = sigma;
  MassPrior prior;
  prior.mass_kg = 1500.0;
  prior.mass_std_kg = 300.0;
  prior.mu_n = 0.0;
  prior.mu_std_n = 200.0;
  std::mt19937_64 rng(20240601);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> w_dist(0.5, 2.0);
  const int runs = 4000;
  int covered = 0;
  RlsEstimator rls(params);
  for (int run = 0; run < runs; ++run) {
    rls.reset(prior);
    const double mass = prior.mass_kg + prior.mass_std_kg * unit(rng);
    const double mu = prior.mu_n + prior.mu_std_n * unit(rng);
    for (int i = 0; i < 40; ++i) {
      const double da = 0.8 * unit(rng);
      const double w = w_dist(rng);
      ASSERT_TRUE(rls.update(make_pair(mass * da + mu + sigma / std::sqrt(w) * unit(rng), da, w)));
    }
    const RegressorState s = rls.state();
    if (s.ci_low_kg <= mass && mass <= s.ci_high_kg) ++covered;
  }
  const double coverage = static_cast<double>(covered) / runs;
  RecordProperty("coverage", std::to_string(coverage));
  EXPECT_GE(coverage, 0.935);
  EXPECT_LE(coverage, 0.965);
}

}  // namespace
}  // namespace vmass
