#include "vmass/core/overall_ratio_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/core/param_check.hpp"

namespace vmass {

namespace {
// A plateau's ratio averages at most this many locked ticks: it follows a slow change (tyre wear
// changes r / v) and one tick never moves it.
constexpr double kPlateauMemoryTicks = 1000.0;
}  // namespace

std::string RatioTrackerParams::validate() const {
  ParamCheck c("ratio_tracker");
  c.positive("window_s", window_s);
  c.in_open_range("steady_fraction", steady_fraction, 0.0, 0.5);
  c.in_open_range("match_fraction", match_fraction, 0.0, 0.5);
  c.non_negative("confirm_speed_mps", confirm_speed_mps);
  c.positive("min_speed_mps", min_speed_mps);
  c.positive("max_ratio", max_ratio);
  return c.message();
}

OverallRatioTracker::OverallRatioTracker(const VehicleParams& vehicle,
                                         const RatioTrackerParams& params, double tick_rate_hz)
    : vehicle_(vehicle),
      params_(params),
      // Without a converter every steady ratio is a gear's.
      confirm_speed_mps_(vehicle.torque_converter ? params.confirm_speed_mps : 0.0),
      window_ticks_(std::clamp(static_cast<int>(std::lround(params.window_s * tick_rate_hz)), 2,
                               kMaxWindowTicks)) {}

void OverallRatioTracker::restart() {
  window_fill_ = 0;
  window_next_ = 0;
  reading_ = RatioReading{};
}

bool OverallRatioTracker::window_steady(double* mean) const {
  double lo = window_[0];
  double hi = window_[0];
  double sum = 0.0;
  for (int k = 0; k < window_ticks_; ++k) {
    const double r = window_[static_cast<std::size_t>(k)];
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    sum += r;
  }
  *mean = sum / window_ticks_;
  return hi - lo <= params_.steady_fraction * *mean;
}

int OverallRatioTracker::plateau_for(double ratio) {
  int best = 0;
  double best_distance = params_.match_fraction;
  for (int id = 1; id <= plateau_count_; ++id) {
    const double distance =
        std::abs(ratio / plateaus_[static_cast<std::size_t>(id - 1)].ratio - 1.0);
    if (distance <= best_distance) {
      best = id;
      best_distance = distance;
    }
  }
  if (best > 0 || plateau_count_ == kMaxPlateaus) return best;
  plateaus_[static_cast<std::size_t>(plateau_count_)] = Plateau{ratio, 0.0, false};
  return ++plateau_count_;
}

void OverallRatioTracker::join(int id, double window_mean, double speed_mps) {
  Plateau& p = plateaus_[static_cast<std::size_t>(id - 1)];
  p.ticks = std::min(p.ticks + 1.0, kPlateauMemoryTicks);
  p.ratio += (window_mean - p.ratio) / p.ticks;
  if (std::abs(speed_mps) >= confirm_speed_mps_) p.confirmed = true;
}

RatioReading OverallRatioTracker::step(double engine_speed_radps, double speed_mps) {
  const double ratio = engine_speed_radps * vehicle_.wheel_radius_m / std::abs(speed_mps);
  // Written so that NaN fails every test.
  if (!(engine_speed_radps > 0.0 && std::abs(speed_mps) >= params_.min_speed_mps &&
        ratio <= params_.max_ratio)) {
    restart();
    return reading_;
  }
  window_[static_cast<std::size_t>(window_next_)] = ratio;
  window_next_ = (window_next_ + 1) % window_ticks_;
  window_fill_ = std::min(window_fill_ + 1, window_ticks_);
  reading_ = RatioReading{};
  reading_.ratio = ratio;
  double mean = 0.0;
  if (window_fill_ < window_ticks_ || !window_steady(&mean)) return reading_;
  const int id = plateau_for(mean);
  if (id == 0) return reading_;  // every slot taken: not a gearbox this tracker knows
  join(id, mean, speed_mps);
  const Plateau& p = plateaus_[static_cast<std::size_t>(id - 1)];
  reading_ = RatioReading{true, p.confirmed, id, p.ratio};
  last_locked_ = id;
  return reading_;
}

double OverallRatioTracker::wheel_torque_nm(double engine_torque_nm) const {
  const double ratio = reading_.locked ? reading_.ratio : plateau_ratio(last_locked_);
  // Losses take from the torque flowing to the wheels, and add to the drag of a dragged engine.
  const double efficiency =
      engine_torque_nm >= 0.0 ? vehicle_.driveline_efficiency : 1.0 / vehicle_.driveline_efficiency;
  return engine_torque_nm * ratio * efficiency;
}

double OverallRatioTracker::rotating_mass_kg(int id) const {
  const double ratio = plateau_ratio(id);
  const double r = vehicle_.wheel_radius_m;
  return vehicle_.rotating_mass_kg +
         vehicle_.driveline_efficiency * vehicle_.engine_inertia_kgm2 * ratio * ratio / (r * r);
}

double OverallRatioTracker::plateau_ratio(int id) const {
  if (id < 1 || id > plateau_count_) return 0.0;
  return plateaus_[static_cast<std::size_t>(id - 1)].ratio;
}

bool OverallRatioTracker::plateau_confirmed(int id) const {
  return id >= 1 && id <= plateau_count_ && plateaus_[static_cast<std::size_t>(id - 1)].confirmed;
}

}  // namespace vmass
