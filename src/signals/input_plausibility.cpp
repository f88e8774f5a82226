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
    : params_(params), rows_(kWindowRows) {
  speed_window_.window_us = static_cast<TimeUs>(params.speed_vs_accel_x.window_s * 1e6);
  yaw_window_.window_us = static_cast<TimeUs>(params.yaw_rate_vs_accel_y.window_s * 1e6);
  yaw_window_.min_speed = params.yaw_rate_vs_accel_y.min_speed_mps;
}

void InputPlausibility::reset() {
  tracks_.fill(Track{});
  verdicts_.fill(InputVerdict{});
  refused_last_tick_ = 0;
  scale_ = ScaleFit{};
  newest_ = -1;
  count_ = 0;
  speed_window_.open = false;
  yaw_window_.open = false;
  has_slow_residual_ = false;
}

InputVerdict InputPlausibility::check_rate(int i, double value, TimeUs update_us) {
  Track& t = tracks_[static_cast<std::size_t>(i)];
  const double max_rate = params_.inputs[static_cast<std::size_t>(i)].max_rate_per_s;
  if (update_us != t.last_update_us) {  // a new frame: compared with the previous one
    const double dt_s =
        t.has_update ? static_cast<double>(update_us - t.last_update_us) * 1e-6 : 0.0;
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
    t.witness_moved_us = kNeverUs;
    t.speed_min = speed;
    return {};
  }
  if (w.available) {
    t.witness_min = std::min(t.witness_min, w.value);
    t.witness_max = std::max(t.witness_max, w.value);
    if (t.witness_moved_us == kNeverUs && t.witness_max - t.witness_min >= w.min_span) {
      t.witness_moved_us = update_us;
    }
  }
  t.speed_min = std::min(t.speed_min, speed);
  const double frozen_s = static_cast<double>(update_us - t.frozen_since_us) * 1e-6;
  // The input had time to follow its witness (a truck's yaw lags its steering by ~0.5 s).
  const bool witness_moved = !w.exists || (t.witness_moved_us != kNeverUs &&
                                           update_us - t.witness_moved_us >= kResponseUs);
  if (frozen_s >= stuck_s && witness_moved && t.speed_min >= w.min_speed) {
    return InputVerdict{InputFault::kStuck, frozen_s, stuck_s};
  }
  return {};
}

void InputPlausibility::push_row(const Sample& s) {
  if (count_ == kWindowRows) forget_row(newest_ - static_cast<std::int64_t>(kWindowRows) + 1);
  ++newest_;
  count_ = std::min(count_ + 1, kWindowRows);
  Row& r = rows_[static_cast<std::size_t>(newest_) & (kWindowRows - 1)];
  r.t = s.time_us;
  r.speed = s.speed_mps;
  r.accel_x = s.accel_x_mps2;
  r.accel_y = s.accel_y_mps2;
  r.yaw_rate = s.yaw_rate_radps;
  r.longitudinal = s.has(Input::kSpeed) && s.has(Input::kAccelX);
  r.lateral = s.has(Input::kSpeed) && s.has(Input::kAccelY) && s.has(Input::kYawRate);
  const Row* previous = count_ >= 2 ? &row(1) : nullptr;
  r.accel_x_area =
      r.longitudinal && previous != nullptr && previous->longitudinal
          ? 0.5 * (previous->accel_x + r.accel_x) * 1e-6 * static_cast<double>(r.t - previous->t)
          : 0.0;
  // Ticks come in time order; one that goes back starts the windows anew.
  const bool time_went_back = previous != nullptr && r.t < previous->t;
  extend_speed_window(time_went_back);
  extend_yaw_window(time_went_back);
}

/// Row `seq`, the oldest, is about to be overwritten: the windows let go of it.
void InputPlausibility::forget_row(std::int64_t seq) {
  SpeedWindow& w = speed_window_;
  if (w.open && w.first == seq) {
    ++w.first;
    w.area.remove(row_at(w.first).accel_x_area);
  }
  if (yaw_window_.open && yaw_window_.first == seq) drop_oldest_yaw_row();
}

void InputPlausibility::extend_speed_window(bool restart) {
  SpeedWindow& w = speed_window_;
  const Row& newest = row(0);
  if (!newest.longitudinal) {
    w.open = false;
    return;
  }
  if (!w.open || restart) {  // a run starts: the newest row alone
    w.open = true;
    w.first = newest_;
    w.area.clear();
    return;
  }
  w.area.add(newest.accel_x_area);
  while (w.first < newest_ && newest.t - row_at(w.first + 1).t >= w.window_us) {
    ++w.first;
    w.area.remove(row_at(w.first).accel_x_area);
  }
  if (!w.area.finite()) recompute_speed_sums();  // see extend_yaw_window
}

void InputPlausibility::extend_yaw_window(bool restart) {
  YawWindow& w = yaw_window_;
  const Row& newest = row(0);
  if (!newest.lateral) {
    w.open = false;
    return;
  }
  if (!w.open || restart) {  // a run starts: empty, the newest row comes next
    w.open = true;
    w.first = newest_;
    w.yaw_rate_sum.clear();
    w.accel_y_sum.clear();
    w.speed_sum.clear();
    w.slow_rows = 0;
    w.yaw_rate_spread.clear();
    w.accel_y_spread.clear();
  }
  w.yaw_rate_sum.add(newest.yaw_rate);
  w.accel_y_sum.add(newest.accel_y);
  w.speed_sum.add(newest.speed);
  w.slow_rows += newest.speed < w.min_speed ? 1 : 0;
  w.yaw_rate_spread.push(newest_, newest.yaw_rate);
  w.accel_y_spread.push(newest_, newest.accel_y);
  while (w.first <= newest_ && newest.t - row_at(w.first).t > w.window_us) drop_oldest_yaw_row();
  if (!(w.yaw_rate_sum.finite() && w.accel_y_sum.finite() && w.speed_sum.finite())) {
    recompute_yaw_sums();  // a NaN or an infinity went in: it stays in the sum after it left
  }
}

void InputPlausibility::drop_oldest_yaw_row() {
  YawWindow& w = yaw_window_;
  const Row& r = row_at(w.first);
  w.yaw_rate_sum.remove(r.yaw_rate);
  w.accel_y_sum.remove(r.accel_y);
  w.speed_sum.remove(r.speed);
  w.slow_rows -= r.speed < w.min_speed ? 1 : 0;
  ++w.first;
  w.yaw_rate_spread.drop_before(w.first);
  w.accel_y_spread.drop_before(w.first);
}

// Exactly: newest row first, as a loop over the window adds them.
void InputPlausibility::recompute_speed_sums() {
  SpeedWindow& w = speed_window_;
  double area = 0.0;
  for (std::int64_t seq = newest_; seq > w.first; --seq) area += row_at(seq).accel_x_area;
  w.area.set(area);
}

void InputPlausibility::recompute_yaw_sums() {
  YawWindow& w = yaw_window_;
  double sum_r = 0.0, sum_ay = 0.0, sum_v = 0.0;
  for (std::int64_t seq = newest_; seq >= w.first; --seq) {
    const Row& r = row_at(seq);
    sum_r += r.yaw_rate;
    sum_ay += r.accel_y;
    sum_v += r.speed;
  }
  w.yaw_rate_sum.set(sum_r);
  w.accel_y_sum.set(sum_ay);
  w.speed_sum.set(sum_v);
}

InputVerdict InputPlausibility::speed_vs_accel() {
  const SpeedAccelCheck& c = params_.speed_vs_accel_x;
  if (!c.enabled || count_ < 2 || !row(0).longitudinal) {
    has_slow_residual_ = false;
    return scale_.ready ? scale_verdict() : InputVerdict{};
  }
  const SpeedWindow& w = speed_window_;
  const Row& oldest = row_at(w.first);
  if (row(0).t - oldest.t < w.window_us) return {};  // not a whole window of history yet
  const double integral = w.area.value();
  const double delta_v = row(0).speed - oldest.speed;
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
  const YawWindow& w = yaw_window_;
  const std::int64_t n = newest_ - w.first + 1;
  if (n < 2 || row(0).t - row_at(w.first).t < w.window_us * 9 / 10) return {};  // not covered
  const double mean_r = w.yaw_rate_sum.value() / static_cast<double>(n);
  const double mean_ay = w.accel_y_sum.value() / static_cast<double>(n);
  const double mean_v = w.speed_sum.value() / static_cast<double>(n);
  const bool steady = w.slow_rows == 0 && std::abs(mean_ay) >= c.min_accel_y_mps2 &&
                      w.accel_y_spread.spread() <= c.steady_accel_y_mps2 &&
                      w.yaw_rate_spread.spread() <= c.steady_yaw_rate_radps;
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
