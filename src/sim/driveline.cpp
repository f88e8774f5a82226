#include "vmass/sim/driveline.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

namespace {
constexpr double kTwoPi = 6.28318530717958647692;
}  // namespace

std::string DrivelineParams::validate(const std::string& prefix) const {
  if (!(mode_frequency_first_gear_hz > 0.0 && mode_frequency_top_gear_hz > 0.0 &&
        mode_frequency_top_gear_hz < 100.0 && mode_frequency_first_gear_hz < 100.0)) {
    return prefix + "mode frequencies must be in (0, 100) Hz";
  }
  if (!(mode_damping_ratio > 0.0 && mode_damping_ratio <= 2.0)) {
    return prefix + "mode_damping_ratio must be in (0, 2]";
  }
  if (!(lag_s >= 0.0 && lag_s <= 0.5)) return prefix + "lag_s must be in [0, 0.5]";
  return "";
}

Driveline::Driveline(const DrivelineParams& params, const PowertrainParams& powertrain,
                     double step_s, Realism effects)
    : p_(params),
      gear_ratios_(powertrain.gear_ratios),
      step_s_(step_s),
      mode_on_(effects.has(Effect::kDrivelineMode)) {
  const double lag = effects.has(Effect::kDrivelineLag) ? params.lag_s : 0.0;
  const auto n = static_cast<std::size_t>(std::lround(lag / step_s));
  delay_.assign(n + 1, 0.0);
}

double Driveline::mode_frequency_hz(int gear) const {
  const double f1 = p_.mode_frequency_first_gear_hz;
  const double ftop = p_.mode_frequency_top_gear_hz;
  if (gear_ratios_.size() < 2) return ftop;
  const double i1 = gear_ratios_.front();
  const double itop = gear_ratios_.back();
  const int g = std::clamp(gear, 1, static_cast<int>(gear_ratios_.size()));
  const double ig = gear_ratios_[static_cast<std::size_t>(g - 1)];
  const double p = std::log(ftop / f1) / std::log(i1 / itop);
  return f1 * std::pow(i1 / ig, p);
}

void Driveline::reset(double torque_nm) {
  std::fill(delay_.begin(), delay_.end(), torque_nm);
  head_ = 0;
  torque_nm_ = torque_nm;
  rate_nm_per_s_ = 0.0;
}

double Driveline::step(double torque_in_nm, int gear) {
  delay_[head_] = torque_in_nm;
  head_ = (head_ + 1) % delay_.size();
  const double u = delay_[head_];  // the oldest entry: lag_s ago
  if (!mode_on_) {
    torque_nm_ = u;
    rate_nm_per_s_ = 0.0;
    return torque_nm_;
  }
  if (gear > 0) last_gear_ = gear;
  const double wn = kTwoPi * mode_frequency_hz(last_gear_);
  const double z = p_.mode_damping_ratio;
  // RK4 on x = (T, T'), input held over the step.
  auto deriv = [&](double x, double v, double* dx, double* dv) {
    *dx = v;
    *dv = wn * wn * (u - x) - 2.0 * z * wn * v;
  };
  const double h = step_s_;
  double k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
  deriv(torque_nm_, rate_nm_per_s_, &k1x, &k1v);
  deriv(torque_nm_ + 0.5 * h * k1x, rate_nm_per_s_ + 0.5 * h * k1v, &k2x, &k2v);
  deriv(torque_nm_ + 0.5 * h * k2x, rate_nm_per_s_ + 0.5 * h * k2v, &k3x, &k3v);
  deriv(torque_nm_ + h * k3x, rate_nm_per_s_ + h * k3v, &k4x, &k4v);
  torque_nm_ += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
  rate_nm_per_s_ += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  return torque_nm_;
}

}  // namespace vmass::sim
