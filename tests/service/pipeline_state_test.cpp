// What leaves the estimator is believable: one band (plausible_band.hpp) at publish, at save and
// at restore. A config whose suspension reads the load as a negative mass (an empty deflection
// written as a ride height) publishes no mass, with the reason, and nothing is saved; a state
// saved at a negative time is refused at the next start.
#include "vmass/service/pipeline_state.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "test_drive.hpp"
#include "vmass/config/config.hpp"
#include "vmass/service/state_store.hpp"

namespace vmass::service {
namespace {

PipelineParams params_with(const std::string& suspension_line) {
  std::string yaml = test::test_config_yaml();
  const std::string anchor = "  stiffness_n_per_m: 30000.0\n";
  yaml.replace(yaml.find(anchor), anchor.size(), anchor + suspension_line);
  const ConfigLoad c = load_config_text(yaml, "t.yaml");
  EXPECT_TRUE(c.ok()) << c.error;
  return c.config->pipeline;
}

std::string temp_path(const char* name) {
  return ::testing::TempDir() + "vmass_pipeline_state_" + std::to_string(::getpid()) + "_" + name;
}

/// Runs the test drive; returns the pipeline after it (flushed, as the daemon saves it).
std::unique_ptr<Pipeline> drive(const PipelineParams& params, bool* any_mass,
                                bool* any_implausible_reason) {
  auto pipeline = std::make_unique<Pipeline>(params);
  *any_mass = *any_implausible_reason = false;
  for (const Sample& s : test::make_drive(test::DriveSpec{})) {
    pipeline->step(s);
    const Estimate& e = pipeline->estimate();
    *any_mass = *any_mass || e.mass_known;
    *any_implausible_reason = *any_implausible_reason || e.reason == StatusReason::kMassImplausible;
  }
  pipeline->flush();
  return pipeline;
}

TEST(PipelineState, AMassOutsideTheBandIsNeitherPublishedNorSaved) {
  bool any_mass = false, implausible = false;
  auto pipeline = drive(params_with("  empty_deflection_m: 0.35\n"), &any_mass, &implausible);
  EXPECT_FALSE(any_mass);
  EXPECT_TRUE(implausible);
  const Estimate& e = pipeline->estimate();
  EXPECT_EQ(e.status, EstimateStatus::kDegraded);
  EXPECT_NE(e.describe_reason().find("kg below the plausible band"), std::string::npos)
      << e.describe_reason();
  const std::string path = temp_path("implausible.state");
  std::remove(path.c_str());
  std::string error;
  EXPECT_EQ(save_pipeline_state(path, pipeline->snapshot(), e.time_us, pipeline->params(), &error),
            StateSave::kNotBelievable);
  EXPECT_NE(error.find("outside the plausible band"), std::string::npos) << error;
  EXPECT_NE(::access(path.c_str(), F_OK), 0) << "an unbelievable state was written";
}

TEST(PipelineState, WhatIsSavedIsRestoredAndANegativeTimeIsNot) {
  bool any_mass = false, implausible = false;
  const PipelineParams params = params_with("");
  auto pipeline = drive(params, &any_mass, &implausible);
  ASSERT_TRUE(any_mass);
  EXPECT_FALSE(implausible);
  const std::string path = temp_path("good.state");
  std::string error;
  const TimeUs end_us = pipeline->estimate().time_us;
  ASSERT_EQ(save_pipeline_state(path, pipeline->snapshot(), end_us, params, &error),
            StateSave::kSaved)
      << error;
  Pipeline restored(params);
  const StateRestore r = restore_pipeline_state(path, restored);
  EXPECT_TRUE(r.restored) << r.message;
  EXPECT_DOUBLE_EQ(restored.estimate().mass_kg, pipeline->estimate().mass_kg);

  // A file written with a negative time (by hand, or by a build that took one): refused.
  SavedState state;
  state.snapshot = pipeline->snapshot();
  state.saved_time_us = -50'000'000;
  state.fingerprint = state_fingerprint(params);
  ASSERT_TRUE(save_state_file(path, state, &error)) << error;
  Pipeline refused(params);
  const StateRestore n = restore_pipeline_state(path, refused);
  EXPECT_FALSE(n.restored);
  EXPECT_NE(n.message.find("negative time"), std::string::npos) << n.message;
  EXPECT_EQ(save_pipeline_state(path, pipeline->snapshot(), -1, params, &error),
            StateSave::kNotBelievable);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace vmass::service
