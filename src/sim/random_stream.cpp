#include "vmass/sim/random_stream.hpp"

#include <cmath>

namespace vmass::sim {

namespace {
constexpr double kTwoPi = 6.28318530717958647692;
}  // namespace

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

std::uint64_t hash_name(const char* text) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (const char* p = text; *p != '\0'; ++p) {
    h ^= static_cast<unsigned char>(*p);
    h *= 0x100000001B3ULL;
  }
  return h;
}

RandomStream::RandomStream(std::uint64_t seed, std::uint64_t stream_id)
    : engine_(splitmix64(seed ^ splitmix64(0xC0FFEE1234ULL + stream_id))) {}

double RandomStream::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double RandomStream::uniform(double low, double high) { return low + (high - low) * uniform(); }

double RandomStream::normal() {
  const double u1 = 1.0 - uniform();  // (0, 1]
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

double RandomStream::log_uniform(double low, double high) {
  return std::exp(uniform(std::log(low), std::log(high)));
}

int RandomStream::index(int n) {
  const int i = static_cast<int>(uniform() * static_cast<double>(n));
  return i < n ? i : n - 1;
}

}  // namespace vmass::sim
