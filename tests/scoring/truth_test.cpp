// The truth at a time is its last row at or before that time; the drive starts when the true
// speed first exceeds 0.5 m/s; a truth that does not contain the first tick is refused.
#include "vmass/scoring/truth.hpp"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

namespace vmass::scoring {
namespace {

Truth load_change() {
  return Truth({0, from_seconds(10.0), from_seconds(20.0)}, {1000.0, 1200.0, 1200.0},
               {0.0, 0.4, 3.0});
}

TEST(Truth, MassIsTheLastRowAtOrBeforeTheTime) {
  const Truth t = load_change();
  EXPECT_EQ(t.mass_at(-1), 1000.0);  // before the first row: the first row
  EXPECT_EQ(t.mass_at(from_seconds(9.999999)), 1000.0);
  EXPECT_EQ(t.mass_at(from_seconds(10.0)), 1200.0);
  EXPECT_EQ(t.mass_at(from_seconds(99.0)), 1200.0);
  EXPECT_TRUE(std::isnan(Truth().mass_at(0)));
}

TEST(Truth, TheDriveStartsWhenTheSpeedExceedsHalfAMetrePerSecond) {
  EXPECT_EQ(load_change().drive_start_us(), from_seconds(20.0));
  const Truth no_speed({from_seconds(5.0), from_seconds(6.0)}, {1000.0, 1000.0});
  EXPECT_EQ(no_speed.drive_start_us(), from_seconds(5.0));  // unknown speed: from the first row
  EXPECT_EQ(Truth().drive_start_us(), 0);
}

TEST(Truth, TimeBaseMustContainTheFirstTick) {
  const Truth truth({0, from_seconds(60.0)}, {1700.0, 1700.0});
  const TimeUs tick = 10'000;
  EXPECT_EQ(truth.check_time_base(0, tick), "");
  EXPECT_EQ(truth.check_time_base(-tick, tick), "");  // one tick early: tolerated
  EXPECT_EQ(truth.check_time_base(from_seconds(60.0), tick), "");
  // A candump log recorded on a car: epoch times.
  const std::string epoch = truth.check_time_base(from_seconds(1.7e9), tick);
  EXPECT_NE(epoch.find("0.000 to 60.000 s"), std::string::npos) << epoch;
  EXPECT_NE(epoch.find("1700000000.000 s"), std::string::npos) << epoch;
  EXPECT_NE(truth.check_time_base(-2 * tick, tick), "");
}

}  // namespace
}  // namespace vmass::scoring
