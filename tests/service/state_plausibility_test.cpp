// A saved state is checked before it is restored: a valid checksum does not make a mass of
// -5000 kg, a NaN or a covariance that is not one believable. Each refusal says why.
#include "vmass/service/state_plausibility.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "test_drive.hpp"
#include "vmass/config/config.hpp"

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
  return s;
}

TEST(StatePlausibility, ABelievableStateIsAccepted) {
  EXPECT_EQ(implausible_state(good_state(), params()), "");
}

TEST(StatePlausibility, EachImplausibleFieldIsRefusedWithItsReason) {
  const PipelineParams p = params();
  PipelineSnapshot s = good_state();
  s.nig_mean[0] = -5000.0;
  EXPECT_EQ(implausible_state(s, p), "Bayes mass -5000 kg outside [750, 7500] kg");
  s = good_state();
  s.prior.mass_kg = 1e9;
  EXPECT_EQ(implausible_state(s, p), "prior mass 1e+09 kg outside [750, 7500] kg");
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
  EXPECT_EQ(implausible_state(s, p), "RLS mass 0 kg outside [750, 7500] kg");
}

}  // namespace
}  // namespace vmass::service
