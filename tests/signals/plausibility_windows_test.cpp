// The cross-checks of InputPlausibility (signals/input_plausibility.hpp) against a plain
// recomputation: at every tick of long irregular drives, loops over every row of the window
// (the checks as first written) give the same verdicts, with the same values to 1e-9. The
// drives hold what a window kept as rows come and go must get right: windows that fill, empty
// on invalid rows and refill; ticks on a 1 ms grid, so that rows are exactly window_s old;
// windows longer than the ring of rows; NaN and infinite rows; values a billion times too
// large that then leave the window (a plain running sum keeps their rounding). And a tick
// whose time goes back starts the windows anew.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <vector>

#include "vmass/signals/input_plausibility.hpp"

namespace vmass::signals {
namespace {

constexpr std::size_t kRingRows = 4096;  ///< the rows InputPlausibility keeps

/// The cross-checks as loops over every row of their window, at every tick.
class PlainCrossChecks {
 public:
  explicit PlainCrossChecks(const PlausibilityParams& params) : params_(params) {}

  int whole_windows = 0;   ///< ticks speed_vs_accel() had a whole window
  int steady_windows = 0;  ///< ticks yaw_vs_accel() found a steady turn

  void push(const Sample& s) {
    rows_.push_back({s.time_us, s.speed_mps, s.accel_x_mps2, s.accel_y_mps2, s.yaw_rate_radps,
                     s.has(Input::kSpeed) && s.has(Input::kAccelX),
                     s.has(Input::kSpeed) && s.has(Input::kAccelY) && s.has(Input::kYawRate)});
    if (rows_.size() > kRingRows) rows_.pop_front();
  }

  InputVerdict speed_vs_accel() {
    const SpeedAccelCheck& c = params_.speed_vs_accel_x;
    if (rows_.size() < 2 || !row(0).longitudinal) {
      has_slow_ = false;
      return {};
    }
    const auto window_us = static_cast<TimeUs>(c.window_s * 1e6);
    double integral = 0.0;
    std::size_t i = 1;
    for (; i < rows_.size() && row(i).longitudinal && row(0).t - row(i - 1).t < window_us; ++i) {
      integral += 0.5 * (row(i).accel_x + row(i - 1).accel_x) * 1e-6 *
                  static_cast<double>(row(i - 1).t - row(i).t);
    }
    if (row(0).t - row(i - 1).t < window_us) return {};
    ++whole_windows;
    const double residual = row(0).speed - row(i - 1).speed - integral;
    if (!has_slow_) {
      slow_ = residual;
      has_slow_ = true;
    }
    const double deviation = residual - slow_;
    const double tolerance = c.tolerance_mps + c.tolerance_fraction * std::abs(integral);
    if (std::abs(deviation) > tolerance) return {InputFault::kSpeedVsAccelX, deviation, tolerance};
    const double dt_s = 1e-6 * static_cast<double>(row(0).t - row(1).t);
    slow_ += (residual - slow_) * std::min(1.0, dt_s / c.smoothing_s);
    return {};
  }

  InputVerdict yaw_vs_accel() {
    const YawAccelCheck& c = params_.yaw_rate_vs_accel_y;
    if (rows_.size() < 2 || !row(0).lateral) return {};
    const auto window_us = static_cast<TimeUs>(c.window_s * 1e6);
    double sum_r = 0.0, sum_ay = 0.0, sum_v = 0.0;
    double r_min = kInf, r_max = -kInf, ay_min = kInf, ay_max = -kInf, v_min = kInf;
    std::size_t n = 0;
    for (; n < rows_.size() && row(n).lateral && row(0).t - row(n).t <= window_us; ++n) {
      const Row& r = row(n);
      sum_r += r.yaw_rate;
      sum_ay += r.accel_y;
      sum_v += r.speed;
      r_min = std::min(r_min, r.yaw_rate);
      r_max = std::max(r_max, r.yaw_rate);
      ay_min = std::min(ay_min, r.accel_y);
      ay_max = std::max(ay_max, r.accel_y);
      v_min = std::min(v_min, r.speed);
    }
    if (n < 2 || row(0).t - row(n - 1).t < window_us * 9 / 10) return {};
    const double mean_r = sum_r / static_cast<double>(n);
    const double mean_ay = sum_ay / static_cast<double>(n);
    const double mean_v = sum_v / static_cast<double>(n);
    const bool steady = v_min >= c.min_speed_mps && std::abs(mean_ay) >= c.min_accel_y_mps2 &&
                        ay_max - ay_min <= c.steady_accel_y_mps2 &&
                        r_max - r_min <= c.steady_yaw_rate_radps;
    if (!steady) return {};
    ++steady_windows;
    const double residual = mean_r - mean_ay / mean_v;
    const double tolerance = c.tolerance_radps + c.tolerance_fraction * std::abs(mean_r);
    if (std::abs(residual) > tolerance) return {InputFault::kYawVsAccelY, residual, tolerance};
    return {};
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  struct Row {
    TimeUs t;
    double speed, accel_x, accel_y, yaw_rate;
    bool longitudinal, lateral;
  };
  const Row& row(std::size_t i) const { return rows_[rows_.size() - 1 - i]; }

  PlausibilityParams params_;
  std::deque<Row> rows_;  ///< the newest last
  bool has_slow_ = false;
  double slow_ = 0.0;
};

/// Only the cross-checks, tight enough to fail now and then on the drive below.
PlausibilityParams cross_checks_only(double window_s) {
  PlausibilityParams p;
  // No limits, no rate or stuck checks: every valid input passes, infinities too.
  p.inputs.fill(InputLimits{-std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity()});
  p.speed_vs_accel_x.window_s = window_s;
  p.speed_vs_accel_x.tolerance_mps = 0.05 + 0.05 * window_s;  // accel_x bumps add up over it
  p.speed_vs_accel_x.tolerance_fraction = 0.05;
  p.speed_vs_accel_x.scale_tolerance = 0.0;  // its fit is not what this test is about
  p.yaw_rate_vs_accel_y.window_s = window_s;
  return p;
}

/// An irregular drive (seeded): straights and turns of 1 to 8 s, in some of them a yaw rate
/// that disagrees with accel_y; accel_x with noise and bumps; ticks 1 ms either side of a
/// spacing of 9, 10 or 11 ms (one per segment); each of speed, accel_x, accel_y and yaw rate
/// invalid for 1 to 300 ticks now and then (dropout_per_tick).
class Drive {
 public:
  Drive(std::uint32_t seed, double dropout_per_tick) : rng_(seed), dropout_(dropout_per_tick) {}

  Sample next() {
    if (segment_left_-- <= 0) new_segment();
    const TimeUs dt_us = 1000 * (spacing_ms_ + static_cast<TimeUs>(uniform(0.0, 3.0)) - 1);
    t_ += dt_us;
    speed_ = std::clamp(speed_ + accel_ * 1e-6 * static_cast<double>(dt_us), 1.0, 40.0);
    if (bump_left_-- <= 0 && uniform(0.0, 1.0) < 0.002) {
      bump_left_ = static_cast<int>(uniform(5.0, 30.0));
      bump_ = uniform(-3.0, 3.0);
    }
    Sample s;
    s.time_us = t_;
    const double grade = 0.3 * std::sin(1e-6 * static_cast<double>(t_) / 60.0);  // slow
    const double values[] = {speed_,
                             accel_ + grade + uniform(-0.3, 0.3) + (bump_left_ > 0 ? bump_ : 0.0),
                             speed_ * speed_ * curvature_ + uniform(-0.1, 0.1),
                             yaw_factor_ * speed_ * curvature_ + uniform(-0.004, 0.004)};
    for (int i = 0; i < 4; ++i) {
      if (dropout_left_[i]-- <= 0 && uniform(0.0, 1.0) < dropout_) {
        dropout_left_[i] = static_cast<int>(uniform(1.0, 300.0));
      }
      if (dropout_left_[i] <= 0) s.set(kInputs[i], values[i]);
    }
    return s;
  }

 private:
  static constexpr Input kInputs[] = {Input::kSpeed, Input::kAccelX, Input::kAccelY,
                                      Input::kYawRate};
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng_()) / 4294967296.0);
  }
  void new_segment() {
    segment_left_ = static_cast<int>(uniform(100.0, 800.0));
    spacing_ms_ = 9 + static_cast<TimeUs>(uniform(0.0, 3.0));
    const bool turn = uniform(0.0, 1.0) < 0.6;
    curvature_ = turn ? 1.0 / uniform(40.0, 200.0) : 0.0;
    accel_ = turn && uniform(0.0, 1.0) < 0.7 ? 0.0 : uniform(0.0, 1.0) * (speed_ < 20 ? 1 : -1);
    const double yaw_factors[] = {1.0, 1.0, -1.0, 1.4, 0.7};
    yaw_factor_ = yaw_factors[static_cast<int>(uniform(0.0, 5.0))];
  }

  std::mt19937 rng_;
  double dropout_;
  TimeUs t_ = 0;
  TimeUs spacing_ms_ = 10;
  int segment_left_ = 0, bump_left_ = 0;
  int dropout_left_[4] = {};
  double speed_ = 15.0, accel_ = 0.0, curvature_ = 0.0, yaw_factor_ = 1.0;
  double bump_ = 0.0;
};

struct Tally {
  int speed_windows = 0, speed_faults = 0;  ///< whole windows, and those that failed
  int yaw_windows = 0, yaw_faults = 0;      ///< steady turns, and those that failed
};

/// Equal to 1e-9, or the same infinity, or both NaN.
bool close(double a, double b) {
  return a == b || std::abs(a - b) <= 1e-9 || (std::isnan(a) && std::isnan(b));
}

/// Runs `ticks` ticks of the drive through both, edit(k, &sample) changing what it likes;
/// expects the same verdicts at every tick.
template <class Edit>
Tally compare(double window_s, Drive drive, int ticks, const Edit& edit) {
  const PlausibilityParams params = cross_checks_only(window_s);
  InputPlausibility checks{params};
  PlainCrossChecks plain{params};
  TimeUs updates[kInputCount];
  Tally tally;
  for (int k = 0; k < ticks; ++k) {
    Sample s = drive.next();
    edit(k, &s);
    for (TimeUs& u : updates) u = s.time_us;
    plain.push(s);
    checks.check(&s, updates);
    const InputVerdict want[] = {plain.speed_vs_accel(), plain.yaw_vs_accel()};
    const InputVerdict got[] = {checks.verdict(Input::kSpeed), checks.verdict(Input::kYawRate)};
    for (int c = 0; c < 2; ++c) {
      const bool same = got[c].fault == want[c].fault && close(got[c].value, want[c].value) &&
                        close(got[c].bound, want[c].bound);
      if (!same) {
        ADD_FAILURE() << "tick " << k << (c == 0 ? " speed_vs_accel_x: " : " yaw_vs_accel_y: ")
                      << describe(got[c]) << " against " << describe(want[c]) << " (values "
                      << got[c].value - want[c].value << " apart)";
        return tally;
      }
    }
    tally.speed_faults += want[0].fault != InputFault::kNone;
    tally.yaw_faults += want[1].fault != InputFault::kNone;
  }
  tally.speed_windows = plain.whole_windows;
  tally.yaw_windows = plain.steady_windows;
  return tally;
}

TEST(PlausibilityWindows, MatchAPlainRecomputationOnALongIrregularDrive) {
  // 200,000 ticks (33 min): windows of 1 s that fill, empty and refill.
  const Tally t = compare(1.0, Drive(12, 0.0015), 200'000, [](int, Sample*) {});
  EXPECT_GT(t.speed_windows, 50'000);  // both checks see whole windows, fail now and then
  EXPECT_GT(t.speed_faults, 5'000);
  EXPECT_GT(t.yaw_windows, 10'000);
  EXPECT_GT(t.yaw_faults, 1'000);
}

/// A steady turn at 20 m/s: yaw rate 0.2 rad/s by accel_y / speed, the yaw rate read as 0.19 (it
/// passes) and as 0.4 (it fails) in turn, `ticks` each.
void steady_turn(int k, Sample* s, int ticks) {
  s->set(Input::kSpeed, 20.0);
  s->set(Input::kAccelX, 0.05 * std::sin(0.7 * k));
  s->set(Input::kAccelY, 4.0 + 0.01 * std::sin(k));
  s->set(Input::kYawRate, (k / ticks % 2 == 0 ? 0.19 : 0.4) + 0.001 * std::sin(1.3 * k));
}

TEST(PlausibilityWindows, KeepNothingOfTheRowsThatLeft) {
  // One window of 1 s that never empties: what its rows leave in the sums stays there.
  const Tally t = compare(1.0, Drive(3, 0.0), 20'000, [](int k, Sample* s) {
    steady_turn(k, s, 1'500);
    if (k >= 2'000 && k < 2'100) {  // a billion times too large: their rounding, 1e-5, stays
      s->accel_y_mps2 *= 1e9;
      s->yaw_rate_radps *= 1e9;
    }
    if (k == 5'000) s->accel_y_mps2 = std::nan("");
    if (k == 8'000) s->yaw_rate_radps = std::numeric_limits<double>::infinity();
    if (k == 11'000) s->speed_mps = -std::numeric_limits<double>::infinity();
  });
  EXPECT_GT(t.yaw_windows, 15'000);
  EXPECT_GT(t.yaw_faults, 5'000);
}

TEST(PlausibilityWindows, MatchAPlainRecomputationWithWindowsLongerThanTheRing) {
  // 41 s windows hold 3,700 to 4,600 ticks, the ring 4,096: the speed check's window is whole
  // only when it fits; the yaw check's is covered by the ring's 37 to 45 s (9/10 of 41 s).
  const Tally t = compare(41.0, Drive(7, 0.0), 30'000, [](int k, Sample* s) {
    if (k >= 10'000 && k < 25'000) steady_turn(k, s, 7'000);  // 150 s
  });
  EXPECT_GT(t.speed_windows, 5'000);
  EXPECT_GT(t.speed_faults, 1'000);
  EXPECT_GT(t.yaw_windows, 1'000);
  EXPECT_GT(t.yaw_faults, 100);
}

TEST(PlausibilityWindows, ATickWhoseTimeGoesBackStartsThemAnew) {
  InputPlausibility p{cross_checks_only(1.0)};
  TimeUs updates[kInputCount];
  TimeUs t = 0;
  std::vector<InputFault> faults;
  for (int k = 0; k < 400; ++k) {
    t += k == 200 ? -5'000'000 : 10'000;
    Sample s;
    s.time_us = t;
    steady_turn(k, &s, 1'000);
    s.set(Input::kYawRate, 0.4);  // disagrees with accel_y / speed
    for (TimeUs& u : updates) u = t;
    p.check(&s, updates);
    faults.push_back(p.verdict(Input::kYawRate).fault);
  }
  EXPECT_EQ(faults[199], InputFault::kYawVsAccelY);
  EXPECT_EQ(std::count(faults.begin() + 200, faults.begin() + 290, InputFault::kNone), 90);
  EXPECT_EQ(faults[290], InputFault::kYawVsAccelY);  // 0.9 s of the new time: covered again
}

}  // namespace
}  // namespace vmass::signals
