// Fixed-point decimal text of a double, byte for byte what printf("%.*f", decimals, v) writes
// in the C locale (correctly rounded from the exact binary value, ties to even; "-0.000" for a
// negative value that rounds to zero; "nan", "-nan", "inf", "-inf"), without printf: no locale,
// no varargs, no allocation.
//
// The digits come from std::to_chars. For |v| * 10^decimals < 2^53 (every number our CSV files
// hold) the value is first rounded to the integer N = round(|v| * 10^decimals) exactly, and N
// is written with the integer std::to_chars, the point inserted `decimals` digits from the
// right. The rounding is exact although |v| * 10^decimals is not: with s = fl(|v| * 10^d) and
// its error e = |v| * 10^d - s = fma(|v|, 10^d, -s) (exact), and n = floor(s),
//     round up  <=>  (s - n) - 1/2 > 0,  or it is 0 and (e > 0, or e == 0 and n is odd)
// because s - n - 1/2 is exact and a multiple of ulp(s), while |e| <= ulp(s) / 2. Other values
// (huge, non-finite) go through std::to_chars(fixed, decimals) itself, which is also exact but
// 2-3 times slower in libstdc++ 12 (vmass-bench format/*, docs/performance.md).
//
// Thread-safe (pure functions).
#pragma once

#include <cstddef>

namespace vmass {

/// Longest text write_fixed() produces for `decimals` <= kMaxFixedDecimals: sign, 309 integer
/// digits (DBL_MAX), the point, the decimals.
constexpr int kMaxFixedDecimals = 9;
constexpr std::size_t kMaxFixedChars = 1 + 309 + 1 + kMaxFixedDecimals;

/// Writes v with `decimals` (0..kMaxFixedDecimals) digits after the point at [out, end) and
/// returns the end of the text, or nullptr when it does not fit (kMaxFixedChars always do).
char* write_fixed(char* out, char* end, double v, int decimals);

}  // namespace vmass
