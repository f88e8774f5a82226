// An automatic's unlocked torque converter: its map, the pairs read through it, and the share of
// the estimate that rests on it in the interval.
#include "vmass/core/converter_map.hpp"

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "extracted_pairs.hpp"
#include "synthetic_drive.hpp"
#include "vmass/core/longitudinal_extractor.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {
namespace {

constexpr double kGearRatio = 2.0, kFinalDrive = 4.0, kEfficiency = 0.9;
constexpr double kStall = 2.0, kCoupling = 0.85;

VehicleParams automatic_vehicle() {
  VehicleParams v = testing::test_vehicle();
  v.gear_ratios = {3.5, kGearRatio, 1.4};
  v.final_drive_ratio = kFinalDrive;
  v.driveline_efficiency = kEfficiency;
  v.torque_converter_stall_torque_ratio = kStall;
  v.torque_converter_coupling_speed_ratio = kCoupling;
  return v;
}

double true_torque_ratio(double speed_ratio, double stall) {
  return speed_ratio >= kCoupling ? 1.0 : stall - (stall - 1.0) * speed_ratio / kCoupling;
}

// The drive as an automatic's bus reports it in gear 2 with the converter unlocked: the engine
// torque before the converter's multiplication (whose stall ratio is `true_stall`) and an engine
// turning 1 / SR faster than the turbine, SR sweeping 0.45-0.80 as a stall curve would.
std::vector<Sample> through_unlocked_converter(std::vector<Sample> samples, const VehicleParams& v,
                                               double true_stall) {
  for (Sample& s : samples) {
    const double speed_ratio = 0.625 + 0.175 * std::sin(0.23 * to_seconds(s.time_us));
    testing::report_engine_torque(&s, v, 2, kGearRatio * kFinalDrive, kEfficiency,
                                  true_torque_ratio(speed_ratio, true_stall), 1.0 / speed_ratio);
  }
  return samples;
}

using testing::least_squares_mass;
using testing::longitudinal_pairs;

TEST(ConverterMap, MultipliesBelowTheCouplingPointOnly) {
  const ConverterMap map(automatic_vehicle());
  EXPECT_DOUBLE_EQ(map.torque_ratio(0.0), kStall);
  EXPECT_DOUBLE_EQ(map.torque_ratio(0.5 * kCoupling), 0.5 * (kStall + 1.0));
  EXPECT_DOUBLE_EQ(map.torque_ratio(kCoupling), 1.0);
  EXPECT_DOUBLE_EQ(map.torque_ratio(0.95), 1.0);
}

TEST(ConverterMap, TellsLockedConverterAndSlipping) {
  const ConverterMap map(automatic_vehicle());
  // Within the 5 % slip tolerance: locked, no multiplication.
  EXPECT_EQ(map.read(103.0, 100.0).coupling, DrivelineCoupling::kLocked);
  const ConverterReading driving = map.read(160.0, 100.0);  // SR 0.625
  EXPECT_EQ(driving.coupling, DrivelineCoupling::kConverter);
  EXPECT_NEAR(driving.torque_ratio, kStall - (kStall - 1.0) * 0.625 / kCoupling, 1e-12);
  // The engine slower than the turbine (overrun through the converter), or near stall.
  EXPECT_EQ(map.read(80.0, 100.0).coupling, DrivelineCoupling::kSlipping);
  EXPECT_EQ(map.read(500.0, 100.0).coupling, DrivelineCoupling::kSlipping);
  // Without a map an unlocked converter is slipping, as before.
  VehicleParams no_map = automatic_vehicle();
  no_map.torque_converter_stall_torque_ratio = 0.0;
  EXPECT_EQ(ConverterMap(no_map).read(160.0, 100.0).coupling, DrivelineCoupling::kSlipping);
}

TEST(ConverterMap, UnlockedTheEngineTorqueThroughTheMapGivesTheMass) {
  const VehicleParams v = automatic_vehicle();
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = v.rotating_mass_kg;
  const auto bus = through_unlocked_converter(
      testing::longitudinal_samples(drive, v, 0.0, 120.0, 15.0, 0.01), v, kStall);
  const auto pairs = longitudinal_pairs(bus, v);
  ASSERT_GT(pairs.size(), 1000u);
  EXPECT_NEAR(least_squares_mass(pairs), drive.mass_kg, 0.01 * drive.mass_kg);
  // The pairs carry the multiplication's part of their force for the interval.
  double largest = 0.0;
  for (const RegressionPair& p : pairs) largest = std::max(largest, std::abs(p.converter_n));
  EXPECT_GT(largest, 100.0);
  // Read without the map, the same bus gives no pair at all (the converter slips).
  VehicleParams no_map = v;
  no_map.torque_converter_stall_torque_ratio = 0.0;
  EXPECT_TRUE(longitudinal_pairs(bus, no_map).empty());
}

// The automatic's config, exact but for its converter map (declared to map_accuracy).
PipelineParams automatic_params(double map_accuracy, bool fit_terms) {
  PipelineParams p;
  p.estimator.fit_pair_terms = fit_terms;
  p.vehicle = automatic_vehicle();
  p.suspension = testing::test_suspension();
  p.vehicle.wheel_torque_accuracy_fraction = 0.0;
  p.vehicle.wheel_radius_accuracy_fraction = 0.0;
  p.vehicle.pitch_gradient_std_deg_per_g = 0.0;
  p.vehicle.torque_converter_map_accuracy_fraction = map_accuracy;
  return p;
}

// A pipeline on the drive (a stop, then 300 s of driving) as `bus` reports it.
template <typename Bus>
Estimate after_drive(const PipelineParams& p, Bus bus, std::optional<PairTermFit>* fit) {
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = p.vehicle.rotating_mass_kg;
  Pipeline pipeline(p);
  const double z = testing::deflection_for(drive.mass_kg, p.vehicle, p.suspension);
  std::vector<Sample> samples = testing::standstill_samples(0.0, 4.0, z);
  const auto moving = bus(testing::longitudinal_samples(drive, p.vehicle, 4.0, 300.0, 15.0, z));
  samples.insert(samples.end(), moving.begin(), moving.end());
  for (const Sample& s : samples) pipeline.step(s);
  pipeline.flush();
  if (fit != nullptr) *fit = pipeline.pair_term_fit();
  return pipeline.estimate();
}

// A pipeline on the automatic's bus whose real converter multiplies more than its map says.
Estimate after_drive_through_converter(double map_accuracy, double true_stall, bool fit_terms,
                                       std::optional<PairTermFit>* fit = nullptr) {
  const PipelineParams p = automatic_params(map_accuracy, fit_terms);
  return after_drive(
      p,
      [&](std::vector<Sample> s) {
        return through_unlocked_converter(std::move(s), p.vehicle, true_stall);
      },
      fit);
}

// The same drive as an automatic's gearbox controller reports it with a wheel torque: the
// multiplication by its own model of the converter (the map) in the torque, and, with
// `engine_speed`, the engine speed and the gear beside it (a truck's EEC1 and ETC2).
std::vector<Sample> wheel_torque_through_tcu(std::vector<Sample> samples, const VehicleParams& v,
                                             double true_stall, bool engine_speed) {
  for (Sample& s : samples) {
    const double speed_ratio = 0.625 + 0.175 * std::sin(0.23 * to_seconds(s.time_us));
    s.set(Input::kWheelTorque, s.wheel_torque_nm * true_torque_ratio(speed_ratio, kStall) /
                                   true_torque_ratio(speed_ratio, true_stall));
    s.set(Input::kGear, 2.0);
    if (engine_speed) {
      s.set(Input::kEngineSpeed,
            s.speed_mps / v.wheel_radius_m * kGearRatio * kFinalDrive / speed_ratio);
    }
  }
  return samples;
}

// A pipeline on that bus, the pair terms fitted.
Estimate after_tcu_drive(bool engine_speed, std::optional<PairTermFit>* fit) {
  PipelineParams p = automatic_params(0.25, true);
  p.vehicle.wheel_torque_input = true;
  return after_drive(
      p,
      [&](std::vector<Sample> s) {
        return wheel_torque_through_tcu(std::move(s), p.vehicle, 1.0 + 1.2 * (kStall - 1.0),
                                        engine_speed);
      },
      fit);
}

TEST(ConverterMap, AWheelTorqueBesideTheEngineSpeedShowsTheConvertersShare) {
  // The TCU's map multiplies 20 % less than the converter: its wheel torque under-reads the
  // force as an engine torque read through that map would. With the engine speed the pairs
  // carry the map's share and the fit takes its error off the mass; without it nothing on the
  // bus says the converter is unlocked.
  const double truth = testing::LongitudinalDrive{}.mass_kg;
  std::optional<PairTermFit> fit, blind_fit;
  const Estimate read = after_tcu_drive(true, &fit);
  const Estimate blind = after_tcu_drive(false, &blind_fit);
  ASSERT_TRUE(fit.has_value());
  EXPECT_TRUE(fit->converter_multiplied);
  EXPECT_NEAR(fit->converter_error, -0.2, 2.0 * fit->converter_error_std) << fit->converter_error;
  EXPECT_NEAR(read.mass_kg, truth, 0.01 * truth);
  EXPECT_LE(read.ci_low_kg, truth);
  EXPECT_GE(read.ci_high_kg, truth);
  ASSERT_TRUE(blind_fit.has_value());
  EXPECT_FALSE(blind_fit->converter_multiplied);
  EXPECT_LT(blind.mass_kg, 0.98 * truth);
}

TEST(ConverterMap, TheIntervalHoldsTheMapsErrorTimesItsShare) {
  // The real converter's TR - 1 is 20 % above the map's: the force is under-read by up to
  // 10 % where the converter multiplies most, in every pair alike.
  const double truth = testing::LongitudinalDrive{}.mass_kg;
  const double true_stall = 1.0 + 1.2 * (kStall - 1.0);
  const Estimate declared = after_drive_through_converter(0.25, true_stall, false);
  EXPECT_LT(declared.mass_kg, truth * 0.98);  // the map's error lands in the mass ...
  EXPECT_LE(declared.ci_low_kg, truth);       // ... and the declared accuracy in the interval
  EXPECT_GE(declared.ci_high_kg, truth);
  // Declared exact, the same drive ends as sure as the regression alone, and wrong.
  const Estimate exact = after_drive_through_converter(0.0, true_stall, false);
  EXPECT_LT(exact.ci_high_kg, truth);
  EXPECT_LT(exact.mass_model_std_kg, declared.mass_model_std_kg);
}

TEST(ConverterMap, TheDrivesPairsTellTheMapsErrorAndTakeItOffTheMass) {
  // The same drive with the pair terms fitted (the default): the pairs read with and without
  // the converter multiplying tell its map's error, and the mass no longer carries it.
  const double truth = testing::LongitudinalDrive{}.mass_kg;
  const double true_stall = 1.0 + 1.2 * (kStall - 1.0);
  std::optional<PairTermFit> fit, no_fit;
  const Estimate fitted = after_drive_through_converter(0.25, true_stall, true, &fit);
  const Estimate unfitted = after_drive_through_converter(0.25, true_stall, false, &no_fit);
  EXPECT_NEAR(fitted.mass_kg, truth, 0.01 * truth);
  EXPECT_LE(fitted.ci_low_kg, truth);
  EXPECT_GE(fitted.ci_high_kg, truth);
  EXPECT_LT(fitted.mass_model_std_kg, unfitted.mass_model_std_kg);
  // What vmass-replay's summary shows: the map's TR - 1 is 20 % low (c_conv = -0.2), told
  // within twice the fit's std.
  ASSERT_TRUE(fit.has_value());
  EXPECT_TRUE(fit->converter_multiplied);
  EXPECT_NEAR(fit->converter_error, -0.2, 2.0 * fit->converter_error_std) << fit->converter_error;
  EXPECT_LT(fit->converter_error_std, 0.25 / std::sqrt(3.0));
  EXPECT_GT(fit->pairs, 1000);
  EXPECT_FALSE(no_fit.has_value());  // fit_pair_terms off: nothing to show
  // What status_t and vmass-monitor show (schema 8): the same fit, carried by the estimate.
  EXPECT_TRUE(fitted.pair_fit_applies);
  EXPECT_TRUE(fitted.pair_fit_converter_multiplied);
  EXPECT_EQ(fitted.pair_fit_pairs, fit->pairs);
  EXPECT_EQ(fitted.pair_fit_converter_error, fit->converter_error);
  EXPECT_EQ(fitted.pair_fit_converter_error_std, fit->converter_error_std);
  EXPECT_EQ(fitted.pair_fit_rotating_error, fit->rotating_error);
  EXPECT_EQ(fitted.pair_fit_shift_kg, fit->mass_shift_kg);
  EXPECT_EQ(fitted.pair_fit_shift_std_kg, fit->mass_std_kg);
  EXPECT_FALSE(unfitted.pair_fit_applies);
  EXPECT_EQ(unfitted.pair_fit_shift_kg, 0.0);
}

}  // namespace
}  // namespace vmass
