// RandomStream: one seeded stream of random numbers for one source of randomness in the
// simulator (one sensor's noise, one vehicle's parameter draws, the wind's gusts). Seeded from
// (seed, stream id) through splitmix64, so that adding a stream or drawing more from one never
// moves another; normals from Box-Muller on 53-bit uniforms, so the same seed gives the same
// numbers on every platform with the same libm.
//
// Not thread-safe (state); cheap to copy.
#pragma once

#include <cstdint>
#include <random>

namespace vmass::sim {

/// splitmix64 finaliser: a well-mixed 64-bit hash of x.
std::uint64_t splitmix64(std::uint64_t x);
/// FNV-1a of a string, for stream ids named by text.
std::uint64_t hash_name(const char* text);

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t stream_id);

  double uniform();                         ///< [0, 1)
  double uniform(double low, double high);  ///< [low, high)
  double normal();                          ///< N(0, 1)
  double normal(double mean, double std) { return mean + std * normal(); }
  /// Log-uniform in [low, high] (both > 0): for ranges spanning a factor of several.
  double log_uniform(double low, double high);
  bool chance(double probability) { return uniform() < probability; }
  /// An integer in [0, n).
  int index(int n);

 private:
  std::mt19937_64 engine_;
};

}  // namespace vmass::sim
