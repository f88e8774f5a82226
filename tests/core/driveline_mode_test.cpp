// A driveline that rings at f_n between the reported torque and the hub: DrivelineMode finds
// f_n from the accelerometer, per gear, and its correction takes out the low bias the mode
// leaves in the pairs' band; a driveline without a mode gets no correction.
#include "vmass/core/driveline_mode.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "vmass/core/low_pass_filter.hpp"

namespace vmass {
namespace {

constexpr double kRateHz = 100.0;
constexpr double kMassKg = 20000.0;
constexpr double kTwoPi = 6.283185307179586;

// The reported force: a driver's steps of torque every 1-4 s, through a 0.1 s actuator lag.
std::vector<double> reported_force(double seconds, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> level(5000.0, 30000.0), hold(1.0, 4.0);
  std::vector<double> f;
  double target = level(rng), next_s = hold(rng), now = target;
  for (double t = 0.0; t < seconds; t += 1.0 / kRateHz) {
    if (t >= next_s) {
      target = level(rng);
      next_s = t + hold(rng);
    }
    now += (target - now) * (1.0 - std::exp(-1.0 / (0.1 * kRateHz)));
    f.push_back(now);
  }
  return f;
}

// The hub's force: the reported one through the mode (semi-implicit Euler, fine steps).
std::vector<double> through_mode(const std::vector<double>& f, double mode_hz, double zeta) {
  const double w = kTwoPi * mode_hz;
  const int sub = 20;
  const double h = 1.0 / (kRateHz * sub);
  double x = f.front(), v = 0.0;
  std::vector<double> out;
  for (double u : f) {
    for (int k = 0; k < sub; ++k) {
      v += h * (w * w * (u - x) - 2.0 * zeta * w * v);
      x += h * v;
    }
    out.push_back(x);
  }
  return out;
}

struct Drive {
  std::vector<double> force, accel;
};

Drive drive(double mode_hz, unsigned seed) {
  Drive d;
  d.force = reported_force(120.0, seed);
  const std::vector<double> hub = mode_hz > 0.0 ? through_mode(d.force, mode_hz, 0.1) : d.force;
  std::mt19937_64 rng(seed + 100);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (double h : hub) d.accel.push_back(h / kMassKg + noise(rng));
  return d;
}

void observe(DrivelineMode* mode, const Drive& d, int gear) {
  for (std::size_t k = 0; k < d.force.size(); ++k)
    mode->observe(d.force[k], d.accel[k], gear, true);
}

// The mass from 0.6 s differences of the 0.7 Hz low-passed force (corrected or not) and a_x.
double pair_mass(DrivelineMode* mode, const Drive& d, int gear) {
  LowPassFilter f_lp(0.7, kRateHz), a_lp(0.7, kRateHz);
  std::vector<double> f, a;
  for (std::size_t k = 0; k < d.force.size(); ++k) {
    f.push_back(f_lp.step(mode->hub_force_n(d.force[k], gear)));
    a.push_back(a_lp.step(d.accel[k]));
  }
  // At the lag where the pairs fit best, as the extractor's LagEstimator takes them.
  double best = 0.0, mass = 0.0;
  for (std::size_t lag = 0; lag <= 15; ++lag) {
    double s_ay = 0.0, s_aa = 0.0, s_yy = 0.0;
    for (std::size_t k = 300; k < f.size(); ++k) {
      const double da = a[k] - a[k - 60];
      const double dy = f[k - lag] - f[k - lag - 60];
      s_ay += da * dy;
      s_aa += da * da;
      s_yy += dy * dy;
    }
    const double fit = s_ay / std::sqrt(s_aa * s_yy);
    if (fit > best) {
      best = fit;
      mass = s_ay / s_aa;
    }
  }
  return mass;
}

TEST(DrivelineMode, FindsEachGearsModeFromTheAccelerometer) {
  DrivelineMode mode(DrivelineModeParams{}, kRateHz);
  EXPECT_EQ(mode.mode_hz(1), 0.0);
  observe(&mode, drive(1.3, 1), 1);
  observe(&mode, drive(3.0, 2), 4);
  EXPECT_NEAR(mode.mode_hz(1), 1.3, 0.13);
  EXPECT_NEAR(mode.mode_hz(4), 3.0, 0.3);
  EXPECT_EQ(mode.mode_hz(2), 0.0);  // never driven
  EXPECT_EQ(mode.mode_hz(0), 0.0);
}

TEST(DrivelineMode, TakesOutTheLowBiasTheModeLeavesInThePairs) {
  const Drive d = drive(1.3, 3);
  DrivelineModeParams off;
  off.enabled = false;
  DrivelineMode raw(off, kRateHz);
  const double uncorrected = pair_mass(&raw, d, 1);
  EXPECT_LT(uncorrected, 0.93 * kMassKg);  // the mode's gain below resonance

  DrivelineMode mode(DrivelineModeParams{}, kRateHz);
  observe(&mode, d, 1);
  ASSERT_GT(mode.mode_hz(1), 0.0);
  EXPECT_NEAR(pair_mass(&mode, d, 1), kMassKg, 0.04 * kMassKg)
      << uncorrected << " " << mode.mode_hz(1);
}

TEST(DrivelineMode, AStiffDrivelineGetsNoCorrection) {
  const Drive d = drive(0.0, 4);
  DrivelineMode mode(DrivelineModeParams{}, kRateHz);
  observe(&mode, d, 1);
  const double f = mode.mode_hz(1);
  // Nothing rings in the band: no mode, or one so high that it changes nothing.
  EXPECT_TRUE(f == 0.0 || f > 8.0) << f;
  EXPECT_NEAR(pair_mass(&mode, d, 1), kMassKg, 0.01 * kMassKg);
}

// An engine's torque report, late and refreshed at 10 Hz, on a stiff driveline: the report's
// staircase and latency must not be read as a soft mode (a low f_n would over-correct the mass).
TEST(DrivelineMode, ALateCoarseTorqueReportIsNotReadAsAMode) {
  Drive d = drive(0.0, 6);
  std::vector<double> report(d.force.size());
  for (std::size_t k = 0; k < report.size(); ++k) {
    const std::size_t late = k >= 12 ? k - 12 : 0;  // 0.12 s
    report[k] = d.force[late - late % 10];          // the value of the last 10 Hz frame
  }
  d.force = report;
  DrivelineMode mode(DrivelineModeParams{}, kRateHz);
  observe(&mode, d, 1);
  const double f = mode.mode_hz(1);
  EXPECT_TRUE(f == 0.0 || f > 4.0) << f;
}

// Shifts every 3 s: the torque drops and comes back while the tick is not clean, and the clean
// ticks just after a shift hold the shift in their lagged candidates. That is not a mode.
TEST(DrivelineMode, TheShiftsJustBeforeCleanTicksDoNotMakeAMode) {
  Drive d = drive(0.0, 7);
  std::vector<bool> clean(d.force.size());
  for (std::size_t k = 0; k < d.force.size(); ++k) {
    const std::size_t in_cycle = k % 300;
    clean[k] = in_cycle >= 40;
    if (in_cycle < 40) {
      d.force[k] *= 0.2;  // the clutch open, the engine's report still high: not clean
      d.accel[k] = 0.0;
    }
  }
  DrivelineMode mode(DrivelineModeParams{}, kRateHz);
  for (std::size_t k = 0; k < d.force.size(); ++k) {
    mode.observe(d.force[k], d.accel[k], 1, clean[k]);
  }
  const double f = mode.mode_hz(1);
  EXPECT_TRUE(f == 0.0 || f > 4.0) << f;
}

TEST(DrivelineMode, UncleanTicksAndARestartTeachNothing) {
  DrivelineMode mode(DrivelineModeParams{}, kRateHz);
  const Drive d = drive(1.3, 5);
  for (std::size_t k = 0; k < d.force.size(); ++k) {
    mode.observe(d.force[k], d.accel[k], 1, false);
  }
  EXPECT_EQ(mode.mode_hz(1), 0.0);
  observe(&mode, d, 1);
  ASSERT_GT(mode.mode_hz(1), 0.0);
  mode.restart();
  EXPECT_GT(mode.mode_hz(1), 0.0);  // a hole in the data keeps what the car taught
  mode.reset();
  EXPECT_EQ(mode.mode_hz(1), 0.0);
}

TEST(DrivelineMode, ParamsAreChecked) {
  EXPECT_EQ(DrivelineModeParams{}.validate(), "");
  DrivelineModeParams p;
  p.max_hz = 0.5;
  EXPECT_NE(p.validate().find("max_hz"), std::string::npos);
  p = DrivelineModeParams{};
  p.min_correlation = 1.0;
  EXPECT_NE(p.validate().find("min_correlation"), std::string::npos);
}

}  // namespace
}  // namespace vmass
