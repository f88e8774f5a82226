#include "vmass/sim/vehicle_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "vmass/sim/suspension.hpp"
#include "vmass/sim/tyre.hpp"

namespace vmass::sim {

namespace {

// Continuous states in integration order.
enum Index : std::size_t {
  kX = 0,
  kY,
  kYaw,
  kVx,
  kVy,
  kR,
  kDist,
  kSlipF,
  kSlipR,
  kLoadAx,
  kLoadAy,
  kZ,
  kZdot,
  kN
};
using Vec = std::array<double, kN>;

constexpr double kBrakeFadeSpeedMps = 0.01;   // brake force fades to 0 below this (|v_x|)
constexpr double kRollingFadeSpeedMps = 0.1;  // rolling resistance ~ tanh(v_x / this)
constexpr double kSlipMinSpeedMps = 1.0;      // slip kinematics use max(v_x, this)
constexpr double kStopSpeedMps = 0.02;        // below this a held car stops

Vec pack(const VehicleState& s) {
  return {s.x_m,
          s.y_m,
          s.yaw_rad,
          s.vx_mps,
          s.vy_mps,
          s.yaw_rate_radps,
          s.distance_m,
          s.slip_front_rad,
          s.slip_rear_rad,
          s.load_accel_x_mps2,
          s.load_accel_y_mps2,
          s.susp_compression_m,
          s.susp_velocity_mps};
}

void unpack(const Vec& v, VehicleState& s) {
  s.x_m = v[kX];
  s.y_m = v[kY];
  s.yaw_rad = v[kYaw];
  s.vx_mps = v[kVx];
  s.vy_mps = v[kVy];
  s.yaw_rate_radps = v[kR];
  s.distance_m = v[kDist];
  s.slip_front_rad = v[kSlipF];
  s.slip_rear_rad = v[kSlipR];
  s.load_accel_x_mps2 = v[kLoadAx];
  s.load_accel_y_mps2 = v[kLoadAy];
  s.susp_compression_m = v[kZ];
  s.susp_velocity_mps = v[kZdot];
}

struct Loads {
  double front_axle, rear_axle, fl, fr, rl, rr;
};

Loads wheel_loads(const TrueVehicle& p, const MassProperties& m, double grade, double ax,
                  double ay) {
  const double g = p.gravity_mps2;
  const double l = p.wheelbase_m;
  const double M = m.mass_kg;
  const double h = m.cg_z_m;
  const double lf = m.cg_x_m;
  const double lr = l - lf;
  Loads w{};
  w.front_axle = (M * g * std::cos(grade) * lr - M * h * ax) / l;
  w.rear_axle = (M * g * std::cos(grade) * lf + M * h * ax) / l;
  const double right = 0.5 - m.cg_y_m / p.track_m;
  const double transfer = M * h * ay / p.track_m;  // left turn (ay > 0) loads the right wheels
  const double df = p.roll_stiffness_front_share * transfer;
  const double dr = (1.0 - p.roll_stiffness_front_share) * transfer;
  w.fr = std::max(0.0, w.front_axle * right + df);
  w.fl = std::max(0.0, w.front_axle * (1.0 - right) - df);
  w.rr = std::max(0.0, w.rear_axle * right + dr);
  w.rl = std::max(0.0, w.rear_axle * (1.0 - right) - dr);
  return w;
}

double corner_sprung_mass_kg(const TrueVehicle& p, const MassProperties& m) {
  const StaticLoads s = static_loads(p, m);
  const double sprung = s.rear_right_n / p.gravity_mps2 - p.rear_right_suspension.unsprung_mass_kg;
  return std::max(20.0, sprung);
}

// The longitudinal forces on each axle (body x), before the steering rotation.
struct AxleForces {
  double front = 0.0;
  double rear = 0.0;
};

// Drive, brake, rolling resistance and the realism effects' longitudinal forces (see the header).
AxleForces longitudinal_forces(const TrueVehicle& p, const Road& road, const Vec& x,
                               const VehicleInputs& in, const Loads& w, Realism fx,
                               VehicleOutputs* o) {
  const double vx = x[kVx];
  const double g = p.gravity_mps2;
  const bool speed_res = fx.has(Effect::kSpeedResistance);
  double brake = p.brake_gain_n_per_pa * in.brake_gain_scale * std::max(0.0, in.brake_pressure_pa) *
                 std::clamp(vx / kBrakeFadeSpeedMps, -1.0, 1.0);
  double esc = 0.0;
  if (fx.has(Effect::kAbsEsc)) {
    const double mu = road.friction(x[kDist]);
    const double limit = 0.95 * mu * (w.front_axle + w.rear_axle);
    o->abs_active = std::abs(brake) > limit;
    brake = std::clamp(brake, -limit, limit);
    const double excess = std::abs(x[kLoadAy]) - 0.75 * mu * g;
    if (excess > 0.0 && vx > kSlipMinSpeedMps) esc = 0.5 * in.mass.mass_kg * excess;
  }
  const double f_roll = p.rolling_resistance_coeff +
                        (speed_res ? p.rolling_resistance_speed_coeff_s2_per_m2 * vx * vx : 0.0);
  const double roll_sign = std::tanh(vx / kRollingFadeSpeedMps);
  const double viscous = speed_res ? p.driveline_viscous_n_per_mps * vx : 0.0;
  double bump = 0.0;
  if (fx.has(Effect::kRoadRoughness) && !road.bumps.empty()) {
    const double lf = in.mass.cg_x_m;
    const double lr = p.wheelbase_m - lf;
    bump = in.mass.mass_kg * (road.bump_deceleration_mps2(x[kDist] + lf, vx) +
                              road.bump_deceleration_mps2(x[kDist] - lr, vx));
  }
  const double drive = o->drive_force_n - viscous;
  const double front_share = front_drive_share(p.driven_axle);
  AxleForces f;
  f.front = front_share * drive - p.brake_front_share * (brake + esc) -
            f_roll * w.front_axle * roll_sign - 0.5 * bump;
  f.rear = (1.0 - front_share) * drive - (1.0 - p.brake_front_share) * (brake + esc) -
           f_roll * w.rear_axle * roll_sign - 0.5 * bump;
  o->brake_force_n = std::abs(brake);
  o->esc_brake_force_n = esc;
  o->rolling_resistance_n = f_roll * (w.front_axle + w.rear_axle) * roll_sign;
  o->viscous_loss_n = viscous;
  o->bump_force_n = bump;
  return f;
}

// The planar motion of a moving car (see the header's equations): fills d's motion states and
// o's forces, returns the specific forces (f_x, f_y).
std::pair<double, double> moving_derivatives(const TrueVehicle& p, const Road& road, Realism fx,
                                             const Vec& x, const VehicleInputs& in, const Loads& w,
                                             Vec& d, VehicleOutputs& o) {
  const MassProperties& m = in.mass;
  const double g = p.gravity_mps2;
  const double M = m.mass_kg;
  const double lf = m.cg_x_m;
  const double lr = p.wheelbase_m - lf;
  const double vx = x[kVx];
  const double vy = x[kVy];
  const double r = x[kR];
  const double delta = in.road_wheel_angle_rad;
  const double fyf = wheel_lateral_force(p.front_tyre, x[kSlipF], w.fl) +
                     wheel_lateral_force(p.front_tyre, x[kSlipF], w.fr);
  const double fyr = wheel_lateral_force(p.rear_tyre, x[kSlipR], w.rl) +
                     wheel_lateral_force(p.rear_tyre, x[kSlipR], w.rr);
  const AxleForces axle = longitudinal_forces(p, road, x, in, w, fx, &o);
  const bool wind = fx.has(Effect::kWind);
  const double v_air = vx + (wind ? in.wind_head_mps : 0.0);
  const double drag = 0.5 * p.air_density_kg_per_m3 * p.drag_area_m2 * v_air * std::abs(v_air);
  const double side = wind ? 0.5 * p.air_density_kg_per_m3 * p.side_force_area_m2 *
                                 in.wind_cross_mps * std::abs(in.wind_cross_mps)
                           : 0.0;
  const double cd = std::cos(delta);
  const double sd = std::sin(delta);
  const double force_x =
      axle.front * cd - fyf * sd + axle.rear - drag - M * g * std::sin(o.grade_rad);
  const double force_y = axle.front * sd + fyf * cd + fyr + side -
                         M * g * std::cos(o.grade_rad) * std::sin(o.bank_rad);
  const double moment_z = lf * (axle.front * sd + fyf * cd) - lr * fyr;

  d[kVx] = (force_x + M * r * vy - in.rotating_mass_kg * vx * in.driven_slip_rate_per_s) /
           (M + in.rotating_mass_kg * (1.0 + in.driven_slip));
  d[kVy] = force_y / M - r * vx;
  d[kR] = moment_z / m.yaw_inertia_kgm2;
  d[kX] = vx * std::cos(x[kYaw]) - vy * std::sin(x[kYaw]);
  d[kY] = vx * std::sin(x[kYaw]) + vy * std::cos(x[kYaw]);
  d[kYaw] = r;
  d[kDist] = std::hypot(vx, vy);
  const double v_eff = std::max(vx, kSlipMinSpeedMps);
  d[kSlipF] = v_eff / p.front_tyre.relaxation_length_m *
              (std::atan2(vy + lf * r, v_eff) - delta - x[kSlipF]);
  d[kSlipR] =
      v_eff / p.rear_tyre.relaxation_length_m * (std::atan2(vy - lr * r, v_eff) - x[kSlipR]);

  o.dvx_dt_mps2 = d[kVx];
  o.dvy_dt_mps2 = d[kVy];
  o.yaw_accel_radps2 = d[kR];
  o.drag_force_n = drag;
  o.side_wind_force_n = side;
  o.lateral_force_front_n = fyf;
  o.lateral_force_rear_n = fyr;
  return {d[kVx] - r * vy + g * std::sin(o.grade_rad),
          d[kVy] + r * vx + g * std::cos(o.grade_rad) * std::sin(o.bank_rad)};
}

Vec derivatives(const TrueVehicle& p, const Road& road, Realism fx, const Vec& x, bool stopped,
                const VehicleInputs& in, VehicleOutputs* out) {
  const MassProperties& m = in.mass;
  const double g = p.gravity_mps2;
  const double theta = road.grade_at(x[kDist]);
  const double phi = road.bank_at(x[kDist]);
  const Loads w = wheel_loads(p, m, theta, x[kLoadAx], x[kLoadAy]);

  Vec d{};
  VehicleOutputs o;
  o.grade_rad = theta;
  o.bank_rad = phi;
  o.drive_force_n = in.wheel_torque_nm / p.wheel_radius_m;
  o.front_axle_load_n = w.front_axle;
  o.rear_axle_load_n = w.rear_axle;
  o.rear_right_load_n = w.rr;
  const auto [f_x, f_y] = stopped
                              ? std::pair{g * std::sin(theta), g * std::cos(theta) * std::sin(phi)}
                              : moving_derivatives(p, road, fx, x, in, w, d, o);
  const double tau = p.load_transfer_time_constant_s;
  d[kLoadAx] = (f_x - x[kLoadAx]) / tau;
  d[kLoadAy] = (f_y - x[kLoadAy]) / tau;
  const SuspensionParams& sp = p.rear_right_suspension;
  const double sprung_load = w.rr - sp.unsprung_mass_kg * g;
  d[kZ] = x[kZdot];
  d[kZdot] = (sprung_load - spring_force(sp, x[kZ]) - sp.damping_n_s_per_m * x[kZdot]) /
             corner_sprung_mass_kg(p, m);
  if (out != nullptr) {
    o.specific_force_x_mps2 = f_x;
    o.specific_force_y_mps2 = f_y;
    *out = o;
  }
  return d;
}

// Force along x that would move a car at rest, without brakes or rolling resistance.
double push_force_at_rest(const TrueVehicle& p, const Road& road, const VehicleState& s,
                          const VehicleInputs& in) {
  return in.wheel_torque_nm / p.wheel_radius_m -
         in.mass.mass_kg * p.gravity_mps2 * std::sin(road.grade_at(s.distance_m));
}

}  // namespace

VehicleModel::VehicleModel(const TrueVehicle& params, const Road& road, Realism effects)
    : p_(params), road_(road), effects_(effects) {}

VehicleState VehicleModel::settled_state(const VehicleInputs& in, double speed_mps) const {
  VehicleState s;
  s.stopped = !(speed_mps > 0.0);
  s.vx_mps = s.stopped ? 0.0 : speed_mps;
  const double theta = road_.grade_at(0.0);
  const double phi = road_.bank_at(0.0);
  const double g = p_.gravity_mps2;
  s.load_accel_x_mps2 = g * std::sin(theta);
  s.load_accel_y_mps2 = g * std::cos(theta) * std::sin(phi);
  const Loads w = wheel_loads(p_, in.mass, theta, s.load_accel_x_mps2, s.load_accel_y_mps2);
  const SuspensionParams& sp = p_.rear_right_suspension;
  s.susp_compression_m = spring_compression(sp, w.rr - sp.unsprung_mass_kg * g);
  return s;
}

void VehicleModel::step(VehicleState& s, const VehicleInputs& in, double dt_s) const {
  const double hold_force = p_.brake_gain_n_per_pa * std::max(0.0, in.brake_pressure_pa);
  if (s.stopped && push_force_at_rest(p_, road_, s, in) > hold_force) s.stopped = false;

  const Vec x0 = pack(s);
  const bool st = s.stopped;
  const Vec k1 = derivatives(p_, road_, effects_, x0, st, in, nullptr);
  Vec xt;
  for (std::size_t i = 0; i < kN; ++i) xt[i] = x0[i] + 0.5 * dt_s * k1[i];
  const Vec k2 = derivatives(p_, road_, effects_, xt, st, in, nullptr);
  for (std::size_t i = 0; i < kN; ++i) xt[i] = x0[i] + 0.5 * dt_s * k2[i];
  const Vec k3 = derivatives(p_, road_, effects_, xt, st, in, nullptr);
  for (std::size_t i = 0; i < kN; ++i) xt[i] = x0[i] + dt_s * k3[i];
  const Vec k4 = derivatives(p_, road_, effects_, xt, st, in, nullptr);
  Vec x1;
  for (std::size_t i = 0; i < kN; ++i) {
    x1[i] = x0[i] + dt_s / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  unpack(x1, s);

  if (!s.stopped) {
    const bool held = push_force_at_rest(p_, road_, s, in) <= hold_force;
    if (s.vx_mps <= 0.0 || (s.vx_mps < kStopSpeedMps && held)) s.stopped = true;
  }
  if (s.stopped) {
    s.vx_mps = 0.0;
    s.vy_mps = 0.0;
    s.yaw_rate_radps = 0.0;
    s.slip_front_rad = 0.0;
    s.slip_rear_rad = 0.0;
  }
}

VehicleOutputs VehicleModel::evaluate(const VehicleState& s, const VehicleInputs& in) const {
  VehicleOutputs o;
  derivatives(p_, road_, effects_, pack(s), s.stopped, in, &o);
  return o;
}

}  // namespace vmass::sim
