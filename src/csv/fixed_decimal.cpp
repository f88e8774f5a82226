// Fixed-point decimal text through std::to_chars (see vmass/csv/fixed_decimal.hpp).
#include "vmass/csv/fixed_decimal.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>

namespace vmass {
namespace {

constexpr double kPow10[kMaxFixedDecimals + 1] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
/// Below 2^52 a double's ulp is at most 1/2, which the exact rounding needs (see the header).
constexpr double kExactScaledLimit = 4503599627370496.0;

/// round(magnitude * scale), ties to even, exactly (see the header); scaled = fl(magnitude *
/// scale) < 2^52.
std::uint64_t round_scaled(double magnitude, double scale, double scaled) {
  const double error = std::fma(magnitude, scale, -scaled);  // exact: scaled's rounding error
  const auto n = static_cast<std::uint64_t>(scaled);         // floor: scaled >= 0
  const double above_half = (scaled - static_cast<double>(n)) - 0.5;  // exact, k ulp(scaled)
  const bool up =
      above_half > 0.0 || (above_half == 0.0 && (error > 0.0 || (error == 0.0 && (n & 1u) != 0)));
  return up ? n + 1 : n;
}

}  // namespace

char* write_fixed(char* out, char* end, double v, int decimals) {
  const double magnitude = std::fabs(v);
  const double scale = kPow10[decimals];
  const double scaled = magnitude * scale;
  if (!(scaled < kExactScaledLimit)) {  // huge, infinite or NaN: the general to_chars
    const std::to_chars_result r = std::to_chars(out, end, v, std::chars_format::fixed, decimals);
    return r.ec == std::errc() ? r.ptr : nullptr;
  }
  char digits[24];
  const std::to_chars_result r =
      std::to_chars(digits, digits + sizeof digits, round_scaled(magnitude, scale, scaled));
  const int count = static_cast<int>(r.ptr - digits);
  const int width = count > decimals ? count : decimals + 1;  // "0.001": leading zeros
  const bool negative = std::signbit(v);
  if (end - out < static_cast<std::ptrdiff_t>(negative) + width + (decimals > 0 ? 1 : 0)) {
    return nullptr;
  }
  char* p = out;
  if (negative) *p++ = '-';
  const int zeros = width - count;
  const int integer_digits = width - decimals;
  for (int i = 0; i < width; ++i) {
    if (i == integer_digits) *p++ = '.';
    *p++ = i < zeros ? '0' : digits[i - zeros];
  }
  return p;
}

}  // namespace vmass
