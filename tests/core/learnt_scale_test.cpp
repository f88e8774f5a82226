// What vmass learns about the car across drives: the lumped longitudinal scale's belief
// (LearntScale) and, through the pipeline, a known mass that makes a drive its evidence.
#include "vmass/core/learnt_scale.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "learning_car.hpp"
#include "synthetic_drive.hpp"
#include "vmass/core/known_mass.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {
namespace {

constexpr double kPriorStd = 0.035;

TEST(LearntScaleTest, StartsFromTheDatasheetAndNarrowsWithEvidence) {
  LearntScale s(LearningParams{}, kPriorStd);
  EXPECT_DOUBLE_EQ(s.scale(), 1.0);
  EXPECT_DOUBLE_EQ(s.relative_std(), kPriorStd);
  EXPECT_FALSE(s.learnt());
  EXPECT_EQ(s.add_evidence(std::log(1.04), 0.012 * 0.012), ScaleEvidence::kTaken);
  EXPECT_TRUE(s.learnt());
  // The normal update: most of the way to the evidence, narrower than either.
  EXPECT_NEAR(s.scale(), 1.0 + 0.04 * (kPriorStd * kPriorStd) / (kPriorStd * kPriorStd + 1.44e-4),
              2e-3);
  EXPECT_LT(s.relative_std(), 0.012);
  const double before = s.relative_std();
  EXPECT_EQ(s.add_evidence(std::log(1.045), 0.012 * 0.012), ScaleEvidence::kTaken);
  EXPECT_LT(s.relative_std(), before);
  EXPECT_EQ(s.state().evidence, 2);
}

TEST(LearntScaleTest, OneOutlierCountsLessAndTwoInARowAreAChange) {
  LearntScale s(LearningParams{}, kPriorStd);
  for (int i = 0; i < 5; ++i) s.add_evidence(std::log(1.03), 1e-4);
  const double settled = s.scale();
  EXPECT_NEAR(settled, 1.03, 2e-3);
  // Someone got in at the weighbridge: one drive reads 8 % off. It moves the belief only to
  // where the evidence is outlier_sigma away: it is taken with a larger variance.
  EXPECT_EQ(s.taken_variance(std::log(1.03 * 1.001), 1e-4), 1e-4);
  EXPECT_GT(s.taken_variance(std::log(1.03 * 0.92), 1e-4), 5.0 * 1e-4);
  EXPECT_EQ(s.taken_variance(std::log(1.5), 1e-4), std::numeric_limits<double>::infinity());
  EXPECT_EQ(s.add_evidence(std::log(1.03 * 0.92), 1e-4), ScaleEvidence::kDownweighted);
  EXPECT_GT(s.scale(), settled - 0.02);
  EXPECT_EQ(s.state().changes, 0);
  // A consistent drive clears the pending outlier.
  EXPECT_EQ(s.add_evidence(std::log(1.03), 1e-4), ScaleEvidence::kTaken);
  EXPECT_EQ(s.state().pending_outlier_sign, 0);
  // New tyres: two drives in a row agree on a new scale; the belief restarts from them.
  EXPECT_EQ(s.add_evidence(std::log(1.08), 1e-4), ScaleEvidence::kDownweighted);
  EXPECT_EQ(s.add_evidence(std::log(1.082), 1e-4), ScaleEvidence::kChange);
  EXPECT_NEAR(s.scale(), 1.081, 2e-3);
  EXPECT_EQ(s.state().changes, 1);
}

TEST(LearntScaleTest, RefusesWhatNoScaleErrorExplainsAndDriftsWhileParked) {
  LearntScale s(LearningParams{}, kPriorStd);
  EXPECT_EQ(s.add_evidence(std::log(1.5), 1e-4), ScaleEvidence::kRefused);
  EXPECT_EQ(s.add_evidence(std::nan(""), 1e-4), ScaleEvidence::kRefused);
  EXPECT_EQ(s.add_evidence(0.01, 0.0), ScaleEvidence::kRefused);
  EXPECT_FALSE(s.learnt());
  s.add_evidence(0.02, 1e-4);
  const double var = s.state().log_scale_var;
  s.drift();
  EXPECT_NEAR(s.state().log_scale_var, var + 0.002 * 0.002, 1e-12);
  s.reset();
  EXPECT_FALSE(s.learnt());
  EXPECT_DOUBLE_EQ(s.relative_std(), kPriorStd);
}

TEST(LearntScaleTest, RestoreRefusesAStateItCouldNotHold) {
  LearntScale s(LearningParams{}, kPriorStd);
  LearntScaleState bad;
  bad.log_scale_var = -1.0;
  EXPECT_FALSE(s.restore(bad));
  bad.log_scale_var = 1e-4;
  bad.log_scale = 0.9;
  EXPECT_FALSE(s.restore(bad));
  bad.log_scale = 0.02;
  bad.changes = 3;  // more changes than evidence
  EXPECT_FALSE(s.restore(bad));
  bad.evidence = 3;
  EXPECT_TRUE(s.restore(bad));
  EXPECT_NEAR(s.scale(), std::exp(0.02), 1e-12);
}

// New tyres: the radius moved by an unmeasured 1-3 %. The belief keeps its mean and widens by
// tyre_change_std_fraction, never past the datasheet's plus one change; the standstill readings
// taken on the old tyres are dropped, and those read since join the belief until a known mass.
TEST(LearntScaleTest, NewTyresWidenTheBeliefAndLetTheStandstillReadingsInAgain) {
  const LearningParams params;
  LearntScale s(params, kPriorStd);
  for (int i = 0; i < 3; ++i) s.add_evidence(std::log(1.03), 1e-4);
  s.add_anchor(std::log(0.99), 4e-4, 0.01);
  const double mean = s.log_scale();
  const double var = s.log_scale_var();
  EXPECT_NEAR(mean, std::log(1.03), 2e-3);  // a known mass outweighs the anchors

  s.tyres_changed();
  const double tyres = params.tyre_change_std_fraction;
  EXPECT_DOUBLE_EQ(s.log_scale(), mean);
  EXPECT_NEAR(s.log_scale_var(), var + tyres * tyres, 1e-12);
  EXPECT_EQ(s.state().anchors, 0);
  EXPECT_EQ(s.state().evidence, 3);
  EXPECT_EQ(s.state().tyre_changes, 1);

  // A reading on the new tyres joins the belief: no known mass since them.
  s.add_anchor(std::log(1.05), 2e-4, 0.005);
  EXPECT_GT(s.log_scale(), mean + 0.005);
  const double joined = s.log_scale();
  // A known mass 2 % above the old belief is no outlier now; from it on, the anchors stand aside.
  EXPECT_EQ(s.add_evidence(std::log(1.05), 1e-4), ScaleEvidence::kTaken);
  EXPECT_EQ(s.state().evidence_since_tyres, 1);
  EXPECT_NE(s.log_scale(), joined);
  EXPECT_NEAR(s.log_scale(), s.state().log_scale, 1e-15);

  // Declared again and again, it stays a belief restore() takes.
  for (int i = 0; i < 1000; ++i) s.tyres_changed();
  EXPECT_LE(s.log_scale_var(), kPriorStd * kPriorStd + tyres * tyres + 1e-15);
  EXPECT_EQ(s.implausible(s.state()), "");
  LearntScaleState bad = s.state();
  bad.evidence_since_tyres = bad.evidence + 1;
  EXPECT_FALSE(s.restore(bad));
  s.reset();
  EXPECT_EQ(s.state().tyre_changes, 0);
}

// The car's force signals read 5 % high (a datasheet torque scale and rolling radius): every
// traction pair reads 1.05 M. No deflection sensor.
PipelineParams scaled_car() { return testing::learning_car(); }

std::vector<Sample> scaled_drive(double mass_kg, double t0_s, unsigned seed,
                                 const VehicleParams& v) {
  testing::LongitudinalDrive d;
  d.mass_kg = mass_kg;
  d.force_noise_std_n = 30.0;
  d.seed = seed;
  std::vector<Sample> out = testing::longitudinal_samples(d, v, t0_s, t0_s + 120.0, 10.0, 0.0);
  for (Sample& s : out) {
    s.set(Input::kWheelTorque, 1.05 * s.wheel_torque_nm);
    s.set(Input::kBrakePressure, 1.05 * s.brake_pressure_pa);
  }
  return out;
}

const Estimate& drive(Pipeline& pipeline, const std::vector<Sample>& samples) {
  for (const Sample& s : samples) pipeline.step(s);
  pipeline.flush();
  return pipeline.estimate();
}

TEST(KnownMassTest, APublishedKnownMassTeachesTheScaleThatTheNextDriveUses) {
  const PipelineParams p = scaled_car();
  const VehicleParams& v = p.vehicle;
  // Drive 1 on a weighbridge's 1600 kg: the pipeline publishes it, the drive reads 5 % more.
  Pipeline first(p);
  ASSERT_TRUE(first.declare_known_mass(1600.0, 10.0));
  const Estimate& e1 = drive(first, scaled_drive(1600.0, 0.0, 1, v));
  EXPECT_EQ(e1.reason, StatusReason::kKnownMass);
  EXPECT_EQ(e1.status, EstimateStatus::kConverged);
  EXPECT_DOUBLE_EQ(e1.mass_kg, 1600.0);
  EXPECT_NEAR(first.learnt_scale_if_ended().scale(), 1.05, 0.01);
  EXPECT_FALSE(first.learnt_scale().learnt());  // taken when the drive ends

  // Drive 2, a day later, loaded to 1800 kg, nothing declared.
  Pipeline second(p);
  ASSERT_TRUE(second.restore(first.snapshot()));
  const Estimate& e2 = drive(second, scaled_drive(1800.0, 86400.0, 2, v));
  EXPECT_TRUE(second.learnt_scale().learnt());
  EXPECT_NEAR(e2.learnt_scale, 1.05, 0.01);
  EXPECT_EQ(e2.learnt_evidence, 1);
  EXPECT_NEAR(e2.mass_kg, 1800.0, 0.01 * 1800.0);
  EXPECT_LE(e2.ci_low_kg, 1800.0);
  EXPECT_GE(e2.ci_high_kg, 1800.0);

  // The same drive without what drive 1 taught reads the scale's 5 % and a wider interval.
  Pipeline fresh(p);
  const Estimate& e3 = drive(fresh, scaled_drive(1800.0, 86400.0, 2, v));
  EXPECT_NEAR(e3.mass_kg, 1.05 * 1800.0, 0.01 * 1800.0);
  EXPECT_GT(e3.ci_high_kg - e3.ci_low_kg, 1.5 * (e2.ci_high_kg - e2.ci_low_kg));
}

// A drive on a known mass is evidence once its regression has pairs and a width that the
// evidence's variance then carries: a wide drive counts little, one that barely started not at
// all.
TEST(KnownMassTest, ADriveIsEvidenceFromEnoughPairsAndANarrowEnoughRegression) {
  const KnownMass known{true, 1600.0, 8.0, 1.02};
  RegressorState drive;
  drive.mass_kg = 1680.0;
  drive.mass_std_kg = 0.05 * 1680.0;
  drive.pairs_used = 400;
  LearningParams params;
  params.drive_error_std_fraction = 0.01;
  ScaleObservation seen;
  ASSERT_TRUE(scale_observation(known, drive, params, &seen));
  EXPECT_NEAR(seen.log_scale, std::log(1.02 * 1680.0 / 1600.0), 1e-12);
  EXPECT_NEAR(seen.variance, 0.05 * 0.05 + 0.005 * 0.005 + 0.01 * 0.01, 1e-12);
  drive.mass_std_kg = 0.07 * 1680.0;  // beyond max_evidence_std_fraction (6 %)
  EXPECT_FALSE(scale_observation(known, drive, params, &seen));
  drive.mass_std_kg = 0.01 * 1680.0;
  drive.pairs_used = 99;  // below min_evidence_pairs
  EXPECT_FALSE(scale_observation(known, drive, params, &seen));
}

TEST(KnownMassTest, AnImplausibleDeclarationIsRefusedAndChangesNothing) {
  Pipeline pipeline(scaled_car());
  EXPECT_FALSE(pipeline.declare_known_mass(100.0, 10.0));      // below the empty mass
  EXPECT_FALSE(pipeline.declare_known_mass(1600.0, 0.0));      // no std
  EXPECT_FALSE(pipeline.declare_known_mass(std::nan(""), 5));  // not a number
  const std::vector<Sample> samples = scaled_drive(1600.0, 0.0, 1, scaled_car().vehicle);
  const Estimate& e = drive(pipeline, samples);
  EXPECT_NE(e.reason, StatusReason::kKnownMass);
}

// Without a load sensor, a load added at a stop is seen in motion: the declaration made before
// it is not published over the drive's suspicion, and the pairs after it are not its evidence.
TEST(KnownMassTest, ALoadChangeInMotionEndsTheKnownMass) {
  const PipelineParams p = scaled_car();
  Pipeline pipeline(p);
  ASSERT_TRUE(pipeline.declare_known_mass(1600.0, 10.0));
  drive(pipeline, scaled_drive(1600.0, 0.0, 1, p.vehicle));
  EXPECT_EQ(pipeline.estimate().reason, StatusReason::kKnownMass);
  std::vector<Sample> stop = testing::standstill_samples(120.0, 180.0, 0.0);
  drive(pipeline, stop);
  // After the stop the declaration is no longer `converged` (the load may have changed
  // unseen); while the drive says the load changed, that suspicion is what is published.
  bool suspected = false;
  bool converged_declared = false;
  for (const Sample& s : scaled_drive(1950.0, 180.0, 2, p.vehicle)) {
    pipeline.step(s);
    const Estimate& e = pipeline.estimate();
    suspected |= e.reason == StatusReason::kLoadChangeSuspected;
    converged_declared |=
        e.reason == StatusReason::kKnownMass && e.status == EstimateStatus::kConverged;
  }
  EXPECT_FALSE(converged_declared);
  pipeline.flush();
  const Estimate& after = pipeline.estimate();
  EXPECT_TRUE(suspected);
  EXPECT_NE(after.reason, StatusReason::kKnownMass);
  EXPECT_GT(after.mass_kg, 1600.0 + 0.5 * 350.0);
  EXPECT_GE(after.ci_high_kg, 1.05 * 1950.0 - 0.05 * 1950.0);
}

// New tyres 3 % larger after a known mass: the scale the car's signals read is 1.05 x 1.03. The
// drive after them reads 3 % high with the old scale. Declared at its start, the known mass's
// evidence (the old tyres') is taken first and the scale then widens by the tyres' 2 %: its
// interval holds the truth, where the undeclared one, as sure as before, does not.
TEST(KnownMassTest, DeclaredNewTyresWidenTheIntervalThatTheOldScaleNoLongerEarns) {
  const PipelineParams p = scaled_car();
  Pipeline first(p);
  ASSERT_TRUE(first.declare_known_mass(1600.0, 10.0));
  drive(first, scaled_drive(1600.0, 0.0, 1, p.vehicle));
  std::vector<Sample> on_new_tyres = scaled_drive(1800.0, 86400.0, 2, p.vehicle);
  for (Sample& s : on_new_tyres) {
    s.set(Input::kWheelTorque, 1.03 * s.wheel_torque_nm);
    s.set(Input::kBrakePressure, 1.03 * s.brake_pressure_pa);
  }
  Pipeline undeclared(p);
  ASSERT_TRUE(undeclared.restore(first.snapshot()));
  const Estimate e1 = drive(undeclared, on_new_tyres);
  Pipeline declared(p);
  ASSERT_TRUE(declared.restore(first.snapshot()));
  declared.tyres_changed();
  EXPECT_EQ(declared.learnt_scale().state().evidence, 1);  // drive 1's, before the widening
  EXPECT_EQ(declared.learnt_scale().state().tyre_changes, 1);
  const Estimate e2 = drive(declared, on_new_tyres);
  EXPECT_NEAR(e1.learnt_scale, 1.05, 0.01);
  EXPECT_NEAR(e2.learnt_scale, e1.learnt_scale, 0.005);  // the mean is kept
  EXPECT_GT(e2.learnt_scale_std, 1.5 * e1.learnt_scale_std);
  EXPECT_NEAR(e1.mass_kg, 1.03 * 1800.0, 0.01 * 1800.0);
  EXPECT_NEAR(e2.mass_kg, e1.mass_kg, 0.005 * 1800.0);
  EXPECT_GT(e1.ci_low_kg, 1800.0);
  EXPECT_LE(e2.ci_low_kg, 1800.0);
  EXPECT_GE(e2.ci_high_kg, 1800.0);
}

// New tyres on a car that learnt nothing: the config's radius is no longer the tyres', so the
// interval's scale part is the datasheet's widened by the tyres' 2 %.
TEST(KnownMassTest, NewTyresOnACarThatLearntNothingWidenItsDatasheetInterval) {
  const PipelineParams p = scaled_car();
  const std::vector<Sample> samples = scaled_drive(1800.0, 0.0, 2, p.vehicle);
  Pipeline plain(p);
  const Estimate e1 = drive(plain, samples);
  Pipeline declared(p);
  declared.tyres_changed();
  EXPECT_FALSE(declared.learnt_scale().learnt());
  const Estimate e2 = drive(declared, samples);
  EXPECT_DOUBLE_EQ(e2.mass_kg, e1.mass_kg);
  const double tyres = p.estimator.learning.tyre_change_std_fraction;
  const double floor = p.estimator.model_error_std_fraction;
  const double declared_var = declared_scale_variance(p.vehicle);
  EXPECT_NEAR(e1.mass_model_std_kg / e1.mass_kg, std::sqrt(declared_var + floor * floor), 0.002);
  EXPECT_NEAR(e2.mass_model_std_kg / e2.mass_kg,
              std::sqrt(declared_var + tyres * tyres + floor * floor), 0.002);
}

// The kappa a known mass measured holds the car's own share of the model error (its datasheet
// aero, rolling and pitch errors read alike on every drive): neither that evidence nor the next
// drive's interval counts it again. The same drives with the whole floor counted again differ
// by the car's share alone: in the interval beyond the learnt scale, and in the scale's std.
TEST(KnownMassTest, TheLearntScaleHoldsTheCarsShareOfTheModelFloor) {
  const PipelineParams p = scaled_car();
  const double drive_floor = p.estimator.learning.drive_error_std_fraction;
  const double whole_floor = p.estimator.model_error_std_fraction;
  ASSERT_LT(drive_floor, 0.75 * whole_floor);
  const auto second_drive = [](const PipelineParams& params) {
    Pipeline first(params);
    EXPECT_TRUE(first.declare_known_mass(1600.0, 10.0));
    drive(first, scaled_drive(1600.0, 0.0, 1, params.vehicle));
    Pipeline second(params);
    EXPECT_TRUE(second.restore(first.snapshot()));
    const Estimate e = drive(second, scaled_drive(1800.0, 86400.0, 2, params.vehicle));
    EXPECT_TRUE(second.learnt_scale().learnt());
    return e;
  };
  PipelineParams counted_again = p;
  counted_again.estimator.learning.drive_error_std_fraction = whole_floor;
  const Estimate shared = second_drive(p);
  const Estimate again = second_drive(counted_again);
  // The model's relative variance beyond the learnt scale's: the floor and the rotating masses.
  const auto beyond_scale = [](const Estimate& e) {
    const double relative = e.mass_model_std_kg / e.mass_kg;
    return relative * relative - e.learnt_scale_std * e.learnt_scale_std;
  };
  EXPECT_NEAR(beyond_scale(again) - beyond_scale(shared),
              whole_floor * whole_floor - drive_floor * drive_floor, 1e-5);
  EXPECT_LT(shared.learnt_scale_std, again.learnt_scale_std - 1e-4);
  EXPECT_LT(shared.mass_model_std_kg, again.mass_model_std_kg);
}

TEST(KnownMassTest, ResetForgetsWhatWasLearnt) {
  const PipelineParams p = scaled_car();
  Pipeline first(p);
  ASSERT_TRUE(first.declare_known_mass(1600.0, 10.0));
  drive(first, scaled_drive(1600.0, 0.0, 1, p.vehicle));
  Pipeline second(p);
  ASSERT_TRUE(second.restore(first.snapshot()));
  drive(second, scaled_drive(1700.0, 86400.0, 3, p.vehicle));
  ASSERT_TRUE(second.learnt_scale().learnt());
  second.reset_learnt();
  EXPECT_FALSE(second.learnt_scale().learnt());
  EXPECT_DOUBLE_EQ(second.learnt_scale().scale(), 1.0);
}

}  // namespace
}  // namespace vmass
