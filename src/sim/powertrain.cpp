#include "vmass/sim/powertrain.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

namespace {
// Share of the prime mover's inertia still coupled to the wheels through an unlocked converter
// (turbine and gearbox side).
constexpr double kUnlockedInertiaShare = 0.2;
// After an upshift the prime mover turns at least this much above the downshift speed.
constexpr double kUpshiftMargin = 1.1;
}  // namespace

std::string_view transmission_name(Transmission t) {
  switch (t) {
    case Transmission::kAutomatedManual:
      return "automated_manual";
    case Transmission::kManual:
      return "manual";
    case Transmission::kAutomatic:
      return "automatic";
    case Transmission::kDualClutch:
      return "dual_clutch";
    case Transmission::kElectric:
      return "electric";
  }
  return "unknown";
}

std::string PowertrainParams::validate(const std::string& prefix) const {
  if (gear_ratios.empty()) return prefix + "gear_ratios must not be empty";
  if (hold_gear < 0 || hold_gear > gear_count()) {
    return prefix + "hold_gear must be 0 (shift) or a gear 1.." + std::to_string(gear_count());
  }
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
  if (!(shift_min_scale >= 0.0 && shift_min_scale <= 1.0)) {
    return prefix + "shift_min_scale must be in [0, 1]";
  }
  if (!(idle_speed_radps > 0.0)) return prefix + "idle_speed_radps must be > 0";
  if (!(drag_torque_nm >= 0.0 && drag_torque_per_radps >= 0.0)) {
    return prefix + "drag torques must be >= 0";
  }
  if (!(accessory_power_w >= 0.0 && accessory_on_s > 0.0 && accessory_off_s > 0.0)) {
    return prefix + "accessory_power_w must be >= 0 and its cycle times > 0";
  }
  if (!(tc_stall_torque_ratio >= 1.0 && tc_coupling_speed_ratio > 0.0 &&
        tc_coupling_speed_ratio < 1.0 && tc_stall_speed_radps > idle_speed_radps)) {
    return prefix +
           "torque converter: stall ratio >= 1, coupling ratio in (0, 1), stall speed > idle";
  }
  if (!(creep_wheel_torque_nm >= 0.0 && creep_fade_speed_mps > 0.0)) {
    return prefix + "creep_wheel_torque_nm must be >= 0, creep_fade_speed_mps > 0";
  }
  if (!(regen_max_force_n >= 0.0 && regen_min_speed_mps > 0.0)) {
    return prefix + "regen_max_force_n must be >= 0, regen_min_speed_mps > 0";
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

Powertrain::Powertrain(const PowertrainParams& params, double wheel_radius_m, Realism effects)
    : p_(params), r_(wheel_radius_m), effects_(effects) {}

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
  if (p_.hold_gear > 0) gear_ = p_.hold_gear;
  target_gear_ = gear_;
  shift_time_s_ = -1.0;
  time_in_gear_s_ = p_.min_time_in_gear_s;
  speed_mps_ = speed_mps;
  pm_torque_nm_ = std::clamp(wheel_torque_nm / (ratio(gear_) * p_.efficiency), 0.0,
                             max_wheel_torque_nm(speed_mps) / (ratio(gear_) * p_.efficiency));
  update_converter(speed_mps);
}

double Powertrain::max_wheel_torque_nm(double speed_mps) const {
  const double w = pm_speed_radps(gear_, speed_mps);
  double t = p_.max_torque_nm;
  if (w > 1e-6) t = std::min(t, p_.max_power_w / w);
  return t * ratio(gear_) * p_.efficiency;
}

double Powertrain::torque_scale() const {
  if (shift_time_s_ < 0.0) return 1.0;
  const double low = p_.shift_min_scale;
  const double t = shift_time_s_;
  if (t < p_.shift_ramp_down_s) return 1.0 - (1.0 - low) * t / p_.shift_ramp_down_s;
  const double t_open_end = p_.shift_ramp_down_s + p_.shift_open_s;
  if (t < t_open_end) return low;
  return std::min(1.0, low + (1.0 - low) * (t - t_open_end) / p_.shift_ramp_up_s);
}

int Powertrain::engaged_gear() const {
  if (shift_time_s_ < 0.0) return gear_;
  // Automatic and dual-clutch gearboxes hand the torque over without opening the driveline.
  if (p_.transmission == Transmission::kAutomatic || p_.transmission == Transmission::kDualClutch) {
    return gear_;
  }
  const double t = shift_time_s_;
  if (t < p_.shift_ramp_down_s) return gear_;
  if (t < p_.shift_ramp_down_s + p_.shift_open_s) return 0;
  return gear_;
}

double Powertrain::drag_torque_nm(double pm_speed_radps) const {
  return p_.drag_torque_nm + p_.drag_torque_per_radps * pm_speed_radps;
}

bool Powertrain::converter_locked() const { return tc_ratio_ == 1.0; }

void Powertrain::update_shift(double dt_s, double speed_mps) {
  // Shift progress. gear_ switches to the target when the torque reaches its low point.
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
    return;
  }
  time_in_gear_s_ += dt_s;
  if (p_.hold_gear > 0) return;
  const double w = pm_speed_radps(gear_, speed_mps);
  if (time_in_gear_s_ < p_.min_time_in_gear_s) return;
  // A gearbox controller does not upshift into a speed it would downshift from at once (a wide
  // first step, as a truck automatic's, would otherwise hunt between the two gears).
  const bool upshift_holds =
      gear_ < p_.gear_count() &&
      pm_speed_radps(gear_ + 1, speed_mps) >= kUpshiftMargin * p_.downshift_speed_radps;
  if (w > p_.upshift_speed_radps && upshift_holds) {
    target_gear_ = gear_ + 1;
    shift_time_s_ = 0.0;
  } else if (w < p_.downshift_speed_radps && gear_ > 1) {
    target_gear_ = gear_ - 1;
    shift_time_s_ = 0.0;
  }
}

// Torque ratio and engine speed of the converter (see the header): a stall curve below the
// coupling point, a fixed slip above it, locked from gear 2 above lockup speed.
void Powertrain::update_converter(double speed_mps) {
  const int g = std::max(1, engaged_gear());
  const double w_turbine = pm_speed_radps(g, speed_mps);
  tc_ratio_ = 1.0;
  if (p_.transmission == Transmission::kElectric) {
    engine_speed_radps_ = w_turbine;
    return;
  }
  engine_speed_radps_ = std::max(p_.idle_speed_radps, w_turbine);
  const bool converter = p_.has_torque_converter() && effects_.has(Effect::kTorqueConverter);
  const bool locked = g >= 2 && speed_mps >= p_.tc_lockup_speed_mps;
  if (!converter || locked) return;
  const double load = std::clamp(pm_torque_nm_ / p_.max_torque_nm, 0.0, 1.0);
  const double w_stall =
      p_.idle_speed_radps + (p_.tc_stall_speed_radps - p_.idle_speed_radps) * std::sqrt(load);
  const double sr_c = p_.tc_coupling_speed_ratio;
  engine_speed_radps_ = std::max(w_stall, w_turbine / sr_c);
  const double sr = w_turbine / engine_speed_radps_;
  if (sr < sr_c)
    tc_ratio_ = p_.tc_stall_torque_ratio - (p_.tc_stall_torque_ratio - 1.0) * sr / sr_c;
}

void Powertrain::step(double t_s, double dt_s, double wheel_torque_demand_nm, double speed_mps,
                      bool braking) {
  update_shift(dt_s, speed_mps);
  speed_mps_ = speed_mps;
  braking_ = braking;
  const double gain = ratio(gear_) * p_.efficiency;
  double cmd = std::clamp(wheel_torque_demand_nm, 0.0, max_wheel_torque_nm(speed_mps)) / gain;
  overrun_ = false;
  if (wheel_torque_demand_nm <= 0.0) {
    const bool electric = p_.transmission == Transmission::kElectric;
    if (electric && effects_.has(Effect::kRegenBraking) && speed_mps > p_.regen_min_speed_mps) {
      cmd = std::max(wheel_torque_demand_nm, -p_.regen_max_force_n * r_) / gain;
    } else if (!electric && effects_.has(Effect::kEngineDrag) && engaged_gear() > 0) {
      cmd = -drag_torque_nm(pm_speed_radps(gear_, speed_mps));
      overrun_ = true;
    }
  }
  // Prime-mover torque: first-order lag towards the command of the current gear.
  const double a = 1.0 - std::exp(-dt_s / p_.torque_time_constant_s);
  pm_torque_nm_ += (cmd - pm_torque_nm_) * a;
  update_converter(speed_mps);
  if (effects_.has(Effect::kAccessoryLoads) && p_.accessory_power_w > 0.0) {
    const double period = p_.accessory_on_s + p_.accessory_off_s;
    const double phase = std::fmod(t_s + p_.accessory_phase_s, period);
    accessory_on_ = phase < p_.accessory_on_s;
  } else {
    accessory_on_ = false;
  }
}

double Powertrain::creep_nm() const {
  if (!effects_.has(Effect::kCreep) || !p_.has_torque_converter() || braking_) return 0.0;
  return p_.creep_wheel_torque_nm * std::max(0.0, 1.0 - speed_mps_ / p_.creep_fade_speed_mps);
}

double Powertrain::wheel_torque_nm() const {
  const int g = engaged_gear();
  if (g == 0) return 0.0;
  const double gain = ratio(g) * p_.efficiency;
  double t = pm_torque_nm_ * torque_scale() * tc_ratio_ * gain;
  if (accessory_on_ && p_.transmission != Transmission::kElectric) {
    t -= p_.accessory_power_w / std::max(engine_speed_radps_, p_.idle_speed_radps) * gain;
  }
  return t + creep_nm();
}

double Powertrain::reported_pm_torque_nm() const {
  return overrun_ ? pm_torque_nm_ * (1.0 + p_.drag_report_error) : pm_torque_nm_;
}

double Powertrain::reported_engine_torque_nm() const {
  // A clutch shift's torque reduction is the engine's own (the driver lifts off, or the gearbox
  // asks the engine for less), so its ECU reports it; a converter or double-clutch gearbox hands
  // the torque over in its clutches, and the engine's torque does not show the dip.
  const bool engine_reduces =
      p_.transmission == Transmission::kManual || p_.transmission == Transmission::kAutomatedManual;
  return reported_pm_torque_nm() * (engine_reduces ? torque_scale() : 1.0);
}

double Powertrain::reported_wheel_torque_nm() const {
  const int g = engaged_gear();
  if (g == 0) return 0.0;
  const double tc_ecu = 1.0 + (tc_ratio_ - 1.0) * (1.0 + p_.tc_model_error);
  return reported_pm_torque_nm() * torque_scale() * tc_ecu * ratio(g) * p_.efficiency +
         creep_nm() * (1.0 + p_.tc_model_error);
}

double Powertrain::engine_speed_radps() const { return engine_speed_radps_; }

int Powertrain::gear_signal() const { return engaged_gear(); }

double Powertrain::rotating_mass_kg() const {
  const int g = engaged_gear();
  if (g >= 1 && !converter_locked()) {
    const double i = ratio(g);
    const double j = p_.wheel_inertia_kgm2 +
                     kUnlockedInertiaShare * p_.efficiency * p_.prime_mover_inertia_kgm2 * i * i;
    return j / (r_ * r_);
  }
  return vmass::sim::rotating_mass_kg(p_, g, r_);
}

}  // namespace vmass::sim
