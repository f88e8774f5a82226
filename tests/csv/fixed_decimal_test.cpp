// write_fixed() against the independent answer: glibc's printf("%.*f") (correctly rounded in
// the C locale), on random values of every magnitude, exact ties, values near the fast path's
// limit, and the special values.
#include "vmass/csv/fixed_decimal.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

namespace vmass {
namespace {

std::string with_printf(double v, int decimals) {
  char buf[kMaxFixedChars + 8];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string with_write_fixed(double v, int decimals) {
  char buf[kMaxFixedChars];
  char* end = write_fixed(buf, buf + sizeof buf, v, decimals);
  return end == nullptr ? std::string("<no room>") : std::string(buf, end);
}

/// Counts the values of `values` (a generator) that differ from printf, printing the first few.
template <class Next>
int mismatches(int count, int decimals, Next next) {
  int bad = 0;
  for (int i = 0; i < count; ++i) {
    const double v = next();
    const std::string expected = with_printf(v, decimals);
    const std::string got = with_write_fixed(v, decimals);
    if (got != expected && ++bad <= 5) {
      ADD_FAILURE() << "%." << decimals << "f of " << std::hexfloat << v << ": printf " << expected
                    << ", write_fixed " << got;
    }
  }
  return bad;
}

TEST(FixedDecimal, MatchesPrintfOnRandomValuesOfEveryMagnitude) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 60);
  for (int decimals = 0; decimals <= kMaxFixedDecimals; ++decimals) {
    EXPECT_EQ(
        mismatches(200'000, decimals, [&] { return std::ldexp(mantissa(rng), exponent(rng)); }), 0);
  }
}

TEST(FixedDecimal, MatchesPrintfOnTheValuesOurFilesHold) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> mass(-5000.0, 5000.0);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  EXPECT_EQ(mismatches(1'000'000, 3, [&] { return mass(rng); }), 0);
  EXPECT_EQ(mismatches(1'000'000, 5, [&] { return fraction(rng); }), 0);
  std::int64_t time_us = 0;  // tick times in seconds, %.2f
  EXPECT_EQ(mismatches(1'000'000, 2, [&] { return static_cast<double>(time_us += 10'000) * 1e-6; }),
            0);
}

TEST(FixedDecimal, RoundsExactTiesToEvenAsPrintfDoes) {
  // k / 2^j with j small: x * 10^d lands exactly on a half for many k (0.0625 -> "0.062").
  for (int decimals = 0; decimals <= 6; ++decimals) {
    int k = -40'000;
    EXPECT_EQ(mismatches(80'000, decimals, [&] { return std::ldexp(k++, -4); }), 0);
    k = -40'000;
    EXPECT_EQ(mismatches(80'000, decimals, [&] { return std::ldexp(k++, -9); }), 0);
  }
  EXPECT_EQ(with_write_fixed(0.0625, 3), "0.062");
  EXPECT_EQ(with_write_fixed(0.1875, 3), "0.188");
  EXPECT_EQ(with_write_fixed(2.5, 0), "2");
  EXPECT_EQ(with_write_fixed(-3.5, 0), "-4");
}

TEST(FixedDecimal, MatchesPrintfAroundTheFastPathsLimit) {
  for (int decimals = 0; decimals <= kMaxFixedDecimals; ++decimals) {
    const double limit = std::ldexp(1.0, 52) / std::pow(10.0, decimals);
    double v = limit * (1.0 - 1e-9);
    EXPECT_EQ(mismatches(20'000, decimals,
                         [&] { return v = std::nextafter(v, std::numeric_limits<double>::max()); }),
              0);
  }
}

TEST(FixedDecimal, WritesSpecialValuesAsPrintfDoes) {
  const double specials[] = {0.0,
                             -0.0,
                             -0.0004,
                             1e-310,
                             -1e-310,
                             1e300,
                             -1.7976931348623157e308,
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN(),
                             -std::numeric_limits<double>::quiet_NaN()};
  for (const double v : specials) {
    for (int decimals = 0; decimals <= kMaxFixedDecimals; ++decimals) {
      EXPECT_EQ(with_write_fixed(v, decimals), with_printf(v, decimals)) << v << " " << decimals;
    }
  }
  EXPECT_EQ(with_write_fixed(-0.0004, 3), "-0.000");
}

TEST(FixedDecimal, SaysWhenTheTextDoesNotFit) {
  char buf[8];
  EXPECT_EQ(write_fixed(buf, buf + 5, 1234.5, 3), nullptr);  // "1234.500" needs 8
  char* end = write_fixed(buf, buf + 8, 1234.5, 3);
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(std::string(buf, end), "1234.500");
  EXPECT_EQ(write_fixed(buf, buf + 8, 1e300, 3), nullptr);
}

}  // namespace
}  // namespace vmass
