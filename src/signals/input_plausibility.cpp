#include "vmass/signals/input_plausibility.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::signals {
namespace {

constexpr double kMinRateDtS = 0.005;  ///< updates closer than this count as 5 ms apart
constexpr double kMaxRateGapS = 1.0;   ///< after a longer gap the rate is not checked
constexpr double kInf = 1e300;
constexpr TimeUs kResponseUs = 1'500'000;  ///< a stuck input must lag its witness this long

/// The witness of an input's stuck check: what moves when the input should (see the header).
struct Witness {
  bool exists = false;
  bool available = false;  ///< the inputs it is made of are valid at this tick
  double value = 0.0;
  double min_span = 0.0;   ///< the witness must span this much
  double min_speed = 0.0;  ///< and the speed stay at least this
};

Witness witness_of(Input in, const Sample& s) {
  Witness w;
  switch (in) {
    case Input::kSteeringWheelAngle:  // the path's curvature r / v: the speed alone moves r
      w = {true, s.has(Input::kYawRate) && s.has(Input::kSpeed) && s.speed_mps >= 3.0,
           s.yaw_rate_radps / std::max(s.speed_mps, 3.0), 0.01, 3.0};
      break;
    case Input::kYawRate:
      w = {true, s.has(Input::kSteeringWheelAngle), s.steering_wheel_angle_rad, 0.35, 5.0};
      break;
    case Input::kAccelY:
      w = {true, s.has(Input::kYawRate) && s.has(Input::kSpeed), s.yaw_rate_radps * s.speed_mps,
           1.5, 0.0};
      break;
    case Input::kAccelX:
      w = {true, s.has(Input::kSpeed), s.speed_mps, 3.0, 0.0};
      break;
    default:
      break;
  }
  return w;
}

}  // namespace

InputPlausibility::InputPlausibility(const PlausibilityParams& params)
    : params_(params), rows_(kWindowRows) {}

void InputPlausibility::reset() {
  tracks_.fill(Track{});
  verdicts_.fill(InputVerdict{});
  refused_last_tick_ = 0;
  scale_ = ScaleFit{};
  head_ = 0;
  count_ = 0;
  has_slow_residual_ = false;
}

InputVerdict InputPlausibility::check_rate(int i, double value, TimeUs update_us) {
  Track& t = tracks_[static_cast<std::size_t>(i)];
  const double max_rate = params_.inputs[static_cast<std::size_t>(i)].max_rate_per_s;
  if (update_us != t.last_update_us) {  // a new frame: compared with the previous one
    const double dt_s = static_cast<double>(update_us - t.last_update_us) * 1e-6;
    t.rate_fault = false;
    if (t.has_update && max_rate > 0.0 && dt_s > 0.0 && dt_s <= kMaxRateGapS) {
      const double rate = std::abs(value - t.last_value) / std::max(dt_s, kMinRateDtS);
      if (rate > max_rate) {
        t.rate_fault = true;
        t.rate_verdict = InputVerdict{InputFault::kRateOfChange, rate, max_rate};
      }
    }
    t.has_update = true;
    t.last_value = value;
    t.last_update_us = update_us;
  }
  return t.rate_fault ? t.rate_verdict : InputVerdict{};
}

InputVerdict InputPlausibility::check_stuck(int i, const Sample& raw, const Sample& witnesses,
                                            TimeUs update_us) {
  const auto input = static_cast<Input>(i);
  const double stuck_s = params_.inputs[static_cast<std::size_t>(i)].stuck_s;
  if (stuck_s <= 0.0) return {};
  Track& t = tracks_[static_cast<std::size_t>(i)];
  const double value = raw.value(input);
  const Witness w = witness_of(input, witnesses);
  const double speed = witnesses.has(Input::kSpeed) ? witnesses.speed_mps : -kInf;
  const double band = params_.inputs[static_cast<std::size_t>(i)].stuck_band;
  // It moved, or its witness is missing or refused (a faulty witness's own jumps prove
  // nothing): the watch starts anew.
  if (!t.has_frozen || !(std::abs(value - t.frozen_value) <= band) || (w.exists && !w.available)) {
    t.has_frozen = true;
    t.frozen_value = value;
    t.frozen_since_us = update_us;
    t.witness_min = w.available ? w.value : kInf;  // empty until the witness is seen
    t.witness_max = w.available ? w.value : -kInf;
    t.witness_moved_us = -1;
    t.speed_min = speed;
    return {};
  }
  if (w.available) {
    t.witness_min = std::min(t.witness_min, w.value);
    t.witness_max = std::max(t.witness_max, w.value);
    if (t.witness_moved_us < 0 && t.witness_max - t.witness_min >= w.min_span) {
      t.witness_moved_us = update_us;
    }
  }
  t.speed_min = std::min(t.speed_min, speed);
  const double frozen_s = static_cast<double>(update_us - t.frozen_since_us) * 1e-6;
  // The input had time to follow its witness (a truck's yaw lags its steering by ~0.5 s).
  const bool witness_moved =
      !w.exists || (t.witness_moved_us >= 0 && update_us - t.witness_moved_us >= kResponseUs);
  if (frozen_s >= stuck_s && witness_moved && t.speed_min >= w.min_speed) {
    return InputVerdict{InputFault::kStuck, frozen_s, stuck_s};
  }
  return {};
}

void InputPlausibility::push_row(const Sample& s) {
  head_ = (head_ + 1) & (kWindowRows - 1);
  count_ = std::min(count_ + 1, kWindowRows);
  Row& r = rows_[head_];
  r.t = s.time_us;
  r.speed = s.speed_mps;
  r.accel_x = s.accel_x_mps2;
  r.accel_y = s.accel_y_mps2;
  r.yaw_rate = s.yaw_rate_radps;
  r.longitudinal = s.has(Input::kSpeed) && s.has(Input::kAccelX);
  r.lateral = s.has(Input::kSpeed) && s.has(Input::kAccelY) && s.has(Input::kYawRate);
}

InputVerdict InputPlausibility::speed_vs_accel() {
  const SpeedAccelCheck& c = params_.speed_vs_accel_x;
  if (!c.enabled || count_ < 2 || !row(0).longitudinal) {
    has_slow_residual_ = false;
    return scale_.ready ? scale_verdict() : InputVerdict{};
  }
  const auto window_us = static_cast<TimeUs>(c.window_s * 1e6);
  double integral = 0.0;
  std::size_t i = 1;
  for (; i < count_ && row(i).longitudinal && row(0).t - row(i - 1).t < window_us; ++i) {
    integral += 0.5 * (row(i).accel_x + row(i - 1).accel_x) * 1e-6 *
                static_cast<double>(row(i - 1).t - row(i).t);
  }
  if (row(0).t - row(i - 1).t < window_us) return {};  // not a whole window of history yet
  const double delta_v = row(0).speed - row(i - 1).speed;
  const double residual = delta_v - integral;
  const double dt_s = 1e-6 * static_cast<double>(row(0).t - row(1).t);
  if (!has_slow_residual_) {
    slow_residual_ = residual;
    has_slow_residual_ = true;
  }
  const double deviation = residual - slow_residual_;
  const double tolerance = c.tolerance_mps + c.tolerance_fraction * std::abs(integral);
  if (std::abs(deviation) > tolerance) {
    return InputVerdict{InputFault::kSpeedVsAccelX, deviation, tolerance};  // slow part frozen
  }
  const double alpha = std::min(1.0, dt_s / c.smoothing_s);
  slow_residual_ += (residual - slow_residual_) * alpha;
  update_scale(delta_v, integral, dt_s);
  return scale_verdict();
}

void InputPlausibility::update_scale(double delta_v, double integral, double dt_s) {
  const SpeedAccelCheck& c = params_.speed_vs_accel_x;
  ScaleFit& f = scale_;
  // Both high-passed (their slow means removed: a grade shifts the integral, not its changes),
  // then fitted delta_v = k * integral with exponential forgetting over scale_time_s.
  const double alpha = std::min(1.0, dt_s / c.smoothing_s);
  f.mean_dv += (delta_v - f.mean_dv) * alpha;
  f.mean_int += (integral - f.mean_int) * alpha;
  const double x = integral - f.mean_int, y = delta_v - f.mean_dv;
  const double forget = std::min(1.0, dt_s / c.scale_time_s);
  f.sxy += (x * y - f.sxy) * forget;
  f.sxx += (x * x - f.sxx) * forget;
  f.weight += (1.0 - f.weight) * forget;
  // Enough excitation: a mean square of the high-passed integral of at least 0.25 (m/s)^2.
  f.ready = f.weight > 0.5 && f.sxx > 0.25 * f.weight;
}

InputVerdict InputPlausibility::scale_verdict() const {
  const SpeedAccelCheck& c = params_.speed_vs_accel_x;
  if (!scale_.ready || c.scale_tolerance <= 0.0) return {};
  const double k = scale_.sxy / scale_.sxx;
  if (std::abs(k - 1.0) <= c.scale_tolerance) return {};
  return InputVerdict{InputFault::kSpeedAccelScale, k, c.scale_tolerance};
}

InputVerdict InputPlausibility::yaw_vs_accel() {
  const YawAccelCheck& c = params_.yaw_rate_vs_accel_y;
  if (!c.enabled || count_ < 2 || !row(0).lateral) return {};
  const auto window_us = static_cast<TimeUs>(c.window_s * 1e6);
  double sum_r = 0.0, sum_ay = 0.0, sum_v = 0.0;
  double r_min = kInf, r_max = -kInf, ay_min = kInf, ay_max = -kInf, v_min = kInf;
  std::size_t n = 0;
  for (; n < count_ && row(n).lateral && row(0).t - row(n).t <= window_us; ++n) {
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
  if (n < 2 || row(0).t - row(n - 1).t < window_us * 9 / 10) return {};  // window not covered
  const double mean_r = sum_r / static_cast<double>(n);
  const double mean_ay = sum_ay / static_cast<double>(n);
  const double mean_v = sum_v / static_cast<double>(n);
  const bool steady = v_min >= c.min_speed_mps && std::abs(mean_ay) >= c.min_accel_y_mps2 &&
                      ay_max - ay_min <= c.steady_accel_y_mps2 &&
                      r_max - r_min <= c.steady_yaw_rate_radps;
  if (!steady) return {};
  const double residual = mean_r - mean_ay / mean_v;
  const double tolerance = c.tolerance_radps + c.tolerance_fraction * std::abs(mean_r);
  if (std::abs(residual) > tolerance) {
    return InputVerdict{InputFault::kYawVsAccelY, residual, tolerance};
  }
  return {};
}

void InputPlausibility::flag(Sample* s, int i, const InputVerdict& v, TimeUs update_us) {
  const auto input = static_cast<Input>(i);
  s->valid &= ~input_bit(input);
  verdicts_[static_cast<std::size_t>(i)] = v;
  Track& t = tracks_[static_cast<std::size_t>(i)];
  if (update_us != t.counted_update_us) {  // each refused update counted once
    t.counted_update_us = update_us;
    ++implausible_[static_cast<std::size_t>(i)];
  }
}

void InputPlausibility::check(Sample* sample, const TimeUs (&update_time_us)[kInputCount]) {
  verdicts_.fill(InputVerdict{});
  if (!params_.enabled) return;
  const Sample raw = *sample;
  std::array<InputVerdict, kInputCount> found{};
  // Each input on its own: limits and rate, then stuck against witnesses that passed (and were
  // not refused at the previous tick: a faulty witness proves nothing).
  Sample clean = raw;
  for (int i = 0; i < kInputCount; ++i) {
    if (!raw.has(static_cast<Input>(i))) continue;
    found[static_cast<std::size_t>(i)] = check_limits_and_rate(i, raw, update_time_us[i]);
    if (found[static_cast<std::size_t>(i)].fault != InputFault::kNone) {
      clean.valid &= ~input_bit(static_cast<Input>(i));
    }
  }
  Sample witnesses = clean;
  witnesses.valid &= ~refused_last_tick_;
  for (int i = 0; i < kInputCount; ++i) {
    if (!clean.has(static_cast<Input>(i))) continue;
    found[static_cast<std::size_t>(i)] = check_stuck(i, raw, witnesses, update_time_us[i]);
    if (found[static_cast<std::size_t>(i)].fault != InputFault::kNone) {
      clean.valid &= ~input_bit(static_cast<Input>(i));
    }
  }
  push_row(clean);  // the cross-checks look at the bus's values that passed on their own
  auto pair = [&](const InputVerdict& v, Input a, Input b) {
    if (v.fault == InputFault::kNone) return;
    for (Input in : {a, b}) {
      InputVerdict& f = found[static_cast<std::size_t>(in)];
      if (f.fault == InputFault::kNone) f = v;
    }
  };
  pair(speed_vs_accel(), Input::kSpeed, Input::kAccelX);
  pair(yaw_vs_accel(), Input::kYawRate, Input::kAccelY);
  refused_last_tick_ = 0;
  for (int i = 0; i < kInputCount; ++i) {
    if (raw.has(static_cast<Input>(i)) &&
        found[static_cast<std::size_t>(i)].fault != InputFault::kNone) {
      flag(sample, i, found[static_cast<std::size_t>(i)], update_time_us[i]);
      refused_last_tick_ |= input_bit(static_cast<Input>(i));
    }
  }
}

InputVerdict InputPlausibility::check_limits_and_rate(int i, const Sample& raw, TimeUs update_us) {
  const double v = raw.value(static_cast<Input>(i));
  const InputLimits& l = params_.inputs[static_cast<std::size_t>(i)];
  // The rate check follows every update, whatever the verdict, to keep its reference current.
  const InputVerdict rate = check_rate(i, v, update_us);
  if (v < l.min) return {InputFault::kBelowMinimum, v, l.min};
  if (v > l.max) return {InputFault::kAboveMaximum, v, l.max};
  return rate;
}

}  // namespace vmass::signals
