#include "vmass/sim/wind.hpp"

#include <cmath>

namespace vmass::sim {

std::string WindParams::validate() const {
  if (!(std::abs(mean_head_mps) < 40.0 && std::abs(mean_cross_mps) < 40.0)) {
    return "wind: mean components must be below 40 m/s";
  }
  if (!(gust_std_mps >= 0.0 && gust_std_mps < 20.0)) return "wind.gust_std_mps in [0, 20)";
  if (!(gust_time_s > 0.0)) return "wind.gust_time_s must be > 0";
  return "";
}

Wind::Wind(const WindParams& params, std::uint64_t seed)
    : params_(params), rng_(seed, hash_name("wind")) {
  // Start from the stationary distribution, not from calm.
  gust_head_ = params.gust_std_mps * rng_.normal();
  gust_cross_ = params.gust_std_mps * rng_.normal();
}

void Wind::step(double dt_s) {
  const double a = std::exp(-dt_s / params_.gust_time_s);
  const double s = params_.gust_std_mps * std::sqrt(1.0 - a * a);
  gust_head_ = a * gust_head_ + s * rng_.normal();
  gust_cross_ = a * gust_cross_ + s * rng_.normal();
}

}  // namespace vmass::sim
