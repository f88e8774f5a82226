#include "vmass/core/launch_integrator.hpp"

#include <cmath>

namespace vmass {

void LaunchIntegrator::forget() {
  launching_ = false;
  stopping_ = false;
  still_s_ = 0.0;
  still_sum_ = 0.0;
  still_n_ = 0;
  lead_count_ = 0;
}

// The reading: the standstill less its lead, whose ticks start the integral instead.
void LaunchIntegrator::start_launch() {
  double lead_s = 0.0;
  double lead_sum = 0.0;
  long lead_n = 0;
  std::size_t i = lead_next_;
  for (std::size_t k = 0; k < lead_count_ && lead_s < kLeadS; ++k) {
    i = (i + kLeadTicks - 1) % kLeadTicks;
    lead_s += lead_[i].dt_s;
    lead_sum += lead_[i].accel_mps2;
    ++lead_n;
  }
  if (still_s_ - lead_s < kMinStandstillS || still_n_ <= lead_n) return;
  reference_ = (still_sum_ - lead_sum) / static_cast<double>(still_n_ - lead_n);
  integral_ = 0.0;
  for (std::size_t k = 0; k < static_cast<std::size_t>(lead_n); ++k, i = (i + 1) % kLeadTicks) {
    integral_ += (lead_[i].accel_mps2 - reference_) * lead_[i].dt_s;
  }
  launching_ = true;
  launch_s_ = lead_s;
  has_mid_ = false;
}

bool LaunchIntegrator::finish(double speed_mps, LaunchSpan* out) const {
  const double end_ratio = integral_ / speed_mps;
  if (!(mid_ratio_ > 0.0) || !(end_ratio > 0.0) ||
      std::abs(std::log(end_ratio / mid_ratio_)) > kMaxRatioChange) {
    return false;
  }
  *out = LaunchSpan{false, speed_mps, integral_};
  return true;
}

void LaunchIntegrator::follow_stop(double accel_mps2, double dt, double speed_mps) {
  if (speed_mps >= kEndSpeedMps) {
    stopping_ = false;
    return;
  }
  if (!stopping_) {
    if (last_speed_ < kEndSpeedMps) return;  // it did not come from above end_mps
    stopping_ = true;
    stop_start_mps_ = speed_mps;
    stop_accel_s_ = stop_s_ = 0.0;
    stop_has_mid_ = false;
    stop_rest_s_ = stop_rest_sum_ = 0.0;
    stop_rest_n_ = 0;
    return;
  }
  if (stop_rest_s_ > 0.0 || speed_mps > stop_start_mps_ + 0.5 || stop_s_ > kMaxLaunchS) {
    stopping_ = false;  // moving again: no stop, or no longer one
    return;
  }
  stop_accel_s_ += accel_mps2 * dt;
  stop_s_ += dt;
  if (!stop_has_mid_ && speed_mps <= kMidSpeedMps) {
    stop_has_mid_ = true;
    stop_mid_mps_ = speed_mps;
    stop_mid_accel_s_ = stop_accel_s_;
    stop_mid_s_ = stop_s_;
  }
}

bool LaunchIntegrator::stop_at_rest(double accel_mps2, double dt, LaunchSpan* out) {
  if (!stopping_) return false;
  stop_rest_s_ += dt;
  if (stop_rest_s_ <= kLeadS) {  // the car may still roll: part of the stop
    stop_accel_s_ += accel_mps2 * dt;
    stop_s_ += dt;
    return false;
  }
  stop_rest_sum_ += accel_mps2;
  ++stop_rest_n_;
  if (stop_rest_s_ < kLeadS + kMinStandstillS) return false;
  stopping_ = false;
  const double reference = stop_rest_sum_ / static_cast<double>(stop_rest_n_);
  const double whole = reference * stop_s_ - stop_accel_s_;  // the speed lost, m/s
  const double to_mid = reference * stop_mid_s_ - stop_mid_accel_s_;
  if (!stop_has_mid_ || !(whole > 0.0) || !(to_mid > 0.0) || !(stop_start_mps_ > stop_mid_mps_)) {
    return false;
  }
  const double whole_ratio = whole / stop_start_mps_;
  const double mid_ratio = to_mid / (stop_start_mps_ - stop_mid_mps_);
  if (std::abs(std::log(whole_ratio / mid_ratio)) > kMaxRatioChange) return false;
  *out = LaunchSpan{true, stop_start_mps_, whole};
  return true;
}

bool LaunchIntegrator::step(const Sample& s, LaunchSpan* out) {
  if (!s.has(Input::kSpeed) || !s.has(Input::kAccelX)) {
    has_last_ = false;
    forget();
    return false;
  }
  const double dt = has_last_ ? to_seconds(s.time_us - last_us_) : 0.0;
  has_last_ = true;
  last_us_ = s.time_us;
  if (!(dt > 0.0) || dt > kMaxTickS) {
    forget();
    return false;
  }
  const double v = std::abs(s.speed_mps);
  if (v < kStandstillMps) {
    const bool stopped = stop_at_rest(s.accel_x_mps2, dt, out);
    launching_ = false;
    still_s_ += dt;
    still_sum_ += s.accel_x_mps2;
    ++still_n_;
    lead_[lead_next_] = Tick{dt, s.accel_x_mps2};
    lead_next_ = (lead_next_ + 1) % kLeadTicks;
    if (lead_count_ < kLeadTicks) ++lead_count_;
    last_speed_ = v;
    return stopped;
  }
  follow_stop(s.accel_x_mps2, dt, v);
  last_speed_ = v;
  if (!launching_ && still_n_ > 0) start_launch();
  still_s_ = 0.0;
  still_sum_ = 0.0;
  still_n_ = 0;
  lead_count_ = 0;
  if (!launching_) return false;
  integral_ += (s.accel_x_mps2 - reference_) * dt;
  launch_s_ += dt;
  if (launch_s_ > kMaxLaunchS) {
    launching_ = false;
    return false;
  }
  if (!has_mid_ && v >= kMidSpeedMps) {
    has_mid_ = true;
    mid_ratio_ = integral_ / v;
  }
  if (v < kEndSpeedMps) return false;
  launching_ = false;
  return finish(v, out);
}

}  // namespace vmass
