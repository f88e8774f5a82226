// Given ballast steps from a known suspension curve, when fit_suspension() runs, then it
// recovers the parameters within their reported uncertainty, detects the bump stop only when
// there is one, resists one bad step, finds the linear range, and rejects bad data by name.
#include "vmass/calibrate/suspension_fit.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "synthetic_ballast.hpp"
#include "vmass/calibrate/calibration_report.hpp"
#include "vmass/config/config.hpp"
#include "vmass/core/static_initializer.hpp"

namespace vmass::calibrate {
namespace {

using testing::make_steps;
using testing::paper_geometry;
using testing::true_linear;
using testing::true_progressive;

TEST(SuspensionFit, NoiseFreeLinearStepsGiveTheExactStiffnessAndNoBumpStop) {
  const auto steps = make_steps(true_linear(), paper_geometry(), 9, 0.0, 1);
  const SuspensionFitResult r = fit_suspension(steps, paper_geometry());
  ASSERT_TRUE(r.ok()) << r.error;
  const SuspensionCalibration& c = *r.calibration;
  EXPECT_NEAR(c.linear.stiffness_n_per_m.value, 30000.0, 1e-4);
  EXPECT_NEAR(c.linear.zero_offset_m.value, 0.012, 1e-10);
  EXPECT_FALSE(c.progressive.detected);
  EXPECT_EQ(c.linear.stats.steps_used, 9);
  EXPECT_DOUBLE_EQ(c.linear_range_kg, 800.0);
  EXPECT_DOUBLE_EQ(c.calibrated_range_kg, 800.0);
  EXPECT_TRUE(std::isinf(c.suspension_params().progressive_knee_m));
  EXPECT_EQ(c.suspension_params().progressive_rate_n_per_m2, 0.0);
}

TEST(SuspensionFit, NoisyProgressiveStepsRecoverEveryParameterWithinItsInterval) {
  const SuspensionParams truth = true_progressive();
  const auto steps = make_steps(truth, paper_geometry(), 9, 0.02e-3, 7);
  const SuspensionFitResult r = fit_suspension(steps, paper_geometry());
  ASSERT_TRUE(r.ok()) << r.error;
  const SuspensionCalibration& c = *r.calibration;
  ASSERT_TRUE(c.progressive.detected) << c.progressive.reason;
  const ProgressiveFit& p = c.progressive;
  auto covers = [](const Estimate& e, double t) { return e.low <= t && t <= e.high; };
  EXPECT_TRUE(covers(p.stiffness_n_per_m, 30000.0)) << p.stiffness_n_per_m.value;
  EXPECT_TRUE(covers(p.zero_offset_m, 0.012)) << p.zero_offset_m.value;
  EXPECT_TRUE(covers(p.knee_m, 0.042)) << p.knee_m.value << " +- " << p.knee_m.std;
  EXPECT_TRUE(covers(p.rate_n_per_m2, 2.0e6)) << p.rate_n_per_m2.value;
  EXPECT_NEAR(p.stiffness_n_per_m.value, 30000.0, 0.01 * 30000.0);
  EXPECT_NEAR(p.knee_m.value, 0.042, 1e-3);
  EXPECT_NEAR(p.rate_n_per_m2.value, 2.0e6, 0.2e6);
  // The linear model uses only the steps below the knee (30 mm above zero = 413 kg).
  EXPECT_EQ(c.linear.stats.steps_used, 5);
  EXPECT_TRUE(covers(c.linear.stiffness_n_per_m, 30000.0));
  EXPECT_GT(c.linear.stiffness_n_per_m.std, 0.0);
}

// The linear range from the true curve, computed independently: the largest step whose
// deflection the true linear spring maps back to the load within 1 %.
TEST(SuspensionFit, LinearRangeIsTheLastStepTheLinearModelReproducesWithinOnePercent) {
  const SuspensionParams truth = true_progressive();
  const LoadGeometry g = paper_geometry();
  const auto steps = make_steps(truth, g, 9, 0.0, 1);
  double expected = 0.0;
  for (const BallastStep& s : steps) {
    if (s.added_mass_kg == 0.0) continue;
    const double m_lin = truth.stiffness_n_per_m * (s.deflection_m - truth.empty_deflection_m) /
                         g.wheel_force_per_kg();
    if (std::abs(m_lin - s.added_mass_kg) > 0.01 * s.added_mass_kg) break;
    expected = s.added_mass_kg;
  }
  ASSERT_EQ(expected, 400.0);  // the knee is at 413 kg; 500 kg is 4 % off
  const SuspensionFitResult r = fit_suspension(steps, g);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_DOUBLE_EQ(r.calibration->linear_range_kg, expected);
  const SuspensionFitResult loose = fit_suspension(steps, g, [] {
    SuspensionFitOptions o;
    o.linear_tolerance = 0.05;
    return o;
  }());
  ASSERT_TRUE(loose.ok());
  EXPECT_DOUBLE_EQ(loose.calibration->linear_range_kg, 500.0);
}

// Over many seeded tests, the 95 % interval of the linear stiffness covers the truth about
// 95 % of the time (binomial: 200 trials, 95 % -> 190 +- 3.1; accept 178..198).
TEST(SuspensionFit, LinearStiffnessIntervalHasItsNominalCoverage) {
  int covered = 0;
  const int trials = 200;
  for (int seed = 0; seed < trials; ++seed) {
    const auto steps =
        make_steps(true_linear(), paper_geometry(), 6, 0.05e-3, static_cast<unsigned>(seed + 100));
    const SuspensionFitResult r = fit_suspension(steps, paper_geometry());
    ASSERT_TRUE(r.ok()) << r.error;
    const Estimate& c = r.calibration->linear.stiffness_n_per_m;
    covered += (c.low <= 30000.0 && 30000.0 <= c.high) ? 1 : 0;
  }
  EXPECT_GE(covered, 178);
  EXPECT_LE(covered, 198);
}

TEST(SuspensionFit, OneBadStepDoesNotBendTheFit) {
  const SuspensionParams truth = true_linear();
  auto steps = make_steps(truth, paper_geometry(), 9, 0.02e-3, 3);
  steps[7].deflection_m += 1.5e-3;  // 700 kg step reads 1.5 mm high (still increasing)
  const SuspensionFitResult robust = fit_suspension(steps, paper_geometry());
  ASSERT_TRUE(robust.ok()) << robust.error;
  const SuspensionCalibration& c = *robust.calibration;
  EXPECT_NEAR(c.linear.stiffness_n_per_m.value, 30000.0, 0.003 * 30000.0);
  EXPECT_TRUE(c.steps[7].outlier);
  for (std::size_t k = 0; k < c.steps.size(); ++k) {
    if (k != 7) {
      EXPECT_FALSE(c.steps[k].outlier) << k;
    }
  }
  EXPECT_FALSE(c.progressive.detected);
  EXPECT_DOUBLE_EQ(c.linear_range_kg, 800.0);  // the outlier does not cut the range short

  // The same data with an effectively quadratic loss (huge scale) are bent much more.
  SuspensionFitOptions squared;
  squared.robust_scale_mm = 1e6;
  const SuspensionFitResult plain = fit_suspension(steps, paper_geometry(), squared);
  ASSERT_TRUE(plain.ok());
  const double robust_err = std::abs(c.linear.stiffness_n_per_m.value - 30000.0);
  const double plain_err = std::abs(plain.calibration->linear.stiffness_n_per_m.value - 30000.0);
  EXPECT_GT(plain_err, 5.0 * robust_err);
  EXPECT_GT(plain_err, 0.005 * 30000.0);
}

TEST(SuspensionFit, OneBadStepBelowTheKneeDoesNotHideTheBumpStop) {
  auto steps = make_steps(true_progressive(), paper_geometry(), 9, 0.02e-3, 5);
  steps[2].deflection_m -= 1.0e-3;
  const SuspensionFitResult r = fit_suspension(steps, paper_geometry());
  ASSERT_TRUE(r.ok()) << r.error;
  const SuspensionCalibration& c = *r.calibration;
  ASSERT_TRUE(c.progressive.detected) << c.progressive.reason;
  EXPECT_TRUE(c.steps[2].outlier);
  EXPECT_NEAR(c.progressive.stiffness_n_per_m.value, 30000.0, 0.01 * 30000.0);
  EXPECT_NEAR(c.linear.stiffness_n_per_m.value, 30000.0, 0.01 * 30000.0);
  EXPECT_NEAR(c.progressive.knee_m.value, 0.042, 1e-3);
}

TEST(SuspensionFit, BadDataIsRejectedWithAClearMessage) {
  const LoadGeometry g = paper_geometry();
  auto steps = make_steps(true_linear(), g, 4, 0.0, 1);

  auto two = std::vector<BallastStep>(steps.begin(), steps.begin() + 2);
  SuspensionFitResult r = fit_suspension(two, g);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.error.find("at least three distinct loads"), std::string::npos) << r.error;

  auto flat = steps;
  flat[2].deflection_m = flat[1].deflection_m;
  r = fit_suspension(flat, g);
  EXPECT_NE(r.error.find("does not increase with the load"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("100 kg"), std::string::npos) << r.error;

  auto nan = steps;
  nan[1].deflection_m = std::nan("");
  r = fit_suspension(nan, g);
  EXPECT_NE(r.error.find("NaN"), std::string::npos) << r.error;

  auto dup = steps;
  dup[2].added_mass_kg = dup[1].added_mass_kg;
  r = fit_suspension(dup, g);
  EXPECT_NE(r.error.find("same added mass"), std::string::npos) << r.error;

  LoadGeometry bad = g;
  bad.cg_to_front_axle_m = 3.0;
  r = fit_suspension(steps, bad);
  EXPECT_NE(r.error.find("vehicle.cg_to_front_axle_m"), std::string::npos) << r.error;

  SuspensionFitOptions o;
  o.confidence = 1.5;
  r = fit_suspension(steps, g, o);
  EXPECT_NE(r.error.find("fit.confidence"), std::string::npos) << r.error;
}

TEST(SuspensionFit, ConfigSnippetLoadsBackThroughTheConfigLoader) {
  const auto steps = make_steps(true_progressive(), paper_geometry(), 9, 0.02e-3, 11);
  const SuspensionFitResult r = fit_suspension(steps, paper_geometry());
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_TRUE(r.calibration->progressive.detected);
  const std::string yaml = suspension_yaml(*r.calibration, {"test"});
  const std::string config =
      "vehicle:\n"
      "  empty_mass_kg: 1500\n  wheelbase_m: 2.7\n  cg_to_front_axle_m: 1.2\n"
      "  wheel_radius_m: 0.31\n  brake_gain_n_per_pa: 0.0033\n  steering_ratio: 15.5\n"
      "  cornering_stiffness_front_n_per_rad: 150000\n"
      "  cornering_stiffness_rear_n_per_rad: 170000\n" +
      yaml;
  const ConfigLoad loaded = load_config_text(config, "snippet");
  ASSERT_TRUE(loaded.ok()) << loaded.error << "\n" << yaml;
  const SuspensionParams& got = loaded.config->pipeline.suspension;
  const SuspensionParams want = r.calibration->suspension_params();
  auto rel = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); };
  EXPECT_TRUE(rel(got.stiffness_n_per_m, want.stiffness_n_per_m));
  EXPECT_TRUE(rel(got.empty_deflection_m, want.empty_deflection_m));
  EXPECT_TRUE(rel(got.progressive_knee_m, want.progressive_knee_m));
  EXPECT_TRUE(rel(got.progressive_rate_n_per_m2, want.progressive_rate_n_per_m2));
  EXPECT_EQ(got.linear_range_kg, want.linear_range_kg);
  EXPECT_EQ(got.calibrated_range_kg, 800.0);

  // Without a bump stop the knee is written as .inf and loads back as infinity.
  const auto lin =
      fit_suspension(make_steps(true_linear(), paper_geometry(), 5, 0.0, 1), paper_geometry());
  ASSERT_TRUE(lin.ok());
  const ConfigLoad lin_loaded = load_config_text(
      config.substr(0, config.find("# test")) + suspension_yaml(*lin.calibration), "lin");
  ASSERT_TRUE(lin_loaded.ok()) << lin_loaded.error;
  EXPECT_TRUE(std::isinf(lin_loaded.config->pipeline.suspension.progressive_knee_m));
}

// The mass check goes through the product's StaticInitializer; compare with eq. (3) by hand.
TEST(SuspensionFit, MassCheckMatchesEquationThreeAndTheProgressiveCurveStaysWithinOnePercent) {
  const LoadGeometry g = paper_geometry();
  const auto steps = make_steps(true_progressive(), g, 9, 0.02e-3, 13);
  const SuspensionFitResult r = fit_suspension(steps, g);
  ASSERT_TRUE(r.ok()) << r.error;
  VehicleParams v;
  v.empty_mass_kg = 1500.0;
  v.wheelbase_m = g.wheelbase_m;
  v.cg_to_front_axle_m = g.cg_to_front_axle_m;
  v.gravity_mps2 = g.gravity_mps2;
  const auto rows = mass_check(*r.calibration, v);
  ASSERT_EQ(rows.size(), 9u);
  const LinearFit& lin = r.calibration->linear;
  for (const MassCheckRow& row : rows) {
    const double by_hand = 1500.0 + 2.0 * 2.7 * lin.stiffness_n_per_m.value *
                                        (row.deflection_m - lin.zero_offset_m.value) /
                                        (1.2 * 9.80665);
    EXPECT_NEAR(row.linear_mass_kg, by_hand, 1e-6);
    EXPECT_NEAR(row.true_mass_kg, 1500.0 + row.added_mass_kg, 1e-12);
    EXPECT_LT(std::abs(row.progressive_error), 0.01) << row.added_mass_kg;
  }
  EXPECT_GT(std::abs(rows.back().linear_error), 0.03);  // the linear model saturates
  EXPECT_TRUE(rows.back().beyond_linear_range);

  // With the written curve, the static initialisation trusts loads up to the calibrated range
  // (800 kg) and flags heavier ones as uncertain (wider prior).
  // The ballast sits at the centre of gravity: eq. (3) reads it as it is.
  StaticInitParams at_cg;
  at_cg.payload_x_min_fraction = v.cg_to_front_axle_m / v.wheelbase_m;
  at_cg.payload_x_max_fraction = at_cg.payload_x_min_fraction;
  at_cg.payload_y_max_fraction = 0.0;
  const StaticInitializer init(v, r.calibration->suspension_params(), at_cg);
  const double z_800 = testing::deflection_for_force(true_progressive(), g.wheel_force_n(790.0));
  const double z_900 = testing::deflection_for_force(true_progressive(), g.wheel_force_n(900.0));
  EXPECT_FALSE(init.static_mass_for(z_800, 0.0).beyond_calibrated_range);
  const StaticMass heavy = init.static_mass_for(z_900, 0.0);
  EXPECT_TRUE(heavy.beyond_calibrated_range);
  EXPECT_NEAR(heavy.prior.mass_kg, 2400.0, 0.01 * 2400.0);  // the curve still extrapolates well
  EXPECT_EQ(heavy.prior.mass_std_kg, StaticInitParams{}.out_of_range_prior_std_kg);
}

}  // namespace
}  // namespace vmass::calibrate
