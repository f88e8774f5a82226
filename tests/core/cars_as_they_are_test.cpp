// Cars as they are: no load sensor, engine torque instead of wheel torque, a torque converter
// that slips, and the interval's model error and plausibility band, each on a synthetic drive
// with a known answer.
#include <cmath>

#include <gtest/gtest.h>

#include "extracted_pairs.hpp"
#include "synthetic_drive.hpp"
#include "vmass/core/longitudinal_extractor.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {
namespace {

constexpr double kGearRatio = 2.0, kFinalDrive = 4.0, kEfficiency = 0.9;

VehicleParams engine_torque_vehicle() {
  VehicleParams v = testing::test_vehicle();
  v.gear_ratios = {3.5, kGearRatio, 1.4};
  v.final_drive_ratio = kFinalDrive;
  v.driveline_efficiency = kEfficiency;
  return v;
}

// The drive as a bus without wheel torque reports it: engine torque in gear 2 and the engine
// speed that the locked driveline (or a slipping one, `slip` above) gives.
std::vector<Sample> as_engine_torque_bus(std::vector<Sample> samples, const VehicleParams& v,
                                         double slip) {
  for (Sample& s : samples) {
    testing::report_engine_torque(&s, v, 2, kGearRatio * kFinalDrive, kEfficiency, 1.0, 1.0 + slip);
  }
  return samples;
}

using testing::least_squares_mass;
using testing::longitudinal_pairs;

TEST(EngineTorque, ThroughTheGearRatiosItGivesTheMass) {
  const VehicleParams v = engine_torque_vehicle();
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = v.rotating_mass_kg;
  const auto bus =
      as_engine_torque_bus(testing::longitudinal_samples(drive, v, 0.0, 120.0, 15.0, 0.01), v, 0.0);
  const auto pairs = longitudinal_pairs(bus, v);
  ASSERT_GT(pairs.size(), 2000u);
  EXPECT_NEAR(least_squares_mass(pairs), drive.mass_kg, 0.01 * drive.mass_kg);
}

TEST(EngineTorque, ASlippingConverterGivesNoPair) {
  const VehicleParams v = engine_torque_vehicle();
  testing::LongitudinalDrive drive;
  // The engine turns 10 % faster than the wheels through the gear: the converter is open.
  const auto bus =
      as_engine_torque_bus(testing::longitudinal_samples(drive, v, 0.0, 60.0, 15.0, 0.01), v, 0.1);
  EXPECT_TRUE(longitudinal_pairs(bus, v).empty());
}

TEST(EngineTorque, WithoutTheDrivelineWheelTorqueIsRequired) {
  const VehicleParams v = testing::test_vehicle();  // no gear ratios
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  EXPECT_NE(ex.required_inputs() & input_bit(Input::kWheelTorque), 0u);
  LongitudinalExtractor with(engine_torque_vehicle(), LongitudinalParams{}, DifferencingParams{});
  EXPECT_EQ(with.required_inputs() & input_bit(Input::kWheelTorque), 0u);
  EXPECT_NE(with.required_inputs() & input_bit(Input::kEngineTorque), 0u);
}

TEST(EngineTorque, LossesTakeFromDrivingAndAddToDragging) {
  const VehicleParams v = engine_torque_vehicle();
  EXPECT_NEAR(v.wheel_torque_from_engine_nm(100.0, 2), 100.0 * 8.0 * 0.9, 1e-9);
  EXPECT_NEAR(v.wheel_torque_from_engine_nm(-100.0, 2), -100.0 * 8.0 / 0.9, 1e-9);
  EXPECT_TRUE(std::isnan(v.wheel_torque_from_engine_nm(100.0, 0)));  // neutral
  EXPECT_TRUE(std::isnan(v.wheel_torque_from_engine_nm(100.0, 4)));  // not a known gear
}

PipelineParams no_load_sensor_params() {
  PipelineParams p;
  p.vehicle = testing::test_vehicle();
  p.vehicle.max_mass_kg = 2100.0;
  p.suspension.has_sensor = false;
  return p;
}

TEST(NoLoadSensor, StartsFromEmptyPlusHalfTheCapacityAndLearns) {
  const PipelineParams p = no_load_sensor_params();
  Pipeline pipeline(p);
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  const auto samples = testing::longitudinal_samples(drive, p.vehicle, 0.0, 120.0, 15.0, 0.0);
  pipeline.step(samples.front());
  const Estimate& first = pipeline.estimate();
  EXPECT_EQ(first.prior_reason, StatusReason::kNoLoadSensor);
  EXPECT_NEAR(first.initial_mass_kg, 1800.0, 1e-9);
  // Uniform between empty and full: std capacity / sqrt(12) (the Bayes prior's Student-t scale
  // makes it a few percent wider), with the model error in quadrature.
  const double prior_std = std::hypot(600.0 / std::sqrt(12.0), first.mass_model_std_kg);
  EXPECT_NEAR(first.mass_std_kg, prior_std, 0.05 * prior_std);
  EXPECT_EQ(first.status, EstimateStatus::kInitialising);  // no pair yet: not static_only
  // The deflection is not needed.
  EXPECT_EQ(first.invalid_inputs & input_bit(Input::kRearRightDeflection), 0u);
  for (const Sample& s : samples) pipeline.step(s);
  pipeline.flush();
  EXPECT_NEAR(pipeline.estimate().mass_kg, drive.mass_kg, 0.01 * drive.mass_kg);
}

// A drive of `before_s` at `before`'s mass, a 10 s stop, then `after` (300 kg heavier) until
// 400 s: the drive a car without a load sensor makes around a loading stop.
struct LoadingStop {
  testing::LongitudinalDrive before;
  testing::LongitudinalDrive after;
  double before_s;

  LoadingStop(const PipelineParams& p, double before_seconds, unsigned after_seed)
      : before_s(before_seconds) {
    before.rotating_mass_kg = p.vehicle.rotating_mass_kg;
    before.accel_noise_std_mps2 = 0.02;
    before.force_noise_std_n = 60.0;
    after = before;
    after.mass_kg = before.mass_kg + 300.0;
    after.seed = after_seed;
  }
  /// Drives `before` and stands; returns the estimate when the car stopped.
  Estimate drive_and_stop(Pipeline* pipeline, const VehicleParams& v) const {
    for (const Sample& s : testing::longitudinal_samples(before, v, 0.0, before_s, 15.0, 0.0)) {
      pipeline->step(s);
    }
    const Estimate at_stop = pipeline->estimate();
    Sample stop = testing::longitudinal_samples(before, v, before_s, before_s + 0.01, 0.0, 0.0)[0];
    for (double t = before_s; t < before_s + 10.0; t += 0.01) {
      stop.time_us = from_seconds(t);
      pipeline->step(stop);
    }
    return at_stop;
  }
  std::vector<Sample> drive_on(const VehicleParams& v) const {
    return testing::longitudinal_samples(after, v, before_s + 10.0, 400.0, 15.0, 0.0);
  }
};

// Given a car without a load sensor that stops for 10 s and drives on 300 kg heavier, the
// interval spans the new mass as soon as the drive since the stop doubts the old belief
// (load_change_suspected, never converged), before the new belief is adopted; the published
// mass is then the drive's since the stop, nearer the new mass than the old.
TEST(NoLoadSensor, ALoadChangeInMotionIsSuspectedBeforeItIsDecided) {
  const PipelineParams p = no_load_sensor_params();
  Pipeline pipeline(p);
  const LoadingStop drive(p, 150.0, 2);
  const Estimate at_stop = drive.drive_and_stop(&pipeline, p.vehicle);
  ASSERT_NEAR(at_stop.mass_kg, drive.before.mass_kg, 0.02 * drive.before.mass_kg);
  const double new_mass_kg = drive.after.mass_kg;
  long suspected = 0, suspected_and_covered = 0, nearer_the_new_mass = 0;
  for (const Sample& s : drive.drive_on(p.vehicle)) {
    pipeline.step(s);
    const Estimate& e = pipeline.estimate();
    if (e.reason != StatusReason::kLoadChangeSuspected) continue;
    ++suspected;
    suspected_and_covered += e.ci_low_kg <= new_mass_kg && new_mass_kg <= e.ci_high_kg;
    nearer_the_new_mass +=
        std::abs(e.mass_kg - new_mass_kg) < std::abs(e.mass_kg - drive.before.mass_kg);
    EXPECT_EQ(e.status, EstimateStatus::kConverging);
  }
  EXPECT_GT(suspected, 100);  // a second of ticks at least
  EXPECT_EQ(suspected_and_covered, suspected);
  EXPECT_EQ(nearer_the_new_mass, suspected);
  pipeline.flush();
  EXPECT_EQ(pipeline.estimate().prior_reason, StatusReason::kLoadChanged);  // then decided
  EXPECT_NEAR(pipeline.estimate().mass_kg, new_mass_kg, 0.02 * new_mass_kg);
}

// Given a car without a load sensor that stands 10 s before its first drive (the usual start)
// and carries 150 kg less than its prior's mass, the drive refines the prior: with no drive
// before the stop there is no belief a challenger could contradict, so no load change is
// suspected (it was, against the prior itself, and the status said so all drive long).
TEST(NoLoadSensor, AStopBeforeTheFirstDriveIsNoLoadChange) {
  const PipelineParams p = no_load_sensor_params();
  Pipeline pipeline(p);
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  drive.accel_noise_std_mps2 = 0.02;
  drive.force_noise_std_n = 60.0;
  Sample stand = testing::longitudinal_samples(drive, p.vehicle, 0.0, 0.01, 0.0, 0.0)[0];
  for (double t = 0.0; t < 10.0; t += 0.01) {
    stand.time_us = from_seconds(t);
    pipeline.step(stand);
  }
  long suspected = 0;
  for (const Sample& s : testing::longitudinal_samples(drive, p.vehicle, 10.0, 200.0, 15.0, 0.0)) {
    pipeline.step(s);
    suspected += pipeline.estimate().reason == StatusReason::kLoadChangeSuspected;
  }
  pipeline.flush();
  EXPECT_EQ(suspected, 0);
  EXPECT_EQ(pipeline.estimate().prior_reason, StatusReason::kNoLoadSensor);
  EXPECT_NEAR(pipeline.estimate().mass_kg, drive.mass_kg, 0.02 * drive.mass_kg);
}

// Given a short drive before a stop (a weak belief) and 300 kg more after it, the belief drifts
// towards the new load as it takes the new pairs, so that the challenger would never differ
// from it enough: the challenger is judged against the belief as it was before the stop.
// (Judged against the running belief, this drive ends undecided.)
TEST(NoLoadSensor, TheChallengerIsJudgedAgainstTheBeliefBeforeTheStop) {
  const PipelineParams p = no_load_sensor_params();
  Pipeline pipeline(p);
  const LoadingStop drive(p, 12.0, 3);
  const Estimate at_stop = drive.drive_and_stop(&pipeline, p.vehicle);
  ASSERT_NEAR(at_stop.mass_kg, drive.before.mass_kg, 0.03 * drive.before.mass_kg);
  for (const Sample& s : drive.drive_on(p.vehicle)) pipeline.step(s);
  pipeline.flush();
  EXPECT_EQ(pipeline.estimate().prior_reason, StatusReason::kLoadChanged);
  EXPECT_NEAR(pipeline.estimate().mass_kg, drive.after.mass_kg, 0.02 * drive.after.mass_kg);
}

// The bus reports the wheel torque `lag_s` before the hub sees it (as an ECU does).
std::vector<Sample> torque_reported_early(std::vector<Sample> samples, double lag_s) {
  const auto ticks = static_cast<std::size_t>(std::lround(lag_s / 0.01));
  for (std::size_t i = 0; i + ticks < samples.size(); ++i) {
    samples[i].wheel_torque_nm = samples[i + ticks].wheel_torque_nm;
    samples[i].brake_pressure_pa = samples[i + ticks].brake_pressure_pa;
  }
  samples.resize(samples.size() - ticks);
  return samples;
}

// Given an extractor that identified its driveline's lag on one load, a load change keeps that
// lag only as a prior and forgets the noise (pooled over two loads the lag's fit misreads it: a
// truck's launch at 33 t after 18 t read 0.003-0.012 s where either load alone gave 0.03), so
// that the new load's lag is read within seconds; another extractor can take what it learnt.
TEST(NoLoadSensor, ALoadChangeKeepsTheLagOfTheLoadBeforeOnlyAsAPrior) {
  const VehicleParams v = no_load_sensor_params().vehicle;
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = v.rotating_mass_kg;
  drive.force_noise_std_n = 60.0;
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  const LongitudinalExtractor fresh = ex;
  for (const Sample& s : testing::longitudinal_samples(drive, v, 0.0, 240.0, 15.0, 0.0)) {
    ex.step(s);
  }
  ASSERT_TRUE(ex.lag().identified());
  ASSERT_NEAR(ex.lag().lag_s(), 0.0, 0.01);
  ASSERT_NE(ex.force_noise_n(), fresh.force_noise_n());

  LongitudinalExtractor taker = fresh;
  taker.take_load(ex);
  EXPECT_EQ(taker.lag().lag_s(), ex.lag().lag_s());
  EXPECT_EQ(taker.force_noise_n(), ex.force_noise_n());

  ex.forget_load();
  EXPECT_TRUE(ex.lag().identified());
  EXPECT_EQ(ex.force_noise_n(), fresh.force_noise_n());
  drive.mass_kg += 300.0;
  drive.seed = 2;
  const auto heavier =
      torque_reported_early(testing::longitudinal_samples(drive, v, 240.0, 300.0, 15.0, 0.0), 0.06);
  for (const Sample& s : heavier) ex.step(s);
  EXPECT_NEAR(ex.lag().lag_s(), 0.06, 0.01);
}

// Given a car without a load sensor (so no reference deflection), its saved belief is restored
// after a restart; switched off for minutes (a power cycle), the mass starts afresh as on a
// first drive (the load may have changed): driving on 300 kg heavier, the new load is found.
TEST(NoLoadSensor, ASavedBeliefIsRestoredAndTheLoadReChecked) {
  const PipelineParams p = no_load_sensor_params();
  Pipeline original(p);
  testing::LongitudinalDrive before;
  before.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  for (const Sample& s : testing::longitudinal_samples(before, p.vehicle, 0.0, 120.0, 15.0, 0.0)) {
    original.step(s);
  }
  original.flush();  // as the daemon before its final save: the open batch is published too
  const PipelineSnapshot saved = original.snapshot();
  ASSERT_FALSE(saved.has_reference);
  ASSERT_GT(saved.pairs_used, 0);

  Pipeline restored(p);
  ASSERT_TRUE(restored.restore(saved));
  EXPECT_EQ(restored.estimate().mass_kg, original.estimate().mass_kg);
  EXPECT_EQ(restored.estimate().reason, StatusReason::kRestored);
  testing::LongitudinalDrive after = before;
  after.mass_kg = before.mass_kg + 300.0;
  for (const Sample& s : testing::longitudinal_samples(after, p.vehicle, 500.0, 700.0, 15.0, 0.0)) {
    restored.step(s);
  }
  restored.flush();
  EXPECT_EQ(restored.estimate().prior_reason, StatusReason::kNoLoadSensor);
  EXPECT_NEAR(restored.estimate().mass_kg, after.mass_kg, 0.01 * after.mass_kg);
}

/// The estimate after a static start (eq. 3 at the drive's mass) and 296 s of driving.
Estimate after_static_start_and_drive(const PipelineParams& p,
                                      const testing::LongitudinalDrive& drive) {
  Pipeline pipeline(p);
  const double z = testing::deflection_for(drive.mass_kg, p.vehicle, p.suspension);
  std::vector<Sample> samples = testing::standstill_samples(0.0, 4.0, z);
  const auto moving = testing::longitudinal_samples(drive, p.vehicle, 4.0, 300.0, 15.0, z);
  samples.insert(samples.end(), moving.begin(), moving.end());
  for (const Sample& s : samples) pipeline.step(s);
  pipeline.flush();
  return pipeline.estimate();
}

/// The test car with a load sensor and the given declared accuracies.
PipelineParams with_declared_accuracies(double torque, double radius, double pitch_std_deg_per_g) {
  PipelineParams p;
  p.vehicle = testing::test_vehicle();
  p.suspension = testing::test_suspension();
  p.vehicle.wheel_torque_accuracy_fraction = torque;
  p.vehicle.wheel_radius_accuracy_fraction = radius;
  p.vehicle.pitch_gradient_std_deg_per_g = pitch_std_deg_per_g;
  return p;
}

TEST(Interval, HoldsTheDeclaredModelErrorThatNoDrivingAveragesAway) {
  const PipelineParams p = with_declared_accuracies(0.05, 0.02, 0.5);
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  const Estimate e = after_static_start_and_drive(p, drive);
  const double relative =
      std::sqrt(std::pow(0.05 / std::sqrt(3.0), 2) + std::pow(0.02 / std::sqrt(3.0), 2) +
                std::pow(0.5 * 3.14159265358979 / 180.0, 2) +
                std::pow(p.estimator.model_error_std_fraction, 2));
  // The rotating masses' share of the estimate is their 40 kg here (dv' = da on this drive).
  const double rotating_kg = 0.3 / std::sqrt(3.0) * p.vehicle.rotating_mass_kg;
  EXPECT_NEAR(e.mass_model_std_kg, std::hypot(relative * e.mass_kg, rotating_kg), 0.1);
  EXPECT_GE(e.mass_std_kg, e.mass_model_std_kg);
  // The 95 % half-width is at least 1.96 model stds, so it never shrinks below ~6 % here ...
  EXPECT_GT(0.5 * (e.ci_high_kg - e.ci_low_kg), 1.9 * e.mass_model_std_kg);
  // ... while the regression itself has converged: more driving would not narrow it, and the
  // status says so rather than `converged` (issue 30: not at +-6 %).
  EXPECT_EQ(e.status, EstimateStatus::kConverging);
  EXPECT_EQ(e.reason, StatusReason::kModelLimited);
  EXPECT_LE(e.ci_low_kg, drive.mass_kg);
  EXPECT_GE(e.ci_high_kg, drive.mass_kg);
}

TEST(Interval, ConvergedMeansThePublishedIntervalIsNarrow) {
  // The same drive with the torque, radius and pitch known: the published half-width is the
  // 1 % model floor's (about 2 %), within the 5 % that `converged` allows.
  PipelineParams p = with_declared_accuracies(0.0, 0.0, 0.0);
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  Estimate e = after_static_start_and_drive(p, drive);
  const double half_width = 0.5 * (e.ci_high_kg - e.ci_low_kg);
  EXPECT_LT(half_width, p.estimator.converged_halfwidth_fraction * e.mass_kg);
  EXPECT_EQ(e.status, EstimateStatus::kConverged);
  EXPECT_EQ(e.reason, StatusReason::kIntervalNarrow);
  // A stricter threshold than that half-width: the same belief is model-limited.
  p.estimator.converged_halfwidth_fraction = 0.5 * half_width / e.mass_kg;
  e = after_static_start_and_drive(p, drive);
  EXPECT_EQ(e.status, EstimateStatus::kConverging);
  EXPECT_EQ(e.reason, StatusReason::kModelLimited);
  EXPECT_NE(e.describe_reason().find("known mass"), std::string::npos);
}

/// A truck's low gears: the engine's inertia through the gearbox is a large part of what the
/// force accelerates, so an error in the configured rotating mass moves the estimate by that
/// error times the rotating masses' share, in every pair alike.
double final_mass_with_rotating_error(double declared_accuracy, Estimate* estimate) {
  PipelineParams p = with_declared_accuracies(0.0, 0.0, 0.0);
  p.vehicle.rotating_mass_kg = 400.0;
  p.vehicle.rotating_mass_accuracy_fraction = declared_accuracy;
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = 520.0;  // the datasheet's inertia was 30 % low
  drive.accel_noise_std_mps2 = 0.01;
  *estimate = after_static_start_and_drive(p, drive);
  return drive.mass_kg;
}

TEST(Interval, HoldsTheRotatingMassesErrorTimesTheirShare) {
  Estimate e;
  const double truth = final_mass_with_rotating_error(0.3, &e);
  // The 120 kg the datasheet left out land in the mass (7 %), whatever the driving ...
  EXPECT_NEAR(e.mass_kg, truth + 120.0, 15.0);
  // ... and the declared 30 % of 400 kg is in the model error: the interval holds the truth.
  EXPECT_GT(e.mass_model_std_kg, 0.3 / std::sqrt(3.0) * 400.0 * 0.95);
  EXPECT_LE(e.ci_low_kg, truth);
  EXPECT_GE(e.ci_high_kg, truth);
  // Declared exact, the same drive ends as sure as the regression alone, and wrong.
  Estimate exact;
  final_mass_with_rotating_error(0.0, &exact);
  EXPECT_GT(exact.ci_low_kg, truth);
}

TEST(Plausibility, AnEstimateBeyondTheMaximumIsHeldAndExplained) {
  PipelineParams p = no_load_sensor_params();
  p.vehicle.max_mass_kg = 1600.0;  // the car is declared lighter than it is: 1650 kg
  p.vehicle.wheel_torque_accuracy_fraction = 0.0;
  Pipeline pipeline(p);
  testing::LongitudinalDrive drive;
  drive.mass_kg = 2200.0;  // above 1.25 x 1600 = 2000 kg
  drive.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  bool refused = false;
  double held = 0.0;
  for (const Sample& s : testing::longitudinal_samples(drive, p.vehicle, 0.0, 120.0, 15.0, 0.0)) {
    pipeline.step(s);
    const Estimate& e = pipeline.estimate();
    if (!e.plausible) {
      if (!refused) held = e.mass_kg;
      refused = true;
      EXPECT_EQ(e.mass_kg, held);  // the last plausible estimate, not the regression's
      EXPECT_LE(e.mass_kg, e.plausible_high_kg);
      EXPECT_GT(e.implausible_mass_kg, e.plausible_high_kg);
    }
  }
  ASSERT_TRUE(refused);
  const std::string why = pipeline.estimate().describe_rejection();
  EXPECT_NE(why.find("above the plausible band (up to 2000 kg)"), std::string::npos) << why;
}

}  // namespace
}  // namespace vmass
