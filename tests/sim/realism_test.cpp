// The real-world effects of the simulator (realism.hpp), each checked against an answer computed
// here: the driveline mode's frequency and damping from a step response, its lag, the IMU's
// vibration spectrum and its speed scaling, the tilt of body pitch, the lever arm, the wind's
// gust statistics, brake fade, speed bumps, the torque converter, and the force balance of a
// drive with every effect on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <utility>
#include <vector>

#include "sim_test_util.hpp"
#include "vmass/core/constants.hpp"
#include "vmass/sim/driveline.hpp"
#include "vmass/sim/imu_model.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/realism.hpp"
#include "vmass/sim/wind.hpp"

namespace vmass::sim {
namespace {

constexpr double kG = 9.80665;

TEST(SimRealism, EffectNamesRoundTripAndRealismParses) {
  for (Effect e : all_effects()) {
    EXPECT_EQ(parse_effect(effect_name(e)), e);
    EXPECT_FALSE(effect_description(e).empty());
  }
  EXPECT_EQ(Realism::parse("all"), Realism::all());
  EXPECT_EQ(Realism::parse("none"), Realism::none());
  EXPECT_EQ(Realism::parse("all-wind"), Realism::all().without(Effect::kWind));
  const auto two = Realism::parse("wind+brake_fade");
  ASSERT_TRUE(two.has_value());
  EXPECT_TRUE(two->has(Effect::kWind) && two->has(Effect::kBrakeFade));
  EXPECT_FALSE(two->has(Effect::kDrivelineMode));
  EXPECT_EQ(Realism::parse(two->describe()), two);
  EXPECT_FALSE(Realism::parse("wind+nonsense").has_value());
}

// Peaks of a step response: the period gives f_d = f_n sqrt(1 - zeta^2), the logarithmic
// decrement of successive overshoots gives zeta.
TEST(SimRealism, DrivelineModeStepResponseHasTheConfiguredFrequencyAndDamping) {
  PowertrainParams pt;  // 6 gears, 3.5 .. 0.65
  DrivelineParams p;
  p.mode_frequency_first_gear_hz = 3.0;
  p.mode_frequency_top_gear_hz = 8.0;
  p.mode_damping_ratio = 0.1;
  const double dt = 1e-4;
  for (int gear : {1, 3, 6}) {
    Driveline d(p, pt, dt, Realism::only(Effect::kDrivelineMode));
    d.reset(0.0);
    std::vector<double> y;
    for (int k = 0; k < 100000; ++k) y.push_back(d.step(100.0, gear));
    std::vector<double> peak_t, peak_v;
    for (std::size_t k = 1; k + 1 < y.size(); ++k) {
      if (y[k] > y[k - 1] && y[k] >= y[k + 1] && y[k] > 100.0) {
        peak_t.push_back(static_cast<double>(k) * dt);
        peak_v.push_back(y[k] - 100.0);
      }
    }
    ASSERT_GE(peak_t.size(), 3u) << gear;
    const double fd = 1.0 / (peak_t[1] - peak_t[0]);
    const double delta = std::log(peak_v[0] / peak_v[1]);
    const double zeta = delta / std::sqrt(4.0 * kPi * kPi + delta * delta);
    const double fn = fd / std::sqrt(1.0 - zeta * zeta);
    EXPECT_NEAR(fn, d.mode_frequency_hz(gear), 0.01 * d.mode_frequency_hz(gear)) << gear;
    EXPECT_NEAR(zeta, 0.1, 0.005) << gear;
    EXPECT_NEAR(y.back(), 100.0, 0.1);  // unit static gain
  }
  Driveline d(p, pt, dt, Realism::only(Effect::kDrivelineMode));
  EXPECT_NEAR(d.mode_frequency_hz(1), 3.0, 1e-9);
  EXPECT_NEAR(d.mode_frequency_hz(6), 8.0, 1e-9);
  EXPECT_GT(d.mode_frequency_hz(3), 3.0);
  EXPECT_LT(d.mode_frequency_hz(3), 8.0);
}

TEST(SimRealism, DrivelineLagDelaysTheTorqueByWholeSteps) {
  DrivelineParams p;
  p.lag_s = 0.025;
  Driveline d(p, PowertrainParams{}, 0.001, Realism::only(Effect::kDrivelineLag));
  d.reset(0.0);
  for (int k = 0; k < 100; ++k) {
    const double out = d.step(static_cast<double>(k), 3);
    EXPECT_DOUBLE_EQ(out, k >= 25 ? static_cast<double>(k - 25) : 0.0) << k;
  }
  Driveline off(p, PowertrainParams{}, 0.001, Realism::none());
  off.reset(0.0);
  EXPECT_DOUBLE_EQ(off.step(7.0, 3), 7.0);
}

// Discrete Fourier amplitude of x (sampled at rate) at frequency f.
double amplitude_at(const std::vector<double>& x, double rate, double f) {
  std::complex<double> sum = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sum += x[k] * std::polar(1.0, -2.0 * kPi * f * static_cast<double>(k) / rate);
  }
  return std::abs(sum) / static_cast<double>(x.size());
}

std::vector<double> vibration(double speed_mps, double roughness, Realism fx, ImuParams p) {
  ImuModel imu(p, 1000.0, kG, 7, fx);
  ImuInput in;
  in.speed_mps = speed_mps;
  in.roughness = roughness;
  std::vector<double> out;
  for (int k = 0; k < 60000; ++k) out.push_back(imu.step(in).accel_x_mps2);
  return out;
}

double rms(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

TEST(SimRealism, ImuVibrationHasItsRmsAtTheReferenceSpeedAndItsEnergyInItsBand) {
  ImuParams p;
  p.vibration_rms_mps2 = 0.05;
  p.vibration_frequency_hz = 14.0;
  p.vibration_q = 2.0;
  p.engine_cylinders = 0;
  const auto only = Realism::only(Effect::kImuVibration);
  const std::vector<double> v30 = vibration(30.0, 0.0, only, p);
  EXPECT_NEAR(rms(v30), 0.05, 0.004);
  // Twice the RMS at twice the roughness scale (1 + roughness), half at half the speed.
  EXPECT_NEAR(rms(vibration(30.0, 1.0, only, p)), 0.10, 0.008);
  EXPECT_NEAR(rms(vibration(15.0, 0.0, only, p)), 0.025, 0.002);
  EXPECT_EQ(rms(vibration(0.0, 0.0, only, p)), 0.0);
  // The spectrum peaks at the vibration frequency and is small far outside the band.
  double peak_f = 0.0, peak_a = 0.0;
  for (double f = 2.0; f <= 48.0; f += 1.0) {
    const double a = amplitude_at(v30, 1000.0, f);
    if (a > peak_a) peak_a = a, peak_f = f;
  }
  EXPECT_NEAR(peak_f, 14.0, 3.0);
  EXPECT_LT(amplitude_at(v30, 1000.0, 1.0), 0.3 * peak_a);
  // The IMU's own 20 Hz low-pass takes most of a 60 Hz vibration away.
  p.vibration_frequency_hz = 60.0;
  p.filter_cutoff_hz = 20.0;
  const double unfiltered = rms(vibration(30.0, 0.0, only, p));
  const double filtered = rms(vibration(30.0, 0.0, only.with(Effect::kImuFilter), p));
  EXPECT_LT(filtered, 0.2 * unfiltered);
}

TEST(SimRealism, BodyPitchOverReadsAccelerationByGTimesThePitchGradient) {
  ImuParams p;
  p.pitch_per_accel_rad_per_mps2 = (1.0 * kPi / 180.0) / kG;  // 1 deg/g
  ImuModel imu(p, 1000.0, kG, 1, Realism::only(Effect::kBodyPitchRoll));
  ImuInput in;
  in.specific_force_x_mps2 = 2.0;
  in.body_accel_x_mps2 = 2.0;
  const double theta = p.pitch_per_accel_rad_per_mps2 * 2.0;
  const double measured = imu.step(in).accel_x_mps2;
  EXPECT_NEAR(measured, 2.0 * std::cos(theta) + kG * std::sin(theta), 1e-12);
  // 1 deg/g is a 1.7 % scale error on changes of a_x.
  EXPECT_NEAR(measured / 2.0 - 1.0, 0.0175, 0.0005);
}

TEST(SimRealism, LeverArmAddsCentripetalAndTangentialAcceleration) {
  ImuParams p;
  p.lever_forward_m = 0.5;
  p.lever_left_m = 0.2;
  p.misalignment_yaw_rad = p.misalignment_pitch_rad = p.misalignment_roll_rad = 0.0;
  ImuModel imu(p, 1000.0, kG, 1, Realism::only(Effect::kImuMounting));
  ImuInput in;
  in.yaw_rate_radps = 0.5;
  in.yaw_accel_radps2 = 1.0;
  const ImuOutput o = imu.step(in);
  EXPECT_NEAR(o.accel_x_mps2, -1.0 * 0.2 - 0.25 * 0.5, 1e-12);
  EXPECT_NEAR(o.accel_y_mps2, 1.0 * 0.5 - 0.25 * 0.2, 1e-12);
}

TEST(SimRealism, WindGustsHaveTheirStationaryStdAndMean) {
  WindParams p{5.0, -2.0, 3.0, 2.0};
  Wind w(p, 3);
  double sum = 0.0, sum2 = 0.0;
  const int n = 400000;
  for (int k = 0; k < n; ++k) {
    w.step(0.01);
    sum += w.head_mps();
    sum2 += w.head_mps() * w.head_mps();
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 5.0, 0.3);
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), 3.0, 0.3);
}

TEST(SimRealism, BrakeGainFadesBetweenItsTemperatures) {
  BrakeParams b;
  b.fade_start_c = 300.0;
  b.fade_full_c = 500.0;
  b.fade_max_fraction = 0.3;
  EXPECT_DOUBLE_EQ(b.gain_scale(20.0), 1.0);
  EXPECT_DOUBLE_EQ(b.gain_scale(400.0), 0.85);
  EXPECT_DOUBLE_EQ(b.gain_scale(900.0), 0.7);
}

TEST(SimRealism, SpeedBumpGivesAHalfSinePulseOnTheBump) {
  Road r;
  r.bumps = {{100.0, 2.0}};
  r.bump_length_m = 0.4;
  EXPECT_EQ(r.bump_deceleration_mps2(99.9, 10.0), 0.0);
  EXPECT_NEAR(r.bump_deceleration_mps2(100.2, 10.0), 2.0, 1e-12);
  EXPECT_NEAR(r.bump_deceleration_mps2(100.2, 4.0), 1.0, 1e-12);  // gentler at 4 m/s
  EXPECT_EQ(r.bump_deceleration_mps2(100.5, 10.0), 0.0);
}

TEST(SimRealism, TorqueConverterMultipliesAtStallAndLocksUp) {
  PowertrainParams p;
  p.transmission = Transmission::kAutomatic;
  p.tc_stall_torque_ratio = 2.0;
  p.tc_coupling_speed_ratio = 0.85;
  p.tc_lockup_speed_mps = 8.0;
  p.tc_model_error = 0.2;
  Powertrain pt(p, 0.31, Realism::only(Effect::kTorqueConverter));
  pt.reset(0.0, 0.0);
  for (int k = 0; k < 1000; ++k) pt.step(k * 0.001, 0.001, 1000.0, 0.0);
  // At stall (the wheels not turning) the converter doubles the torque; the ECU's model of it
  // is off by 20 % of the multiplication.
  EXPECT_NEAR(pt.converter_ratio(), 2.0, 1e-9);
  EXPECT_NEAR(pt.reported_wheel_torque_nm() / pt.wheel_torque_nm(), 2.2 / 2.0, 1e-9);
  EXPECT_FALSE(pt.converter_locked());
  // Fast in second gear it is locked: no multiplication, the report is right.
  Powertrain cruising(p, 0.31, Realism::only(Effect::kTorqueConverter));
  cruising.reset(20.0, 200.0);
  cruising.step(0.0, 0.001, 200.0, 20.0);
  EXPECT_TRUE(cruising.converter_locked());
  EXPECT_DOUBLE_EQ(cruising.reported_wheel_torque_nm(), cruising.wheel_torque_nm());
}

// A first step wider than the upshift and downshift speeds' ratio (a truck automatic's): an
// upshift at the upshift speed would land below the downshift speed and hunt between the two
// gears. The gearbox holds first until second turns 10 % above the downshift speed.
TEST(SimPowertrain, AWideFirstStepDoesNotHunt) {
  PowertrainParams p;
  p.gear_ratios = {3.6, 1.9, 1.4, 1.0};
  p.upshift_speed_radps = 1650.0 * 3.14159265358979 / 30.0;
  p.downshift_speed_radps = 1000.0 * 3.14159265358979 / 30.0;
  auto gear_after_10_s = [&](double speed_mps) {
    Powertrain pt(p, 0.31);
    pt.reset(2.0, 100.0);
    int shifts = 0, gear = pt.selected_gear();
    for (int k = 0; k < 10000; ++k) {
      pt.step(k * 0.001, 0.001, 300.0, speed_mps);
      shifts += pt.selected_gear() != gear;
      gear = pt.selected_gear();
    }
    return std::pair{gear, shifts};
  };
  // 4.2 m/s: first turns past the upshift speed, second would turn below the downshift speed.
  EXPECT_EQ(gear_after_10_s(4.2), std::pair(1, 0));
  // 5.0 m/s: second turns 17 % above the downshift speed: one upshift, and it stays.
  EXPECT_EQ(gear_after_10_s(5.0), std::pair(2, 1));
}

// A clutch gearbox's shift is a torque reduction of the engine itself (the driver lifts off, or
// the gearbox asks the engine for less), so a car that reports only its engine torque shows it;
// a converter automatic hands the torque over in its clutches, and the engine's report does not.
TEST(SimRealism, AClutchShiftIsInTheEnginesReportAConverterShiftIsNot) {
  auto halfway_through_the_ramp_down = [](Transmission t) {
    PowertrainParams p;
    p.transmission = t;
    p.shift_min_scale = 0.4;
    Powertrain pt(p, 0.31);
    pt.reset(0.0, 0.0);
    // 7.5 m/s in first gear turns the engine past its upshift speed: the shift starts, and
    // half its 0.1 s ramp down later the torque at the wheels is down to 0.7 of the engine's.
    for (int k = 0; k <= 50; ++k) pt.step(k * 0.001, 0.001, 500.0, 7.5);
    const double through_first = p.gear_ratios[0] * p.final_drive_ratio * p.efficiency;
    return pt.wheel_torque_nm() / (pt.reported_engine_torque_nm() * through_first);
  };
  EXPECT_NEAR(halfway_through_the_ramp_down(Transmission::kAutomatedManual), 1.0, 1e-9);
  EXPECT_NEAR(halfway_through_the_ramp_down(Transmission::kManual), 1.0, 1e-9);
  EXPECT_NEAR(halfway_through_the_ramp_down(Transmission::kAutomatic), 0.7, 0.01);
}

TEST(SimRealism, EngineDragIsReportedWithItsError) {
  PowertrainParams p;
  p.drag_torque_nm = 20.0;
  p.drag_torque_per_radps = 0.0;
  p.drag_report_error = 0.3;
  Powertrain pt(p, 0.31, Realism::only(Effect::kEngineDrag));
  pt.reset(20.0, 100.0);
  for (int k = 0; k < 2000; ++k) pt.step(k * 0.001, 0.001, 0.0, 20.0);
  EXPECT_LT(pt.wheel_torque_nm(), 0.0);
  EXPECT_NEAR(pt.reported_wheel_torque_nm() / pt.wheel_torque_nm(), 1.3, 1e-6);
}

// Every effect on: the simulated car obeys its own longitudinal force balance at every tick,
// from the forces the truth reports (no effect adds a force it does not report), and the work
// of those forces along the road equals the change of kinetic and potential energy between
// ticks (an independent check of the integration).
double non_gravity_force(const TruthRow& t, double radius) {
  return t.hub_torque_nm / radius - t.brake_force_n - t.esc_brake_force_n - t.drag_force_n -
         t.rolling_resistance_n - t.viscous_loss_n - t.bump_force_n;
}

TEST(SimRealism, ForceAndEnergyBalanceHoldWithEveryEffectOn) {
  const DrawnVehicle v = draw_vehicle(VehicleClass::kCompact, 11);
  PopulationRun run;
  ASSERT_EQ(make_population_run(v, "paper_exp1_eps1", 2, Realism::all(), &run), "");
  run.physics.wind = WindParams{6.0, 0.0, 2.0, 3.0};  // a wind, and no steering in exp1
  SimulationOptions o;
  o.realism = Realism::all();
  o.seed = 2;
  const SimulationResult r = test::run(run.physics, o);
  const double radius = r.vehicle.wheel_radius_m;
  double work_j = 0.0, energy_j = 0.0, scale_j = 0.0;
  int checked = 0;
  for (std::size_t k = 0; k + 1 < r.truth.size(); ++k) {
    const TruthRow& t = r.truth[k];
    const TruthRow& n = r.truth[k + 1];
    if (t.stopped || n.stopped || t.speed_mps < 0.5) continue;
    const double m = t.mass_kg;
    const double grade_n = m * kG * std::sin(t.grade_rad);
    // The driveline turns with the driven wheels, slip included (VehicleModel).
    const double rotating_n = t.rotating_mass_kg * (t.long_accel_mps2 * (1.0 + t.driven_slip) +
                                                    t.speed_mps * t.driven_slip_rate_per_s);
    EXPECT_NEAR(m * t.long_accel_mps2 + rotating_n, non_gravity_force(t, radius) - grade_n,
                1e-6 * m * kG)
        << k;
    ++checked;
    if (t.rotating_mass_kg != n.rotating_mass_kg) continue;  // a shift: m_rot jumps
    const double ds = n.distance_m - t.distance_m;
    const double work = 0.5 * (non_gravity_force(t, radius) + non_gravity_force(n, radius)) * ds;
    const double kinetic =
        0.5 * (m + t.rotating_mass_kg) * (n.speed_mps * n.speed_mps - t.speed_mps * t.speed_mps);
    const double potential = m * kG * 0.5 * (std::sin(t.grade_rad) + std::sin(n.grade_rad)) * ds;
    work_j += work;
    energy_j += kinetic + potential;
    scale_j += std::abs(work);
  }
  EXPECT_GT(checked, 10000);
  EXPECT_NEAR(work_j, energy_j, 0.005 * scale_j);
}

TEST(SimRealism, TheDrivelineTurnsWithTheDrivenWheelsSlipIncluded) {
  // Given a truck's urban drive with only the wheel speed effect (the tyres' slip)
  const DrawnVehicle v = draw_vehicle(VehicleClass::kHeavyTruck, 7);
  PopulationRun run;
  const Realism slip = Realism::only(Effect::kWheelSpeed);
  ASSERT_EQ(make_population_run(v, "urban", 1, slip, &run), "");
  SimulationOptions o;
  o.realism = slip;
  o.seed = 1;
  const SimulationResult r = test::run(run.physics, o);
  double max_slip = 0.0;
  double max_slip_rate_n = 0.0;  // what the slip's rate takes from the force, N
  for (const TruthRow& t : r.truth) {
    if (t.stopped) continue;
    max_slip = std::max(max_slip, t.driven_slip);
    max_slip_rate_n = std::max(
        max_slip_rate_n, std::abs(t.rotating_mass_kg * t.speed_mps * t.driven_slip_rate_per_s));
  }
  // Then the driven wheels slip under traction (slip stiffness 8-12), below a tyre's peak (~0.1)
  EXPECT_GT(max_slip, 0.002);
  EXPECT_LT(max_slip, 0.1);
  // And the driveline's inertia takes up the slip's rate: m_rot v dk/dt reaches more than 1 % of
  // the truck's weight at some torque change (the force balance is checked with every effect on)
  EXPECT_GT(max_slip_rate_n, 0.01 * r.truth.front().mass_kg * kG);
}

}  // namespace
}  // namespace vmass::sim
