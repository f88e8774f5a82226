#include "vmass/sim/lifetime.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "seats.hpp"
#include "vmass/sim/random_stream.hpp"

namespace vmass::sim {

namespace {

// Who sits where and what is in the boot (a car); the driver and one block of cargo (a van,
// pickup or truck).
struct Load {
  double driver_kg = 80.0;
  std::array<double, 4> passengers{};  ///< front right, rear left, rear right, rear middle; 0: free
  double boot_kg = 0.0;
  double cargo_kg = 0.0;
  double cargo_x_m = 0.0;
};

constexpr std::array<double, 4> kPassengerY = {-0.37, 0.40, -0.40, 0.0};

double total_kg(const Load& l) {
  double sum = l.driver_kg + l.boot_kg + l.cargo_kg;
  for (double p : l.passengers) sum += p;
  return sum;
}

std::vector<LoadItem> items_of(const Load& l, const Seats& s) {
  std::vector<LoadItem> items = {{l.driver_kg, s.front_x, 0.37, s.seat_z}};
  for (std::size_t i = 0; i < l.passengers.size(); ++i) {
    if (l.passengers[i] <= 0.0) continue;
    items.push_back({l.passengers[i], i == 0 ? s.front_x : s.rear_x, kPassengerY[i], s.seat_z});
  }
  if (l.boot_kg > 0.0) items.push_back({l.boot_kg, s.boot_x, 0.0, s.cargo_z});
  if (l.cargo_kg > 0.0) items.push_back({l.cargo_kg, l.cargo_x_m, 0.0, s.cargo_z});
  return items;
}

double full_boot_kg(const DrawnVehicle& d) {
  return std::clamp(0.3 * d.payload_capacity_kg, 60.0, 200.0);
}

double person_kg(RandomStream& rng) {
  return rng.chance(0.25) ? rng.uniform(20.0, 45.0) : rng.uniform(55.0, 100.0);
}

Load first_load(const DrawnVehicle& d, const Seats& s, RandomStream& rng) {
  Load l;
  l.driver_kg = rng.uniform(60.0, 100.0);
  if (s.cargo) {
    l.cargo_kg = rng.uniform(0.0, 0.7) * (d.payload_capacity_kg - l.driver_kg);
    l.cargo_x_m = rng.uniform(s.cargo_x0, s.cargo_x1);
    return l;
  }
  for (double& p : l.passengers) p = rng.chance(0.35) ? person_kg(rng) : 0.0;
  l.boot_kg = rng.uniform(0.0, 0.6) * full_boot_kg(d);
  return l;
}

std::string signed_kg(double kg) {
  const long rounded = std::lround(kg);
  return (rounded >= 0 ? "+" : "") + std::to_string(rounded) + " kg";
}

// A few passengers get in or out.
std::string change_passengers(const DrawnVehicle& d, RandomStream& rng, Load* l) {
  int seated = 0;
  for (double p : l->passengers) seated += p > 0.0 ? 1 : 0;
  const int free = static_cast<int>(l->passengers.size()) - seated;
  const bool in = seated == 0 || (free > 0 && rng.chance(0.6));
  const int count = 1 + rng.index(std::min(3, in ? free : seated));
  int moved = 0;
  for (double& p : l->passengers) {
    if (moved == count) break;
    if (in && p <= 0.0) {
      p = person_kg(rng);
      ++moved;
    } else if (!in && p > 0.0) {
      p = 0.0;
      ++moved;
    }
  }
  // Never above the permitted mass: the last passenger in stays out when it would be.
  for (double& p : l->passengers) {
    if (total_kg(*l) <= d.payload_capacity_kg) break;
    p = 0.0;
  }
  return std::to_string(moved) + (moved == 1 ? " passenger " : " passengers ") +
         (in ? "in" : "out");
}

std::string change_boot(const DrawnVehicle& d, RandomStream& rng, Load* l) {
  const double full = full_boot_kg(d);
  if (l->boot_kg < 0.5 * full) {
    l->boot_kg = rng.uniform(0.7, 1.0) * full;
    l->boot_kg = std::min(l->boot_kg, d.payload_capacity_kg - (total_kg(*l) - l->boot_kg));
    return "boot filled";
  }
  l->boot_kg = rng.uniform(0.0, 10.0);
  return "boot emptied";
}

std::string change_cargo(const DrawnVehicle& d, const Seats& s, RandomStream& rng, Load* l) {
  const double room = d.payload_capacity_kg - l->driver_kg;
  double cargo = rng.uniform(0.0, 0.9) * room;
  // A change worth the name: at least a tenth of the capacity.
  if (std::abs(cargo - l->cargo_kg) < 0.1 * room) {
    cargo = l->cargo_kg > 0.45 * room ? rng.uniform(0.0, 0.2) * room : rng.uniform(0.5, 0.9) * room;
  }
  const bool loaded = cargo > l->cargo_kg;
  l->cargo_kg = cargo;
  l->cargo_x_m = rng.uniform(s.cargo_x0, s.cargo_x1);
  return loaded ? "cargo loaded" : "cargo unloaded";
}

// One change of the load while parked: cargo (a van, pickup, truck), or passengers or the boot.
std::string change_load(const DrawnVehicle& vehicle, const Seats& seats, RandomStream& rng,
                        Load* load) {
  if (seats.cargo) return change_cargo(vehicle, seats, rng, load);
  if (rng.chance(0.5)) return change_passengers(vehicle, rng, load);
  return change_boot(vehicle, rng, load);
}

// New tyres: worn tread (about 2 mm) replaced by new (7-9 mm) on a radius of about 0.3 m
// (cars) to 0.5 m (trucks): the radius grows by 1-3 %.
double new_tyres_factor(const DrawnVehicle& vehicle, std::uint64_t life) {
  RandomStream rng(vehicle.stream_seed(), hash_name("lifetime_tyres") + life);
  return 1.0 + rng.uniform(0.01, 0.03);
}

std::string percent_of(double factor) {
  std::array<char, 16> text{};
  std::snprintf(text.data(), text.size(), "%+.1f %%", (factor - 1.0) * 100.0);
  return text.data();
}

// A semi-trailer's kind, against the first one's: its factors of the combination's drag area
// and rolling coefficient.
struct Trailer {
  double drag_factor = 1.0;
  double rolling_factor = 1.0;
  std::string described() const {
    return "another trailer (drag area " + percent_of(drag_factor) + ", rolling " +
           percent_of(rolling_factor) + ")";
  }
};

// Another semi-trailer, of another kind and load, drawn apart from the life's loads: its load
// is a cargo change worth the name, its factors those of a flatbed to a high box (the drag area)
// and of its tyres and axles (the rolling coefficient).
Trailer couple_another_trailer(const DrawnVehicle& vehicle, const Seats& seats, std::uint64_t life,
                               Load* load) {
  RandomStream rng(vehicle.stream_seed(), hash_name("lifetime_trailer") + life);
  change_cargo(vehicle, seats, rng, load);
  Trailer trailer;
  trailer.drag_factor = rng.uniform(0.75, 1.3);
  trailer.rolling_factor = rng.uniform(0.85, 1.2);
  return trailer;
}

}  // namespace

std::vector<std::string> lifetime_scenario_names() {
  return {"urban",           "highway",    "paper_exp1_eps1", "mountain",
          "paper_exp2_eps2", "rough_road", "windy",           "load_change"};
}

double payload_mass_kg(const std::vector<LoadItem>& items) {
  double sum = 0.0;
  for (const LoadItem& it : items) sum += it.mass_kg;
  return sum;
}

void fit_tyres(double tyre_radius_factor, TrueVehicle* vehicle) {
  vehicle->wheel_radius_m *= tyre_radius_factor;
  double& speed_error = vehicle->wheel_speed.radius_error_fraction;
  speed_error = (1.0 + speed_error) / tyre_radius_factor - 1.0;
}

void couple_trailer(double drag_factor, double rolling_factor, TrueVehicle* vehicle) {
  vehicle->drag_area_m2 *= drag_factor;
  vehicle->rolling_resistance_coeff *= rolling_factor;
  vehicle->rolling_resistance_speed_coeff_s2_per_m2 *= rolling_factor;
}

std::vector<LifetimeDrive> plan_lifetime(const DrawnVehicle& vehicle, int drives,
                                         std::uint64_t life, int tyre_change_drive,
                                         int trailer_change_drive) {
  const double new_tyres = new_tyres_factor(vehicle, life);
  const Seats seats = seats_of(vehicle);
  RandomStream rng(vehicle.stream_seed(), hash_name("lifetime") + life);
  const std::vector<std::string> scenarios = lifetime_scenario_names();
  const std::size_t offset =
      static_cast<std::size_t>(rng.index(static_cast<int>(scenarios.size())));
  Load load = first_load(vehicle, seats, rng);
  const bool trailer_change = vehicle.tractor && trailer_change_drive > 1;
  Trailer trailer;  // the first one's until the change
  std::vector<LifetimeDrive> out;
  for (int i = 1; i <= drives; ++i) {
    LifetimeDrive drive;
    drive.index = i;
    drive.scenario = scenarios[(offset + static_cast<std::size_t>(i) - 1) % scenarios.size()];
    drive.seed = life * 1000 + static_cast<std::uint64_t>(i);
    const double before = total_kg(load);
    const bool change = i > 1 && (i % 2 == 0 || rng.chance(0.3));
    const bool new_trailer = trailer_change && i == trailer_change_drive;
    if (change) {
      // A new trailer replaces that drive's load change, drawn all the same (on a copy) so that
      // the life's later changes are drawn as without it.
      Load discarded = load;
      drive.load_change = change_load(vehicle, seats, rng, new_trailer ? &discarded : &load);
    }
    if (new_trailer) {
      trailer = couple_another_trailer(vehicle, seats, life, &load);
      drive.load_change = "another trailer";
      drive.car_change = trailer.described();
    }
    if (!drive.load_change.empty()) {
      drive.payload_change_kg = total_kg(load) - before;
      drive.load_change += " (" + signed_kg(drive.payload_change_kg) + ")";
    }
    drive.payload = items_of(load, seats);
    drive.trailer_drag_factor = trailer.drag_factor;
    drive.trailer_rolling_factor = trailer.rolling_factor;
    if (tyre_change_drive > 1 && i >= tyre_change_drive) {
      drive.tyre_radius_factor = new_tyres;
      if (i == tyre_change_drive) {
        if (!drive.car_change.empty()) drive.car_change += "; ";
        drive.car_change += "new tyres (radius " + percent_of(new_tyres) + ")";
      }
    }
    out.push_back(drive);
  }
  return out;
}

}  // namespace vmass::sim
