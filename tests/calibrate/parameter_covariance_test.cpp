// Given ballast steps from a known suspension curve, when fit_suspension() runs, then each fit's
// parameter covariance (SI units) and correlation are symmetric with a unit diagonal, agree with
// the reported standard deviations and with s^2 (J^T W J)^-1 computed here from a
// finite-difference Jacobian of the true curve's own inverse (bisection, not the fit's closed
// form), a rank-deficient or missing covariance is said in words (never NaN), strongly
// correlated pairs are named with advice, and the JSON carries both matrices keyed by parameter.
#include "vmass/calibrate/parameter_covariance.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "synthetic_ballast.hpp"
#include "vmass/calibrate/calibration_report.hpp"
#include "vmass/calibrate/suspension_fit.hpp"

namespace vmass::calibrate {
namespace {

using testing::deflection_for_force;
using testing::make_steps;
using testing::paper_geometry;
using testing::true_linear;
using testing::true_progressive;

// Steps at the given added masses on the given curve, 0.02 mm of seeded noise.
std::vector<BallastStep> steps_at(const SuspensionParams& s, const std::vector<double>& masses,
                                  unsigned seed) {
  std::vector<BallastStep> steps;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.02e-3);
  for (double m : masses) {
    BallastStep st;
    st.added_mass_kg = m;
    st.deflection_m = deflection_for_force(s, paper_geometry().wheel_force_n(m)) + noise(rng);
    st.sample_count = 1;
    steps.push_back(st);
  }
  return steps;
}

SuspensionCalibration fit(const std::vector<BallastStep>& steps) {
  const SuspensionFitResult r = fit_suspension(steps, paper_geometry());
  EXPECT_TRUE(r.ok()) << r.error;
  return r.ok() ? *r.calibration : SuspensionCalibration{};
}

void expect_a_covariance(const ParameterCovariance& c, const std::vector<const Estimate*>& stds) {
  ASSERT_TRUE(c.estimable) << c.reason;
  ASSERT_EQ(c.size(), stds.size());
  ASSERT_EQ(c.covariance.size(), c.size() * c.size());
  ASSERT_EQ(c.correlation.size(), c.size() * c.size());
  EXPECT_EQ(c.reason, "");
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c.correlation_at(i, i), 1.0) << c.names[i];
    // sqrt of the diagonal is the reported std.
    EXPECT_NEAR(std::sqrt(c.covariance_at(i, i)), stds[i]->std, 1e-9 * stds[i]->std) << c.names[i];
    for (std::size_t j = 0; j < c.size(); ++j) {
      EXPECT_EQ(c.covariance_at(i, j), c.covariance_at(j, i)) << i << ", " << j;
      EXPECT_EQ(c.correlation_at(i, j), c.correlation_at(j, i)) << i << ", " << j;
      EXPECT_LE(std::abs(c.correlation_at(i, j)), 1.0);
      EXPECT_NEAR(c.correlation_at(i, j),
                  c.covariance_at(i, j) / std::sqrt(c.covariance_at(i, i) * c.covariance_at(j, j)),
                  1e-12);
    }
  }
}

TEST(ParameterCovariance, BothFitsGiveASymmetricCovarianceWithUnitDiagonalCorrelation) {
  const SuspensionCalibration c =
      fit(make_steps(true_progressive(), paper_geometry(), 9, 0.02e-3, 7));
  ASSERT_TRUE(c.progressive.detected) << c.progressive.reason;
  EXPECT_EQ(c.linear.covariance.names,
            (std::vector<std::string>{"stiffness_n_per_m", "zero_offset_m"}));
  expect_a_covariance(c.linear.covariance, {&c.linear.stiffness_n_per_m, &c.linear.zero_offset_m});
  EXPECT_EQ(
      c.progressive.covariance.names,
      (std::vector<std::string>{"stiffness_n_per_m", "zero_offset_m", "knee_m", "rate_n_per_m2"}));
  const ProgressiveFit& p = c.progressive;
  expect_a_covariance(p.covariance,
                      {&p.stiffness_n_per_m, &p.zero_offset_m, &p.knee_m, &p.rate_n_per_m2});
}

// s^2 (J^T W J)^-1 from a central-difference Jacobian of the residuals (mm) with respect to
// the reported parameters, W the Cauchy weights 1 / (1 + (r / a)^2) at the fit's residuals, s the
// scale the fit reports (max of the residual std and the step means' s.e.).
Eigen::MatrixXd finite_difference_covariance(const std::vector<BallastStepFit>& steps,
                                             const std::vector<double>& phi,
                                             SuspensionParams (*curve)(const std::vector<double>&),
                                             bool linear_steps_only,
                                             double residual_m(const BallastStepFit&),
                                             const FitStats& stats) {
  const std::size_t p = phi.size();
  std::vector<const BallastStepFit*> used;
  for (const BallastStepFit& s : steps) {
    if (!linear_steps_only || s.in_linear_fit) used.push_back(&s);
  }
  Eigen::MatrixXd j(static_cast<int>(used.size()), static_cast<int>(p));
  Eigen::VectorXd w(static_cast<int>(used.size()));
  for (std::size_t k = 0; k < used.size(); ++k) {
    const double force = used[k]->force_n;
    for (std::size_t i = 0; i < p; ++i) {
      const double h = 1e-6 * std::abs(phi[i]);
      std::vector<double> up = phi, down = phi;
      up[i] += h;
      down[i] -= h;
      // r = 1e3 (z_meas - z(F; phi)): dr/dphi = -1e3 dz/dphi
      j(static_cast<int>(k), static_cast<int>(i)) =
          -1e3 *
          (deflection_for_force(curve(up), force) - deflection_for_force(curve(down), force)) /
          (2.0 * h);
    }
    const double r_mm = residual_m(*used[k]) * 1e3;
    w(static_cast<int>(k)) =
        1.0 / (1.0 + (r_mm / stats.robust_scale_mm) * (r_mm / stats.robust_scale_mm));
  }
  const double s = std::max(stats.residual_std_mm, stats.step_se_mm);
  const Eigen::MatrixXd jtwj = j.transpose() * w.asDiagonal() * j;
  return s * s * jtwj.inverse();
}

SuspensionParams progressive_curve(const std::vector<double>& phi) {
  SuspensionParams s;
  s.stiffness_n_per_m = phi[0];
  s.empty_deflection_m = phi[1];
  s.progressive_knee_m = phi[2];
  s.progressive_rate_n_per_m2 = phi[3];
  return s;
}

SuspensionParams linear_curve(const std::vector<double>& phi) {
  SuspensionParams s;
  s.stiffness_n_per_m = phi[0];
  s.empty_deflection_m = phi[1];
  return s;
}

double progressive_residual(const BallastStepFit& s) { return s.progressive_residual_m; }
double linear_residual(const BallastStepFit& s) { return s.linear_residual_m; }

void expect_matches(const ParameterCovariance& got, const Eigen::MatrixXd& want) {
  ASSERT_TRUE(got.estimable) << got.reason;
  ASSERT_EQ(static_cast<int>(got.size()), want.rows());
  for (std::size_t i = 0; i < got.size(); ++i) {
    for (std::size_t j = 0; j < got.size(); ++j) {
      const int a = static_cast<int>(i), b = static_cast<int>(j);
      const double scale = std::sqrt(want(a, a) * want(b, b));
      EXPECT_NEAR(got.covariance_at(i, j), want(a, b), 1e-4 * scale)
          << got.names[i] << ", " << got.names[j];
      EXPECT_NEAR(got.correlation_at(i, j), want(a, b) / scale, 1e-4)
          << got.names[i] << ", " << got.names[j];
    }
  }
}

TEST(ParameterCovariance, ProgressiveCovarianceMatchesAFiniteDifferenceJacobian) {
  // One step 1 mm off: the Cauchy weights are not all 1, so W matters.
  auto steps = make_steps(true_progressive(), paper_geometry(), 9, 0.02e-3, 5);
  steps[2].deflection_m -= 1.0e-3;
  const SuspensionCalibration c = fit(steps);
  ASSERT_TRUE(c.progressive.detected) << c.progressive.reason;
  ASSERT_TRUE(c.steps[2].outlier);
  const ProgressiveFit& p = c.progressive;
  const std::vector<double> phi = {p.stiffness_n_per_m.value, p.zero_offset_m.value, p.knee_m.value,
                                   p.rate_n_per_m2.value};
  expect_matches(p.covariance, finite_difference_covariance(c.steps, phi, progressive_curve, false,
                                                            progressive_residual, p.stats));
}

TEST(ParameterCovariance, LinearCovarianceMatchesAFiniteDifferenceJacobian) {
  const SuspensionCalibration c = fit(make_steps(true_linear(), paper_geometry(), 7, 0.05e-3, 9));
  const std::vector<double> phi = {c.linear.stiffness_n_per_m.value, c.linear.zero_offset_m.value};
  expect_matches(c.linear.covariance,
                 finite_difference_covariance(c.steps, phi, linear_curve, true, linear_residual,
                                              c.linear.stats));
  // Below the knee only: the finite differences of a progressive test's linear fit, too.
  const SuspensionCalibration pc =
      fit(make_steps(true_progressive(), paper_geometry(), 9, 0.02e-3, 7));
  ASSERT_EQ(pc.linear.stats.steps_used, 5);
  const std::vector<double> lphi = {pc.linear.stiffness_n_per_m.value,
                                    pc.linear.zero_offset_m.value};
  expect_matches(pc.linear.covariance,
                 finite_difference_covariance(pc.steps, lphi, linear_curve, true, linear_residual,
                                              pc.linear.stats));
}

TEST(ParameterCovariance, ALinearSpringHasNoProgressiveCovarianceAndSaysWhy) {
  const SuspensionCalibration c = fit(make_steps(true_linear(), paper_geometry(), 9, 0.02e-3, 3));
  ASSERT_FALSE(c.progressive.detected);
  expect_a_covariance(c.linear.covariance, {&c.linear.stiffness_n_per_m, &c.linear.zero_offset_m});
  EXPECT_FALSE(c.progressive.covariance.estimable);
  EXPECT_TRUE(c.progressive.covariance.covariance.empty());
  EXPECT_NE(c.progressive.covariance.reason.find("without a bump stop"), std::string::npos)
      << c.progressive.covariance.reason;
  const std::string text = calibration_text(c, {});
  EXPECT_NE(text.find("  correlation     not estimable: without a bump stop"), std::string::npos)
      << text;
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
}

// 0.005 mm per 50 t: c is so large that dz/dc is 1e-10 of dz/dz0, and Ceres finds J^T J rank
// deficient (reciprocal condition number below 1e-14).
TEST(ParameterCovariance, ARankDeficientFitIsSaidInWordsNeverAsNaN) {
  std::vector<BallastStep> steps;
  for (const auto& [m, z] : {std::pair{0.0, 0.012}, {50000.0, 0.012005}, {100000.0, 0.01201}}) {
    BallastStep s;
    s.added_mass_kg = m;
    s.deflection_m = z;
    s.sample_count = 1;
    steps.push_back(s);
  }
  const SuspensionCalibration c = fit(steps);
  const ParameterCovariance& lc = c.linear.covariance;
  EXPECT_FALSE(lc.estimable);
  EXPECT_TRUE(lc.covariance.empty());
  EXPECT_TRUE(lc.correlation.empty());
  EXPECT_EQ(lc.reason.rfind("rank deficient", 0), 0u) << lc.reason;
  EXPECT_TRUE(strongly_correlated(lc).empty());
  const std::string text = calibration_text(c, {});
  EXPECT_NE(text.find("  correlation     not estimable: rank deficient"), std::string::npos)
      << text;
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  const nlohmann::json j = nlohmann::json::parse(calibration_json(c, {}));
  EXPECT_EQ(j["linear"]["covariance_estimable"], false);
  EXPECT_TRUE(j["linear"]["correlation"].is_null());
  EXPECT_TRUE(j["linear"]["covariance"].is_null());
  EXPECT_EQ(j["linear"]["covariance_reason"], lc.reason);
}

TEST(ParameterCovariance, OnlyACovarianceIsAccepted) {
  const std::vector<std::string> two = {"stiffness_n_per_m", "zero_offset_m"};
  const ParameterCovariance ok = make_parameter_covariance(two, {4.0, 1.0, 1.0, 1.0});
  ASSERT_TRUE(ok.estimable) << ok.reason;
  EXPECT_DOUBLE_EQ(ok.correlation_at(0, 1), 0.5);
  EXPECT_EQ(ok.correlation_at(0, 0), 1.0);
  // Singular (perfectly correlated), zero variance, NaN, asymmetric, wrong size.
  const ParameterCovariance singular = make_parameter_covariance(two, {1.0, 2.0, 2.0, 4.0});
  EXPECT_FALSE(singular.estimable);
  EXPECT_EQ(singular.reason.rfind("rank deficient", 0), 0u) << singular.reason;
  const ParameterCovariance zero = make_parameter_covariance(two, {1.0, 0.0, 0.0, 0.0});
  EXPECT_FALSE(zero.estimable);
  EXPECT_EQ(zero.reason, "rank deficient: zero_offset_m has no variance");
  EXPECT_FALSE(make_parameter_covariance(two, {1.0, NAN, NAN, 1.0}).estimable);
  EXPECT_FALSE(make_parameter_covariance(two, {1.0, 0.5, 0.4, 1.0}).estimable);
  EXPECT_FALSE(make_parameter_covariance(two, {1.0}).estimable);
  for (const ParameterCovariance& c : {singular, zero}) {
    EXPECT_TRUE(c.covariance.empty());
    EXPECT_TRUE(c.correlation.empty());
  }
  // A single parameter (a spring with only its stiffness): a 1 x 1 correlation of 1.
  const ParameterCovariance one = make_parameter_covariance({"stiffness_n_per_m"}, {25.0});
  ASSERT_TRUE(one.estimable);
  EXPECT_EQ(one.correlation_at(0, 0), 1.0);
  EXPECT_TRUE(strongly_correlated(one).empty());
}

TEST(ParameterCovariance, StronglyCorrelatedPairsAreSaidWithWhatWouldSeparateThem) {
  // No step near zero load: stiffness and zero offset trade off.
  const SuspensionCalibration far =
      fit(steps_at(true_linear(), {300.0, 400.0, 500.0, 600.0, 700.0}, 1));
  const auto pairs = strongly_correlated(far.linear.covariance);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_GT(pairs[0].correlation, 0.9);
  std::string text = calibration_text(far, {});
  EXPECT_NE(text.find("  trade-off       stiffness and zero offset trade off (r = 0.9"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("a step at zero added load (the lightest is 300 kg) would separate them"),
            std::string::npos)
      << text;
  // Steps from zero: no strong pair, and the text says so.
  const SuspensionCalibration near =
      fit(steps_at(true_linear(), {0.0, 100.0, 200.0, 300.0, 400.0}, 1));
  EXPECT_TRUE(strongly_correlated(near.linear.covariance).empty());
  EXPECT_NE(calibration_text(near, {}).find("  trade-offs      none (every |r| <= 0.9)"),
            std::string::npos);

  // A short linear part (0-100 kg) and a wide gap to the first step beyond the knee: stiffness
  // and knee trade off; the advice names the gap.
  const SuspensionCalibration gap =
      fit(steps_at(true_progressive(), {0, 50, 100, 600, 700, 800, 900, 1000, 1100, 1200}, 3));
  ASSERT_TRUE(gap.progressive.detected) << gap.progressive.reason;
  text = calibration_text(gap, {});
  EXPECT_NE(text.find("stiffness and knee trade off (r = 0.9"), std::string::npos) << text;
  EXPECT_NE(text.find("more ballast steps between 100 and 600 kg, where the linear part ends"),
            std::string::npos)
      << text;
  // Filling the gap separates them, as the advice says.
  const SuspensionCalibration filled = fit(steps_at(
      true_progressive(), {0, 50, 100, 200, 300, 400, 600, 700, 800, 900, 1000, 1100, 1200}, 3));
  ASSERT_TRUE(filled.progressive.detected);
  EXPECT_LT(std::abs(filled.progressive.covariance.correlation_at(0, 2)),
            0.5 * std::abs(gap.progressive.covariance.correlation_at(0, 2)));
}

TEST(ParameterCovariance, JsonCarriesBothMatricesKeyedByParameter) {
  const SuspensionCalibration c =
      fit(make_steps(true_progressive(), paper_geometry(), 9, 0.02e-3, 7));
  ASSERT_TRUE(c.progressive.detected);
  const nlohmann::json j = nlohmann::json::parse(calibration_json(c, {}));
  for (const auto& [model, cov] :
       {std::pair{"linear", &c.linear.covariance}, {"progressive", &c.progressive.covariance}}) {
    SCOPED_TRACE(model);
    const nlohmann::json& m = j[model];
    EXPECT_EQ(m["covariance_estimable"], true);
    EXPECT_EQ(m["covariance_reason"], "");
    EXPECT_EQ(m["parameters"].get<std::vector<std::string>>(), cov->names);
    for (std::size_t a = 0; a < cov->size(); ++a) {
      for (std::size_t b = 0; b < cov->size(); ++b) {
        const std::string& ka = cov->names[a];
        const std::string& kb = cov->names[b];
        ASSERT_TRUE(m["correlation"][ka][kb].is_number()) << ka << ", " << kb;
        EXPECT_NEAR(m["correlation"][ka][kb].get<double>(), cov->correlation_at(a, b), 1e-9);
        EXPECT_NEAR(m["covariance"][ka][kb].get<double>(), cov->covariance_at(a, b),
                    1e-9 * std::abs(cov->covariance_at(a, b)));
      }
    }
    ASSERT_TRUE(m["trade_offs"].is_array());
    EXPECT_EQ(m["trade_offs"].size(), strongly_correlated(*cov).size());
  }
  // The knee and rate of this test trade off (the model's shape): named with its advice.
  const nlohmann::json& t = j["progressive"]["trade_offs"];
  ASSERT_GE(t.size(), 1u);
  EXPECT_EQ(t[0]["parameters"], (nlohmann::json{"knee_m", "rate_n_per_m2"}));
  EXPECT_GT(t[0]["correlation"].get<double>(), 0.9);
  EXPECT_NE(t[0]["text"].get<std::string>().find("knee and rate trade off (r = 0."),
            std::string::npos);
  EXPECT_NE(t[0]["advice"].get<std::string>().find("a later knee with a steeper rate"),
            std::string::npos);
}

}  // namespace
}  // namespace vmass::calibrate
