// Given the residual functors of the suspension fit, then their autodiff Jacobians agree with
// numeric differentiation (ceres::GradientChecker) on both sides of the knee, and the
// progressive model's closed-form z(F) inverts the core's forward curve F(z).
#include "vmass/calibrate/suspension_residuals.hpp"

#include <memory>

#include <gtest/gtest.h>

#include "synthetic_ballast.hpp"

namespace vmass::calibrate {
namespace {

bool probe(const ceres::CostFunction& cost, const std::vector<double>& params, std::string* log) {
  // Ridders' first step is 1e-3 relative: the probes below stay further than that from the
  // knee, where the second derivative jumps and a finite difference straddling it is wrong.
  ceres::NumericDiffOptions numeric;
  numeric.ridders_relative_initial_step_size = 1e-3;
  ceres::GradientChecker checker(
      &cost, static_cast<const std::vector<const ceres::Manifold*>*>(nullptr), numeric);
  std::vector<const double*> blocks;
  for (const double& p : params) blocks.push_back(&p);
  ceres::GradientChecker::ProbeResults results;
  const bool ok = checker.Probe(blocks.data(), 1e-7, &results);
  *log = results.error_log;
  return ok;
}

TEST(SuspensionResiduals, LinearJacobianMatchesNumeric) {
  std::unique_ptr<ceres::CostFunction> cost(LinearDeflectionResidual::Create(871.6, 41.3));
  std::string log;
  EXPECT_TRUE(probe(*cost, {11.8, 29.7}, &log)) << log;
  EXPECT_TRUE(probe(*cost, {-3.0, 120.0}, &log)) << log;
}

TEST(SuspensionResiduals, ProgressiveJacobianMatchesNumericBelowAndBeyondTheKnee) {
  // z0 12 mm, c 30 N/mm, d 30 mm (knee force 900 N), k2 2 N/mm^2.
  const std::vector<double> params = {12.0, 30.0, 30.0, 2.0};
  std::string log;
  for (double force_n : {0.0, 300.0, 850.0, 960.0, 1200.0, 1743.0}) {
    std::unique_ptr<ceres::CostFunction> cost(ProgressiveDeflectionResidual::Create(force_n, 40.0));
    EXPECT_TRUE(probe(*cost, params, &log)) << "F = " << force_n << ": " << log;
  }
  // A tiny k2 beyond the knee (near the linear limit; k2 < 0 is refused, so a finite difference
  // cannot straddle k2 = 0 itself).
  std::unique_ptr<ceres::CostFunction> cost(ProgressiveDeflectionResidual::Create(1500.0, 60.0));
  EXPECT_TRUE(probe(*cost, {12.0, 30.0, 30.0, 0.05}, &log)) << log;
}

TEST(SuspensionResiduals, ProgressiveResidualRejectsNonPhysicalParameters) {
  const ProgressiveDeflectionResidual r(1000.0, 40.0);
  const double z0 = 12.0, d = 30.0, k2 = 2.0;
  double c = -1.0, out = 0.0;
  EXPECT_FALSE(r(&z0, &c, &d, &k2, &out));
  c = 30.0;
  const double k2_negative = -1.0;
  EXPECT_FALSE(r(&z0, &c, &d, &k2_negative, &out));
}

TEST(SuspensionResiduals, ProgressivePredictionInvertsTheCoreCurve) {
  const SuspensionParams s = testing::true_progressive();
  for (double force_n : {0.0, 250.0, 899.9, 900.1, 1300.0, 2500.0}) {
    const double z_mm = ProgressiveDeflectionResidual::predicted_deflection_mm(
        force_n, s.empty_deflection_m * 1e3, s.stiffness_n_per_m * 1e-3,
        (s.progressive_knee_m - s.empty_deflection_m) * 1e3, s.progressive_rate_n_per_m2 * 1e-6);
    EXPECT_NEAR(s.wheel_force_n(z_mm * 1e-3), force_n, 1e-9 * (1.0 + force_n)) << force_n;
    EXPECT_NEAR(z_mm * 1e-3, testing::deflection_for_force(s, force_n), 1e-11);
  }
}

}  // namespace
}  // namespace vmass::calibrate
