// A saved state is checked before it is restored: a valid checksum does not make a mass of
// -5000 kg, a NaN or a covariance that is not one believable. Each refusal says why.
#include "vmass/service/state_plausibility.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "test_drive.hpp"
#include "vmass/config/config.hpp"
#include "vmass/core/plausible_band.hpp"

namespace vmass::service {
namespace {

PipelineParams params() {
  const ConfigLoad c = load_config_text(test::test_config_yaml(), "t.yaml");
  EXPECT_TRUE(c.ok()) << c.error;
  return c.config->pipeline;
}

/// A believable Bayes state of the test car (empty 1500 kg): 1800 kg after 300 pairs.
PipelineSnapshot good_state() {
  PipelineSnapshot s;
  s.type = RegressorType::kBayes;
  s.has_prior = true;
  s.prior = MassPrior{1750.0, 60.0, 0.0, 300.0};
  s.pairs_used = 300;
  s.nig_mean[0] = 1800.0;
  s.nig_mean[1] = 12.0;
  s.nig_scaled_covariance[0] = 2e-3;
  s.nig_scaled_covariance[1] = s.nig_scaled_covariance[2] = 1e-5;
  s.nig_scaled_covariance[3] = 1e-2;
  s.nig_shape = 152.0;
  s.nig_scale = 1.5e6;
  s.blocks[0] = BlockCounters{4000, 500, 300, 20};
  s.learnt.log_scale = 0.03;  // one drive on a known mass taught a 3 % scale
  s.learnt.log_scale_var = 1.2e-4;
  s.learnt.evidence = 1;
  return s;
}

TEST(StatePlausibility, ABelievableStateIsAccepted) {
  EXPECT_EQ(implausible_state(good_state(), params()), "");
}

TEST(StatePlausibility, EachImplausibleFieldIsRefusedWithItsReason) {
  const PipelineParams p = params();
  PipelineSnapshot s = good_state();
  s.nig_mean[0] = -5000.0;
  EXPECT_EQ(implausible_state(s, p),
            "Bayes mass -5000 kg outside the plausible band [1350, 4500] kg");
  s = good_state();
  s.prior.mass_kg = 1e9;
  EXPECT_EQ(implausible_state(s, p),
            "prior mass 1e+09 kg outside the plausible band [1350, 4500] kg");
  s = good_state();
  s.nig_scale = std::nan("");
  EXPECT_EQ(implausible_state(s, p), "Bayes scale nan is not > 0");
  s = good_state();
  s.nig_scaled_covariance[1] = 1.0;
  EXPECT_EQ(implausible_state(s, p), "Bayes scaled covariance is not symmetric");
  s = good_state();
  s.nig_scaled_covariance[1] = s.nig_scaled_covariance[2] = 1.0;
  EXPECT_EQ(implausible_state(s, p), "Bayes scaled covariance is not positive semi-definite");
  s = good_state();
  s.blocks[1].accepted = 5;  // more accepted than candidates
  EXPECT_NE(implausible_state(s, p).find("block counters out of order"), std::string::npos);
  s = good_state();
  s.type = RegressorType::kRls;  // the RLS fields are all zero: no covariance
  EXPECT_EQ(implausible_state(s, p), "RLS mass 0 kg outside the plausible band [1350, 4500] kg");
}

// The band is the one the pipeline publishes in: a state it refuses was never published, and a
// mass just inside what it publishes is restored.
TEST(StatePlausibility, TheBandIsThePublishedOne) {
  const PipelineParams p = params();
  const MassBand band = plausible_mass_band(p.vehicle);
  PipelineSnapshot s = good_state();
  s.nig_mean[0] = band.high_kg;
  EXPECT_EQ(implausible_state(s, p), "");
  s.nig_mean[0] = std::nextafter(band.high_kg, 1e300);
  EXPECT_NE(implausible_state(s, p).find("outside the plausible band"), std::string::npos);
}

// A posterior narrower than any data could make it would publish a zero-width interval and
// never move again: refused, as are the degenerate shapes of it.
TEST(StatePlausibility, ADegenerateVarianceIsRefused) {
  const PipelineParams p = params();
  PipelineSnapshot s = good_state();
  s.nig_scaled_covariance[0] = 1e-30;
  s.nig_scaled_covariance[1] = s.nig_scaled_covariance[2] = 0.0;
  EXPECT_NE(implausible_state(s, p).find("Bayes mass std"), std::string::npos)
      << implausible_state(s, p);
  s = good_state();
  s.nig_scale = 1e-300;
  EXPECT_NE(implausible_state(s, p).find("below the floor"), std::string::npos)
      << implausible_state(s, p);
  s = good_state();
  s.type = RegressorType::kRls;
  s.rls_theta[0] = 1800.0;
  s.rls_covariance[0] = 1e-20;
  s.rls_covariance[3] = 1.0;
  EXPECT_NE(implausible_state(s, p).find("RLS mass std"), std::string::npos)
      << implausible_state(s, p);
  s.rls_covariance[0] = 25.0;  // 5 kg
  EXPECT_EQ(implausible_state(s, p), "");
}

// The standstill the load was measured in: a deflection of 5 m reads as millions of kg (eq. 3),
// and an infinite grade is no grade.
TEST(StatePlausibility, TheReferenceStandstillIsChecked) {
  const PipelineParams p = params();
  PipelineSnapshot s = good_state();
  s.has_reference = true;
  s.reference_deflection_m = p.suspension.empty_deflection_m + 0.01;
  s.reference_deflection_std_m = 1e-4;
  s.reference_grade_accel_mps2 = 0.1;
  EXPECT_EQ(implausible_state(s, p), "");
  s.reference_grade_accel_mps2 = std::nan("");  // unknown
  EXPECT_EQ(implausible_state(s, p), "");
  PipelineSnapshot bad = s;
  bad.reference_deflection_m = 5.0;
  EXPECT_NE(implausible_state(bad, p).find("reference deflection's static mass (eq. 3)"),
            std::string::npos)
      << implausible_state(bad, p);
  bad = s;
  bad.reference_grade_accel_mps2 = INFINITY;
  EXPECT_NE(implausible_state(bad, p).find("reference grade acceleration inf"), std::string::npos)
      << implausible_state(bad, p);
  bad = s;
  bad.reference_deflection_std_m = -1e-3;
  EXPECT_NE(implausible_state(bad, p).find("reference deflection std"), std::string::npos)
      << implausible_state(bad, p);
}

// What was learnt about the car and the known mass of the load are checked as the rest is.
TEST(StatePlausibility, TheLearntSectionAndTheKnownMassAreChecked) {
  const PipelineParams p = params();
  PipelineSnapshot s = good_state();
  s.known_mass = KnownMass{true, 1800.0, 9.0, 1.0};
  s.pair_scale = std::exp(0.03);
  EXPECT_EQ(implausible_state(s, p), "");
  PipelineSnapshot bad = s;
  bad.learnt.log_scale = 0.6;  // 82 %: a wrong config, not a scale error
  EXPECT_NE(implausible_state(bad, p).find("learnt scale log"), std::string::npos)
      << implausible_state(bad, p);
  bad = s;
  bad.learnt.log_scale_var = 0.0;
  EXPECT_NE(implausible_state(bad, p).find("learnt scale variance"), std::string::npos);
  bad = s;
  bad.known_mass.mass_kg = 90000.0;
  EXPECT_NE(implausible_state(bad, p).find("known mass 90000 kg outside"), std::string::npos)
      << implausible_state(bad, p);
  bad = s;
  bad.pair_scale = 2.0;
  EXPECT_NE(implausible_state(bad, p).find("pair scale 2"), std::string::npos)
      << implausible_state(bad, p);
  // A state from before the learnt section: nothing of it is checked, nothing restored.
  bad = s;
  bad.learnt = LearntScaleState{};
  bad.learnt_saved = false;
  EXPECT_EQ(implausible_state(bad, p), "");
}

}  // namespace
}  // namespace vmass::service
