// The inputs' plausibility checks (signals/input_plausibility.hpp) on synthetic 100 Hz drives
// whose physics is written out here: limits; a bit flip costs two updates; a steering angle
// frozen in a corner is stuck, one held on a straight or in a steady turn is not; speed against
// the integrated accel_x holds on a changing grade, fails on a speed spoofed to 0 and on a
// speed unit declared wrong; yaw rate against accel_y / speed holds in a steady turn with
// understeer, fails with the sign flipped.
#include "vmass/signals/input_plausibility.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace vmass::signals {
namespace {

constexpr TimeUs kTickUs = 10'000;

/// Runs `ticks` ticks of a drive: fill(k, &sample) sets the inputs of tick k (every input a
/// fresh frame at every tick). Returns the verdicts of every tick for one input.
struct Trace {
  std::vector<InputFault> faults;
  int first_fault_tick = -1;
};

Trace drive(InputPlausibility& p, int ticks, Input watched,
            const std::function<void(int, Sample*)>& fill) {
  Trace r;
  TimeUs updates[kInputCount];
  for (int k = 0; k < ticks; ++k) {
    Sample s;
    s.time_us = k * kTickUs;
    fill(k, &s);
    for (TimeUs& u : updates) u = s.time_us;
    const bool had = s.has(watched);
    p.check(&s, updates);
    const InputFault f = p.verdict(watched).fault;
    r.faults.push_back(f);
    if (f != InputFault::kNone) {
      EXPECT_FALSE(s.has(watched));  // a refused input is invalid in the sample
      if (r.first_fault_tick < 0) r.first_fault_tick = k;
    } else {
      EXPECT_EQ(s.has(watched), had);
    }
  }
  return r;
}

int count(const Trace& r, InputFault f) {
  int n = 0;
  for (InputFault x : r.faults) n += x == f;
  return n;
}

TEST(Plausibility, LimitsPerInputKind) {
  InputPlausibility p{PlausibilityParams{}};
  const Trace r = drive(p, 3, Input::kSpeed, [](int k, Sample* s) {
    s->set(Input::kSpeed, k == 1 ? 1e38 : 20.0);  // 1e38 km/h, accepted before
  });
  EXPECT_EQ(r.faults[1], InputFault::kAboveMaximum);
  EXPECT_EQ(p.verdict(Input::kSpeed).fault, InputFault::kRateOfChange);  // back from 1e38
  EXPECT_EQ(p.implausible(Input::kSpeed), 2);
}

TEST(Plausibility, ABitFlipInRangeCostsTwoUpdates) {
  InputPlausibility p{PlausibilityParams{}};
  // 20 m/s, bit 11 of a 0.01 km/h signal flipped at tick 50: +20.48 km/h, in range.
  const Trace r = drive(p, 100, Input::kSpeed, [](int k, Sample* s) {
    s->set(Input::kSpeed, 20.0 + 0.01 * k + (k == 50 ? 20.48 / 3.6 : 0.0));
  });
  EXPECT_EQ(count(r, InputFault::kRateOfChange), 2);
  EXPECT_EQ(r.faults[50], InputFault::kRateOfChange);
  EXPECT_EQ(r.faults[51], InputFault::kRateOfChange);
  EXPECT_EQ(r.faults[52], InputFault::kNone);
}

TEST(Plausibility, ASteeringAngleFrozenInACornerIsStuck) {
  InputPlausibility p{PlausibilityParams{}};
  // 10 m/s on a path whose curvature goes from 0.01 to 0.04 1/m and back over 20 s; the
  // steering sensor freezes at tick 500 (5 s).
  const Trace r = drive(p, 2000, Input::kSteeringWheelAngle, [](int k, Sample* s) {
    const double t = k * 0.01;
    const double curvature = 0.025 - 0.015 * std::cos(2.0 * M_PI * t / 20.0);
    const double steering = 15.5 * 2.7 * curvature;  // wheel angle = ratio * L * curvature
    s->set(Input::kSpeed, 10.0);
    s->set(Input::kYawRate, 10.0 * curvature);
    s->set(Input::kSteeringWheelAngle, k < 500 ? steering : 15.5 * 2.7 * 0.025 - 0.4);
  });
  ASSERT_GT(r.first_fault_tick, 500);
  EXPECT_LT(r.first_fault_tick, 500 + 1000);  // within 10 s
  EXPECT_EQ(r.faults[r.first_fault_tick], InputFault::kStuck);
}

TEST(Plausibility, AHeldSteeringAngleIsNotStuckWhenNothingTurns) {
  InputPlausibility p{PlausibilityParams{}};
  // A straight road for 60 s at 25 m/s (steering exactly 0, yaw noise), then into a turn at
  // 10 m/s, speeding up in it: the yaw rate follows the speed, the curvature does not move.
  const Trace r = drive(p, 12000, Input::kSteeringWheelAngle, [](int k, Sample* s) {
    const double v = k < 6000 ? 25.0 : 10.0 + 0.001 * (k - 6000);
    const double curvature = 0.02 * std::clamp((k - 6000) / 300.0, 0.0, 1.0);  // in over 3 s
    s->set(Input::kSpeed, v);
    s->set(Input::kYawRate, v * curvature + 0.002 * std::sin(k * 0.7));
    s->set(Input::kSteeringWheelAngle, 15.5 * 2.7 * curvature);
  });
  EXPECT_EQ(r.first_fault_tick, -1);
}

/// accel_x and speed of a car on a road with grade theta(t): a_x measured = dv/dt + g sin(theta).
void longitudinal(int k, Sample* s, double (*accel)(double), double (*grade)(double),
                  double speed_factor = 1.0) {
  // Exact integration on the tick grid.
  double v = 10.0;
  const double dt = 0.01;
  for (int j = 0; j < k; ++j) v += 0.5 * (accel(j * dt) + accel((j + 1) * dt)) * dt;
  s->set(Input::kSpeed, v * speed_factor);
  s->set(Input::kAccelX, accel(k * dt) + 9.80665 * std::sin(grade(k * dt)));
}

double pulses(double t) { return 1.5 * std::sin(2.0 * M_PI * t / 8.0); }
double hill(double t) { return std::atan(0.10 * std::min(1.0, t / 30.0)); }  // 0 -> 10 % in 30 s
double flat(double) { return 0.0; }

TEST(Plausibility, SpeedAgainstAccelHoldsOnAChangingGrade) {
  InputPlausibility p{PlausibilityParams{}};
  const Trace speed =
      drive(p, 6000, Input::kSpeed, [](int k, Sample* s) { longitudinal(k, s, pulses, hill); });
  EXPECT_EQ(speed.first_fault_tick, -1);
}

TEST(Plausibility, SpeedSpoofedToZeroFailsTheCrossCheck) {
  InputPlausibility p{PlausibilityParams{}};
  PlausibilityParams loose;  // the rate check off: the cross-check alone must see it
  loose.inputs[static_cast<int>(Input::kSpeed)].max_rate_per_s = 0.0;
  InputPlausibility q{loose};
  const Trace r = drive(q, 3000, Input::kAccelX, [](int k, Sample* s) {
    longitudinal(k, s, pulses, flat);
    if (k >= 2000 && k < 2300) s->set(Input::kSpeed, 0.0);
  });
  EXPECT_EQ(r.first_fault_tick, 2000);
  EXPECT_EQ(r.faults[2000], InputFault::kSpeedVsAccelX);
  EXPECT_EQ(r.faults[1999], InputFault::kNone);
}

TEST(Plausibility, ASpeedUnitDeclaredWrongIsSeenByTheScale) {
  InputPlausibility p{PlausibilityParams{}};
  // mph read as km/h: the speed reads 1.609 times too high, consistently.
  const Trace r = drive(p, 12000, Input::kSpeed,
                        [](int k, Sample* s) { longitudinal(k, s, pulses, hill, 1.609344); });
  ASSERT_GE(r.first_fault_tick, 0);
  EXPECT_EQ(r.faults.back(), InputFault::kSpeedAccelScale);
  EXPECT_NEAR(p.verdict(Input::kSpeed).value, 1.609344, 0.05);
}

void turn(int k, Sample* s, double yaw_sign, double bank_rad) {
  const double v = 20.0, radius = 100.0;
  s->set(Input::kSpeed, v);
  s->set(Input::kYawRate, yaw_sign * v / radius);
  // A body-fixed accelerometer: v^2 / R plus gravity's share on a banked road; understeer
  // changes the steering it takes, not this.
  s->set(Input::kAccelY, v * v / radius + 9.80665 * std::sin(bank_rad) + 0.01 * std::sin(k));
}

TEST(Plausibility, YawRateAgainstLateralAccelInASteadyTurn) {
  InputPlausibility good{PlausibilityParams{}};
  EXPECT_EQ(drive(good, 1000, Input::kYawRate, [](int k, Sample* s) { turn(k, s, 1.0, 0.05); })
                .first_fault_tick,
            -1);
  InputPlausibility flipped{PlausibilityParams{}};  // a mapping that forgot gain: -1
  const Trace r =
      drive(flipped, 1000, Input::kAccelY, [](int k, Sample* s) { turn(k, s, -1.0, 0.0); });
  EXPECT_GE(r.first_fault_tick, 90);  // after one window
  EXPECT_LE(r.first_fault_tick, 110);
  EXPECT_EQ(flipped.verdict(Input::kYawRate).fault, InputFault::kYawVsAccelY);
}

TEST(Plausibility, OffMeansOff) {
  PlausibilityParams off;
  off.enabled = false;
  InputPlausibility p{off};
  const Trace r = drive(p, 10, Input::kSpeed, [](int, Sample* s) { s->set(Input::kSpeed, 1e38); });
  EXPECT_EQ(r.first_fault_tick, -1);
}

TEST(Plausibility, VerdictsAreDescribed) {
  EXPECT_EQ(describe({InputFault::kRateOfChange, 1780.0, 50.0}), "rate_of_change: 1780 > 50 per s");
  EXPECT_EQ(describe({InputFault::kAboveMaximum, 1e38, 120.0}), "above_maximum: 1e+38 > 120");
  EXPECT_EQ(describe({InputFault::kMessageInvalid, 0, 0, 3}, "ESC_Speed"),
            "message_invalid: ESC_Speed");
  EXPECT_EQ(describe({}), "");
}

}  // namespace
}  // namespace vmass::signals
