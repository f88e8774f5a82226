#include "vmass/sim/population_scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <utility>

#include "paper_roads.hpp"
#include "seats.hpp"
#include "vmass/sim/random_stream.hpp"

namespace vmass::sim {

namespace {

constexpr double kKmh = 1.0 / 3.6;
constexpr double kG = 9.80665;
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// How a class drives: speeds, accelerations and lateral accelerations it can and does reach.
struct DrivingStyle {
  double speed_scale = 1.0;  ///< of the car speeds
  double max_speed_mps = 36.0;
  double accel_scale = 1.0;  ///< of the car accelerations
  double max_lateral_mps2 = 3.5;
};

DrivingStyle style_of(const DrawnVehicle& d) {
  switch (d.vehicle_class) {
    case VehicleClass::kHeavyTruck:
      return {0.75, 23.6, 0.35, 2.0};
    case VehicleClass::kVan:
    case VehicleClass::kPickup:
      return {0.95, 36.0, 0.75, 3.0};
    case VehicleClass::kSuv:
      return {1.0, 36.0, 0.9, 3.2};
    default:
      return {1.0, 36.0, 1.0, 3.5};
  }
}

// Speed and steering references built segment by segment.
class ProfileBuilder {
 public:
  ProfileBuilder(const DrawnVehicle& d, DrivingStyle style)
      : ratio_(d.vehicle.steering_ratio), wheelbase_(d.vehicle.wheelbase_m), style_(style) {
    speed_.push_back({0.0, 0.0});
    steer_.push_back({0.0, 0.0});
  }

  double time() const { return t_; }
  /// Start the drive already moving at car_mps (scaled).
  void start_at(double car_mps) {
    v_ = speed_for(car_mps);
    speed_.front().y = v_;
  }
  double speed() const { return v_; }
  double speed_for(double car_mps) const {
    return std::min(car_mps * style_.speed_scale, style_.max_speed_mps);
  }

  void stand(double s) { hold(s); }
  void cruise(double s) { hold(s); }
  /// Accelerate (or brake) to car_mps (scaled for the class) at car_accel (scaled).
  void change_to(double car_mps, double car_accel) {
    const double v = car_mps <= 0.0 ? 0.0 : speed_for(car_mps);
    const double accel = std::max(
        0.2, car_accel * (v > v_ ? style_.accel_scale : std::max(0.5, style_.accel_scale)));
    t_ += std::abs(v - v_) / accel;
    v_ = v;
    speed_.push_back({t_, v_});
  }
  /// A slalom at the current speed: lateral acceleration amplitude (capped for the class).
  void slalom(double ay_mps2, double frequency_hz, double duration_s) {
    sines_.push_back({t_, t_ + duration_s, steering_for(ay_mps2), frequency_hz});
    cruise(duration_s);
  }
  /// A constant-radius turn at the current speed, entered and left over 2 s.
  void turn(double ay_mps2, double hold_s, bool left) {
    const double a = (left ? 1.0 : -1.0) * steering_for(ay_mps2);
    steer_.push_back({t_, 0.0});
    steer_.push_back({t_ + 2.0, a});
    steer_.push_back({t_ + 2.0 + hold_s, a});
    steer_.push_back({t_ + 4.0 + hold_s, 0.0});
    cruise(4.0 + hold_s);
  }

  DriverProfile build(double duration_s) {
    if (t_ < duration_s) hold(duration_s - t_);
    DriverProfile p;
    p.speed_mps = PiecewiseLinear(speed_);
    p.steering_wheel_angle_rad = PiecewiseLinear(steer_);
    p.steering_sines = sines_;
    p.hold_reached_speed_from_s = hold_reached_from_;
    return p;
  }
  /// From now + s on, the speed controller holds whatever speed the vehicle has reached.
  void hold_reached_speed_after(double s) { hold_reached_from_ = t_ + s; }

 private:
  void hold(double s) {
    t_ += s;
    speed_.push_back({t_, v_});
  }
  // Kinematic steering for a_y at the current speed: delta = l a_y / v^2.
  double steering_for(double ay_mps2) const {
    const double ay = std::min(ay_mps2, style_.max_lateral_mps2);
    const double v = std::max(v_, 3.0);
    return std::min(ratio_ * wheelbase_ * ay / (v * v), 450.0 * kDeg);
  }

  double ratio_, wheelbase_;
  DrivingStyle style_;
  double t_ = 0.0;
  double v_ = 0.0;
  std::vector<PiecewiseLinear::Point> speed_, steer_;
  std::optional<double> hold_reached_from_;
  std::vector<SteeringSine> sines_;
};

// --- payload -------------------------------------------------------------------------------

enum class PayloadKind : std::uint8_t { kTypical, kHeavyRear, kLoadChange };

std::vector<LoadItem> people_and_luggage(const DrawnVehicle& d, RandomStream& rng, double fill) {
  const Seats s = seats_of(d);
  std::vector<LoadItem> items;
  items.push_back({rng.uniform(70, 95), s.front_x, 0.37, s.seat_z});  // driver (left-hand drive)
  const double capacity = d.payload_capacity_kg;
  if (s.cargo) {
    // Cargo spread over the cargo area, its centre somewhere along it.
    const double cargo = std::max(0.0, fill * capacity - items[0].mass_kg);
    const double x = rng.uniform(s.cargo_x0, s.cargo_x1);
    items.push_back({cargo, x, rng.uniform(-0.2, 0.2), s.cargo_z});
    return items;
  }
  if (rng.chance(fill)) items.push_back({rng.uniform(55, 95), s.front_x, -0.37, s.seat_z});
  for (double y : {0.40, -0.40, 0.0}) {
    if (rng.chance(fill * 0.8)) items.push_back({rng.uniform(20, 95), s.rear_x, y, s.seat_z});
  }
  items.push_back({rng.uniform(0.0, 60.0 * fill + 5.0), s.boot_x, 0.0, s.cargo_z});
  return items;
}

std::vector<LoadItem> heavy_rear(const DrawnVehicle& d, RandomStream& rng) {
  const Seats s = seats_of(d);
  const double capacity = d.payload_capacity_kg * rng.uniform(0.85, 1.0);
  std::vector<LoadItem> items = {{rng.uniform(70, 95), s.front_x, 0.37, s.seat_z}};
  double left = capacity - items[0].mass_kg;
  if (s.cargo) {
    items.push_back(
        {left, rng.uniform(0.5 * (s.cargo_x0 + s.cargo_x1), s.cargo_x1), 0.0, s.cargo_z});
    return items;
  }
  for (double y : {0.40, -0.40}) {
    const double m = std::min(left, rng.uniform(70, 95));
    items.push_back({m, s.rear_x, y, s.seat_z});
    left -= m;
  }
  items.push_back({std::max(0.0, left), s.boot_x, 0.0, s.cargo_z});
  return items;
}

std::vector<LoadItem> added_at_stop(const DrawnVehicle& d, RandomStream& rng) {
  const Seats s = seats_of(d);
  const double mass = d.payload_capacity_kg * rng.uniform(0.3, 0.5);
  if (s.cargo) return {{mass, rng.uniform(s.cargo_x0, s.cargo_x1), 0.0, s.cargo_z}};
  return {{0.4 * mass, s.rear_x, 0.40, s.seat_z},
          {0.35 * mass, s.rear_x, -0.40, s.seat_z},
          {0.25 * mass, s.boot_x, 0.0, s.cargo_z}};
}

// Without payload_position, every item sits at the empty car's centre of gravity (eq. 3 holds).
void place_items(std::vector<LoadItem>& items, const TrueVehicle& v, Realism realism) {
  if (realism.has(Effect::kPayloadPosition)) return;
  for (LoadItem& it : items) it = {it.mass_kg, v.empty.cg_x_m, 0.0, v.empty.cg_z_m};
}

// --- drives --------------------------------------------------------------------------------

void paper_exp1(ProfileBuilder& b) {
  // ECE-15 elementary urban cycle, twice, as in the paper's Fig. 4 (speeds in km/h).
  for (int i = 0; i < 2; ++i) {
    b.stand(5);
    b.change_to(15 * kKmh, 1.04);
    b.cruise(8);
    b.change_to(0, 0.83);
    b.stand(13);
    b.change_to(32 * kKmh, 0.8);
    b.cruise(24);
    b.change_to(10 * kKmh, 0.8);
    b.change_to(0, 0.9);
    b.stand(8);
    b.change_to(50 * kKmh, 0.6);
    b.cruise(12);
    b.change_to(35 * kKmh, 0.52);
    b.cruise(13);
    b.change_to(0, 0.97);
  }
}

void paper_exp2(ProfileBuilder& b) {
  b.stand(5);
  b.change_to(14, 1.8);
  b.slalom(2.8, 0.35, 16);
  b.change_to(8, 1.5);
  b.change_to(16, 1.2);
  b.turn(3.0, 10, true);
  b.change_to(10, 1.5);
  b.turn(2.5, 7, false);
  b.change_to(18, 1.3);
  b.slalom(2.0, 0.25, 22);
  b.change_to(12, 1.2);
  b.turn(2.8, 8, true);
  b.change_to(15, 1.0);
  b.slalom(2.5, 0.4, 16);
  b.change_to(0, 2.0);
}

void urban(ProfileBuilder& b, RandomStream& rng) {
  b.stand(5);
  while (b.time() < 270) {
    b.change_to(rng.uniform(30, 50) * kKmh, rng.uniform(1.0, 2.0));
    if (rng.chance(0.4)) {
      b.change_to(rng.uniform(15, 20) * kKmh, 1.5);
      b.turn(rng.uniform(1.2, 2.0), rng.uniform(2, 4), rng.chance(0.5));
    } else {
      b.cruise(rng.uniform(5, 15));
    }
    b.change_to(0, rng.uniform(1.5, 3.0));
    b.stand(rng.uniform(4, 12));
  }
}

void highway(ProfileBuilder& b, RandomStream& rng) {
  b.cruise(2);
  while (b.time() < 290) {
    b.change_to(rng.uniform(105, 130) * kKmh, 0.4);
    b.cruise(rng.uniform(8, 20));
    if (rng.chance(0.6)) b.slalom(rng.uniform(0.5, 1.0), 0.2, 5);
  }
}

void mountain(ProfileBuilder& b, RandomStream& rng) {
  b.stand(3);
  while (b.time() < 280) {
    b.change_to(rng.uniform(50, 75) * kKmh, 1.2);
    b.cruise(rng.uniform(6, 14));
    b.change_to(rng.uniform(25, 35) * kKmh, rng.uniform(1.5, 2.5));
    b.turn(rng.uniform(2.0, 3.0), rng.uniform(3, 6), rng.chance(0.5));
  }
}

void rural(ProfileBuilder& b, RandomStream& rng) {
  b.stand(3);
  while (b.time() < 180) {
    b.change_to(rng.uniform(55, 80) * kKmh, 1.2);
    b.cruise(rng.uniform(8, 16));
    if (rng.chance(0.5)) b.turn(rng.uniform(1.5, 2.5), rng.uniform(3, 6), rng.chance(0.5));
    b.change_to(30 * kKmh, 1.5);
    b.cruise(rng.uniform(6, 10));  // the village with the bumps
  }
}

struct Built {
  double duration_s = 200.0;
  std::vector<LoadItem> payload;
  std::vector<LoadChange> changes;
  bool no_brakes = false;  ///< the driver never brakes (coasts whatever the speed error)
};

using Builder = std::function<void(const DrawnVehicle&, RandomStream&, ProfileBuilder&,
                                   PopulationRun&, Built&)>;

struct ScenarioEntry {
  const char* name;
  const char* description;
  Builder build;
  bool truck_drive = false;  ///< the truck population's own drives (not in the car suite)
};

void typical(const DrawnVehicle& d, RandomStream& rng, Built& out) {
  out.payload = people_and_luggage(d, rng, rng.uniform(0.1, 0.8));
}

void exp1(NoiseSet eps, const DrawnVehicle& d, RandomStream& rng, ProfileBuilder& b,
          PopulationRun& run, Built& out) {
  typical(d, rng, out);
  paper_exp1(b);
  out.duration_s = std::max(200.0, b.time() + 5.0);
  run.bus.eps = eps;
  run.physics.road = paper_exp1_road();
}

void exp2(NoiseSet eps, const DrawnVehicle& d, RandomStream& rng, ProfileBuilder& b,
          PopulationRun& run, Built& out) {
  typical(d, rng, out);
  paper_exp2(b);
  out.duration_s = std::max(200.0, b.time() + 5.0);
  run.bus.eps = eps;
  run.physics.road = paper_exp2_road();
}

void exp1_eps1(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  exp1(NoiseSet::kEps1, d, g, b, r, o);
}
void exp1_eps2(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  exp1(NoiseSet::kEps2, d, g, b, r, o);
}
void exp1_eps3(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  exp1(NoiseSet::kEps3, d, g, b, r, o);
}
void exp2_eps1(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  exp2(NoiseSet::kEps1, d, g, b, r, o);
}
void exp2_eps2(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  exp2(NoiseSet::kEps2, d, g, b, r, o);
}
void exp2_eps3(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  exp2(NoiseSet::kEps3, d, g, b, r, o);
}

void urban_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  typical(d, g, o);
  urban(b, g);
  o.duration_s = 300.0;
  r.physics.road.grade_rad = slope_percent({{0, 0}, {400, 2}, {900, -1}, {1600, 1}, {2400, 0}});
  r.physics.road.friction =
      PiecewiseLinear({{0, 1.0}, {1500, 1.0}, {1501, 0.35}, {1560, 0.35}, {1561, 1.0}});
}

void highway_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
                 Built& o) {
  typical(d, g, o);
  b.start_at(110 * kKmh);
  r.physics.initial_speed_mps = b.speed();
  highway(b, g);
  o.duration_s = 300.0;
  r.physics.road.grade_rad = slope_percent({{0, 0}, {2000, 2}, {5000, -1.5}, {8000, 0}});
}

void mountain_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
                  Built& o) {
  typical(d, g, o);
  mountain(b, g);
  o.duration_s = 300.0;
  const double s = d.vehicle_class == VehicleClass::kHeavyTruck ? 0.6 : 1.0;
  r.physics.road.grade_rad = slope_percent({{0, 0},
                                            {200, 8 * s},
                                            {1200, 10 * s},
                                            {1800, 6 * s},
                                            {2200, -8 * s},
                                            {3200, -10 * s},
                                            {3800, -4 * s},
                                            {4200, 0}});
  r.physics.road.bank_rad = PiecewiseLinear({{0, 0},
                                             {600, 0},
                                             {650, 0.04},
                                             {800, 0.04},
                                             {850, 0},
                                             {2600, 0},
                                             {2650, -0.04},
                                             {2800, -0.04},
                                             {2850, 0}});
}

void heavy_rear_load_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun&,
                         Built& o) {
  o.payload = heavy_rear(d, g);
  paper_exp2(b);
  o.duration_s = std::max(200.0, b.time() + 5.0);
}

void windy_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
               Built& o) {
  typical(d, g, o);
  paper_exp2(b);
  b.change_to(100 * kKmh, 1.0);
  b.cruise(40);
  b.change_to(0, 1.5);
  o.duration_s = b.time() + 5.0;
  const double w = g.uniform(8, 15);
  const bool head = g.chance(0.5);
  r.physics.wind = {head ? w : 0.3 * w, head ? 0.3 * w : w, g.uniform(3, 5), g.uniform(2, 6)};
}

void rough_road_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
                    Built& o) {
  typical(d, g, o);
  rural(b, g);
  o.duration_s = std::max(200.0, b.time() + 5.0);
  r.physics.road.roughness = PiecewiseLinear(g.uniform(1.5, 3.0));
  for (double x = 300; x < 6000; x += g.uniform(400, 900)) {
    r.physics.road.bumps.push_back({x, g.uniform(1.0, 3.0)});
  }
}

void torque_bias_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
                     Built& o) {
  typical(d, g, o);
  paper_exp2(b);
  o.duration_s = std::max(200.0, b.time() + 5.0);
  r.bus.torque_report_scale *= 1.03;
}

void load_change_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun&,
                     Built& o) {
  typical(d, g, o);
  paper_exp2(b);
  const double stop = b.time();
  b.stand(25);
  LoadChange c;
  c.start_s = stop + 5.0;
  c.duration_s = 5.0;
  c.items = added_at_stop(d, g);
  o.changes.push_back(c);
  paper_exp2(b);
  o.duration_s = b.time() + 5.0;
}

void sensor_faults_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun& r,
                       Built& o) {
  typical(d, g, o);
  paper_exp2(b);
  o.duration_s = std::max(200.0, b.time() + 5.0);
  using K = BusFault::Kind;
  r.bus.faults = {{K::kMissing, "dynamics", 40.0, 3.0},
                  {K::kFrozen, d.sensors.lateral ? "steering" : "speed", 60.0, 10.0},
                  {K::kAbsurd, "speed", 90.0, 0.05},
                  {K::kAbsurd, "dynamics", 95.0, 0.05},
                  {K::kUnknownBurst, "", 110.0, 0.5},
                  {K::kMalformedBurst, "powertrain", 130.0, 0.5}};
}

// --- truck drives (issue 29): what a tractor-trailer's recordings hold ----------------------

// Pulling away with the accelerator floored: a reference no truck follows, so the torque (then
// the power) sits at its limit, then a long cruise held by the speed controller's small
// corrections. Returns when the accelerator is floored.
double truck_launch(ProfileBuilder& b, RandomStream& rng) {
  b.stand(rng.uniform(3, 8));
  const double launch_s = b.time();
  b.change_to(200 * kKmh, 6.0);
  b.cruise(300);
  return launch_s;
}

// The driver sets the cruise at the speed reached after 30-60 s floored (from `start_s`), as
// in a partner's recordings. Drawn last, so that the drive's other draws stay as they were.
void cruise_after_floored(ProfileBuilder& b, RandomStream& rng, double start_s) {
  b.hold_reached_speed_after(start_s - b.time() + rng.uniform(30, 60));
}

// A grade over distance that rises and falls sinusoidally (amplitude and wavelength drawn).
PiecewiseLinear rolling_grade(RandomStream& rng, double length_m) {
  const double amplitude = rng.uniform(1.5, 3.0);
  const double wavelength = rng.uniform(800, 1600);
  const double phase = rng.uniform(0.0, 6.283185307179586);
  std::vector<PiecewiseLinear::Point> points;
  for (double x = 0.0; x <= length_m; x += 50.0) {
    points.push_back({x, amplitude * std::sin(6.283185307179586 * x / wavelength + phase)});
  }
  return slope_percent(points);
}

void truck_launch_flat_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b,
                           PopulationRun&, Built& o) {
  typical(d, g, o);
  const double launch_s = truck_launch(b, g);
  o.duration_s = 240.0;
  cruise_after_floored(b, g, launch_s);
}

// The gear the gearbox would pick at that speed: the engine nearest the middle of its band.
int gear_for_speed(const PowertrainParams& p, double speed_mps, double radius_m) {
  const double middle = 0.5 * (p.upshift_speed_radps + p.downshift_speed_radps);
  int gear = 1;
  while (gear < p.gear_count() && speed_mps / radius_m *
                                          p.gear_ratios[static_cast<std::size_t>(gear - 1)] *
                                          p.final_drive_ratio >
                                      middle) {
    ++gear;
  }
  return gear;
}

// One gear throughout and never a brake, as a partner's tractor recordings: rolling at 40-55
// km/h in the gear that suits it, the accelerator floored (the torque at its limit for 30-60 s),
// then a long cruise that the speed controller holds with small corrections.
void truck_one_gear(PopulationRun& r, RandomStream& g, ProfileBuilder& b, Built& o) {
  b.start_at(g.uniform(40, 55) * kKmh / 0.75);
  r.physics.initial_speed_mps = b.speed();
  PowertrainParams& gearbox = r.physics.vehicle.powertrain;
  gearbox.hold_gear = gear_for_speed(gearbox, b.speed(), r.physics.vehicle.wheel_radius_m);
  b.change_to(200 * kKmh, 6.0);
  b.cruise(300);
  o.duration_s = 240.0;
  o.no_brakes = true;
}

void truck_one_gear_flat_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b,
                             PopulationRun& r, Built& o) {
  typical(d, g, o);
  truck_one_gear(r, g, b, o);
  cruise_after_floored(b, g, 0.0);
}

void truck_one_gear_grade_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b,
                              PopulationRun& r, Built& o) {
  typical(d, g, o);
  truck_one_gear(r, g, b, o);
  r.physics.road.grade_rad = PiecewiseLinear(3.0 * kDeg);
  cruise_after_floored(b, g, 0.0);
}

void truck_one_gear_rolling_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b,
                                PopulationRun& r, Built& o) {
  typical(d, g, o);
  truck_one_gear(r, g, b, o);
  r.physics.road.grade_rad = rolling_grade(g, 7000.0);
  cruise_after_floored(b, g, 0.0);
}

// Pulling away to a town speed, holding it, stopping: `cycles` times.
void stop_and_go(ProfileBuilder& b, RandomStream& rng, int cycles) {
  for (int i = 0; i < cycles; ++i) {
    b.change_to(rng.uniform(30, 50) * kKmh / 0.75, rng.uniform(1.0, 2.0));
    b.cruise(rng.uniform(10, 25));
    b.change_to(0, rng.uniform(1.5, 3.0));
    b.stand(rng.uniform(4, 12));
  }
}

// A tractor drives solo, couples a semi-trailer at a stop (100-200 % of its own mass, on the
// fifth wheel), drives loaded, and uncouples it at a second stop.
void truck_coupling_run(const DrawnVehicle& d, RandomStream& g, ProfileBuilder& b, PopulationRun&,
                        Built& o) {
  const Seats seats = seats_of(d);
  o.payload = {{g.uniform(70, 95), seats.front_x, 0.37, seats.seat_z}};
  b.stand(3);
  stop_and_go(b, g, 3);
  const double trailer_kg =
      std::min(g.uniform(1.0, 2.0) * d.vehicle.empty.mass_kg, d.payload_capacity_kg - 100.0);
  const LoadItem fifth_wheel = {trailer_kg, 0.5 * (seats.cargo_x0 + seats.cargo_x1), 0.0,
                                seats.cargo_z};
  LoadChange couple;
  couple.start_s = b.time() + 10.0;
  couple.duration_s = 20.0;
  couple.items = {fifth_wheel};
  b.stand(60);
  o.changes.push_back(couple);
  b.change_to(200 * kKmh, 6.0);
  b.cruise(120);
  b.change_to(0, 1.0);
  LoadChange uncouple = couple;
  uncouple.start_s = b.time() + 10.0;
  uncouple.items[0].mass_kg = -trailer_kg;
  b.stand(60);
  o.changes.push_back(uncouple);
  stop_and_go(b, g, 3);
  o.duration_s = b.time() + 5.0;
}

const std::vector<ScenarioEntry>& registry() {
  static const std::vector<ScenarioEntry> entries = {
      {"paper_exp1_eps1",
       "paper experiment 1, eps1 = N(0, 60^2) N on the wheel force: slopes, resistive loads",
       exp1_eps1},
      {"paper_exp1_eps2", "paper experiment 1, eps2 = N(300, 60^2) N: a force offset", exp1_eps2},
      {"paper_exp1_eps3", "paper experiment 1, eps3 = U(0, 600) N: non-Gaussian force noise",
       exp1_eps3},
      {"paper_exp2_eps1", "paper experiment 2, eps1: accelerating, braking, slaloms, turns",
       exp2_eps1},
      {"paper_exp2_eps2", "paper experiment 2, eps2: a force offset", exp2_eps2},
      {"paper_exp2_eps3", "paper experiment 2, eps3: non-Gaussian force noise", exp2_eps3},
      {"urban", "stop-and-go: short excitations, shifts, creep, junction turns, a low-mu stop",
       urban_run},
      {"highway", "steady high speed and lane changes: little excitation, aero, vibration",
       highway_run},
      {"mountain", "grades to 10 %, hairpins on banked curves, long braking (brake fade)",
       mountain_run},
      {"heavy_rear_load", "payload near capacity in the boot / rear: eq. (3) over-reads, bump stop",
       heavy_rear_load_run},
      {"windy", "mean head or cross wind of 8-15 m/s with 3-5 m/s gusts", windy_run},
      {"rough_road", "rural road on a rough surface, a village with speed bumps", rough_road_run},
      {"torque_bias", "the ECU's torque reads 3 % high (known-scale config): what a bias does",
       torque_bias_run},
      {"load_change", "drive, stop, 30-50 % of the payload capacity loaded at the stop, drive",
       load_change_run},
      {"sensor_faults",
       "a message missing 3 s, a frozen sensor 10 s, absurd values, bursts of unknown and "
       "malformed frames",
       sensor_faults_run},
      {"truck_launch_flat", "truck: accelerator floored from rest (torque at its limit), cruise",
       truck_launch_flat_run, true},
      {"truck_one_gear_flat", "truck: one gear, never braking, floored from 40-55 km/h, cruise",
       truck_one_gear_flat_run, true},
      {"truck_one_gear_grade",
       "truck: one gear, never braking, floored up a 3 degree grade, cruise",
       truck_one_gear_grade_run, true},
      {"truck_one_gear_rolling", "truck: one gear, never braking, floored, cruise, rolling hills",
       truck_one_gear_rolling_run, true},
      {"truck_coupling", "tractor: solo, a semi-trailer (+100-200 %) coupled at a stop, uncoupled",
       truck_coupling_run, true},
  };
  return entries;
}

void configure_driver(const DrawnVehicle& d, const MassProperties& mass, Scenario& s) {
  const TrueVehicle& v = s.vehicle;
  DriverParams& p = s.driver_params;
  p.nominal_mass_kg = mass.mass_kg;
  p.coast_band_n = 0.05 * mass.mass_kg;
  p.hold_pressure_pa = 0.3 * kG * d.max_mass_kg / v.brake_gain_n_per_pa;
  p.max_brake_pressure_pa = 1.0 * kG * d.max_mass_kg / v.brake_gain_n_per_pa;
}

}  // namespace

std::vector<std::string> population_scenario_names() {
  std::vector<std::string> out;
  for (const ScenarioEntry& e : registry()) {
    if (!e.truck_drive) out.emplace_back(e.name);
  }
  return out;
}

std::vector<std::string> truck_scenario_names() {
  std::vector<std::string> out = population_scenario_names();
  for (const ScenarioEntry& e : registry()) {
    if (e.truck_drive) out.emplace_back(e.name);
  }
  return out;
}

std::string population_scenario_description(std::string_view name) {
  for (const ScenarioEntry& e : registry()) {
    if (name == e.name) return e.description;
  }
  return "";
}

std::string make_population_run(const DrawnVehicle& vehicle, std::string_view scenario,
                                std::uint64_t seed, Realism realism, PopulationRun* out,
                                const std::vector<LoadItem>* payload) {
  const ScenarioEntry* entry = nullptr;
  for (const ScenarioEntry& e : registry()) {
    if (scenario == e.name) entry = &e;
  }
  if (entry == nullptr) return "unknown population scenario '" + std::string(scenario) + "'";
  // Built in a local and moved out: assigning a temporary to *out made GCC 12 at -O3 warn of
  // its vectors as maybe uninitialised (a false positive).
  PopulationRun run;
  run.scenario = entry->name;
  run.simulation.seed = seed;
  run.simulation.realism = realism;
  run.simulation.record_ecu_trace = true;  // the bus samples it at each message's own times
  run.bus.realism = realism;
  run.bus.seed = seed;
  Scenario& s = run.physics;
  s.name = vehicle.id + "/" + entry->name;
  s.description = entry->description;
  s.vehicle = vehicle.true_vehicle(realism);
  s.sensors = SensorSpec::ideal();
  s.default_noise = NoiseSet::kNone;
  // One stream per (vehicle, scenario, seed): the payload and the drive's random choices.
  RandomStream rng(seed * 1000003ULL + vehicle.stream_seed(), hash_name(entry->name));
  ProfileBuilder builder(vehicle, style_of(vehicle));
  Built built;
  entry->build(vehicle, rng, builder, run, built);
  if (payload != nullptr) built.payload = *payload;
  place_items(built.payload, s.vehicle, realism);
  for (LoadChange& c : built.changes) place_items(c.items, s.vehicle, realism);
  s.initial_payload = built.payload;
  s.load_changes = built.changes;
  s.duration_s = built.duration_s;
  s.driver = builder.build(built.duration_s);
  configure_driver(vehicle, s.mass_at(0.0), s);
  if (built.no_brakes) s.driver_params.coast_band_n = std::numeric_limits<double>::infinity();
  if (!realism.has(Effect::kWind)) s.wind = WindParams{};
  if (!realism.has(Effect::kRoadRoughness)) {
    s.road.roughness = PiecewiseLinear(0.0);
    s.road.bumps.clear();
  }
  std::string invalid = s.validate();
  *out = std::move(run);
  return invalid;
}

}  // namespace vmass::sim
