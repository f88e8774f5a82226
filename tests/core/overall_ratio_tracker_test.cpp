// OverallRatioTracker: the overall ratio from the engine speed (locked, slipping, shifts, no
// speed, bad inputs), and the longitudinal block on a bus with engine torque and engine speed
// but no gear and no ratios in the config.
#include "vmass/core/overall_ratio_tracker.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "synthetic_drive.hpp"
#include "vmass/core/longitudinal_extractor.hpp"

namespace vmass {
namespace {

constexpr double kTickHz = 100.0;
constexpr double kEfficiency = 0.9;
constexpr double kRadius = 0.3;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

VehicleParams derived_ratio_vehicle() {
  VehicleParams v = testing::test_vehicle();
  v.wheel_radius_m = kRadius;
  v.derive_overall_ratio = true;
  v.driveline_efficiency = kEfficiency;
  v.rotating_mass_kg = 30.0;
  v.engine_inertia_kgm2 = 0.2;
  return v;
}

double engine_speed(double ratio, double speed_mps) { return ratio * speed_mps / kRadius; }

// n ticks at `ratio`, the speed rising from v0 at `accel`; the last tick's reading.
RatioReading drive(OverallRatioTracker* t, double ratio, double v0, double accel, int n) {
  RatioReading r;
  for (int k = 0; k < n; ++k) {
    const double v = v0 + accel * k / kTickHz;
    r = t->step(engine_speed(ratio, v), v);
  }
  return r;
}

TEST(OverallRatioTracker, ALockedDriveIsOneConfirmedPlateauAtItsRatio) {
  OverallRatioTracker t(derived_ratio_vehicle(), RatioTrackerParams{}, kTickHz);
  // The first window is not full yet: not locked.
  EXPECT_FALSE(drive(&t, 8.0, 15.0, 1.0, 10).locked);
  const RatioReading r = drive(&t, 8.0, 15.1, 1.0, 300);
  EXPECT_TRUE(r.locked);
  EXPECT_TRUE(r.confirmed);
  EXPECT_EQ(r.plateau, 1);
  EXPECT_EQ(t.plateau_count(), 1);
  EXPECT_NEAR(r.ratio, 8.0, 1e-9);
  EXPECT_NEAR(t.wheel_torque_nm(100.0), 100.0 * 8.0 * kEfficiency, 1e-6);
  EXPECT_NEAR(t.wheel_torque_nm(-50.0), -50.0 * 8.0 / kEfficiency, 1e-6);
}

TEST(OverallRatioTracker, AStallingConverterDriftsAndNeverLocks) {
  OverallRatioTracker t(derived_ratio_vehicle(), RatioTrackerParams{}, kTickHz);
  // Pulling away on the stall curve: the engine held near 2000 rpm while the car speeds up.
  bool locked = false;
  for (int k = 0; k < 400; ++k) {
    const double v = 2.0 + 2.0 * k / kTickHz;
    locked = locked || t.step(210.0 + 0.05 * k, v).locked;
  }
  EXPECT_FALSE(locked);
  EXPECT_EQ(t.plateau_count(), 0);
}

TEST(OverallRatioTracker, ACouplingConverterBelowLockUpSpeedIsNeverConfirmed) {
  OverallRatioTracker t(derived_ratio_vehicle(), RatioTrackerParams{}, kTickHz);
  // Gear 2 with the converter at its coupling point (SR_c 0.85) at 6-8 m/s: steady, but off.
  const RatioReading slipping = drive(&t, 8.0 / 0.85, 6.0, 0.5, 400);
  EXPECT_TRUE(slipping.locked);
  EXPECT_FALSE(slipping.confirmed);
  // Locked up above 12 m/s: the gear's own plateau, 15 % lower, is another one, confirmed.
  const RatioReading locked = drive(&t, 8.0, 13.0, 0.5, 300);
  EXPECT_TRUE(locked.confirmed);
  EXPECT_NE(locked.plateau, slipping.plateau);
  EXPECT_FALSE(t.plateau_confirmed(slipping.plateau));
}

TEST(OverallRatioTracker, WithoutAConverterALowGearIsConfirmedAtLowSpeed) {
  VehicleParams manual = derived_ratio_vehicle();
  manual.torque_converter = false;
  OverallRatioTracker t(manual, RatioTrackerParams{}, kTickHz);
  const RatioReading first = drive(&t, 14.0, 3.0, 1.0, 200);
  EXPECT_TRUE(first.locked);
  EXPECT_TRUE(first.confirmed);
  OverallRatioTracker automatic(derived_ratio_vehicle(), RatioTrackerParams{}, kTickHz);
  EXPECT_FALSE(drive(&automatic, 14.0, 3.0, 1.0, 200).confirmed);
}

TEST(OverallRatioTracker, AShiftMovesToAnotherPlateauAndBackToTheSame) {
  OverallRatioTracker t(derived_ratio_vehicle(), RatioTrackerParams{}, kTickHz);
  const RatioReading second = drive(&t, 12.0, 13.0, 0.5, 300);
  // The shift: the engine speed falls over 0.3 s from gear 2's ratio to gear 3's. Only a tick
  // whose ratio is still within the steady band of gear 2's may read locked.
  int locked_during_shift = 0;
  for (int k = 0; k < 30; ++k) {
    const double ratio = 12.0 + (8.0 - 12.0) * (k + 1) / 30.0;
    const RatioReading r = t.step(engine_speed(ratio, 16.0), 16.0);
    if (!r.locked) continue;
    ++locked_during_shift;
    EXPECT_EQ(r.plateau, second.plateau);
    EXPECT_LT(std::abs(ratio / 12.0 - 1.0), RatioTrackerParams{}.steady_fraction) << k;
  }
  EXPECT_LE(locked_during_shift, 1);
  const RatioReading third = drive(&t, 8.0, 16.0, 0.2, 300);
  EXPECT_TRUE(third.locked);
  EXPECT_NE(third.plateau, second.plateau);
  EXPECT_NEAR(third.ratio, 8.0, 1e-4);  // its first windows held the shift's last ticks
  // Down again, with 1 % of tyre slip: gear 2's plateau, not a new one.
  const RatioReading back = drive(&t, 12.0 * 1.01, 14.0, 0.0, 300);
  EXPECT_EQ(back.plateau, second.plateau);
  EXPECT_EQ(t.plateau_count(), 2);
}

TEST(OverallRatioTracker, NearStandstillTheRatioIsNotRead) {
  OverallRatioTracker t(derived_ratio_vehicle(), RatioTrackerParams{}, kTickHz);
  drive(&t, 8.0, 15.0, 0.0, 100);
  // Idling engine, car nearly stopped: w r / v is noise (or infinite).
  for (double v : {0.5, 0.0, -0.0, 1e-300}) {
    const RatioReading r = t.step(84.0, v);
    EXPECT_FALSE(r.locked) << v;
  }
  // The torque stays finite: the last plateau's ratio stands in (such ticks are not clean).
  EXPECT_NEAR(t.wheel_torque_nm(100.0), 100.0 * 8.0 * kEfficiency, 1e-6);
}

TEST(OverallRatioTracker, InvalidInputsBreakTheWindow) {
  OverallRatioTracker t(derived_ratio_vehicle(), RatioTrackerParams{}, kTickHz);
  ASSERT_TRUE(drive(&t, 8.0, 15.0, 0.0, 100).locked);
  for (const auto& [w, v] : std::vector<std::pair<double, double>>{
           {kNan, 15.0}, {120.0, kNan}, {-400.0, 15.0}, {0.0, 15.0}, {1e6, 15.0}}) {
    EXPECT_FALSE(t.step(w, v).locked) << w << " " << v;
    // The window starts again: a full window of good ticks before it locks.
    EXPECT_FALSE(drive(&t, 8.0, 15.0, 0.0, 29).locked);
    EXPECT_TRUE(drive(&t, 8.0, 15.0, 0.0, 1).locked);
  }
  EXPECT_EQ(t.plateau_count(), 1);
}

TEST(OverallRatioTracker, TheEngineInertiaGrowsWithTheRatioSquared) {
  const VehicleParams v = derived_ratio_vehicle();
  OverallRatioTracker t(v, RatioTrackerParams{}, kTickHz);
  EXPECT_NEAR(t.rotating_mass_kg(0), 30.0, 1e-12);  // no plateau: the wheels only
  drive(&t, 12.0, 15.0, 0.0, 100);
  drive(&t, 6.0, 15.0, 0.0, 100);
  const double low = 30.0 + kEfficiency * 0.2 * 144.0 / (kRadius * kRadius);
  const double high = 30.0 + kEfficiency * 0.2 * 36.0 / (kRadius * kRadius);
  EXPECT_NEAR(t.rotating_mass_kg(1), low, 1e-6);
  EXPECT_NEAR(t.rotating_mass_kg(2), high, 1e-6);
}

TEST(OverallRatioTracker, ParamsAreValidated) {
  EXPECT_EQ(RatioTrackerParams{}.validate(), "");
  RatioTrackerParams p;
  p.steady_fraction = 0.0;
  p.window_s = -1.0;
  const std::string message = p.validate();
  EXPECT_NE(message.find("steady_fraction"), std::string::npos) << message;
  EXPECT_NE(message.find("window_s"), std::string::npos) << message;
  VehicleParams v = derived_ratio_vehicle();
  v.engine_inertia_kgm2 = -1.0;
  v.driveline_efficiency_accuracy_fraction = 0.6;
  EXPECT_NE(v.validate().find("engine_inertia_kgm2"), std::string::npos);
  EXPECT_NE(v.validate().find("driveline_efficiency_accuracy_fraction"), std::string::npos);
}

// The synthetic drive as a bus with engine torque and engine speed and no gear: gear 2 (ratio
// 8) until `shift_s`, then gear 3 (ratio 5.6); the converter at its coupling point (the engine
// 1 / 0.85 faster, no torque multiplication) where `coupling` says.
std::vector<Sample> as_engine_speed_bus(std::vector<Sample> samples, double shift_s,
                                        bool coupling) {
  for (Sample& s : samples) {
    const double t = static_cast<double>(s.time_us) * 1e-6;
    const double ratio = t < shift_s ? 8.0 : 5.6;
    const double wheel_nm = s.wheel_torque_nm;
    const double efficiency = wheel_nm >= 0.0 ? kEfficiency : 1.0 / kEfficiency;
    s.valid &= ~input_bit(Input::kWheelTorque);
    s.set(Input::kEngineTorque, wheel_nm / (ratio * efficiency));
    s.set(Input::kEngineSpeed, engine_speed(ratio / (coupling ? 0.85 : 1.0), s.speed_mps));
  }
  return samples;
}

struct Pairs {
  std::vector<RegressionPair> pairs;
  double mass_kg = 0.0;  ///< their least-squares mass
};

Pairs longitudinal_pairs(const std::vector<Sample>& samples, const VehicleParams& v) {
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  Pairs out;
  double saa = 0.0, say = 0.0;
  auto take = [&](const Extraction& e) {
    if (!e.has_pair()) return;
    out.pairs.push_back(e.pair);
    saa += e.pair.delta_accel_mps2 * e.pair.delta_accel_mps2;
    say += e.pair.delta_accel_mps2 * e.pair.y_n;
  };
  for (const Sample& s : samples) {
    take(ex.step(s));
    Extraction released;
    while (ex.pop_released(&released)) take(released);
  }
  out.mass_kg = saa > 0.0 ? say / saa : 0.0;
  return out;
}

TEST(DerivedRatio, TheBlockNeedsEngineTorqueAndSpeedNotTheGear) {
  LongitudinalExtractor ex(derived_ratio_vehicle(), LongitudinalParams{}, DifferencingParams{});
  const InputMask required = ex.required_inputs();
  EXPECT_NE(required & input_bit(Input::kEngineTorque), 0u);
  EXPECT_NE(required & input_bit(Input::kEngineSpeed), 0u);
  EXPECT_EQ(required & input_bit(Input::kGear), 0u);
  EXPECT_EQ(required & input_bit(Input::kWheelTorque), 0u);
}

TEST(DerivedRatio, GivesTheMassAcrossAShiftWithNoPairStraddlingIt) {
  VehicleParams v = derived_ratio_vehicle();
  v.engine_inertia_kgm2 = 0.0;
  testing::LongitudinalDrive d;
  d.rotating_mass_kg = v.rotating_mass_kg;
  const double shift_s = 60.0;
  const auto bus = as_engine_speed_bus(testing::longitudinal_samples(d, v, 0.0, 120.0, 15.0, 0.01),
                                       shift_s, false);
  const Pairs p = longitudinal_pairs(bus, v);
  ASSERT_GT(p.pairs.size(), 2000u);
  EXPECT_NEAR(p.mass_kg, d.mass_kg, 0.01 * d.mass_kg);
  // No pair ends within a window (and its settling) after the shift.
  const DifferencingParams differencing;
  const double quiet_s = differencing.differencing_dt_s + LongitudinalParams{}.settle_s;
  for (const RegressionPair& pair : p.pairs) {
    const double end_s = static_cast<double>(pair.time_us) * 1e-6;
    EXPECT_FALSE(end_s >= shift_s && end_s < shift_s + quiet_s) << end_s;
  }
}

TEST(DerivedRatio, ACouplingConverterGivesNoPair) {
  const VehicleParams v = derived_ratio_vehicle();
  testing::LongitudinalDrive d;
  d.accel_mps2 = [](double t) { return 0.3 * std::sin(0.6 * t); };
  // 6-8 m/s, below any lock-up speed: the 18 % too high ratio would read an 18 % heavier car.
  const auto bus =
      as_engine_speed_bus(testing::longitudinal_samples(d, v, 0.0, 60.0, 7.0, 0.01), 1e9, true);
  EXPECT_TRUE(longitudinal_pairs(bus, v).pairs.empty());
}

}  // namespace
}  // namespace vmass
