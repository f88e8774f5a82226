// The tracker keeps the last time each tolerance was exceeded; no estimate (NaN) exceeds all.
// One tick's error is signed, in percent; its interval covers a truth on either bound.
#include "vmass/scoring/within_tracker.hpp"

#include <limits>

#include <gtest/gtest.h>

#include "vmass/scoring/tick_comparison.hpp"

namespace vmass::scoring {
namespace {

TEST(WithinTracker, KeepsTheLastTimeEachToleranceWasExceeded) {
  WithinTracker w({5.0, 2.0, 1.0});
  w.add(0, std::numeric_limits<double>::quiet_NaN());  // no estimate: outside every tolerance
  w.add(1, 3.0);                                       // outside 2 % and 1 %
  w.add(2, 1.5);                                       // outside 1 %
  w.add(3, 1.0);                                       // on the bound: within
  EXPECT_EQ(w.last_outside_us(0), TimeUs{0});
  EXPECT_EQ(w.last_outside_us(1), TimeUs{1});
  EXPECT_EQ(w.last_outside_us(2), TimeUs{2});
  EXPECT_FALSE(WithinTracker({5.0, 2.0, 1.0}).last_outside_us(0).has_value());
}

TEST(TickComparison, ErrorIsSignedAndCoverageIncludesTheBounds) {
  EXPECT_DOUBLE_EQ(error_pct(1100.0, 1000.0), 10.0);
  EXPECT_DOUBLE_EQ(error_pct(950.0, 1000.0), -5.0);
  EXPECT_TRUE(interval_covers(990.0, 1010.0, 990.0));
  EXPECT_TRUE(interval_covers(990.0, 1010.0, 1010.0));
  EXPECT_FALSE(interval_covers(990.0, 1010.0, 1010.5));
}

}  // namespace
}  // namespace vmass::scoring
