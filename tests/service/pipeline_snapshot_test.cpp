// Pipeline::snapshot()/restore() and the state file: round trips, atomic writes, refusal of
// corrupt or foreign files, and the load-change check after a restore.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "test_drive.hpp"
#include "vmass/config/config.hpp"
#include "vmass/service/pipeline_state.hpp"
#include "vmass/service/state_plausibility.hpp"
#include "vmass/service/state_store.hpp"

namespace vmass {
namespace {

namespace fs = std::filesystem;
using service::SavedState;

PipelineParams test_params(const std::string& type = "bayes") {
  ConfigLoad c = load_config_text(test::test_config_yaml("", type));
  EXPECT_TRUE(c.ok()) << c.error;
  return c.config->pipeline;
}

/// Runs the drive through a pipeline and returns it.
void drive(Pipeline& p, const std::vector<Sample>& samples) {
  for (const Sample& s : samples) p.step(s);
}

/// Same drive shifted by `offset_us` (so a second drive continues the time line).
std::vector<Sample> shifted(std::vector<Sample> samples, TimeUs offset_us) {
  for (Sample& s : samples) s.time_us += offset_us;
  return samples;
}

/// `text` (a state file) as an older format wrote it: version `version`, without the lines of
/// `dropped`, with its own checksum. "" when a dropped key is not in it.
std::string as_older_format(const std::string& text, int version,
                            std::initializer_list<const char*> dropped) {
  std::string out = text.substr(0, text.find("checksum "));
  out.replace(0, out.find('\n'), "vmass-state " + std::to_string(version));
  for (const char* key : dropped) {
    const std::size_t at = out.find(std::string("\n") + key + " ");
    if (at == std::string::npos) return "";
    out.erase(at + 1, out.find('\n', at + 1) - at);
  }
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : out) h = (h ^ c) * 0x100000001b3ull;
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return out + "checksum " + hex + "\n";
}

void expect_same(const PipelineSnapshot& a, const PipelineSnapshot& b) {
  EXPECT_EQ(a.type, b.type);
  EXPECT_EQ(a.has_prior, b.has_prior);
  EXPECT_EQ(a.prior.mass_kg, b.prior.mass_kg);
  EXPECT_EQ(a.prior.mass_std_kg, b.prior.mass_std_kg);
  EXPECT_EQ(a.pairs_used, b.pairs_used);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(a.rls_theta[i], b.rls_theta[i]);
    EXPECT_EQ(a.nig_mean[i], b.nig_mean[i]);
  }
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(a.rls_covariance[i], b.rls_covariance[i]);
    EXPECT_EQ(a.nig_scaled_covariance[i], b.nig_scaled_covariance[i]);
  }
  EXPECT_EQ(a.nig_shape, b.nig_shape);
  EXPECT_EQ(a.nig_scale, b.nig_scale);
  EXPECT_EQ(a.has_reference, b.has_reference);
  EXPECT_EQ(a.reference_deflection_m, b.reference_deflection_m);
  EXPECT_EQ(a.reference_deflection_std_m, b.reference_deflection_std_m);
  EXPECT_TRUE(
      a.reference_grade_accel_mps2 == b.reference_grade_accel_mps2 ||
      (std::isnan(a.reference_grade_accel_mps2) && std::isnan(b.reference_grade_accel_mps2)));
  for (int b_ = 0; b_ < kBlockCount; ++b_) {
    EXPECT_EQ(a.blocks[b_].ticks, b.blocks[b_].ticks);
    EXPECT_EQ(a.blocks[b_].accepted, b.blocks[b_].accepted);
  }
  EXPECT_EQ(a.learnt_saved, b.learnt_saved);
  EXPECT_EQ(a.learnt.log_scale, b.learnt.log_scale);
  EXPECT_EQ(a.learnt.log_scale_var, b.learnt.log_scale_var);
  EXPECT_EQ(a.learnt.evidence, b.learnt.evidence);
  EXPECT_EQ(a.learnt.changes, b.learnt.changes);
  EXPECT_EQ(a.learnt.pending_outlier_sign, b.learnt.pending_outlier_sign);
  EXPECT_EQ(a.learnt.pending_log_scale, b.learnt.pending_log_scale);
  EXPECT_EQ(a.learnt.pending_var, b.learnt.pending_var);
  EXPECT_EQ(a.learnt.anchor_weight, b.learnt.anchor_weight);
  EXPECT_EQ(a.learnt.anchor_weighted_log_scale, b.learnt.anchor_weighted_log_scale);
  EXPECT_EQ(a.learnt.anchor_weighted_common_std, b.learnt.anchor_weighted_common_std);
  EXPECT_EQ(a.learnt.anchors, b.learnt.anchors);
  EXPECT_EQ(a.learnt.tyre_changes, b.learnt.tyre_changes);
  const auto same_launches = [](const LaunchSums& x, const LaunchSums& y) {
    EXPECT_EQ(x.count, y.count);
    EXPECT_EQ(x.sum, y.sum);
    EXPECT_EQ(x.sum_sq, y.sum_sq);
  };
  for (std::size_t k = 0; k < kSpanKinds; ++k) {
    same_launches(a.tyre_watch.settled.kind[k], b.tyre_watch.settled.kind[k]);
    same_launches(a.tyre_watch.drive.kind[k], b.tyre_watch.drive.kind[k]);
    EXPECT_EQ(a.tyre_watch.window_drives, b.tyre_watch.window_drives);
    for (long i = 0; i < a.tyre_watch.window_drives; ++i) {
      same_launches(a.tyre_watch.window[std::size_t(i)].kind[k],
                    b.tyre_watch.window[std::size_t(i)].kind[k]);
    }
  }
  EXPECT_EQ(a.tyre_watch.spread_sum_sq, b.tyre_watch.spread_sum_sq);
  EXPECT_EQ(a.tyre_watch.spread_dof, b.tyre_watch.spread_dof);
  EXPECT_EQ(a.tyre_watch.changes, b.tyre_watch.changes);
  EXPECT_EQ(a.learnt.evidence_since_tyres, b.learnt.evidence_since_tyres);
  EXPECT_EQ(a.static_anchor_pending, b.static_anchor_pending);
  EXPECT_EQ(a.static_anchor.log_scale, b.static_anchor.log_scale);
  EXPECT_EQ(a.static_anchor.variance, b.static_anchor.variance);
  EXPECT_EQ(a.static_anchor.common_std, b.static_anchor.common_std);
  EXPECT_EQ(a.pair_scale, b.pair_scale);
  EXPECT_EQ(a.known_mass.active, b.known_mass.active);
  EXPECT_EQ(a.known_mass.mass_kg, b.known_mass.mass_kg);
  EXPECT_EQ(a.known_mass.std_kg, b.known_mass.std_kg);
  EXPECT_EQ(a.known_mass.scale_used, b.known_mass.scale_used);
  EXPECT_EQ(a.gear_masses_saved, b.gear_masses_saved);
  EXPECT_EQ(a.gear_masses.gears, b.gear_masses.gears);
  EXPECT_EQ(a.gear_masses.drives, b.gear_masses.drives);
  EXPECT_EQ(a.gear_masses.correction_kg, b.gear_masses.correction_kg);
  EXPECT_EQ(a.gear_masses.covariance_kg2, b.gear_masses.covariance_kg2);
  EXPECT_EQ(a.gear_masses.reference_share_per_kg, b.gear_masses.reference_share_per_kg);
  EXPECT_EQ(a.gear_masses.reference_applied, b.gear_masses.reference_applied);
  EXPECT_EQ(a.gear_masses.reference_precision, b.gear_masses.reference_precision);
  EXPECT_EQ(a.pair_term_fit_applies, b.pair_term_fit_applies);
  EXPECT_EQ(a.pair_term_sums.normal, b.pair_term_sums.normal);
  EXPECT_EQ(a.pair_term_sums.moment, b.pair_term_sums.moment);
  EXPECT_EQ(a.pair_term_sums.pairs, b.pair_term_sums.pairs);
}

class PipelineSnapshotTest : public ::testing::TestWithParam<const char*> {};

TEST_P(PipelineSnapshotTest, RestoreGivesBackTheSameBelief) {
  const PipelineParams params = test_params(GetParam());
  const test::DriveSpec spec;
  Pipeline original(params);
  drive(original, test::make_drive(spec));
  original.flush();  // as the daemon before its final save: the open batch is published too
  const PipelineSnapshot saved = original.snapshot();
  ASSERT_TRUE(saved.has_prior);
  ASSERT_TRUE(saved.has_reference);
  ASSERT_GT(saved.pairs_used, 50) << "the drive must have produced events";
  // Reference deflection = the drive's (eq. 3 at the true mass).
  EXPECT_NEAR(saved.reference_deflection_m, test::deflection_for_mass(spec, spec.mass_kg), 1e-12);

  Pipeline restored(params);
  ASSERT_TRUE(restored.restore(saved));
  expect_same(restored.snapshot(), saved);
  EXPECT_EQ(restored.estimate().mass_kg, original.estimate().mass_kg);
  EXPECT_EQ(restored.estimate().ci_low_kg, original.estimate().ci_low_kg);
  EXPECT_EQ(restored.estimate().reason, StatusReason::kRestored);
  EXPECT_TRUE(restored.estimate().has_mass());
}

TEST_P(PipelineSnapshotTest, SameLoadAfterRestartKeepsTheEstimate) {
  const PipelineParams params = test_params(GetParam());
  test::DriveSpec spec;
  Pipeline original(params);
  const std::vector<Sample> first = test::make_drive(spec);
  drive(original, first);
  original.flush();  // as the daemon before its final save: the open batch is published too
  const PipelineSnapshot saved = original.snapshot();

  // Restart: the next drive starts standing with the same load.
  Pipeline restored(params);
  ASSERT_TRUE(restored.restore(saved));
  const std::vector<Sample> second = shifted(test::make_drive(spec), first.back().time_us + 10'000);
  bool reinitialised = false;
  for (int i = 0; i < 500; ++i) {  // the whole first standstill (5 s): window completes at 3 s
    reinitialised |= restored.step(second[static_cast<std::size_t>(i)]).reinitialised;
  }
  EXPECT_FALSE(reinitialised);
  EXPECT_EQ(restored.estimate().pairs_used, saved.pairs_used);
  EXPECT_NE(restored.estimate().reason, StatusReason::kLoadChanged);
}

TEST_P(PipelineSnapshotTest, LoadChangedWhileOffRestartsFromTheNewStaticMass) {
  const PipelineParams params = test_params(GetParam());
  test::DriveSpec spec;
  Pipeline original(params);
  const std::vector<Sample> first = test::make_drive(spec);
  drive(original, first);
  original.flush();  // as the daemon before its final save: the open batch is published too
  const PipelineSnapshot saved = original.snapshot();

  // While the daemon was off, 300 kg were loaded.
  test::DriveSpec loaded = spec;
  loaded.mass_kg = spec.mass_kg + 300.0;
  Pipeline restored(params);
  ASSERT_TRUE(restored.restore(saved));
  const std::vector<Sample> second =
      shifted(test::make_drive(loaded), first.back().time_us + 10'000);
  bool reinitialised = false;
  for (int i = 0; i < 500; ++i) {
    reinitialised |= restored.step(second[static_cast<std::size_t>(i)]).reinitialised;
  }
  EXPECT_TRUE(reinitialised);
  EXPECT_EQ(restored.estimate().pairs_used, 0);
  EXPECT_EQ(restored.estimate().reason, StatusReason::kLoadChanged);
  // What the first drive taught is kept and shifted by the load eq. (3) saw added (corrected
  // for where payload may sit: the static initialiser's mean over-read factor).
  const StaticInitializer init(params.vehicle, params.suspension, params.estimator.static_init);
  EXPECT_NEAR(restored.estimate().initial_mass_kg,
              original.estimate().mass_kg + init.payload_factor_mean() * 300.0, 1.0);
}

// A save in the middle of a drive (the daemon's periodic one) keeps the pairs of the open Bayes
// batch: the saved belief is the published one, and a restart publishes the same mass.
TEST_P(PipelineSnapshotTest, AMidDriveSaveKeepsWhatTheEstimatePublished) {
  const PipelineParams params = test_params(GetParam());
  Pipeline original(params);
  drive(original, test::make_drive(test::DriveSpec{}));
  const long published_pairs = original.estimate().pairs_used;
  ASSERT_GT(published_pairs, 0);
  if (params.estimator.type == RegressorType::kBayes) {
    ASSERT_NE(published_pairs % params.estimator.bayes.batch_size, 0)
        << "the drive must end with a batch open";
  }
  const PipelineSnapshot saved = original.snapshot();
  EXPECT_EQ(saved.pairs_used, published_pairs);

  Pipeline restored(params);
  ASSERT_TRUE(restored.restore(saved));
  EXPECT_EQ(restored.estimate().pairs_used, original.estimate().pairs_used);
  EXPECT_DOUBLE_EQ(restored.estimate().mass_kg, original.estimate().mass_kg);
  EXPECT_DOUBLE_EQ(restored.estimate().ci_high_kg, original.estimate().ci_high_kg);
}

INSTANTIATE_TEST_SUITE_P(BothRegressors, PipelineSnapshotTest, ::testing::Values("bayes", "rls"));

TEST(PipelineRestore, RefusesWhatDoesNotFitAndChangesNothing) {
  const PipelineParams params = test_params("bayes");
  Pipeline p(params);
  drive(p, test::make_drive(test::DriveSpec{}));
  const PipelineSnapshot good = p.snapshot();

  Pipeline fresh(params);
  const PipelineSnapshot before = fresh.snapshot();
  PipelineSnapshot other_type = good;
  other_type.type = RegressorType::kRls;
  EXPECT_FALSE(fresh.restore(other_type));
  PipelineSnapshot no_prior = good;
  no_prior.has_prior = false;
  EXPECT_FALSE(fresh.restore(no_prior));
  PipelineSnapshot nan_posterior = good;
  nan_posterior.nig_mean[0] = std::nan("");
  EXPECT_FALSE(fresh.restore(nan_posterior));
  PipelineSnapshot indefinite = good;
  indefinite.nig_scaled_covariance[1] = indefinite.nig_scaled_covariance[2] = 1e9;
  EXPECT_FALSE(fresh.restore(indefinite));
  expect_same(fresh.snapshot(), before);
  EXPECT_FALSE(fresh.estimate().has_mass());
}

// A state saved before any settled standstill at its load (no reference deflection) is restored:
// a restart within the drive goes on with it; after a power cycle the next standstill's static
// mass is the start, as on a first drive. What yesterday's standstill reading anchored of the
// scale (StaticAnchor) carries over; the load does not.
TEST(PipelineRestore, WithoutAReferenceTheNextDrivesStandstillGivesTheStart) {
  const PipelineParams params = test_params("bayes");
  Pipeline p(params);
  drive(p, test::make_drive(test::DriveSpec{}));
  PipelineSnapshot saved = p.snapshot();
  saved.has_reference = false;

  Pipeline next_day(params);
  ASSERT_TRUE(next_day.restore(saved));
  test::DriveSpec heavier;
  heavier.mass_kg = 2100.0;
  std::vector<Sample> samples = test::make_drive(heavier);
  for (Sample& s : samples) s.time_us += 86'400'000'000;  // a day later
  drive(next_day, samples);
  Pipeline fresh(params);
  drive(fresh, samples);
  EXPECT_EQ(next_day.estimate().prior_reason, StatusReason::kStaticInitialised);
  EXPECT_EQ(next_day.estimate().initial_mass_kg, fresh.estimate().initial_mass_kg);
  // Yesterday's reading (a load whose position the prior spreads) against its pairs: weak
  // evidence, the kerb mass's share never averaged away.
  EXPECT_TRUE(saved.static_anchor_pending);
  EXPECT_GT(saved.static_anchor.variance, 0.0);
  EXPECT_GT(saved.static_anchor.common_std, 0.0);
  EXPECT_EQ(next_day.learnt_scale().state().anchors, 1);
  EXPECT_EQ(fresh.learnt_scale().state().anchors, 0);
  EXPECT_GT(next_day.learnt_scale().relative_std(), saved.static_anchor.common_std / 2.0);
  EXPECT_NEAR(next_day.learnt_scale().scale(), 1.0, 2.0 * next_day.learnt_scale().relative_std());
  EXPECT_NEAR(next_day.estimate().mass_kg, heavier.mass_kg, 0.03 * heavier.mass_kg);
  EXPECT_LE(next_day.estimate().ci_low_kg, heavier.mass_kg);
  EXPECT_GE(next_day.estimate().ci_high_kg, heavier.mass_kg);
}

// ------------------------------------------------------------------------------ state file

class StateFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vmass_state_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const PipelineParams params = test_params("bayes");
    Pipeline p(params);
    drive(p, test::make_drive(test::DriveSpec{}));
    state_.snapshot = p.snapshot();
    state_.saved_time_us = 60'000'000;
    state_.fingerprint = service::state_fingerprint(params);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  fs::path dir_;
  SavedState state_;
};

TEST_F(StateFileTest, TextRoundTripIsExact) {
  SavedState back;
  std::string error;
  ASSERT_TRUE(service::parse_state(service::format_state(state_), &back, &error)) << error;
  EXPECT_EQ(back.fingerprint, state_.fingerprint);
  EXPECT_EQ(back.saved_time_us, state_.saved_time_us);
  expect_same(back.snapshot, state_.snapshot);
}

TEST_F(StateFileTest, EveryReasonABeliefStartsFromIsReadBack) {
  // A car without a load sensor saves no_load_sensor (8, after restored in the enumeration): a
  // range check up to restored refused its file, and the car began again at every restart.
  for (const StatusReason reason :
       {StatusReason::kStaticInitialised, StatusReason::kLoadChanged, StatusReason::kNoStaticPrior,
        StatusReason::kRestored, StatusReason::kNoLoadSensor}) {
    SavedState state = state_;
    state.snapshot.prior_reason = reason;
    SavedState back;
    std::string error;
    ASSERT_TRUE(service::parse_state(service::format_state(state), &back, &error))
        << reason_name(reason) << ": " << error;
    EXPECT_EQ(back.snapshot.prior_reason, reason);
  }
  SavedState suspected = state_;
  suspected.snapshot.prior_reason = StatusReason::kLoadChangeSuspected;  // not a prior's reason
  SavedState back;
  std::string error;
  EXPECT_FALSE(service::parse_state(service::format_state(suspected), &back, &error));
  EXPECT_NE(error.find("prior_reason"), std::string::npos) << error;
}

TEST_F(StateFileTest, AtomicWriteReplacesAndLeavesNoTemporary) {
  const std::string p = path("vmassd.state");
  std::string error;
  ASSERT_TRUE(service::save_state_file(p, state_, &error)) << error;
  SavedState second = state_;
  second.saved_time_us += 1;
  ASSERT_TRUE(service::save_state_file(p, second, &error)) << error;
  EXPECT_FALSE(fs::exists(p + ".tmp"));
  const service::StateLoad loaded = service::load_state_file(p, state_.fingerprint);
  ASSERT_EQ(loaded.status, service::StateLoadStatus::kLoaded) << loaded.error;
  EXPECT_EQ(loaded.state.saved_time_us, second.saved_time_us);
  expect_same(loaded.state.snapshot, state_.snapshot);
}

TEST_F(StateFileTest, FailedWriteKeepsThePreviousFile) {
  const std::string p = path("vmassd.state");
  std::string error;
  ASSERT_TRUE(service::save_state_file(p, state_, &error)) << error;
  const std::string before = read(p);
  // The temporary cannot be created: a directory is in its way.
  fs::create_directories(p + ".tmp");
  SavedState other = state_;
  other.saved_time_us = 1;
  EXPECT_FALSE(service::save_state_file(p, other, &error));
  EXPECT_NE(error.find(".tmp"), std::string::npos) << error;
  EXPECT_EQ(read(p), before);
}

TEST_F(StateFileTest, CorruptTruncatedOrForeignFilesAreRejected) {
  const std::string text = service::format_state(state_);
  const std::string p = path("vmassd.state");

  EXPECT_EQ(service::load_state_file(path("absent"), state_.fingerprint).status,
            service::StateLoadStatus::kMissing);

  ASSERT_TRUE(test::write_text(p, text.substr(0, text.size() / 2)));  // torn write
  service::StateLoad r = service::load_state_file(p, state_.fingerprint);
  EXPECT_EQ(r.status, service::StateLoadStatus::kRejected);

  std::string flipped = text;
  flipped[text.find("nig_mean_0 ") + 11] ^= 1;  // one digit changed
  ASSERT_TRUE(test::write_text(p, flipped));
  r = service::load_state_file(p, state_.fingerprint);
  EXPECT_EQ(r.status, service::StateLoadStatus::kRejected);
  EXPECT_NE(r.error.find("checksum"), std::string::npos) << r.error;

  ASSERT_TRUE(test::write_text(p, text));
  r = service::load_state_file(p, state_.fingerprint ^ 1);
  EXPECT_EQ(r.status, service::StateLoadStatus::kRejected);
  EXPECT_NE(r.error.find("parameters"), std::string::npos) << r.error;
  EXPECT_EQ(service::load_state_file(p, state_.fingerprint).status,
            service::StateLoadStatus::kLoaded);
}

// Format version 2 carries what was learnt about the car and the known mass; a version-1 file
// (before them) still restores its mass and leaves the pipeline's own learnt belief alone.
TEST_F(StateFileTest, TheLearntSectionRoundTripsAndAVersionOneFileStillLoads) {
  SavedState learnt = state_;
  learnt.snapshot.learnt = LearntScaleState{0.0312, 1.7e-4, 2, 0, 1, -0.05, 2e-4};
  learnt.snapshot.pair_scale = 1.031;
  learnt.snapshot.known_mass = KnownMass{true, 1712.5, 8.5, 1.031};
  learnt.learnt_fingerprint = 77;
  SavedState back;
  std::string error;
  ASSERT_TRUE(service::parse_state(service::format_state(learnt), &back, &error)) << error;
  expect_same(back.snapshot, learnt.snapshot);
  EXPECT_EQ(back.learnt_fingerprint, 77u);

  // The same state as version 1 wrote it: no learnt section, its own checksum.
  std::string v1 = service::format_state(state_);
  v1 = v1.substr(0, v1.find("learnt_fingerprint "));
  v1.replace(0, v1.find('\n'), "vmass-state 1");
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : v1) h = (h ^ c) * 0x100000001b3ull;
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  v1 += std::string("checksum ") + hex + "\n";
  ASSERT_TRUE(service::parse_state(v1, &back, &error)) << error;
  EXPECT_FALSE(back.snapshot.learnt_saved);
  EXPECT_EQ(back.snapshot.nig_mean[0], state_.snapshot.nig_mean[0]);
}

// Format version 3 added the learnt gear masses, version 4 their reference relative to the mass,
// 5 the static anchors, 6 the tyre changes. A version-2 file (before them) and a version-3 one
// (whose reference was in kg) still load their learnt scale and leave the pipeline's own gear
// masses alone.
TEST_F(StateFileTest, TheLearntSectionsRoundTripAndOlderFormatsStillLoad) {
  SavedState geared = state_;
  GearMassesState& g = geared.snapshot.gear_masses;
  g.gears = 3;
  g.drives = 4;
  g.correction_kg = {-412.25, -80.5, 3.125};
  g.reference_share_per_kg = {0.25, 0.5, 0.125};
  g.reference_applied = -0.0625;
  g.reference_precision = 3125.5;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      g.covariance_kg2[std::size_t(i) * kMaxLearntGears + std::size_t(j)] =
          i == j ? 900.0 + i : 0.1 * (i + j);
  }
  geared.snapshot.learnt = LearntScaleState{0.0312, 1.7e-4, 2, 0, 1, -0.05, 2e-4};
  LearntScaleState& anchors = geared.snapshot.learnt;
  anchors.anchor_weight = 2500.25;
  anchors.anchor_weighted_log_scale = 62.5;
  anchors.anchor_weighted_common_std = 50.125;
  anchors.anchors = 3;
  anchors.tyre_changes = 1;
  anchors.evidence_since_tyres = 1;
  geared.snapshot.static_anchor_pending = true;
  geared.snapshot.static_anchor = AnchorObservation{0.0275, 6.25e-4, 0.0234375};
  const std::string text = service::format_state(geared);
  SavedState back;
  std::string error;
  ASSERT_TRUE(service::parse_state(text, &back, &error)) << error;
  expect_same(back.snapshot, geared.snapshot);

  // The same state as version 2 wrote it: no gear section, its own checksum.
  std::string v2 = text.substr(0, text.find("learnt_gears "));
  v2.replace(0, v2.find('\n'), "vmass-state 2");
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : v2) h = (h ^ c) * 0x100000001b3ull;
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  ASSERT_TRUE(service::parse_state(v2 + "checksum " + hex + "\n", &back, &error)) << error;
  EXPECT_TRUE(back.snapshot.learnt_saved);
  EXPECT_EQ(back.snapshot.learnt.log_scale, 0.0312);
  EXPECT_FALSE(back.snapshot.gear_masses_saved);

  // Version 3: its gear section is not taken.
  std::string v3 = text.substr(0, text.find("checksum "));
  v3.replace(0, v3.find('\n'), "vmass-state 3");
  h = 0xcbf29ce484222325ull;
  for (unsigned char c : v3) h = (h ^ c) * 0x100000001b3ull;
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  ASSERT_TRUE(service::parse_state(v3 + "checksum " + hex + "\n", &back, &error)) << error;
  EXPECT_EQ(back.snapshot.learnt.log_scale, 0.0312);
  EXPECT_FALSE(back.snapshot.gear_masses_saved);

  // Version 4: no static anchors (none taken, none pending).
  const std::string v4 = as_older_format(
      text, 4,
      {"learnt_anchor_weight", "learnt_anchor_weighted_log_scale",
       "learnt_anchor_weighted_common_std", "learnt_anchors", "static_anchor_pending",
       "static_anchor_log_scale", "static_anchor_variance", "static_anchor_common_std"});
  ASSERT_FALSE(v4.empty());
  ASSERT_TRUE(service::parse_state(v4, &back, &error)) << error;
  EXPECT_TRUE(back.snapshot.gear_masses_saved);
  EXPECT_EQ(back.snapshot.learnt.log_scale, 0.0312);
  EXPECT_EQ(back.snapshot.learnt.anchors, 0);
  EXPECT_EQ(back.snapshot.learnt.anchor_weight, 0.0);
  EXPECT_FALSE(back.snapshot.static_anchor_pending);

  // Version 5: no tyre change; every known mass counts as one since the tyres.
  const std::string v5 =
      as_older_format(text, 5, {"learnt_tyre_changes", "learnt_evidence_since_tyres"});
  ASSERT_FALSE(v5.empty());
  ASSERT_TRUE(service::parse_state(v5, &back, &error)) << error;
  EXPECT_EQ(back.snapshot.learnt.anchors, 3);
  EXPECT_EQ(back.snapshot.learnt.tyre_changes, 0);
  EXPECT_EQ(back.snapshot.learnt.evidence_since_tyres, 2);

  // A gear line one number short names its key.
  std::string short_row = text.substr(0, text.find("checksum "));
  const std::size_t row = short_row.find("learnt_gear_correction_kg ");
  short_row.erase(short_row.find(' ', row + 27),
                  short_row.find('\n', row) - short_row.find(' ', row + 27));
  h = 0xcbf29ce484222325ull;
  for (unsigned char c : short_row) h = (h ^ c) * 0x100000001b3ull;
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  EXPECT_FALSE(service::parse_state(short_row + "checksum " + hex + "\n", &back, &error));
  EXPECT_NE(error.find("learnt_gear_correction_kg"), std::string::npos) << error;
}

// Format version 7 added the current load's pair-term fit (PairTermSums): it round-trips; a
// version-6 file loads without it (the fit does not apply to the restored load); sums that no
// pairs could have summed to are named.
TEST_F(StateFileTest, ThePairTermFitRoundTripsAndAVersionSixFileStillLoads) {
  SavedState fitted = state_;
  fitted.snapshot.pair_term_fit_applies = true;
  PairTermSumsState& sums = fitted.snapshot.pair_term_sums;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      sums.normal[4 * std::size_t(r) + std::size_t(c)] = r == c ? 10.0 + r : 0.125 * (r + c + 1);
    }
    sums.moment[std::size_t(r)] = 1650.5 * (r + 1);
  }
  sums.pairs = 4321;
  const std::string text = service::format_state(fitted);
  SavedState back;
  std::string error;
  ASSERT_TRUE(service::parse_state(text, &back, &error)) << error;
  expect_same(back.snapshot, fitted.snapshot);

  const std::string v6 = as_older_format(
      text, 6,
      {"pair_term_fit_applies", "pair_term_pairs", "pair_term_normal", "pair_term_moment"});
  ASSERT_FALSE(v6.empty());
  ASSERT_TRUE(service::parse_state(v6, &back, &error)) << error;
  EXPECT_FALSE(back.snapshot.pair_term_fit_applies);
  EXPECT_EQ(back.snapshot.pair_term_sums.pairs, 0);

  const PipelineParams params = test_params("bayes");
  PipelineSnapshot skewed = fitted.snapshot;
  skewed.pair_term_sums.normal[1] += 1.0;
  EXPECT_NE(service::implausible_state(skewed, params).find("pair_term_normal"), std::string::npos);
  Pipeline pipeline(params);
  EXPECT_FALSE(pipeline.restore(skewed));
}

// Format version 8 added the launches' log s (TyreWatchState): it round-trips; a version-7 file
// loads with nothing watched; sums no launches could have summed to are named.
TEST_F(StateFileTest, TheTyreWatchRoundTripsAndAVersionSevenFileStillLoads) {
  SavedState watched = state_;
  TyreWatchState& t = watched.snapshot.tyre_watch;
  t.settled.kind[0] = LaunchSums{12.0, 0.096, 0.0009};
  t.settled.kind[1] = LaunchSums{7.0, 0.28, 0.0113};
  t.window_drives = 2;
  t.window[0].kind[0] = LaunchSums{2.0, 0.02, 0.00021};
  t.window[1].kind[1] = LaunchSums{1.0, 0.031, 0.000961};
  t.drive.kind[0] = LaunchSums{1.0, 0.012, 0.000144};
  t.spread_sum_sq = 0.0007;
  t.spread_dof = 9.0;
  t.changes = 1;
  const std::string text = service::format_state(watched);
  SavedState back;
  std::string error;
  ASSERT_TRUE(service::parse_state(text, &back, &error)) << error;
  expect_same(back.snapshot, watched.snapshot);

  const std::string v7 =
      as_older_format(text, 7,
                      {"tyre_watch_settled", "tyre_watch_window_drives", "tyre_watch_window_1",
                       "tyre_watch_window_2", "tyre_watch_drive", "tyre_watch_spread_sum_sq",
                       "tyre_watch_spread_dof", "tyre_watch_changes"});
  ASSERT_FALSE(v7.empty());
  ASSERT_TRUE(service::parse_state(v7, &back, &error)) << error;
  EXPECT_EQ(back.snapshot.tyre_watch.settled.count(), 0.0);
  EXPECT_EQ(back.snapshot.tyre_watch.window_drives, 0);

  const PipelineParams params = test_params("bayes");
  PipelineSnapshot wild = watched.snapshot;
  wild.tyre_watch.window[1].kind[1].sum = 0.9;  // a mean log s of 0.9: no tyres do that
  EXPECT_NE(service::implausible_state(wild, params).find("tyre_watch_window"), std::string::npos);
  Pipeline pipeline(params);
  EXPECT_FALSE(pipeline.restore(wild));

  // What status_t shows (schema 8) from the restored watch at the next drive's first tick: the
  // launches and stops held, and the largest step its window holds.
  Pipeline restored(params);
  ASSERT_TRUE(restored.restore(watched.snapshot));
  restored.step(test::make_drive(test::DriveSpec{}).front());
  const Estimate& e = restored.estimate();
  EXPECT_EQ(e.tyre_watch_launches, 15);  // 12 settled, 2 and 1 in the window and the drive
  EXPECT_EQ(e.tyre_watch_stops, 8);
  EXPECT_EQ(e.tyre_watch_changes, 1);
  // The step is the watch's own after the restart ended the saved drive (a power cycle).
  TyreWatch watch(params.estimator.learning.tyre_watch);
  ASSERT_TRUE(watch.restore(t));
  watch.end_drive();
  EXPECT_GT(e.tyre_watch_step_sigma, 0.0);
  EXPECT_EQ(e.tyre_watch_step_sigma, watch.standing().best_sigma);
  EXPECT_EQ(e.tyre_watch_step, std::expm1(watch.standing().log_step));
  EXPECT_FALSE(e.tyre_watch_suspected);  // 0.1 std
}

// Another rolling radius makes what was learnt wrong: it is dropped and the mass kept. Another
// suspension calibration refuses the mass and keeps what was learnt about the car.
TEST_F(StateFileTest, EachSectionHasItsOwnFingerprint) {
  const PipelineParams params = test_params("bayes");
  const std::uint64_t learnt_fp = service::learnt_fingerprint(params);
  SavedState learnt = state_;
  learnt.learnt_fingerprint = learnt_fp;
  learnt.snapshot.learnt = LearntScaleState{0.02, 1e-4, 1, 0, 0, 0.0, 0.0};
  const std::string p = path("vmassd.state");
  std::string error;
  ASSERT_TRUE(service::save_state_file(p, learnt, &error)) << error;

  PipelineParams retyred = params;
  retyred.vehicle.wheel_radius_m *= 1.02;
  EXPECT_NE(service::learnt_fingerprint(retyred), learnt_fp);
  EXPECT_EQ(service::state_fingerprint(retyred), state_.fingerprint);
  service::StateLoad r =
      service::load_state_file(p, state_.fingerprint, service::learnt_fingerprint(retyred));
  EXPECT_EQ(r.status, service::StateLoadStatus::kLoaded);
  EXPECT_FALSE(r.state.snapshot.learnt_saved);
  EXPECT_NE(r.learnt_dropped.find("rolling radius"), std::string::npos) << r.learnt_dropped;
  // The ratio derived from the engine speed instead of the wheel torque: what was learnt is not
  // this path's scale.
  PipelineParams derived = params;
  derived.vehicle.derive_overall_ratio = true;
  EXPECT_NE(service::learnt_fingerprint(derived), learnt_fp);
  // Another converter map: pairs read through it carry its curve. No map keeps the fingerprint.
  PipelineParams mapped = params;
  mapped.vehicle.torque_converter_stall_torque_ratio = 2.0;
  mapped.vehicle.torque_converter_coupling_speed_ratio = 0.85;
  const std::uint64_t mapped_fp = service::learnt_fingerprint(mapped);
  EXPECT_NE(mapped_fp, learnt_fp);
  mapped.vehicle.torque_converter_coupling_speed_ratio = 0.88;
  EXPECT_NE(service::learnt_fingerprint(mapped), mapped_fp);
  PipelineParams unmapped = params;
  unmapped.vehicle.torque_converter_map_accuracy_fraction = 0.1;
  EXPECT_EQ(service::learnt_fingerprint(unmapped), learnt_fp);

  r = service::load_state_file(p, state_.fingerprint ^ 1, learnt_fp);
  EXPECT_EQ(r.status, service::StateLoadStatus::kRejected);
  EXPECT_TRUE(r.learnt_kept);
  EXPECT_EQ(r.state.snapshot.learnt.log_scale, 0.02);

  // Through the daemon's restore: the mass refused, the learnt scale taken.
  PipelineParams recalibrated = params;
  recalibrated.suspension.stiffness_n_per_m *= 1.1;
  Pipeline pipeline(recalibrated);
  const service::StateRestore restore = service::restore_pipeline_state(p, pipeline);
  EXPECT_FALSE(restore.restored);
  EXPECT_NE(restore.message.find("learnt about the car is kept"), std::string::npos)
      << restore.message;
  EXPECT_NEAR(pipeline.learnt_scale().scale(), std::exp(0.02), 1e-12);
}

TEST(StateFingerprint, ChangesWithTheVehicleNotWithTuning) {
  const PipelineParams base = test_params("bayes");
  PipelineParams tuned = base;
  tuned.estimator.supervisor.innovation_gate_sigma = 3.0;
  EXPECT_EQ(service::state_fingerprint(base), service::state_fingerprint(tuned));
  PipelineParams heavier = base;
  heavier.vehicle.empty_mass_kg += 1.0;
  EXPECT_NE(service::state_fingerprint(base), service::state_fingerprint(heavier));
  PipelineParams recalibrated = base;
  recalibrated.suspension.stiffness_n_per_m *= 1.01;
  EXPECT_NE(service::state_fingerprint(base), service::state_fingerprint(recalibrated));
  EXPECT_NE(service::state_fingerprint(base), service::state_fingerprint(test_params("rls")));
}

}  // namespace
}  // namespace vmass
