// Powertrain: the simulated car's prime mover (engine or motor) and gearbox, up to the torque
// that enters the driveline at the wheels, and the torque the ECU REPORTS on CAN. The two differ
// when realism effects are on (see realism.hpp); with none they are equal and the model is the
// automated 6-speed of the demo car.
//
//   T_wheel = T_pm * s(t) * TR * i_g * i_f * eta - T_acc * i_g * i_f * eta + T_creep
//   T_pm'   = (T_cmd - T_pm) / tau,  T_cmd in [-T_drag(w_pm), min(T_max, P_max / w_pm)]
//   m_rot(g) = (J_w + eta J_pm (i_g i_f)^2) / r^2         equivalent rotating mass, per gear
//   m_rot(0) = J_w / r^2                                    clutch open (during a shift)
// with s(t) the shift's torque scale (ramp down, clutch open, ramp up), and:
//   TR      torque-converter ratio (automatic, unlocked): TR_stall - (TR_stall - 1) SR / SR_c
//           for the speed ratio SR = w_turbine / w_engine below the coupling point SR_c, else 1.
//           The engine speed while unlocked follows a stall curve: w_e = max(w_stall(T), w_t/SR_c)
//           with w_stall(T) = w_idle + (w_stall - w_idle) sqrt(T / T_max). Locks up from gear 2
//           above lockup_speed_mps.
//   T_drag  engine drag in overrun (demand <= 0): d0 + d1 w_pm at the engine (engine_drag).
//   T_acc   accessory torque P_acc / w_e while the A/C compressor is on (accessory_loads).
//   T_creep automatic in gear, brakes released: creep_nm (1 - v / creep_fade_mps) (creep).
//   regen   electric: the demand may go down to -regen_max_force_n * r (regen_braking).
//
// The REPORTED wheel torque is the ECU's estimate: T_pm * s * TR_ecu * i_g * i_f * eta + creep
// (times report_scale), where TR_ecu = 1 + (TR - 1)(1 + tc_model_error) and the drag part of T_pm
// is reported as T_drag (1 + drag_report_error): the ECU does not see the accessory load. The
// reported ENGINE torque (cars that only publish engine torque and gear) is T_pm (same errors)
// times s(t) with a clutch gearbox (manual, automated manual), whose shift is a torque reduction
// of the engine itself; with a converter or double clutch the dip is in the gearbox's clutches,
// and the engine's report stays T_pm.
//
// Not thread-safe (it has state); no allocation after construction.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/sim/realism.hpp"

namespace vmass::sim {

enum class Transmission : std::uint8_t {
  kAutomatedManual = 0,  ///< the demo car: clutch opens during a short shift
  kManual,               ///< driver's clutch: longer interruptions
  kAutomatic,            ///< planetary with a torque converter: torque dip, no interruption
  kDualClutch,           ///< fast torque handover
  kElectric,             ///< single speed, regenerative braking
};
std::string_view transmission_name(Transmission t);

struct PowertrainParams {
  Transmission transmission = Transmission::kAutomatedManual;
  std::vector<double> gear_ratios = {3.50, 2.10, 1.40, 1.00, 0.80, 0.65};  ///< i_g, gear 1..N
  double final_drive_ratio = 4.0;                                          ///< i_f
  double efficiency = 0.92;      ///< eta, driveline, applied to torque
  double max_torque_nm = 320.0;  ///< prime mover
  double max_power_w = 110000.0;
  double prime_mover_inertia_kgm2 = 0.08;  ///< J_pm (rotor/crank, flywheel, clutch)
  double wheel_inertia_kgm2 = 3.6;         ///< J_w: four wheels, discs, half shafts
  double torque_time_constant_s = 0.08;    ///< tau
  double upshift_speed_radps = 314.159;    ///< 3000 rpm of the prime mover
  double downshift_speed_radps = 125.664;  ///< 1200 rpm
  double min_time_in_gear_s = 1.5;
  double shift_ramp_down_s = 0.10;
  double shift_open_s = 0.10;
  double shift_ramp_up_s = 0.10;
  /// Torque scale while an automatic or dual-clutch shift hands over (no open clutch): the
  /// shift's s(t) falls to this instead of 0.
  double shift_min_scale = 0.0;
  /// > 0: the gearbox stays in this gear whatever the speed (a truck driven in one gear).
  int hold_gear = 0;

  double idle_speed_radps = 83.78;  ///< 800 rpm
  // engine_drag
  double drag_torque_nm = 0.0;         ///< d0, at the engine
  double drag_torque_per_radps = 0.0;  ///< d1
  double drag_report_error = 0.0;      ///< reported drag = true (1 + this)
  // accessory_loads
  double accessory_power_w = 0.0;  ///< A/C compressor while on
  double accessory_on_s = 12.0;    ///< compressor cycle: on for this long ...
  double accessory_off_s = 18.0;   ///< ... then off for this long
  double accessory_phase_s = 0.0;  ///< where in the cycle t = 0 falls
  // torque_converter (automatic only)
  double tc_stall_torque_ratio = 2.0;
  double tc_coupling_speed_ratio = 0.85;
  double tc_stall_speed_radps = 230.0;  ///< about 2200 rpm at full torque
  double tc_lockup_speed_mps = 8.0;     ///< locks up above this from gear 2
  double tc_model_error = 0.0;          ///< the ECU's (TR - 1) is off by this fraction
  // creep (automatic only)
  double creep_wheel_torque_nm = 0.0;
  double creep_fade_speed_mps = 2.0;
  // regen_braking (electric only)
  double regen_max_force_n = 0.0;    ///< at the wheels
  double regen_min_speed_mps = 1.5;  ///< regeneration fades out below this

  std::string validate(const std::string& prefix) const;
  int gear_count() const { return static_cast<int>(gear_ratios.size()); }
  bool has_torque_converter() const { return transmission == Transmission::kAutomatic; }
};

/// Equivalent rotating mass J/r^2 in gear 1..N, or with the clutch open (gear 0), kg.
double rotating_mass_kg(const PowertrainParams& p, int gear, double wheel_radius_m);

class Powertrain {
 public:
  /// effects: which of torque_converter, engine_drag, accessory_loads, creep, regen_braking apply.
  Powertrain(const PowertrainParams& params, double wheel_radius_m,
             Realism effects = Realism::none());

  /// Start at rest or cruising: the gear that suits the speed, no shift, torque torque_nm at the
  /// wheels (clamped to what is available).
  void reset(double speed_mps, double wheel_torque_nm);

  /// Advance by dt_s towards the wheel-torque demand (negative only for regeneration), at time
  /// t_s, shifting by prime-mover speed. braking: the driver is on the brake (no creep).
  void step(double t_s, double dt_s, double wheel_torque_demand_nm, double speed_mps,
            bool braking = false);

  double wheel_torque_nm() const;            ///< true torque into the driveline at the wheels
  double reported_wheel_torque_nm() const;   ///< what the ECU reports (see the header)
  double reported_engine_torque_nm() const;  ///< the ECU's engine (motor) torque
  double engine_speed_radps() const;         ///< prime-mover speed
  int gear_signal() const;                   ///< engaged gear, 0 while the clutch is open
  int selected_gear() const { return gear_; }
  bool shifting() const { return shift_time_s_ >= 0.0; }
  bool converter_locked() const;                        ///< true without a converter
  double converter_ratio() const { return tc_ratio_; }  ///< TR now
  bool accessory_on() const { return accessory_on_; }
  double rotating_mass_kg() const;  ///< current m_rot
  /// Largest wheel torque available at this speed in the current gear.
  double max_wheel_torque_nm(double speed_mps) const;
  const PowertrainParams& params() const { return p_; }

 private:
  double ratio(int gear) const;  ///< i_g * i_f
  double pm_speed_radps(int gear, double speed_mps) const;
  double torque_scale() const;  ///< s(t) of the shift
  /// T_pm as the ECU reports it (its drag error in overrun), before the shift's scale.
  double reported_pm_torque_nm() const;
  int engaged_gear() const;  ///< gear the clutch connects, 0 when open
  double drag_torque_nm(double pm_speed_radps) const;
  void update_shift(double dt_s, double speed_mps);
  void update_converter(double speed_mps);
  double creep_nm() const;

  PowertrainParams p_;
  double r_;
  Realism effects_;
  int gear_ = 1;
  int target_gear_ = 1;
  double pm_torque_nm_ = 0.0;
  double time_in_gear_s_ = 0.0;
  double shift_time_s_ = -1.0;  ///< < 0: no shift in progress
  double speed_mps_ = 0.0;
  double tc_ratio_ = 1.0;
  double engine_speed_radps_ = 0.0;
  bool accessory_on_ = false;
  bool braking_ = false;
  bool overrun_ = false;  ///< T_pm is drag (demand <= 0)
};

}  // namespace vmass::sim
