// BayesEstimator against independent answers: k batches vs one conjugate update over all pairs,
// the posterior mean vs weighted regularised least squares (QR), tabulated Student-t quantiles,
// the prior predictive derived by hand, and the Bayesian coverage of the credible interval.
#include "vmass/core/bayes_estimator.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "regression_test_data.hpp"
#include "vmass/core/constants.hpp"

namespace vmass {
namespace {

constexpr double kZ975 = 1.959963984540054;  // standard normal 0.975 quantile (tables)
constexpr double kT975Dof10 = 2.228138852;   // Student-t 0.975 quantile, 10 dof (tables)
constexpr double kT950Dof10 = 1.812461123;   // Student-t 0.95 quantile, 10 dof (tables)

MassPrior test_prior() {
  MassPrior p;
  p.mass_kg = 1500.0;
  p.mass_std_kg = 300.0;
  p.mu_n = 0.0;
  p.mu_std_n = 200.0;
  return p;
}

using testing::make_pair;

std::vector<RegressionPair> synthetic_pairs(int n, double mass, double mu, double sigma,
                                            std::uint64_t seed) {
  return testing::synthetic_pairs(n, mass, mu, sigma, seed, 0.3, 1.2);
}

void expect_posterior_near(const NigPosterior& got, const NigPosterior& want, double tol) {
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(got.mean(i), want.mean(i), tol * std::abs(want.mean(i))) << "mean " << i;
    for (int j = 0; j < 2; ++j) {
      const Eigen::Matrix2d& v = want.scaled_covariance;
      EXPECT_NEAR(got.scaled_covariance(i, j), v(i, j), tol * std::sqrt(v(i, i) * v(j, j)))
          << "V(" << i << "," << j << ")";
    }
  }
  EXPECT_NEAR(got.shape, want.shape, tol * want.shape);
  EXPECT_NEAR(got.scale, want.scale, tol * want.scale);
}

TEST(BayesParams, ValidateNamesKeyAndBound) {
  EXPECT_EQ(BayesParams{}.validate(), "");
  BayesParams p;
  p.batch_size = 0;
  EXPECT_EQ(p.validate(), "bayes.batch_size must be >= 1, got 0");
  p = BayesParams{};
  p.noise_std_guess_n = -1.0;
  EXPECT_EQ(p.validate(), "bayes.noise_std_guess_n must be > 0, got -1");
  p = BayesParams{};
  p.prior_noise_dof = 0.0;
  EXPECT_EQ(p.validate(), "bayes.prior_noise_dof must be > 0, got 0");
  p = BayesParams{};
  p.credible_level = 1.0;
  EXPECT_EQ(p.validate(), "bayes.credible_level must be in (0, 1), got 1");
  p.credible_level = std::nan("");
  EXPECT_NE(p.validate().find("bayes.credible_level"), std::string::npos);
}

TEST(BayesEstimator, PriorMatchesMassPriorAndNoiseGuess) {
  BayesParams params;
  params.noise_std_guess_n = 80.0;
  params.prior_noise_dof = 4.0;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const RegressorState s = bayes.state();
  EXPECT_EQ(s.mass_kg, 1500.0);
  EXPECT_EQ(s.mu_n, 0.0);
  EXPECT_NEAR(s.mass_std_kg, 300.0, 1e-9);
  EXPECT_NEAR(s.mu_std_n, 200.0, 1e-9);
  EXPECT_NEAR(s.noise_std_n, 80.0, 1e-9);  // sqrt(E[sigma^2])
  EXPECT_EQ(s.pairs_used, 0);
  EXPECT_EQ(bayes.posterior().shape, 2.0);
  // Marginal of M: t with 4 dof, scale^2 = variance * (nu - 2) / nu; t_{0.975,4} = 2.776445105.
  const double half = 2.776445105 * 300.0 * std::sqrt(2.0 / 4.0);
  EXPECT_NEAR(s.ci_high_kg - 1500.0, half, 1e-6);
  EXPECT_NEAR(1500.0 - s.ci_low_kg, half, 1e-6);
  // Prior predictive variance derived by hand: Var(M da + mu + e) = da^2 var_M + var_mu +
  // E[sigma^2] / w (M, mu, e uncorrelated under the prior).
  const PairPrediction pred = bayes.predict(make_pair(0.0, 1.3, 2.0));
  EXPECT_DOUBLE_EQ(pred.y_n, 1500.0 * 1.3);
  EXPECT_NEAR(pred.variance_n2, 1.3 * 1.3 * 300.0 * 300.0 + 200.0 * 200.0 + 80.0 * 80.0 / 2.0,
              1e-9 * pred.variance_n2);
  EXPECT_EQ(bayes.name(), "bayes");
}

TEST(BayesEstimator, HeavyTailedPriorUsesTheTScale) {
  // 2 a0 = 1: the marginal of M is Cauchy (t, 1 dof) whose 0.975 quantile is tan(0.475 pi).
  BayesParams params;
  params.noise_std_guess_n = 80.0;
  params.prior_noise_dof = 1.0;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const RegressorState s = bayes.state();
  const double t975_dof1 = std::tan(0.475 * kPi);
  EXPECT_NEAR(s.mass_std_kg, 300.0, 1e-9);  // the t scale (the variance does not exist)
  EXPECT_NEAR(s.ci_high_kg - 1500.0, t975_dof1 * 300.0, 1e-8 * t975_dof1 * 300.0);
  // Gaussian-equivalent predictive variance: scale^2 * (t_q / z_q)^2.
  const double scale2 = 1.3 * 1.3 * 300.0 * 300.0 + 200.0 * 200.0 + 80.0 * 80.0 / 2.0;
  const double ratio = t975_dof1 / kZ975;
  EXPECT_NEAR(bayes.predict(make_pair(0.0, 1.3, 2.0)).variance_n2, scale2 * ratio * ratio,
              1e-9 * scale2 * ratio * ratio);
}

TEST(BayesEstimator, PublishesOnlyWhenABatchCompletes) {
  BayesParams params;
  params.batch_size = 10;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const std::vector<RegressionPair> pairs = synthetic_pairs(25, 1800.0, 100.0, 100.0, 1);
  const RegressorState prior_state = bayes.state();
  for (int i = 0; i < 25; ++i) {
    const bool changed = bayes.update(pairs[i]);
    EXPECT_EQ(changed, (i + 1) % 10 == 0) << i;
    EXPECT_EQ(bayes.pending_pairs(), (i + 1) % 10);
    EXPECT_EQ(bayes.state().pairs_used, (i + 1) / 10 * 10);
    if (i < 9) {
      EXPECT_EQ(bayes.state().mass_kg, prior_state.mass_kg);
    }
  }
  EXPECT_NE(bayes.state().mass_kg, prior_state.mass_kg);
}

TEST(BayesEstimator, FlushTakesTheOpenBatchIntoThePosterior) {
  // Given 25 pairs in batches of 10, when the estimator is flushed, then the 5 pairs of the
  // open batch are in the posterior: exactly one conjugate update over all 25.
  BayesParams params;
  params.batch_size = 10;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const NigPosterior prior = bayes.posterior();
  const std::vector<RegressionPair> pairs = synthetic_pairs(25, 1800.0, 100.0, 100.0, 3);
  BayesEstimator::Sufficient all;
  for (const RegressionPair& pair : pairs) {
    bayes.update(pair);
    all.add(pair);
  }
  ASSERT_EQ(bayes.state().pairs_used, 20);
  EXPECT_TRUE(bayes.flush());
  EXPECT_EQ(bayes.pending_pairs(), 0);
  EXPECT_EQ(bayes.state().pairs_used, 25);
  expect_posterior_near(bayes.posterior(), BayesEstimator::conjugate_update(prior, all), 1e-9);
  // Nothing left: a second flush changes nothing.
  const NigPosterior flushed = bayes.posterior();
  EXPECT_FALSE(bayes.flush());
  EXPECT_EQ(bayes.posterior().mean, flushed.mean);
}

TEST(BayesEstimator, SequentialBatchesEqualOneConjugateUpdate) {
  BayesParams params;
  params.batch_size = 25;
  params.noise_std_guess_n = 90.0;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const NigPosterior prior = bayes.posterior();
  const std::vector<RegressionPair> pairs = synthetic_pairs(200, 1850.0, 120.0, 70.0, 2);
  BayesEstimator::Sufficient all;  // about the origin 0: raw y statistics
  BayesEstimator::Sufficient shifted;
  shifted.origin = Eigen::Vector2d(1000.0, -300.0);
  for (const RegressionPair& pair : pairs) {
    bayes.update(pair);
    all.add(pair);
    shifted.add(pair);
  }
  ASSERT_EQ(bayes.pending_pairs(), 0);
  ASSERT_EQ(bayes.state().pairs_used, 200);
  const NigPosterior one = BayesEstimator::conjugate_update(prior, all);
  expect_posterior_near(bayes.posterior(), one, 1e-9);
  expect_posterior_near(BayesEstimator::conjugate_update(prior, shifted), one, 1e-9);
  EXPECT_EQ(one.shape, prior.shape + 100.0);
}

TEST(BayesEstimator, LongRunStaysEqualToOneBatch) {
  // 1e5 pairs in batches of 100: the recursion must not drift from the one-shot posterior.
  BayesParams params;
  params.batch_size = 100;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const NigPosterior prior = bayes.posterior();
  BayesEstimator::Sufficient all;
  all.origin = prior.mean;
  for (const RegressionPair& pair : synthetic_pairs(100000, 2200.0, 300.0, 100.0, 3)) {
    bayes.update(pair);
    all.add(pair);
  }
  expect_posterior_near(bayes.posterior(), BayesEstimator::conjugate_update(prior, all), 1e-9);
  EXPECT_NEAR(bayes.state().noise_std_n, 100.0, 1.0);
}

TEST(BayesEstimator, PosteriorIsWeightedRegularisedLeastSquares) {
  BayesParams params;
  params.batch_size = 40;
  params.noise_std_guess_n = 50.0;
  params.prior_noise_dof = 6.0;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const NigPosterior prior = bayes.posterior();
  const std::vector<RegressionPair> pairs = synthetic_pairs(120, 1700.0, 60.0, 50.0, 4);
  for (const RegressionPair& pair : pairs) bayes.update(pair);
  // argmin (theta - m0)^T V0^-1 (theta - m0) + sum w_i (y_i - phi_i theta)^2, by QR of the
  // stacked whitened rows (V0 is diagonal: pseudo-observations theta_j = m0_j, weight 1/V0_jj).
  const int n = static_cast<int>(pairs.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + 2, 2);
  Eigen::VectorXd b(n + 2);
  for (int j = 0; j < 2; ++j) {
    const double s = 1.0 / std::sqrt(prior.scaled_covariance(j, j));
    a(j, j) = s;
    b(j) = s * prior.mean(j);
  }
  for (int i = 0; i < n; ++i) {
    const double s = std::sqrt(pairs[i].weight);
    a(i + 2, 0) = s * pairs[i].delta_accel_mps2;
    a(i + 2, 1) = s;
    b(i + 2) = s * pairs[i].y_n;
  }
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  NigPosterior want;
  want.mean = qr.solve(b);
  const Eigen::Matrix2d r = qr.matrixQR().topRows<2>().triangularView<Eigen::Upper>();
  const Eigen::Matrix2d r_inv = r.inverse();
  want.scaled_covariance = r_inv * r_inv.transpose();
  want.shape = prior.shape + 0.5 * n;
  // b_n = b0 + (weighted residual sum of squares + prior penalty) / 2, the residual form.
  double rss = 0.0;
  for (const RegressionPair& p : pairs) {
    const double e = p.y_n - want.mean(0) * p.delta_accel_mps2 - want.mean(1);
    rss += p.weight * e * e;
  }
  const Eigen::Vector2d d = want.mean - prior.mean;
  rss += d(0) * d(0) / prior.scaled_covariance(0, 0) + d(1) * d(1) / prior.scaled_covariance(1, 1);
  want.scale = prior.scale + 0.5 * rss;
  expect_posterior_near(bayes.posterior(), want, 1e-9);
}

TEST(BayesEstimator, IntervalUsesTheStudentTQuantile) {
  NigPosterior post;
  post.mean << 1700.0, 80.0;
  post.scaled_covariance << 0.5, 0.01, 0.01, 2.0;
  post.shape = 5.0;  // 10 dof
  post.scale = 3.0e4;
  for (const double level : {0.95, 0.90}) {
    BayesParams params;
    params.credible_level = level;
    BayesEstimator bayes(params);
    ASSERT_TRUE(bayes.restore(post, 777));
    const RegressorState s = bayes.state();
    const double t = level == 0.95 ? kT975Dof10 : kT950Dof10;
    const double scale = std::sqrt(post.scale / post.shape * post.scaled_covariance(0, 0));
    EXPECT_NEAR(s.ci_high_kg - 1700.0, t * scale, 1e-9 * t * scale) << level;
    EXPECT_NEAR(1700.0 - s.ci_low_kg, t * scale, 1e-9 * t * scale) << level;
    EXPECT_DOUBLE_EQ(s.mass_std_kg, std::sqrt(post.scale / 4.0 * 0.5));
    EXPECT_DOUBLE_EQ(s.mu_std_n, std::sqrt(post.scale / 4.0 * 2.0));
    EXPECT_DOUBLE_EQ(s.noise_std_n, std::sqrt(post.scale / 4.0));
    EXPECT_EQ(s.pairs_used, 777);
    // Predictive variance of y: E[sigma^2] (1/w + phi V phi^T).
    const double da = -0.7;
    const double phi_v_phi = da * da * 0.5 + 2.0 * da * 0.01 + 2.0;
    const PairPrediction pred = bayes.predict(make_pair(0.0, da, 4.0));
    EXPECT_DOUBLE_EQ(pred.y_n, 1700.0 * da + 80.0);
    EXPECT_NEAR(pred.variance_n2, post.scale / 4.0 * (0.25 + phi_v_phi), 1e-9 * pred.variance_n2);
  }
}

TEST(BayesEstimator, NoUpdatesLeaveStateUnchanged) {
  BayesEstimator bayes(BayesParams{});
  bayes.reset(test_prior());
  const RegressorState before = bayes.state();
  for (int i = 0; i < 10; ++i) (void)bayes.predict(make_pair(100.0, 0.5, 1.0));
  const RegressorState after = bayes.state();
  EXPECT_EQ(after.mass_kg, before.mass_kg);
  EXPECT_EQ(after.mass_std_kg, before.mass_std_kg);
  EXPECT_EQ(after.ci_low_kg, before.ci_low_kg);
  EXPECT_EQ(after.ci_high_kg, before.ci_high_kg);
  EXPECT_EQ(after.pairs_used, 0);
  EXPECT_EQ(bayes.pending_pairs(), 0);
}

TEST(BayesEstimator, InvalidPairsAreIgnored) {
  BayesParams params;
  params.batch_size = 5;
  BayesEstimator bayes(params);
  bayes.reset(test_prior());
  const std::vector<RegressionPair> pairs = synthetic_pairs(8, 1800.0, 100.0, 100.0, 6);
  for (const RegressionPair& pair : pairs) bayes.update(pair);
  ASSERT_EQ(bayes.pending_pairs(), 3);
  const NigPosterior before = bayes.posterior();
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const RegressionPair bad[] = {make_pair(nan, 1.0, 1.0),    make_pair(100.0, nan, 1.0),
                                make_pair(inf, 1.0, 1.0),    make_pair(100.0, 1.0, 0.0),
                                make_pair(100.0, 1.0, -1.0), make_pair(100.0, 1.0, nan)};
  for (const RegressionPair& pair : bad) {
    EXPECT_FALSE(bayes.update(pair));
    const PairPrediction pred = bayes.predict(pair);
    EXPECT_FALSE(std::isnan(pred.y_n));
    EXPECT_EQ(pred.variance_n2, inf);
  }
  EXPECT_EQ(bayes.pending_pairs(), 3);
  EXPECT_EQ(bayes.posterior().mean, before.mean);
  EXPECT_EQ(bayes.posterior().scale, before.scale);
  // The batch then completes with the same two valid pairs as without the bad ones.
  BayesEstimator clean(params);
  clean.reset(test_prior());
  for (const RegressionPair& pair : pairs) clean.update(pair);
  const std::vector<RegressionPair> more = synthetic_pairs(2, 1800.0, 100.0, 100.0, 7);
  for (const RegressionPair& pair : more) {
    bayes.update(pair);
    clean.update(pair);
  }
  EXPECT_EQ(bayes.posterior().mean, clean.posterior().mean);
  EXPECT_EQ(bayes.posterior().scale, clean.posterior().scale);
}

TEST(BayesEstimator, RestoreRejectsInvalidPosterior) {
  BayesEstimator bayes(BayesParams{});
  bayes.reset(test_prior());
  const NigPosterior before = bayes.posterior();
  NigPosterior bad = before;
  bad.scale = 0.0;
  EXPECT_FALSE(bayes.restore(bad, 1));
  bad = before;
  bad.scaled_covariance << 1.0, 2.0, 2.0, 1.0;  // indefinite
  EXPECT_FALSE(bayes.restore(bad, 1));
  bad = before;
  bad.mean(0) = std::nan("");
  EXPECT_FALSE(bayes.restore(bad, 1));
  EXPECT_EQ(bayes.posterior().mean, before.mean);
  EXPECT_EQ(bayes.posterior().scale, before.scale);
}

double coverage(bool exact_nig_truth, int runs, int pairs_per_run, int batch_size,
                std::uint64_t seed) {
  BayesParams params;
  params.batch_size = batch_size;
  params.noise_std_guess_n = 80.0;
  params.prior_noise_dof = 4.0;
  const MassPrior prior = test_prior();
  BayesEstimator bayes(params);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> w_dist(0.5, 2.0);
  int covered = 0;
  for (int run = 0; run < runs; ++run) {
    bayes.reset(prior);
    const NigPosterior& p0 = bayes.posterior();
    double sigma = params.noise_std_guess_n;
    double mass = 0.0;
    double mu = 0.0;
    if (exact_nig_truth) {
      // The full prior: sigma^2 ~ InvGamma(a0, b0), theta | sigma^2 ~ N(m0, sigma^2 V0).
      std::gamma_distribution<double> gamma(p0.shape, 1.0);
      sigma = std::sqrt(p0.scale / gamma(rng));
      mass = p0.mean(0) + sigma * std::sqrt(p0.scaled_covariance(0, 0)) * unit(rng);
      mu = p0.mean(1) + sigma * std::sqrt(p0.scaled_covariance(1, 1)) * unit(rng);
    } else {
      // M and mu from the MassPrior's normal, the noise at its guessed level.
      mass = prior.mass_kg + prior.mass_std_kg * unit(rng);
      mu = prior.mu_n + prior.mu_std_n * unit(rng);
    }
    for (int i = 0; i < pairs_per_run; ++i) {
      const double da = 0.8 * unit(rng);
      const double w = w_dist(rng);
      bayes.update(make_pair(mass * da + mu + sigma / std::sqrt(w) * unit(rng), da, w));
    }
    const RegressorState s = bayes.state();
    if (s.ci_low_kg <= mass && mass <= s.ci_high_kg) ++covered;
  }
  return static_cast<double>(covered) / runs;
}

TEST(BayesEstimator, CredibleIntervalCoversTruthDrawnFromThePrior) {
  // Bayesian calibration is exact when the truth comes from the model's own prior: few pairs,
  // so the prior and the unknown sigma both matter.
  const double exact = coverage(true, 4000, 12, 4, 99);
  RecordProperty("coverage_nig_prior", std::to_string(exact));
  EXPECT_GE(exact, 0.935);
  EXPECT_LE(exact, 0.965);
  // M drawn from the MassPrior's normal, noise at the guessed sigma, enough pairs that the data
  // dominate.
  const double data = coverage(false, 2000, 200, 50, 100);
  RecordProperty("coverage_normal_prior", std::to_string(data));
  EXPECT_GE(data, 0.935);
  EXPECT_LE(data, 0.965);
}

}  // namespace
}  // namespace vmass
