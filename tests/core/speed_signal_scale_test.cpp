// The speed signal's scale against the engine speed: a display speed that over-reads makes a
// locked driveline look as if it slipped, until the scale is learnt.
#include "vmass/core/speed_signal_scale.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "extracted_pairs.hpp"
#include "synthetic_drive.hpp"
#include "vmass/core/longitudinal_extractor.hpp"

namespace vmass {
namespace {

constexpr double kGearRatio = 2.0, kFinalDrive = 4.0, kEfficiency = 0.9;

TEST(SpeedSignalScale, LearnsTheMedianOfLockedTicksOnly) {
  SpeedSignalScale scale(SpeedSignalScaleParams{}, /*torque_converter=*/false);
  EXPECT_DOUBLE_EQ(scale.scale(), 1.0);
  // 20 s of a display speed 6 % high, one tick in five a slipping clutch (q 1.1) or a wrong
  // gear (q 0.6): the median settles on 1 / 1.06 and ignores them.
  for (int k = 0; k < 2000; ++k) {
    const double q = k % 5 == 0 ? 1.1 : (k % 5 == 1 ? 0.6 : 1.0 / 1.06);
    scale.observe(100.0 * q, 100.0, 10.0);
  }
  EXPECT_NEAR(scale.scale(), 1.0 / 1.06, 2e-4);
  // An engine steadily faster than the gear is a slip, never the speed signal's scale.
  SpeedSignalScale slipping(SpeedSignalScaleParams{}, false);
  for (int k = 0; k < 2000; ++k) slipping.observe(110.0, 100.0, 10.0);
  EXPECT_DOUBLE_EQ(slipping.scale(), 1.0);
  // Below 2 m/s nothing is learnt (a launch).
  SpeedSignalScale slow(SpeedSignalScaleParams{}, false);
  for (int k = 0; k < 2000; ++k) slow.observe(94.0, 100.0, 1.5);
  EXPECT_DOUBLE_EQ(slow.scale(), 1.0);
  // With a converter only above its lock-up speeds (12 m/s): below, a converter at its coupling
  // point would teach its own slip as the speed signal's scale.
  SpeedSignalScale automatic(SpeedSignalScaleParams{}, true);
  for (int k = 0; k < 2000; ++k) automatic.observe(100.0 / 0.87, 100.0, 8.0);
  EXPECT_DOUBLE_EQ(automatic.scale(), 1.0);
}

VehicleParams clutch_vehicle() {
  VehicleParams v = testing::test_vehicle();
  v.gear_ratios = {3.5, kGearRatio, 1.4};
  v.final_drive_ratio = kFinalDrive;
  v.driveline_efficiency = kEfficiency;
  v.torque_converter = false;  // an automated manual
  return v;
}

// A locked driveline in gear 2 whose speed signal is the cluster's, `overread` high.
std::vector<Sample> with_display_speed(std::vector<Sample> samples, const VehicleParams& v,
                                       double overread) {
  for (Sample& s : samples) {
    testing::report_engine_torque(&s, v, 2, kGearRatio * kFinalDrive, kEfficiency);
    s.speed_mps *= 1.0 + overread;
  }
  return samples;
}

TEST(SpeedSignalScale, ADisplaySpeedNoLongerLooksLikeASlippingClutch) {
  const VehicleParams v = clutch_vehicle();
  testing::LongitudinalDrive drive;
  drive.rotating_mass_kg = v.rotating_mass_kg;
  // 8 % high: outside the 5 % slip tolerance on every tick.
  const auto bus =
      with_display_speed(testing::longitudinal_samples(drive, v, 0.0, 120.0, 8.0, 0.01), v, 0.08);
  const auto pairs = testing::longitudinal_pairs(bus, v);
  EXPECT_GT(pairs.size(), 1000u);
  EXPECT_NEAR(testing::least_squares_mass(pairs), drive.mass_kg, 0.02 * drive.mass_kg);
  // The same bus of an automatic below its lock-up speeds: nothing is learnt, and the ticks stay
  // slipping (the converter may be at its coupling point).
  VehicleParams automatic = v;
  automatic.torque_converter = true;
  EXPECT_TRUE(testing::longitudinal_pairs(bus, automatic).empty());
}

}  // namespace
}  // namespace vmass
