#include "vmass/sim/powertrain.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

std::string PowertrainParams::validate(const std::string& prefix) const {
  if (gear_ratios.empty()) return prefix + "gear_ratios must not be empty";
  for (std::size_t i = 0; i < gear_ratios.size(); ++i) {
    if (!(gear_ratios[i] > 0.0)) return prefix + "gear_ratios must be > 0";
    if (i > 0 && !(gear_ratios[i] < gear_ratios[i - 1])) {
      return prefix + "gear_ratios must decrease from gear 1";
    }
  }
  if (!(final_drive_ratio > 0.0)) return prefix + "final_drive_ratio must be > 0";
  if (!(efficiency > 0.0 && efficiency <= 1.0)) return prefix + "efficiency must be in (0, 1]";
  if (!(max_torque_nm > 0.0)) return prefix + "max_torque_nm must be > 0";
  if (!(max_power_w > 0.0)) return prefix + "max_power_w must be > 0";
  if (!(prime_mover_inertia_kgm2 >= 0.0)) return prefix + "prime_mover_inertia_kgm2 must be >= 0";
  if (!(wheel_inertia_kgm2 >= 0.0)) return prefix + "wheel_inertia_kgm2 must be >= 0";
  if (!(torque_time_constant_s > 0.0)) return prefix + "torque_time_constant_s must be > 0";
  if (!(upshift_speed_radps > downshift_speed_radps && downshift_speed_radps > 0.0)) {
    return prefix + "upshift_speed_radps must be > downshift_speed_radps > 0";
  }
  if (!(min_time_in_gear_s >= 0.0)) return prefix + "min_time_in_gear_s must be >= 0";
  if (!(shift_ramp_down_s > 0.0 && shift_open_s > 0.0 && shift_ramp_up_s > 0.0)) {
    return prefix + "shift phase durations must be > 0";
  }
  return "";
}

double rotating_mass_kg(const PowertrainParams& p, int gear, double wheel_radius_m) {
  const double r2 = wheel_radius_m * wheel_radius_m;
  double j = p.wheel_inertia_kgm2;
  if (gear >= 1 && gear <= p.gear_count()) {
    const double i = p.gear_ratios[static_cast<std::size_t>(gear - 1)] * p.final_drive_ratio;
    j += p.efficiency * p.prime_mover_inertia_kgm2 * i * i;
  }
  return j / r2;
}

Powertrain::Powertrain(const PowertrainParams& params, double wheel_radius_m)
    : p_(params), r_(wheel_radius_m) {}

double Powertrain::ratio(int gear) const {
  return p_.gear_ratios[static_cast<std::size_t>(gear - 1)] * p_.final_drive_ratio;
}

double Powertrain::pm_speed_radps(int gear, double speed_mps) const {
  return std::max(0.0, speed_mps) / r_ * ratio(gear);
}

void Powertrain::reset(double speed_mps, double wheel_torque_nm) {
  gear_ = 1;
  while (gear_ < p_.gear_count() && pm_speed_radps(gear_, speed_mps) >
                                        0.5 * (p_.upshift_speed_radps + p_.downshift_speed_radps)) {
    ++gear_;
  }
  target_gear_ = gear_;
  shift_time_s_ = -1.0;
  time_in_gear_s_ = p_.min_time_in_gear_s;
  pm_torque_nm_ = std::clamp(wheel_torque_nm / (ratio(gear_) * p_.efficiency), 0.0,
                             max_wheel_torque_nm(speed_mps) / (ratio(gear_) * p_.efficiency));
}

double Powertrain::max_wheel_torque_nm(double speed_mps) const {
  const double w = pm_speed_radps(gear_, speed_mps);
  double t = p_.max_torque_nm;
  if (w > 1e-6) t = std::min(t, p_.max_power_w / w);
  return t * ratio(gear_) * p_.efficiency;
}

double Powertrain::torque_scale() const {
  if (shift_time_s_ < 0.0) return 1.0;
  const double t = shift_time_s_;
  if (t < p_.shift_ramp_down_s) return 1.0 - t / p_.shift_ramp_down_s;
  const double t_open_end = p_.shift_ramp_down_s + p_.shift_open_s;
  if (t < t_open_end) return 0.0;
  return std::min(1.0, (t - t_open_end) / p_.shift_ramp_up_s);
}

int Powertrain::engaged_gear() const {
  if (shift_time_s_ < 0.0) return gear_;
  const double t = shift_time_s_;
  if (t < p_.shift_ramp_down_s) return gear_;
  if (t < p_.shift_ramp_down_s + p_.shift_open_s) return 0;
  return gear_;
}

void Powertrain::step(double dt_s, double wheel_torque_demand_nm, double speed_mps) {
  // Shift progress. gear_ switches to the target when the clutch opens.
  if (shift_time_s_ >= 0.0) {
    const double before = shift_time_s_;
    shift_time_s_ += dt_s;
    if (before < p_.shift_ramp_down_s && shift_time_s_ >= p_.shift_ramp_down_s) {
      gear_ = target_gear_;
      time_in_gear_s_ = 0.0;
    }
    if (shift_time_s_ >= p_.shift_ramp_down_s + p_.shift_open_s + p_.shift_ramp_up_s) {
      shift_time_s_ = -1.0;
    }
  } else {
    time_in_gear_s_ += dt_s;
    const double w = pm_speed_radps(gear_, speed_mps);
    if (time_in_gear_s_ >= p_.min_time_in_gear_s) {
      if (w > p_.upshift_speed_radps && gear_ < p_.gear_count()) {
        target_gear_ = gear_ + 1;
        shift_time_s_ = 0.0;
      } else if (w < p_.downshift_speed_radps && gear_ > 1) {
        target_gear_ = gear_ - 1;
        shift_time_s_ = 0.0;
      }
    }
  }
  // Prime-mover torque: first-order lag towards the clamped command of the current gear.
  const double gain = ratio(gear_) * p_.efficiency;
  const double cmd = std::clamp(wheel_torque_demand_nm, 0.0, max_wheel_torque_nm(speed_mps)) / gain;
  const double a = 1.0 - std::exp(-dt_s / p_.torque_time_constant_s);
  pm_torque_nm_ += (cmd - pm_torque_nm_) * a;
}

double Powertrain::wheel_torque_nm() const {
  const int g = engaged_gear();
  if (g == 0) return 0.0;
  return pm_torque_nm_ * torque_scale() * ratio(g) * p_.efficiency;
}

int Powertrain::gear_signal() const { return engaged_gear(); }

double Powertrain::rotating_mass_kg() const {
  return vmass::sim::rotating_mass_kg(p_, engaged_gear(), r_);
}

}  // namespace vmass::sim
