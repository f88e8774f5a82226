// Test helper: synthetic regression pairs y = M da + mu + e with known M, mu and noise, shared
// by the RLS and Bayes tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "vmass/core/regression_pair.hpp"

namespace vmass::testing {

inline RegressionPair make_pair(double y, double da, double w) {
  RegressionPair p;
  p.y_n = y;
  p.delta_accel_mps2 = da;
  p.weight = w;
  return p;
}

/// n pairs with da ~ N(da_mean, da_std^2), weights ~ U(0.5, 2) and noise sigma / sqrt(w).
inline std::vector<RegressionPair> synthetic_pairs(int n, double mass, double mu, double sigma,
                                                   std::uint64_t seed, double da_mean,
                                                   double da_std) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> da_dist(da_mean, da_std);
  std::uniform_real_distribution<double> w_dist(0.5, 2.0);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<RegressionPair> pairs;
  for (int i = 0; i < n; ++i) {
    const double da = da_dist(rng);
    const double w = w_dist(rng);
    pairs.push_back(make_pair(mass * da + mu + sigma / std::sqrt(w) * unit(rng), da, w));
  }
  return pairs;
}

}  // namespace vmass::testing
