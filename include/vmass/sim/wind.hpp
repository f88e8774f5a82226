// Wind: the air's velocity relative to the ground, seen in the car's frame, for the wind effect.
// A mean head and cross component plus gusts, each gust component an Ornstein-Uhlenbeck process
// (exponentially correlated, stationary std gust_std_mps, correlation time gust_time_s):
//   w(t + dt) = w(t) e^(-dt/T) + gust_std sqrt(1 - e^(-2 dt/T)) N(0, 1)
// Head wind is positive against the car (it adds to the airspeed); cross wind positive from the
// right (it pushes the car to the left). The car's heading changes are ignored: the wind is
// given relative to the road the car follows.
//
// Not thread-safe (random stream); no allocation.
#pragma once

#include <cstdint>
#include <string>

#include "vmass/sim/random_stream.hpp"

namespace vmass::sim {

struct WindParams {
  double mean_head_mps = 0.0;
  double mean_cross_mps = 0.0;
  double gust_std_mps = 0.0;
  double gust_time_s = 3.0;

  std::string validate() const;
};

class Wind {
 public:
  Wind(const WindParams& params, std::uint64_t seed);
  void step(double dt_s);
  double head_mps() const { return params_.mean_head_mps + gust_head_; }
  double cross_mps() const { return params_.mean_cross_mps + gust_cross_; }

 private:
  WindParams params_;
  RandomStream rng_;
  double gust_head_ = 0.0;
  double gust_cross_ = 0.0;
};

}  // namespace vmass::sim
